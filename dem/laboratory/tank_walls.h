#pragma once
// The walls of a tank being filled (tank_filling.h): base, side walls, the lid a lift grows under
// and, once a sheet is laid, the front wall cut at the sheet's slot. Every system of a fill (a
// lift growing, the fill settling, a lift taken from the cache) gets them in the same order, so
// one TankWalls indexes them all.
#include "dem/dem_system.h"
#include "tank_filling.h"

namespace geohybrid::dem
{
/// Adds the tank's walls to `system`, the lid at `lid_level`; with slot_top > slot_bottom, the
/// front wall (x = width) is cut into a part below the slot and one above it.
TankWalls add_tank_walls(DemSystem &system, const TankFillingSpec &spec, double lid_level, double slot_bottom = 0.0,
                         double slot_top = 0.0);
} // namespace geohybrid::dem
