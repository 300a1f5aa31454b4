#include "snapshot_contents.h"

namespace geohybrid::dem::snapshot_detail
{
namespace
{
double value_or_zero(const SoaVector<double> &v, std::size_t q) { return q < v.size() ? v[q] : 0.0; }
} // namespace

ContactLines pair_lines(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  const PairContacts &c = system.pair_contacts();
  ContactLines lines;
  for (std::size_t q = 0; q < c.size(); ++q)
    {
      const ContactState &s = c.state[q];
      if (!s.touching)
        continue;
      const std::uint32_t i = c.disc_i[q], j = c.disc_j[q];
      lines.add(Vec2(p.disc_x[i], p.disc_y[i]), Vec2(p.disc_x[j], p.disc_y[j]),
                value_or_zero(c.elastic_normal_force, q), s.tangential_force, value_or_zero(c.force_x, q),
                value_or_zero(c.force_y, q), s.bonded);
    }
  return lines;
}

ContactLines wall_lines(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  ContactLines lines;
  const auto &all = system.wall_contacts();
  for (std::size_t w = 0; w < all.size() && w < system.walls().size(); ++w)
    {
      const Wall &wall = system.walls()[w];
      const WallContacts &c = all[w];
      for (std::size_t q = 0; q < c.disc.size(); ++q)
        {
          const ContactState &s = c.state[q];
          if (!s.touching)
            continue;
          const std::uint32_t d = c.disc[q];
          const Vec2 centre(p.disc_x[d], p.disc_y[d]);
          Vec2 closest;
          closest_point_on_segment(centre, wall.start, wall.end, closest);
          lines.add(centre, closest, value_or_zero(c.elastic_normal_force, q), s.tangential_force,
                    value_or_zero(c.force_x, q), value_or_zero(c.force_y, q), s.bonded);
          lines.wall_index.push_back(static_cast<std::int32_t>(w));
        }
    }
  return lines;
}

ContactLines sheet_contact_lines(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  ContactLines lines;
  const auto &all = system.sheet_contacts();
  for (std::size_t s = 0; s < all.size() && s < system.sheets().size(); ++s)
    {
      const SparSheet &sheet = system.sheets()[s];
      const SheetContacts &c = all[s];
      for (std::size_t q = 0; q < c.size(); ++q)
        {
          const ContactState &state = c.state[q];
          if (!state.touching)
            continue;
          const std::uint32_t d = c.disc[q];
          lines.add(Vec2(p.disc_x[d], p.disc_y[d]), point_on_segment(sheet, c.segment[q], value_or_zero(c.position, q)),
                    value_or_zero(c.elastic_normal_force, q), state.tangential_force, value_or_zero(c.force_x, q),
                    value_or_zero(c.force_y, q), state.bonded);
          lines.wall_index.push_back(static_cast<std::int32_t>(s));
        }
    }
  return lines;
}

SheetGeometry sheet_geometry(const DemSystem &system)
{
  SheetGeometry g;
  for (std::size_t s = 0; s < system.sheets().size(); ++s)
    {
      const SparSheet &sheet = system.sheets()[s];
      const auto first = static_cast<std::int64_t>(g.n_nodes());
      for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
        {
          g.position.insert(g.position.end(), {sheet.x[k], sheet.y[k], 0.0});
          g.velocity.insert(g.velocity.end(), {sheet.vx[k], sheet.vy[k], 0.0});
          g.sheet_index.push_back(static_cast<std::int32_t>(s));
        }
      for (std::size_t k = 0; k < sheet.n_segments(); ++k)
        {
          g.connectivity.insert(g.connectivity.end(), {first + static_cast<std::int64_t>(k),
                                                       first + static_cast<std::int64_t>(k) + 1});
          g.tension.push_back(value_or_zero(sheet.tension, k));
          g.strain.push_back(sheet.segment_strain(k));
        }
    }
  return g;
}
} // namespace geohybrid::dem::snapshot_detail
