#pragma once
// Laying a sheet in a tank being filled (tank_filling.h, SheetLaying): the sheet the spec's
// functions make, checked against the tank (the clamp outside the front wall, every other node
// in the tank), and the height of the slot cut for it in the front wall.
#include "dem/dem_system.h"
#include "dem/spar_sheet.h"
#include "tank_filling.h"

namespace geohybrid::dem
{
/// The sheet of `laying`, made on the settled layers below it, checked against the tank, and the
/// height of its slot. Throws std::invalid_argument naming the sheet.
SparSheet lay_sheet(const SheetLaying &laying, const DemSystem &settled, const TankFillingSpec &spec, double &slot_height);

/// The whole sheet of a two-stage `laying`, from `laid` (the sheet as it stands in the settled
/// layers), checked: the clamp where it was (the slot was cut at its level), no node dropped,
/// every node in the tank. Throws std::invalid_argument naming the sheet.
SparSheet lay_second_part(const SheetLaying &laying, const DemSystem &settled, const SparSheet &laid,
                          const TankFillingSpec &spec);
} // namespace geohybrid::dem
