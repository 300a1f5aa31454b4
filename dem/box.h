#pragma once
// A rectangular box of four rigid walls, as in a biaxial test or a pull-out tank: it knows which
// walls are its sides and turns their forces into the sample's stresses.
#include "dem_system.h"

namespace geohybrid::dem
{
struct RectangularBox
{
  std::size_t left, right, bottom, top; ///< indices into DemSystem::walls()

  /// Adds the four walls of the box [x0, x1] x [y0, y1], each with its active side inward and
  /// overhanging the corners by `overhang` so that no particle escapes when the walls move apart.
  static RectangularBox add_to(DemSystem &system, double x0, double y0, double x1, double y1,
                               const LinearContactLaw &law, double overhang);

  double width(const DemSystem &system) const;
  double height(const DemSystem &system) const;
  double area(const DemSystem &system) const { return width(system) * height(system); }
  /// Sets each wall's loaded length to the current side of the box, so that stresses and servos
  /// use the box and not the overhanging segments. Call after the walls move.
  void update_loaded_lengths(DemSystem &system) const;
  /// Mean compressive stress on the left and right walls, and on the bottom and top walls [Pa].
  double horizontal_stress(const DemSystem &system) const;
  double vertical_stress(const DemSystem &system) const;
  /// Servo-controls the named walls to a compressive stress (the other walls keep their control).
  void servo_sides(DemSystem &system, double horizontal_stress, bool horizontal_walls,
                   double vertical_stress, bool vertical_walls, double max_speed) const;
};

/// Solid area of all bodies [m^2 per m of thickness].
double total_solid_area(const ParticleSet &particles);
} // namespace geohybrid::dem
