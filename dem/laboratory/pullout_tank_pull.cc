// The pull of a filled tank: the clamp moved at its rate, the head tension recorded
// (pullout_tank.h: PullOut, pull_out).
#include "pullout_tank.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace geohybrid::dem
{
DemSystem with_threads(const DemSystem &system, int n_threads)
{
  DemSystemState state = system.export_state();
  DemSettings settings = system.settings();
  settings.n_threads = n_threads;
  DemSystem copy(state.particles, system.particle_law(), settings);
  for (const Wall &wall : system.walls())
    copy.add_wall(wall);
  copy.set_sheet_local_damping(system.sheet_local_damping() >= 0.0 ? system.sheet_local_damping()
                                                                   : settings.local_damping);
  copy.restore_state(std::move(state));
  return copy;
}

namespace
{
bool positive(double v) { return v > 0.0 && std::isfinite(v); }

void check_pull_spec(const PullSpec &spec)
{
  if (!positive(spec.rate))
    throw std::invalid_argument("pull-out: 'Pull/rate' = " + std::to_string(spec.rate) + " must be positive [m/s]");
  if (!positive(spec.final_displacement))
    throw std::invalid_argument("pull-out: 'Pull/final displacement' = " + std::to_string(spec.final_displacement) +
                                " must be positive [m]");
  if (!positive(spec.record_interval))
    throw std::invalid_argument("pull-out: 'Pull/record interval' = " + std::to_string(spec.record_interval) +
                                " must be positive [m]");
  if (!(spec.ramp_displacement >= 0.0 && spec.ramp_displacement < spec.final_displacement))
    throw std::invalid_argument("pull-out: 'Pull/ramp displacement' = " + std::to_string(spec.ramp_displacement) +
                                " must lie in [0, final displacement) [m]");
}
} // namespace

PullOut::PullOut(DemSystem &system, const PullSpec &spec, std::function<void()> advance)
  : system_(system), spec_(spec), advance_(std::move(advance))
{
  if (!advance_)
    throw std::invalid_argument("pull-out: the function that advances the system is empty");
  start();
}

PullOut::PullOut(DemSystem &system, const PullSpec &spec) : system_(system), spec_(spec)
{
  start();
}

void PullOut::start()
{
  check_pull_spec(spec_);
  // Constant acceleration over the ramp: it covers ramp_displacement in 2 ramp_displacement / rate.
  ramp_time_ = 2.0 * spec_.ramp_displacement / spec_.rate;
  SparSheet &sheet = system_.sheets().at(0);
  progress_.clamp_x0 = sheet.x[0];
  progress_.time0 = system_.time();
  progress_.next_record = spec_.record_interval;
  sheet.prescribe_velocity(0, Vec2(clamp_speed(), 0.0));
  system_.set_sheet_local_damping(spec_.sheet_local_damping);
  if (spec_.grain_local_damping)
    system_.set_local_damping(*spec_.grain_local_damping);
  // A system stepped by someone else keeps its forces current (a coupled stepper's include the
  // coupling's, which a new evaluation would apply twice).
  if (!advance_)
    system_.initialise_forces();
  last_point_.head_tension = head_tension(system_);
  last_point_.parts = head_tension_parts(system_);
}

PullOut::PullOut(DemSystem &system, const PullSpec &spec, const PullProgress &progress, std::function<void()> advance)
  : PullOut(system, spec, progress)
{
  if (!advance)
    throw std::invalid_argument("pull-out: the function that advances the system is empty");
  advance_ = std::move(advance);
}

PullOut::PullOut(DemSystem &system, const PullSpec &spec, const PullProgress &progress)
  : system_(system), spec_(spec), progress_(progress)
{
  check_pull_spec(spec);
  ramp_time_ = 2.0 * spec.ramp_displacement / spec.rate;
  // The sheet's damping is a setting of the system, not of its state. The clamp's velocity is
  // in the state, and is what clamp_speed() gives for the same spec (each step prescribes it
  // for the next): prescribed again, it changes nothing when resuming the same pull, and it
  // makes a pull of the same filled tank at another rate start at its own speed.
  system.set_sheet_local_damping(spec.sheet_local_damping);
  if (spec.grain_local_damping)
    system.set_local_damping(*spec.grain_local_damping);
  if (!progress.finished)
    system.sheets().at(0).prescribe_velocity(0, Vec2(clamp_speed(), 0.0));
  last_point_.head_displacement = head_displacement();
  last_point_.head_tension = head_tension(system);
  last_point_.parts = head_tension_parts(system);
}

void PullOut::stop_clamp() { system_.sheets()[0].prescribe_velocity(0, Vec2::Zero()); }

PullPoint PullOut::start_point() const
{
  PullPoint p;
  p.head_tension = head_tension(system_);
  p.parts = head_tension_parts(system_);
  return p;
}

double PullOut::clamp_speed() const
{
  const double t = system_.time() - progress_.time0 + 0.5 * system_.time_step(); // at the middle of the next step
  return ramp_time_ > 0.0 && t < ramp_time_ ? spec_.rate * t / ramp_time_ : spec_.rate;
}

double PullOut::head_displacement() const { return system_.sheets()[0].x[0] - progress_.clamp_x0; }

std::uint64_t PullOut::expected_steps() const
{
  const double distance = spec_.final_displacement + spec_.ramp_displacement; // the ramp takes twice its length in time
  return static_cast<std::uint64_t>(std::ceil(distance / spec_.rate / system_.time_step()));
}

bool PullOut::step()
{
  if (progress_.finished)
    return false;
  if (advance_)
    advance_();
  else
    system_.step();
  SparSheet &sheet = system_.sheets()[0];
  sheet.prescribe_velocity(0, Vec2(clamp_speed(), 0.0));
  progress_.tension_sum += head_tension(system_);
  progress_.parts_sum.add(head_tension_parts(system_));
  ++progress_.n_summed;
  ++progress_.n_steps;
  const double u = sheet.x[0] - progress_.clamp_x0, end = spec_.final_displacement;
  if (!(u >= progress_.next_record - 1e-12 * end || u >= end - 1e-12 * end))
    return false;
  last_point_.head_displacement = u;
  last_point_.head_tension = progress_.tension_sum / static_cast<double>(progress_.n_summed);
  last_point_.parts = progress_.parts_sum;
  last_point_.parts.scale(1.0 / static_cast<double>(progress_.n_summed));
  progress_.parts_sum = HeadTensionParts();
  progress_.tension_sum = 0.0;
  progress_.n_summed = 0;
  progress_.next_record += spec_.record_interval;
  progress_.finished = u >= end - 1e-12 * end;
  return true;
}

std::vector<PullPoint> pull_out(DemSystem &system, const PullSpec &spec,
                                const std::function<void(const PullPoint &, const DemSystem &)> &record,
                                const std::function<void()> &advance)
{
  PullOut pull = advance ? PullOut(system, spec, advance) : PullOut(system, spec);
  std::vector<PullPoint> points{pull.start_point()};
  if (record)
    record(points.back(), system);
  while (!pull.finished())
    if (pull.step())
      {
        points.push_back(pull.last_point());
        if (record)
          record(points.back(), system);
      }
  pull.stop_clamp();
  return points;
}
} // namespace geohybrid::dem
