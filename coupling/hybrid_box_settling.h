#pragma once
// The hybrid pull-out's particle box on its own, after its fill and before the coupling
// (hybrid_pullout.h): settled under the overburden of the continuum that will lie above it, or
// after its sheet was cut at the DEM core's edge.
#include "dem/dem_system.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace geohybrid::coupling
{
/// The top of the highest grain: the fill's surface before a lid presses it [m].
double highest_grain_top(const dem::ParticleSet &particles);

/// Steps the particles 200 at a time until `at_rest()` (checked after each 200); returns the
/// steps taken. Throws std::runtime_error with `failure()` past `max_steps`.
std::uint64_t step_particles_until(dem::DemSystem &particles, const std::function<bool()> &at_rest,
                                   std::uint64_t max_steps, const std::function<std::string()> &failure);

/// What settle_under_overburden measured.
struct OverburdenSettling
{
  std::uint64_t steps = 0;   ///< taken [-]
  double stress_reached = 0; ///< the lid's last stress [Pa]
  double top_surface = 0;    ///< the lid's height then: the box's top surface, in the box's frame [m]
};

/// Loads the top of the filled particle box with `stress` [Pa] through its lid (the wall
/// `lid_index`, parked above the fill: brought down onto the highest grain, frictionless,
/// servo-controlled) until the lid's stress is within 1 % of it and the unbalanced-force ratio
/// below `target`, then parks the lid above the fill again with its law. Throws
/// std::runtime_error naming `where` past `max_steps`.
OverburdenSettling settle_under_overburden(dem::DemSystem &particles, std::size_t lid_index, double stress,
                                           double target, std::uint64_t max_steps, const std::string &where);
} // namespace geohybrid::coupling
