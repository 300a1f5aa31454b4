#include "run_health.h"

#include "apps/run_directory.h"
#include "apps/summary.h"

#include "dem/dem_system.h"
#include "dem/laboratory/sheet_inertia_estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>

namespace geohybrid::apps
{
void report_warnings(const std::vector<std::string> &warnings, const std::string &command, Summary &summary,
                     std::ostream &terminal)
{
  summary.set("warnings", warnings);
  for (const std::string &w : warnings)
    terminal << command << ": warning: " << w << '\n';
}

double pull_inertial_number(double rate, double density, double vertical_stress)
{
  return rate * std::sqrt(density / vertical_stress);
}

std::optional<std::string> check_pull_rate(double rate, double density, double vertical_stress,
                                           const std::string &where, const PullRateBounds &bounds)
{
  if (!(vertical_stress > 0.0) || !(density > 0.0))
    return std::nullopt; // no stress at the sheet: nothing to compare the rate with
  const double I = pull_inertial_number(rate, density, vertical_stress);
  const double quasi_static_rate = bounds.warning / std::sqrt(density / vertical_stress);
  if (I > bounds.refusal)
    throw std::invalid_argument(
      where + ": 'Pull/rate' = " + number(rate, 4) + " m/s is far too fast for a quasi-static pull-out: its inertial " +
      "number v sqrt(rho / sigma_v) is " + number(I, 3) + " (rho " + number(density, 4) + " kg/m3, sigma_v = gamma H " +
      number(vertical_stress, 4) + " Pa), above " + number(bounds.refusal, 2) +
      ", where the grains' inertia at the clamp's speed outweighs the confining stress; the rate check found "
      "I = 0.028 quasi-static (bench/RESULTS.md): lower 'Pull/rate' to " +
      number(quasi_static_rate, 2) + " m/s or less");
  if (I > bounds.warning)
    return "'Pull/rate' = " + number(rate, 4) + " m/s gives an inertial number of " + number(I, 3) + ", above " +
           number(bounds.warning, 2) + " (twice the rate check's quasi-static one): check that halving the rate "
           "does not change the curve, or pull at " + number(quasi_static_rate, 2) + " m/s or less";
  return std::nullopt;
}

void check_particle_speeds(const dem::DemSystem &system, const std::string &where)
{
  const dem::ParticleSet &p = system.particles();
  const double dt = system.time_step();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      if (p.inverse_mass[b] == 0.0)
        continue;
      double radius = std::numeric_limits<double>::infinity();
      for (std::size_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
        radius = std::min(radius, p.disc_radius[d]);
      const double speed = std::hypot(p.vx[b], p.vy[b]);
      if (!(speed * dt <= 0.5 * radius))
        throw std::invalid_argument(where + ": particle " + std::to_string(p.body_id[b]) + " moves at " +
                                    number(speed, 4) + " m/s, " + number(speed * dt / radius, 3) +
                                    " times its radius in one time step of " + number(dt, 4) +
                                    " s: its contacts cannot act before it passes through a wall or a grain; "
                                    "lower its velocity in the CSV file ('Particles/csv file'), or 'Simulation/time step'");
    }
}

double SheetInertiaCheck::ramp_force() const
{
  // The mean force to bring M to speed v over the ramp (a = v^2 / (2 d)); without a ramp the
  // clamp starts at full speed, in one step.
  const double ramp = std::max(ramp_displacement, rate * time_step);
  return inertial_mass * rate * rate / (2.0 * ramp);
}

std::optional<std::string> check_sheet_inertia(const SheetInertiaCheck &c, const std::string &where)
{
  if (!(c.friction_limit > 0.0))
    return std::nullopt;
  const double share = c.ramp_force() / c.friction_limit;
  const std::string what = "the sheet's inertial mass (" + number(c.inertial_mass, 4) + " kg/m, its masses scaled by " +
                           number(c.mass_scaling, 4) + " to the grains' time step) takes " + number(c.ramp_force(), 4) +
                           " N/m to follow the clamp's ramp, " + number(100.0 * share, 3) +
                           " % of the interface's friction limit 2 sigma_v L tan(delta) = " +
                           number(c.friction_limit, 4) + " N/m";
  if (share > 0.5)
    throw std::invalid_argument(where + ": " + what + ": its inertia, not the soil, would set the head tension; " +
                                "lower 'Sheet/axial stiffness' (the stiffer the sheet, the more mass its stable step " +
                                "needs), or lower 'Pull/rate', or lengthen 'Pull/ramp displacement'");
  if (share > 0.05)
    return what + " (lower 'Pull/rate' or lengthen 'Pull/ramp displacement')";
  return std::nullopt;
}

void refuse_sheet_inertia_before_the_fill(const dem::PullOutTankSpec &tank, const dem::PullSpec &pull,
                                          const std::string &where)
{
  const dem::SheetInertiaEstimate estimate = dem::estimate_sheet_inertia(tank);
  SheetInertiaCheck c;
  c.inertial_mass = estimate.inertial_mass;
  c.rate = pull.rate;
  c.ramp_displacement = pull.ramp_displacement;
  c.time_step = estimate.grain_time_step;
  c.mass_scaling = estimate.mass_scaling;
  const dem::PullOutGeometry &g = tank.geometry;
  c.friction_limit = 2.0 * tank.unit_weight * g.cover * g.anchorage_length *
                     std::tan(dem::degrees_to_radians(tank.sheet.interface.friction_angle_deg));
  const double share = c.ramp_force() / c.friction_limit;
  if (share > sheet_inertia_setup_share)
    throw std::invalid_argument(
      where + ": 'Sheet/axial stiffness' = " + number(tank.sheet.axial_stiffness, 4) +
      " N/m makes the sheet's inertia, not the soil, set the head tension: to stay stable at the grains' time step (" +
      number(c.time_step, 4) + " s, estimated before the fill) its masses are scaled by " + number(c.mass_scaling, 4) +
      ", an inertial mass of " + number(c.inertial_mass, 4) + " kg/m that takes " + number(c.ramp_force(), 4) +
      " N/m to follow the clamp's ramp, " + number(100.0 * share, 3) +
      " % of the interface's geostatic friction limit 2 gamma H L tan(delta) = " + number(c.friction_limit, 4) +
      " N/m; lower 'Sheet/axial stiffness' (the stiffer the sheet, the more mass its stable step needs), or lower "
      "'Pull/rate', or lengthen 'Pull/ramp displacement'");
}

std::optional<std::string> check_fem_tension(double T_max, double interface_limit)
{
  if (!std::isfinite(T_max))
    throw RunWentWrong("the head tension is not finite: the continuum's pull diverged; lower 'Pull/rate' or "
                       "'Continuum/safety factor'");
  if (!(interface_limit > 0.0))
    return std::nullopt;
  const double ratio = T_max / interface_limit;
  const std::string what = "T_max = " + number(T_max / 1e3, 4) + " kN/m is " + number(ratio, 3) +
                           " x the interface's geostatic limit " + number(interface_limit / 1e3, 4) + " kN/m";
  if (ratio > 10.0)
    throw RunWentWrong(what + ": the sheet's and the soil's inertia carry the pull, not the interface (runs give " +
                       "1.2-1.4 x); lower 'Pull/rate' (and check 'Continuum/sheet mass scaling' if set)");
  if (ratio > 3.0)
    return what + " (runs give 1.2-1.4 x): check that halving 'Pull/rate' does not change the curve";
  return std::nullopt;
}

GrainsOutside grains_outside(const dem::DemSystem &system, double x0, double x1, double y0, double y1,
                             double side_height)
{
  const dem::ParticleSet &p = system.particles();
  GrainsOutside out;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      double r = 0.0;
      for (std::size_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
        r = std::max(r, p.disc_radius[d]);
      const double x = p.x[b], y = p.y[b];
      const bool below = y < y0 - r, above = y > y1 + r, beside = y < side_height && (x < x0 - r || x > x1 + r);
      if (below || above || beside || !std::isfinite(x) || !std::isfinite(y))
        {
          if (out.count++ == 0)
            {
              out.first_id = p.body_id[b];
              out.first_x = x;
              out.first_y = y;
            }
        }
    }
  return out;
}

DemRunWatch::DemRunWatch(double width, double height, bool top_wall)
  : width_(width), height_(height), top_wall_(top_wall)
{}

void DemRunWatch::check(const dem::DemSystem &system, const dem::EnergyBudget &e, double balance_error)
{
  const auto when = [&system] { // only to throw
    return "at t = " + number(system.time(), 6) + " s (step " + std::to_string(system.step_count()) + ")";
  };
  if (!std::isfinite(e.kinetic) || !std::isfinite(e.gravitational) || !std::isfinite(e.elastic) ||
      !std::isfinite(balance_error))
    throw RunWentWrong(when() + " the energy is not finite (kinetic " + number(e.kinetic, 4) + " J/m, gravitational " +
                       number(e.gravitational, 4) + " J/m): velocities or forces beyond any physics; likely "
                       "'Simulation/gravity', the CSV file's velocities ('Particles/csv file') or 'Simulation/time step'");
  const GrainsOutside out =
    grains_outside(system, 0.0, width_, 0.0, top_wall_ ? height_ : std::numeric_limits<double>::infinity(), height_);
  if (out.count > 0)
    throw RunWentWrong(when() + " " + std::to_string(out.count) + " of " + std::to_string(system.particles().n_bodies()) +
                       " particles have left the box (particle " + std::to_string(out.first_id) + " at (" +
                       number(out.first_x, 4) + ", " + number(out.first_y, 4) +
                       ") m): they crossed a wall in a time step; likely 'Simulation/gravity' or the CSV file's "
                       "velocities ('Particles/csv file') far too high, or 'Simulation/time step' too large");
  if (std::abs(balance_error) > fatal_balance_error)
    throw RunWentWrong(when() + " the energy balance's error is " + number(balance_error, 4) +
                       " of the budget's largest term: energy is created or lost by the integration, not the physics; "
                       "lower 'Simulation/time step' (or 'time step safety factor')");
  if (std::abs(balance_error) > std::abs(worst_error_))
    {
      worst_error_ = balance_error;
      worst_error_time_ = system.time();
    }
}

std::vector<std::string> DemRunWatch::warnings() const
{
  if (std::abs(worst_error_) <= warning_balance_error)
    return {};
  return {"the energy balance's error reached " + number(worst_error_, 3) + " of the budget's largest term at t = " +
          number(worst_error_time_, 4) + " s (above " + number(warning_balance_error, 2) +
          "): lower 'Simulation/time step' (or 'time step safety factor')"};
}
} // namespace geohybrid::apps
