#include "tank_walls.h"

#include <algorithm>

namespace geohybrid::dem
{
TankWalls add_tank_walls(DemSystem &system, const TankFillingSpec &t, double lid_level, double slot_bottom,
                         double slot_top)
{
  const LinearContactLaw law(t.wall_contact);
  const double overhang = 0.1 * std::max(t.width, t.height), w = t.width, h = t.height;
  const bool slot = slot_top > slot_bottom;
  // Active side on the left of start -> end (dem/wall.h), counter-clockwise as in RectangularBox.
  TankWalls walls;
  walls.base = system.add_wall(Wall("base", Vec2(-overhang, 0.0), Vec2(w + overhang, 0.0), law));
  walls.right = system.add_wall(Wall(slot ? "right below the slot" : "right", Vec2(w, -overhang),
                                     Vec2(w, slot ? slot_bottom : h + overhang), law));
  walls.lid = system.add_wall(Wall("lid", Vec2(w + overhang, lid_level), Vec2(-overhang, lid_level), law));
  walls.left = system.add_wall(Wall("left", Vec2(0.0, h + overhang), Vec2(0.0, -overhang), law));
  system.walls()[walls.base].loaded_length = w;
  system.walls()[walls.lid].loaded_length = w;
  system.walls()[walls.left].loaded_length = h;
  system.walls()[walls.right].loaded_length = slot ? slot_bottom : h;
  // The lid is the growth's gauge (a lift is jammed when its grains press the lid beyond the
  // growth stress), not a wall the sheet meets: a held part of a sheet standing through a lift's
  // level (a wrap-around's return) must not load it. One did: in the particle box of
  // examples/pullout_hybrid_wraparound_h040_b025.prm as it then was (0.1 m lifts, 3,667 clusters) a held
  // node of the return lay 0.1 mm below the second lift's lid, pressed it with kn (t/2 - 0.1 mm)
  // = 15 kN/m, 13.6 kPa over the box's 1.1 m, and the lift "jammed" at porosity 0.53 against 0.25.
  system.walls()[walls.lid].touches_sheets = false;
  if (slot)
    {
      walls.right_upper = system.add_wall(Wall("right above the slot", Vec2(w, slot_top), Vec2(w, h + overhang), law));
      system.walls()[walls.right_upper].loaded_length = std::max(h - slot_top, 0.0);
      system.walls()[walls.right].touches_sheets = false;
      system.walls()[walls.right_upper].touches_sheets = false;
    }
  return walls;
}
} // namespace geohybrid::dem
