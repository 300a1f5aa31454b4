#include "pull_watch.h"

#include "apps/run_directory.h"
#include "apps/run_health.h"

#include "coupling/particle_box.h"
#include "dem/io/checkpoint.h"
#include "dem/measurements.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace geohybrid::apps
{
namespace
{
double pull_kinetic_energy(const dem::DemSystem &system)
{
  const dem::EnergyBudget e = system.energy();
  return e.kinetic + e.sheet_kinetic;
}

const char *const state_key = "pull_watch";
constexpr std::size_t n_state = 12;
} // namespace

PullWatch::PullWatch(const Setup &setup, const dem::DemSystem &system, const dem::CommandState *saved)
  : setup_(setup), check_kinetic_(setup.kinetic_energy), kinetic_start_(pull_kinetic_energy(system))
{
  if (!saved)
    return;
  const auto found = saved->reals.find(state_key);
  if (found == saved->reals.end() || found->second.size() != n_state)
    {
      check_kinetic_ = false;
      return;
    }
  const std::vector<double> &s = found->second;
  check_kinetic_ = setup.kinetic_energy && s[0] != 0.0;
  kinetic_start_ = s[1];
  work_ = s[2];
  last_u_ = s[3];
  T_max_ = s[4];
  have_last_ = s[5] != 0.0;
  worst_inertia_ = s[6];
  worst_inertia_u_ = s[7];
  worst_kinetic_ = s[8];
  worst_kinetic_u_ = s[9];
  worst_unbalanced_ = s[10];
  worst_unbalanced_u_ = s[11];
}

void PullWatch::store(dem::CommandState &command) const
{
  command.reals[state_key] = {check_kinetic_ ? 1.0 : 0.0, kinetic_start_,   work_,          last_u_,
                              T_max_,                     have_last_ ? 1.0 : 0.0, worst_inertia_, worst_inertia_u_,
                              worst_kinetic_,             worst_kinetic_u_, worst_unbalanced_, worst_unbalanced_u_};
}

void PullWatch::check(const dem::PullPoint &p, const dem::DemSystem &system)
{
  const double u = p.head_displacement, T = p.head_tension;
  const auto at = [u] { return "at " + number(1e3 * u, 4) + " mm of the pull"; }; // only to throw
  if (!std::isfinite(T) || !std::isfinite(u))
    throw RunWentWrong(at() + " the head tension is not finite (" + number(T, 4) +
                       " N/m): the pull diverged; likely 'Pull/rate' far too fast or 'Sheet/axial stiffness' too high "
                       "for the time step");
  if (have_last_)
    {
      const double du = u - last_u_;
      if (du > record_step_factor * setup_.record_interval)
        throw RunWentWrong(at() + " the head moved " + number(1e3 * du, 4) + " mm since the last point, where " +
                           "'Pull/record interval' asks " + number(1e3 * setup_.record_interval, 4) +
                           " mm: the clamp moves farther in one time step than the curve's resolution; lower 'Pull/rate'");
      work_ += T * du; // T is the mean over the interval: its work, to the rounding of the steps
    }
  have_last_ = true;
  last_u_ = u;
  T_max_ = std::max(T_max_, T);

  const GrainBounds &b = setup_.grains_inside;
  const GrainsOutside out =
    grains_outside(system, b.x0, b.x1, b.y0, b.y1, std::numeric_limits<double>::infinity());
  if (out.count > 0)
    throw RunWentWrong(at() + " " + std::to_string(out.count) + " grains have left " + b.name + " (grain " +
                       std::to_string(out.first_id) + " at (" + number(out.first_x, 4) + ", " +
                       number(out.first_y, 4) + ") m in the particles' frame): they crossed a wall or the coupling in a "
                       "time step; likely 'Pull/rate' far too fast, or 'Soil/Particle contact' stiffnesses too low for "
                       "the stress");

  // The sheet's share: its mean inertial force over the interval against the tension it carries.
  if (T_max_ > 0.0)
    {
      const double share = std::abs(p.parts.inertia) / T_max_;
      if (share > fatal_inertia_share)
        throw RunWentWrong(at() + " the sheet's inertia takes " + number(100.0 * share, 3) + " % of the head tension (" +
                           number(p.parts.inertia, 4) + " of " + number(T_max_, 4) +
                           " N/m): the mass-scaled sheet, not the soil, sets the answer; lower 'Sheet/axial stiffness' "
                           "(its masses are scaled with it) or 'Pull/rate'");
      if (std::abs(p.parts.inertia) > worst_inertia_)
        {
          worst_inertia_ = std::abs(p.parts.inertia);
          worst_inertia_u_ = u;
        }
    }

  if (check_kinetic_ && u > setup_.ramp_displacement + 2.0 * setup_.record_interval && work_ > 0.0)
    {
      const double share = (pull_kinetic_energy(system) - kinetic_start_) / work_;
      if (share > fatal_kinetic_share)
        throw RunWentWrong(at() + " the grains' and the sheet's kinetic energy is " + number(100.0 * share, 3) +
                           " % of the clamp's work: the pull flings the soil instead of shearing it; lower "
                           "'Pull/rate'");
      if (share > worst_kinetic_)
        {
          worst_kinetic_ = share;
          worst_kinetic_u_ = u;
        }
    }

  const double unbalanced = dem::unbalanced_force_ratio(system);
  if (std::isfinite(unbalanced) && unbalanced > worst_unbalanced_)
    {
      worst_unbalanced_ = unbalanced;
      worst_unbalanced_u_ = u;
    }
}

std::optional<std::string> check_dem_sheet_inertia(const dem::SparSheet &sheet, const dem::PullSpec &pull,
                                                   double time_step, double friction_limit, const std::string &where)
{
  SheetInertiaCheck c;
  for (std::size_t k = 1; k < sheet.n_nodes(); ++k) // node 0 is the clamp
    c.inertial_mass += sheet.mass[k];
  c.rate = pull.rate;
  c.ramp_displacement = pull.ramp_displacement;
  c.time_step = time_step;
  c.friction_limit = friction_limit;
  c.mass_scaling = sheet.parameters().mass_scaling;
  return check_sheet_inertia(c, where);
}

GrainBounds particle_box_bounds(const coupling::ParticleBox &box)
{
  const double room = box.lift_thickness, open = std::numeric_limits<double>::infinity();
  return {box.left_shared ? -room : 0.0, box.x1 - box.x0, box.bottom_shared ? -room : 0.0,
          box.top_shared ? box.y1 - box.y0 + room : open, "the particle box"};
}

std::vector<std::string> PullWatch::warnings() const
{
  std::vector<std::string> w;
  const auto mm = [](double u) { return number(1e3 * u, 4) + " mm"; };
  if (worst_inertia_ > warning_inertia_share * T_max_)
    w.push_back("the sheet's inertia took up to " + number(100.0 * worst_inertia_ / T_max_, 3) + " % of T_max (at " +
                mm(worst_inertia_u_) + "; the rate check's was below 0.1 %): lower 'Pull/rate', lengthen 'Pull/ramp "
                "displacement', or check 'Sheet/axial stiffness'");
  if (worst_kinetic_ > warning_kinetic_share)
    w.push_back("the pull's kinetic energy reached " + number(100.0 * worst_kinetic_, 3) + " % of the clamp's work (at " +
                mm(worst_kinetic_u_) + "): not quasi-static; lower 'Pull/rate'");
  if (worst_unbalanced_ > warning_unbalanced_ratio)
    w.push_back("the unbalanced-force ratio reached " + number(worst_unbalanced_, 3) + " (at " +
                mm(worst_unbalanced_u_) + ", above " + number(warning_unbalanced_ratio, 2) +
                "): the soil accelerates rather than shears; lower 'Pull/rate' or raise 'Pull/grain local damping'");
  return w;
}
} // namespace geohybrid::apps
