#include "box.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geohybrid::dem
{
RectangularBox RectangularBox::add_to(DemSystem &system, double x0, double y0, double x1, double y1,
                                      const LinearContactLaw &law, double overhang)
{
  // Active side on the left of start -> end (dem/wall.h): walk the box clockwise.
  RectangularBox box;
  box.bottom = system.add_wall(Wall("bottom", Vec2(x0 - overhang, y0), Vec2(x1 + overhang, y0), law));
  box.right = system.add_wall(Wall("right", Vec2(x1, y0 - overhang), Vec2(x1, y1 + overhang), law));
  box.top = system.add_wall(Wall("top", Vec2(x1 + overhang, y1), Vec2(x0 - overhang, y1), law));
  box.left = system.add_wall(Wall("left", Vec2(x0, y1 + overhang), Vec2(x0, y0 - overhang), law));
  box.update_loaded_lengths(system);
  return box;
}

double RectangularBox::width(const DemSystem &system) const
{
  return system.walls()[right].start.x() - system.walls()[left].start.x();
}

double RectangularBox::height(const DemSystem &system) const
{
  return system.walls()[top].start.y() - system.walls()[bottom].start.y();
}

void RectangularBox::update_loaded_lengths(DemSystem &system) const
{
  const double w = width(system), h = height(system);
  system.walls()[bottom].loaded_length = w;
  system.walls()[top].loaded_length = w;
  system.walls()[left].loaded_length = h;
  system.walls()[right].loaded_length = h;
}

double RectangularBox::horizontal_stress(const DemSystem &system) const
{
  return 0.5 * (system.walls()[left].normal_stress() + system.walls()[right].normal_stress());
}

double RectangularBox::vertical_stress(const DemSystem &system) const
{
  return 0.5 * (system.walls()[bottom].normal_stress() + system.walls()[top].normal_stress());
}

void RectangularBox::servo_sides(DemSystem &system, double sigma_h, bool horizontal_walls, double sigma_v,
                                 bool vertical_walls, double max_speed) const
{
  const auto servo = [&](std::size_t w, double target) {
    Wall &wall = system.walls()[w];
    wall.control = WallControl::servo_stress;
    wall.servo.target_stress = target;
    wall.servo.max_speed = max_speed;
  };
  if (horizontal_walls)
    {
      servo(left, sigma_h);
      servo(right, sigma_h);
    }
  if (vertical_walls)
    {
      servo(bottom, sigma_v);
      servo(top, sigma_v);
    }
}

void check_convex_polygon(const std::vector<Vec2> &v)
{
  const std::size_t n = v.size();
  if (n < 3)
    throw std::invalid_argument("wall polygon: " + std::to_string(n) + " vertices; a polygon needs at least three");
  double turning = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    {
      const Vec2 a = v[(k + 1) % n] - v[k], b = v[(k + 2) % n] - v[(k + 1) % n];
      if (!(a.norm() > 0.0) || !std::isfinite(a.norm()))
        throw std::invalid_argument("wall polygon: vertices " + std::to_string(k) + " and " +
                                    std::to_string((k + 1) % n) + " coincide or are not finite");
      const double turn = cross(a, b);
      if (!(turn > 1e-12 * a.norm() * b.norm()))
        throw std::invalid_argument("wall polygon: the turn at vertex " + std::to_string((k + 1) % n) +
                                    (turn < 0.0 ? " is clockwise; give a convex polygon's vertices counter-clockwise"
                                                : " is straight; drop that vertex"));
      turning += std::atan2(turn, a.dot(b));
    }
  // Left turns all the way round once: a star polygon turns round twice or more.
  if (std::abs(turning - 2.0 * pi) > 1e-6)
    throw std::invalid_argument("wall polygon: the sides cross each other; give a convex polygon");
}

double polygon_area(const std::vector<Vec2> &v)
{
  double twice_area = 0.0;
  for (std::size_t k = 0; k < v.size(); ++k)
    twice_area += cross(v[k], v[(k + 1) % v.size()]);
  return 0.5 * twice_area;
}

WallPolygon WallPolygon::add_to(DemSystem &system, const std::vector<Vec2> &vertices, const LinearContactLaw &law,
                                double overhang)
{
  check_convex_polygon(vertices);
  WallPolygon polygon;
  const std::size_t n = vertices.size();
  for (std::size_t k = 0; k < n; ++k)
    {
      const Vec2 a = vertices[k], b = vertices[(k + 1) % n];
      const Vec2 direction = (b - a).normalized();
      polygon.walls.push_back(system.add_wall(
        Wall("side_" + std::to_string(k + 1), a - overhang * direction, b + overhang * direction, law)));
    }
  polygon.update_loaded_lengths(system);
  return polygon;
}

std::vector<Vec2> WallPolygon::vertices(const DemSystem &system) const
{
  const std::size_t n = walls.size();
  std::vector<Vec2> corners(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      // Where the line of wall k-1 (a + t d_a) meets the line of wall k (b + s d_b).
      const Wall &previous = system.walls()[walls[(k + n - 1) % n]], &wall = system.walls()[walls[k]];
      const Vec2 da = previous.end - previous.start, db = wall.end - wall.start;
      const double t = cross(wall.start - previous.start, db) / cross(da, db);
      corners[k] = previous.start + t * da;
    }
  return corners;
}

double WallPolygon::area(const DemSystem &system) const { return polygon_area(vertices(system)); }

void WallPolygon::update_loaded_lengths(DemSystem &system) const
{
  const std::vector<Vec2> corners = vertices(system);
  for (std::size_t k = 0; k < walls.size(); ++k)
    system.walls()[walls[k]].loaded_length = (corners[(k + 1) % walls.size()] - corners[k]).norm();
}

double WallPolygon::mean_stress(const DemSystem &system) const
{
  const std::vector<Vec2> corners = vertices(system);
  // Area centroid of the polygon: the formula is independent of the origin only when the wall
  // forces balance, so take the natural one.
  Vec2 centroid = Vec2::Zero();
  double twice_area = 0.0;
  for (std::size_t k = 0; k < corners.size(); ++k)
    {
      const Vec2 &a = corners[k], &b = corners[(k + 1) % corners.size()];
      const double c = cross(a, b);
      twice_area += c;
      centroid += c * (a + b);
    }
  centroid /= 3.0 * twice_area;
  double sum = 0.0;
  for (const std::size_t w : walls)
    {
      const Wall &wall = system.walls()[w];
      const double normal_force = -wall.force_from_particles.dot(wall.normal());
      sum += normal_force * wall.normal().dot(centroid - wall.start);
    }
  return sum / twice_area;
}

double WallPolygon::largest_relative_stress_error(const DemSystem &system, double target) const
{
  double error = 0.0;
  for (const std::size_t w : walls)
    error = std::max(error, std::abs(system.walls()[w].normal_stress() / target - 1.0));
  return error;
}

void WallPolygon::servo_walls(DemSystem &system, double stress, double max_speed) const
{
  for (const std::size_t w : walls)
    {
      Wall &wall = system.walls()[w];
      wall.control = WallControl::servo_stress;
      wall.servo.target_stress = stress;
      wall.servo.max_speed = max_speed;
    }
}

double total_solid_area(const ParticleSet &particles)
{
  double area = 0.0;
  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    area += particles.body_area(b);
  return area;
}
} // namespace geohybrid::dem
