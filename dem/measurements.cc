#include "measurements.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geohybrid::dem
{
std::array<double, 3> love_weber_stress(const DemSystem &system, const Region &region)
{
  const ParticleSet &p = system.particles();
  const PairContacts &c = system.pair_contacts();
  double s_xx = 0.0, s_yy = 0.0, s_xy = 0.0, s_yx = 0.0;
  // Contribution of one contact force f (on the body) applied at lever r from its centre.
  const auto add = [&](double fx, double fy, double rx, double ry) {
    s_xx += fx * rx;
    s_yy += fy * ry;
    s_xy += fx * ry;
    s_yx += fy * rx;
  };
  for (std::size_t q = 0; q < c.size(); ++q)
    {
      if (!c.state[q].touching)
        continue;
      const std::uint32_t i = c.disc_i[q], j = c.disc_j[q];
      const std::uint32_t bi = p.disc_body[i], bj = p.disc_body[j];
      const double dx = p.disc_x[j] - p.disc_x[i], dy = p.disc_y[j] - p.disc_y[i];
      const double distance = std::hypot(dx, dy);
      const double overlap = p.disc_radius[i] + p.disc_radius[j] - distance;
      const double a = (p.disc_radius[i] - 0.5 * overlap) / distance;
      const double cx = p.disc_x[i] + a * dx, cy = p.disc_y[i] + a * dy;
      if (region.contains(p.x[bi], p.y[bi]))
        add(c.force_x[q], c.force_y[q], cx - p.x[bi], cy - p.y[bi]);
      if (region.contains(p.x[bj], p.y[bj]))
        add(-c.force_x[q], -c.force_y[q], cx - p.x[bj], cy - p.y[bj]);
    }
  for (std::size_t w = 0; w < system.walls().size(); ++w)
    {
      const WallContacts &wc = system.wall_contacts()[w];
      const Wall &wall = system.walls()[w];
      for (std::size_t q = 0; q < wc.disc.size(); ++q)
        {
          if (!wc.state[q].touching)
            continue;
          const std::uint32_t d = wc.disc[q], b = p.disc_body[d];
          if (!region.contains(p.x[b], p.y[b]))
            continue;
          Vec2 closest;
          closest_point_on_segment(Vec2(p.disc_x[d], p.disc_y[d]), wall.start, wall.end, closest);
          add(wc.force_x[q], wc.force_y[q], closest.x() - p.x[b], closest.y() - p.y[b]);
        }
    }
  // Sheets act on the bodies as walls do, at the contact's point on the sheet's centre line.
  for (std::size_t s = 0; s < system.sheets().size(); ++s)
    {
      const SheetContacts &sc = system.sheet_contacts()[s];
      for (std::size_t q = 0; q < sc.size(); ++q)
        {
          if (!sc.state[q].touching)
            continue;
          const std::uint32_t b = p.disc_body[sc.disc[q]];
          if (!region.contains(p.x[b], p.y[b]))
            continue;
          const Vec2 point = point_on_segment(system.sheets()[s], sc.segment[q], sc.position[q]);
          add(sc.force_x[q], sc.force_y[q], point.x() - p.x[b], point.y() - p.y[b]);
        }
    }
  // The force on a body at lever r pushes inward in compression: sum f (x) r is negative there,
  // which is the continuum sign (compression negative).
  const double A = region.area();
  return {s_xx / A, s_yy / A, 0.5 * (s_xy + s_yx) / A};
}

SheetFaceStresses sheet_face_stresses(const DemSystem &system, std::size_t s, std::size_t first, std::size_t last)
{
  if (s >= system.sheets().size())
    throw std::out_of_range("sheet_face_stresses: there is no sheet " + std::to_string(s));
  const SparSheet &sheet = system.sheets()[s];
  const SheetContacts &c = system.sheet_contacts()[s];
  const ParticleSet &p = system.particles();
  last = std::min(last, sheet.n_segments());
  SheetFaceStresses out;
  double length = 0.0;
  for (std::size_t k = first; k < last; ++k)
    length += sheet.segment_length(k);
  if (!(length > 0.0))
    return out;
  for (std::size_t q = 0; q < c.size(); ++q)
    {
      const std::size_t k = c.segment[q];
      if (!c.state[q].touching || k < first || k >= last)
        continue;
      const Vec2 a = sheet.node(k), u = (sheet.node(k + 1) - a).normalized();
      const Vec2 on_sheet(-c.force_x[q], -c.force_y[q]);
      const bool left = cross(u, Vec2(p.disc_x[c.disc[q]], p.disc_y[c.disc[q]]) - a) > 0.0;
      // The normal force pushes the sheet away from the disc: toward -perp(u) from the left.
      const double normal = left ? -on_sheet.dot(perp(u)) : on_sheet.dot(perp(u));
      (left ? out.normal_left : out.normal_right) += normal / length;
      (left ? out.shear_left : out.shear_right) += on_sheet.dot(u) / length;
    }
  return out;
}

double porosity(const DemSystem &system, const Region &region)
{
  const ParticleSet &p = system.particles();
  double solid = 0.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (region.contains(p.x[b], p.y[b]))
      solid += p.body_area(b);
  return 1.0 - solid / region.area();
}

double coordination_number(const DemSystem &system)
{
  const std::size_t nb = system.particles().n_bodies();
  if (nb == 0)
    return 0.0;
  return (2.0 * static_cast<double>(system.n_touching_pairs()) + static_cast<double>(system.n_touching_wall_contacts()) +
          static_cast<double>(system.n_touching_sheet_contacts())) /
         static_cast<double>(nb);
}

double unbalanced_force_ratio(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  const PairContacts &c = system.pair_contacts();
  double resultant = 0.0, contact = 0.0;
  std::size_t n_bodies = 0, n_contacts = 0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (p.inverse_mass[b] > 0.0)
      {
        resultant += std::hypot(p.fx[b], p.fy[b]);
        ++n_bodies;
      }
  for (std::size_t q = 0; q < c.size(); ++q)
    if (c.state[q].touching)
      {
        contact += std::hypot(c.force_x[q], c.force_y[q]);
        ++n_contacts;
      }
  for (const WallContacts &wc : system.wall_contacts())
    for (std::size_t q = 0; q < wc.disc.size(); ++q)
      if (wc.state[q].touching)
        {
          contact += std::hypot(wc.force_x[q], wc.force_y[q]);
          ++n_contacts;
        }
  for (const SheetContacts &sc : system.sheet_contacts())
    for (std::size_t q = 0; q < sc.size(); ++q)
      if (sc.state[q].touching)
        {
          contact += std::hypot(sc.force_x[q], sc.force_y[q]);
          ++n_contacts;
        }
  if (n_bodies == 0 || n_contacts == 0 || contact == 0.0)
    return n_bodies == 0 ? 0.0 : 1.0;
  return (resultant / n_bodies) / (contact / n_contacts);
}

double energy_balance_error(const EnergyBudget &start, const EnergyBudget &now)
{
  double scale = 0.0;
  for (const EnergyBudget *e : {&start, &now})
    scale = std::max({scale, std::abs(e->kinetic), std::abs(e->gravitational), std::abs(e->elastic),
                      std::abs(e->friction_dissipated), std::abs(e->viscous_dissipated),
                      std::abs(e->local_damping_dissipated), std::abs(e->boundary_work), std::abs(e->sheet_kinetic),
                      std::abs(e->sheet_elastic), std::abs(e->interface_friction_dissipated)});
  const double change = now.total() - start.total();
  return scale > 0.0 ? change / scale : change;
}
} // namespace geohybrid::dem
