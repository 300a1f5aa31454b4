#include "pullout_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace geohybrid::dem
{
namespace
{
void check_same_bodies(const ParticleSet &start, const ParticleSet &now)
{
  if (start.n_bodies() != now.n_bodies())
    throw std::invalid_argument("pull-out fields: " + std::to_string(start.n_bodies()) + " bodies at the start, " +
                                std::to_string(now.n_bodies()) + " now");
  for (std::size_t b = 0; b < now.n_bodies(); ++b)
    if (start.body_id[b] != now.body_id[b])
      throw std::invalid_argument("pull-out fields: body " + std::to_string(b) + " is not the same body as at the start");
}
} // namespace

std::vector<GrainDisplacement> grain_displacements(const ParticleSet &start, const ParticleSet &now)
{
  check_same_bodies(start, now);
  std::vector<GrainDisplacement> rows(now.n_bodies());
  for (std::size_t b = 0; b < now.n_bodies(); ++b)
    {
      GrainDisplacement &g = rows[b];
      g.body_id = now.body_id[b];
      g.x0 = start.x[b];
      g.y0 = start.y[b];
      g.x = now.x[b];
      g.y = now.y[b];
      g.dx = now.x[b] - start.x[b];
      g.dy = now.y[b] - start.y[b];
      g.vx = now.vx[b];
      g.vy = now.vy[b];
    }
  return rows;
}

std::vector<SurfacePoint> surface_uplift(const ParticleSet &start, const ParticleSet &now, double width, double strip)
{
  if (!(strip > 0.0 && width > 0.0))
    throw std::invalid_argument("pull-out fields: the surface strips and the tank's width must be positive");
  check_same_bodies(start, now);
  const std::size_t n_strips = static_cast<std::size_t>(std::ceil(width / strip));
  std::vector<std::size_t> highest(n_strips, start.n_bodies());
  std::vector<double> top(n_strips, -std::numeric_limits<double>::infinity());
  for (std::size_t b = 0; b < start.n_bodies(); ++b)
    {
      if (!(start.x[b] >= 0.0 && start.x[b] <= width))
        continue;
      const std::size_t s = std::min(n_strips - 1, static_cast<std::size_t>(start.x[b] / strip));
      double body_top = -std::numeric_limits<double>::infinity();
      for (std::uint32_t d = start.first_disc[b]; d < start.first_disc[b] + start.n_discs[b]; ++d)
        body_top = std::max(body_top, start.disc_y[d] + start.disc_radius[d]);
      if (body_top > top[s])
        {
          top[s] = body_top;
          highest[s] = b;
        }
    }
  std::vector<SurfacePoint> surface;
  for (std::size_t s = 0; s < n_strips; ++s)
    if (highest[s] < start.n_bodies())
      {
        const std::size_t b = highest[s];
        surface.push_back(SurfacePoint{now.body_id[b], start.x[b], top[s], now.y[b] - start.y[b]});
      }
  std::sort(surface.begin(), surface.end(), [](const SurfacePoint &a, const SurfacePoint &b) { return a.x0 < b.x0; });
  return surface;
}

std::vector<ForceChain> contact_force_network(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  const PairContacts &c = system.pair_contacts();
  std::vector<ForceChain> network;
  for (std::size_t q = 0; q < c.size(); ++q)
    if (c.state[q].touching)
      {
        const std::uint32_t i = c.disc_i[q], j = c.disc_j[q];
        network.push_back(ForceChain{p.disc_x[i], p.disc_y[i], p.disc_x[j], p.disc_y[j], c.elastic_normal_force[q]});
      }
  return network;
}
} // namespace geohybrid::dem
