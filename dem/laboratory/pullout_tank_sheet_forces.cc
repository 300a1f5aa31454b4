// What the soil does to the sheet of a pull-out tank: the head tension and where it comes from,
// the normal stresses on the lower part (pullout_tank.h).
#include "pullout_tank.h"

#include "dem/measurements.h"

#include <algorithm>

namespace geohybrid::dem
{
SheetLevelStress measure_sheet_level_stress(const DemSystem &system, const PullOutTank &tank,
                                            const PullOutGeometry &geometry, double band)
{
  SheetLevelStress s;
  const SparSheet &sheet = system.sheets().at(0);
  // The segments of the lower part inside the tank now: from the one through the slot (the
  // lower part runs along -x from the clamp) to its end; their length inside the front wall.
  std::size_t first = 0;
  while (first < tank.lower_part_end && std::min(sheet.x[first], sheet.x[first + 1]) >= geometry.tank_length)
    ++first;
  double full_length = 0.0;
  for (std::size_t k = first; k < tank.lower_part_end; ++k)
    {
      const double length = sheet.segment_length(k);
      const double x_in = std::min(sheet.x[k], sheet.x[k + 1]), x_out = std::max(sheet.x[k], sheet.x[k + 1]);
      const double inside = x_out > geometry.tank_length ? (geometry.tank_length - x_in) / (x_out - x_in) : 1.0;
      full_length += length;
      s.lower_part_length += inside * length;
    }
  if (!(s.lower_part_length > 0.0))
    return s;
  // The lower part runs along -x from the clamp: perp(u) points down, so its "left" face is the
  // bottom one (dem/measurements.h). sheet_face_stresses divides by the segments' whole length.
  const SheetFaceStresses faces = sheet_face_stresses(system, 0, first, tank.lower_part_end);
  const double to_inside = full_length / s.lower_part_length;
  s.top_face = faces.normal_right * to_inside;
  s.bottom_face = faces.normal_left * to_inside;
  s.normal_force_both_faces = (faces.normal_left + faces.normal_right) * full_length;
  const Region above{geometry.tank_length - geometry.anchorage_length, tank.sheet_level, geometry.tank_length,
                     tank.sheet_level + band};
  s.love_weber_above = -love_weber_stress(system, above)[1];
  return s;
}

double head_tension(const DemSystem &system) { return system.sheets().at(0).reaction(0).x(); }

HeadTensionParts head_tension_parts(const DemSystem &system)
{
  const SparSheet &sheet = system.sheets().at(0);
  const SheetContacts &c = system.sheet_contacts().at(0);
  const ParticleSet &p = system.particles();
  HeadTensionParts parts;
  parts.reaction = head_tension(system);
  for (std::size_t q = 0; q < c.size(); ++q)
    {
      if (c.force_x[q] == 0.0 && c.force_y[q] == 0.0)
        continue;
      const Vec2 centre(p.disc_x[c.disc[q]], p.disc_y[c.disc[q]]);
      const Vec2 to_sheet = point_on_segment(sheet, c.segment[q], c.position[q]) - centre;
      const double distance = to_sheet.norm();
      const Vec2 on_sheet(-c.force_x[q], -c.force_y[q]);
      // The normal force pushes the sheet away from the disc, along to_sheet.
      const Vec2 n = distance > 0.0 ? Vec2(to_sheet / distance) : Vec2(on_sheet.normalized());
      const double normal = on_sheet.dot(n);
      const Vec2 tangential = on_sheet - normal * n;
      parts.interface_normal -= normal * n.x();
      parts.interface_friction -= tangential.x();
      parts.normal_force += normal;
      parts.elastic_normal_force += c.elastic_normal_force[q];
      parts.tangential_force += tangential.norm();
    }
  for (const SheetWallContacts &w : c.walls)
    for (std::size_t q = 0; q < w.size(); ++q)
      parts.node_wall -= w.force_x[q];
  for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
    if (!sheet.is_kinematic(k))
      {
        // fx is the resultant without local damping (dem/spar_sheet.h): m a = fx + damping_fx.
        parts.inertia += sheet.fx[k] + sheet.damping_fx[k];
        parts.damping -= sheet.damping_fx[k];
      }
  return parts;
}

// Field by field: add() runs at every step of a pull.
void HeadTensionParts::add(const HeadTensionParts &o)
{
  reaction += o.reaction;
  interface_friction += o.interface_friction;
  interface_normal += o.interface_normal;
  node_wall += o.node_wall;
  inertia += o.inertia;
  damping += o.damping;
  normal_force += o.normal_force;
  elastic_normal_force += o.elastic_normal_force;
  tangential_force += o.tangential_force;
}

void HeadTensionParts::scale(double factor)
{
  auto a = as_array();
  for (double &v : a)
    v *= factor;
  *this = from_array(a);
}

std::array<double, HeadTensionParts::n_terms> HeadTensionParts::as_array() const
{
  return {reaction, interface_friction, interface_normal, node_wall, inertia, damping, normal_force,
          elastic_normal_force, tangential_force};
}

HeadTensionParts HeadTensionParts::from_array(const std::array<double, n_terms> &v)
{
  HeadTensionParts p;
  p.reaction = v[0];
  p.interface_friction = v[1];
  p.interface_normal = v[2];
  p.node_wall = v[3];
  p.inertia = v[4];
  p.damping = v[5];
  p.normal_force = v[6];
  p.elastic_normal_force = v[7];
  p.tangential_force = v[8];
  return p;
}
} // namespace geohybrid::dem
