#include "sheet_laying.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace geohybrid::dem
{
namespace
{
/// Throws unless every node of `sheet` but the first (the clamp, outside) lies in the tank.
void check_nodes_in_tank(const SparSheet &sheet, const TankFillingSpec &t)
{
  const Vec2 clamp = sheet.node(0);
  // Nodes between the clamp and the front wall are outside the tank too, in front of the slot.
  for (std::size_t k = 1; k < sheet.n_nodes(); ++k)
    if (!(sheet.x[k] > 0.0 && sheet.x[k] <= clamp.x() && sheet.y[k] > 0.0 && sheet.y[k] < t.height))
      throw std::invalid_argument("tank filling: node " + std::to_string(k) + " of sheet '" + sheet.name() +
                                  "' lies outside the tank");
}
} // namespace

SparSheet lay_sheet(const SheetLaying &laying, const DemSystem &settled, const TankFillingSpec &t, double &slot_height)
{
  SparSheet sheet = laying.lay(settled);
  const Vec2 clamp = sheet.node(0);
  if (!(clamp.x() > t.width))
    throw std::invalid_argument("tank filling: the first node of sheet '" + sheet.name() + "' (x = " +
                                std::to_string(clamp.x()) + " m) must lie outside the front wall (x = " +
                                std::to_string(t.width) + " m), where the clamp holds it");
  check_nodes_in_tank(sheet, t);
  const ParticleSet &p = settled.particles();
  const double smallest = 2.0 * *std::min_element(p.disc_radius.begin(), p.disc_radius.end());
  // The clamp holds the sheet at the slot's mid-height, so the slot leaves a gap of
  // (slot height - thickness) / 2 above and below it; a grain escapes only through a gap wider
  // than itself. The automatic slot leaves a quarter of the smallest grain on each side, so that
  // grains smaller than the sheet is thick (a fine tank: 25,000 clusters in the INSA tank have
  // 2.6 mm grains against GT230's 3.2 mm) stay in too.
  slot_height = laying.slot_height > 0.0 ? laying.slot_height : sheet.thickness() + 0.5 * smallest;
  if (!(slot_height > sheet.thickness()))
    throw std::invalid_argument("tank filling: the slot height " + std::to_string(slot_height) +
                                " m must exceed the thickness of sheet '" + sheet.name() + "' (" +
                                std::to_string(sheet.thickness()) + " m)");
  if (!(slot_height - sheet.thickness() < smallest))
    throw std::invalid_argument("tank filling: the slot height " + std::to_string(slot_height) +
                                " m leaves a gap of " + std::to_string(slot_height - sheet.thickness()) +
                                " m beside sheet '" + sheet.name() + "' (" + std::to_string(sheet.thickness()) +
                                " m thick): it must be below the smallest grain's diameter (" + std::to_string(smallest) +
                                " m), or the soil runs out through it");
  return sheet;
}

SparSheet lay_second_part(const SheetLaying &laying, const DemSystem &settled, const SparSheet &laid,
                          const TankFillingSpec &t)
{
  SparSheet sheet = laying.lay_second_part(settled, laid);
  if (sheet.n_nodes() < laid.n_nodes())
    throw std::invalid_argument("tank filling: laying the second part of sheet '" + laid.name() + "' dropped " +
                                std::to_string(laid.n_nodes() - sheet.n_nodes()) + " of its nodes");
  if (!(sheet.node(0) == laid.node(0)))
    throw std::invalid_argument("tank filling: laying the second part of sheet '" + laid.name() +
                                "' moved its clamp (node 0), which the front wall's slot was cut for");
  check_nodes_in_tank(sheet, t);
  return sheet;
}
} // namespace geohybrid::dem
