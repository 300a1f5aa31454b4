#pragma once
// The sheet's inertia in the pull-out tank, known before the tank is filled.
//
// fill_pull_out_tank scales the sheet's masses so that its stable step is the grains' critical
// step (SparSheet::required_mass_scaling): a very stiff sheet (axial stiffness 1e10 N/m) gets
// masses so large that its inertia, not the soil, sets the head tension. The filled tank's check
// (apps/pull_watch.h, check_dem_sheet_inertia) sees that after the fill, which on the full tank
// takes hours. The sheet's stiffness, its nodes and the grains' sizes are known before: the
// grains' critical step comes from the smallest grain of the fill's size distribution, scaled as
// REDF scales it to the target porosity, with the stiffest of the soil's and the walls' laws.
// An estimate, not the fill's figure: the fill's sizes are scaled lift by lift and the sheet is
// re-laid on the grains, so the two differ by some tens of per cent (callers use a margin).
#include "pullout_tank.h"

namespace geohybrid::dem
{
struct SheetInertiaEstimate
{
  double grain_time_step = 0.0; ///< the step the filled tank will take: safety x critical [s]
  double mass_scaling = 1.0;    ///< the factor on the sheet's masses [-]
  double inertial_mass = 0.0;   ///< of the nodes the clamp does not hold, scaled [kg/m]
};

/// Throws std::invalid_argument as spec.validate() and redf_starting_sizes do.
SheetInertiaEstimate estimate_sheet_inertia(const PullOutTankSpec &spec);
} // namespace geohybrid::dem
