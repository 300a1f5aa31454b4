#pragma once
// Boxes of rigid walls: a rectangle of four walls, as in a biaxial test or a pull-out tank, and a
// convex polygon of walls for REDF samples of other shapes. Each knows which walls are its sides
// and turns their forces into the sample's stresses.
#include "dem/dem_system.h"

#include <vector>

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

/// A convex polygon of rigid walls (a rectangle is one), as a wall-bounded REDF sample needs:
/// one wall per side, each on the line of its side and overhanging the corners, listed
/// counter-clockwise so that each wall's active side (the left of start -> end) faces inward.
/// The corners are where consecutive walls' lines meet, so the polygon follows its walls as they
/// translate (servo-controlled along their normals); the walls never rotate.
struct WallPolygon
{
  std::vector<std::size_t> walls; ///< indices into DemSystem::walls(), counter-clockwise

  /// Adds one wall per side of the polygon of `vertices` (counter-clockwise), each extended by
  /// `overhang` beyond both corners. Throws std::invalid_argument unless the vertices make a
  /// convex polygon (check_convex_polygon).
  static WallPolygon add_to(DemSystem &system, const std::vector<Vec2> &vertices, const LinearContactLaw &law,
                            double overhang);

  /// The corners now: corner k is where wall k-1 meets wall k (the start of side k) [m].
  std::vector<Vec2> vertices(const DemSystem &system) const;
  double area(const DemSystem &system) const;
  /// Sets each wall's loaded length to its side between the corners (see RectangularBox).
  void update_loaded_lengths(DemSystem &system) const;
  /// Mean stress of the enclosed sample from the walls' normal forces N_w:
  ///   p = (1 / 2A) sum_w N_w h_w,
  /// h_w the distance from the centroid to wall w's line: the trace of the boundary form of the
  /// average stress, sigma_ij = (1/A) sum x_i f_j, over the walls (their friction is left out:
  /// REDF walls are frictionless). For a rectangle, the mean of its four wall stresses [Pa].
  double mean_stress(const DemSystem &system) const;
  /// Largest |wall stress / target - 1| over the walls [-].
  double largest_relative_stress_error(const DemSystem &system, double target) const;
  /// Servo-controls every wall along its normal to a compressive stress [Pa].
  void servo_walls(DemSystem &system, double stress, double max_speed) const;
};

/// Throws std::invalid_argument, naming the fault, unless `vertices` are at least three distinct
/// points making a convex polygon listed counter-clockwise (no three consecutive ones aligned).
void check_convex_polygon(const std::vector<Vec2> &vertices);
/// Area of a polygon by the shoelace formula, positive counter-clockwise [m^2].
double polygon_area(const std::vector<Vec2> &vertices);

/// Solid area of all bodies [m^2 per m of thickness].
double total_solid_area(const ParticleSet &particles);
} // namespace geohybrid::dem
