#pragma once
// A region of a filled pull-out tank taken out as a tank of its own: the grains whose centres lie
// in the region and the sheet, in the region's frame, between the region's own walls. The hybrid
// pull-out takes its particle box from a pure-DEM fill this way, so that the two models pull the
// same grains round the sheet and differ only where the continuum replaces them: the difference
// between their curves is then the coupling's and the continuum's, not a packing's scatter (one
// seed of the INSA tank scatters T_max by about 1 kN/m, 7 %).
#include "pullout_tank.h"

#include <string>

namespace geohybrid::dem
{
/// The grains of `tank` (filled in the tank's frame) whose centres lie inside the rectangle
/// [origin, origin + (width, height)] of `region` (its resolved filling's width and height, in the
/// tank's frame), moved into the region's frame, at rest, their contacts with each other and with
/// the sheet keeping their history (the tangential forces); the sheet moved the same way, as it stands
/// (its clamp through the front wall's slot, so the region must reach the tank's front wall); the
/// region's walls: the front wall with the tank's slot, the base and the left wall at the
/// region's sides or moved out past the grains the cut left standing beyond them (they touch
/// none), the lid parked above everything. No layers are recorded (the grains' lifts are the
/// tank's). Throws std::invalid_argument, naming `where`, if the region leaves the tank or misses
/// its front wall, or if the sheet does not lie wholly inside it.
PullOutTank cut_pull_out_tank(const PullOutTank &tank, double tank_length, const PullOutTankSpec &region,
                              const Vec2 &origin, const std::string &where);
} // namespace geohybrid::dem
