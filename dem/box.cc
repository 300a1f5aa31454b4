#include "box.h"

namespace geohybrid::dem
{
RectangularBox RectangularBox::add_to(DemSystem &system, double x0, double y0, double x1, double y1,
                                      const LinearContactLaw &law, double overhang)
{
  // Active side on the left of start -> end (wall.h): walk the box clockwise.
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

double total_solid_area(const ParticleSet &particles)
{
  double area = 0.0;
  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    area += particles.body_area(b);
  return area;
}
} // namespace geohybrid::dem
