#pragma once
// One prepared sample, many materials: a sample made once (by REDF) is given other contact laws
// and brought back to equilibrium at its confining stress, so that tests of several sets of
// micro-parameters share one fabric. A calibration needs this: on a sample of a few hundred
// grains, making a new REDF sample for every parameter set changes the peak friction angle by
// several degrees (a different random assembly every time, however small the parameter change),
// while on one shared fabric the response varies smoothly with the parameters.
#include "dem/dem_system.h"
#include "box.h"

#include <cstdint>

namespace geohybrid::dem
{
/// When a sample counts as in equilibrium at its stress (as at the end of REDF).
struct EquilibriumCriteria
{
  double stress_tolerance = 0.02;       ///< relative error of each wall pair's stress [-]
  double unbalanced_ratio = 1e-3;       ///< unbalanced-force ratio [-]
  std::uint64_t max_steps = 1'000'000;  ///< give up beyond this many steps
};

/// Replaces the particle-particle law and every wall's law, resets the time step to the safety
/// fraction of the new critical step (stiffer contacts need a shorter one), servo-controls the
/// four walls of `box` to the isotropic `stress` and steps until `criteria` hold. Returns the
/// steps taken. Throws std::runtime_error naming the stress error if no equilibrium is reached.
std::uint64_t change_contact_laws(DemSystem &system, const RectangularBox &box, const ContactParameters &particle,
                                  const ContactParameters &wall, double stress, const EquilibriumCriteria &criteria = {});
} // namespace geohybrid::dem
