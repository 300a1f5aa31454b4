#include "band_particles.h"

#include <stdexcept>

namespace geohybrid::coupling
{
namespace
{
enum class Role
{
  free,
  tied,
  driven
};

Role role_of(const OverlapBand &band, const dem::ParticleSet &particles, std::size_t b, double tie_margin,
             double driven_from)
{
  const double s = band.coordinate(Vec2(particles.x[b], particles.y[b]));
  return s >= driven_from ? Role::driven : s > -tie_margin ? Role::tied : Role::free;
}

std::vector<Vec2> positions(const OverlapBand &band, const dem::ParticleSet &particles, double tie_margin,
                            double driven_from, Role role)
{
  std::vector<Vec2> found;
  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    if (role_of(band, particles, b, tie_margin, driven_from) == role)
      found.emplace_back(particles.x[b], particles.y[b]);
  if (found.empty() && role == Role::tied)
    throw std::invalid_argument("coupling: no particle lies inside the overlap band (check 'band width' and the "
                                "band's position)");
  return found;
}
} // namespace

BandParticles::BandParticles(const OverlapBand &band, const dem::ParticleSet &particles,
                             const fem::DisplacementSpace &space, const BandPoints::Vector &layout,
                             double tie_margin, double driven_below_weight)
  : driven_from(band.driven_from(driven_below_weight))
  , reference_position(positions(band, particles, tie_margin, driven_from, Role::tied))
  , points(space, layout, reference_position, tie_margin)
  , driven_reference_position(positions(band, particles, tie_margin, driven_from, Role::driven))
  , driven_points(space, layout, driven_reference_position, tie_margin)
{
  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    {
      const Role role = role_of(band, particles, b, tie_margin, driven_from);
      if (role == Role::tied)
        body.push_back(static_cast<std::uint32_t>(b));
      else if (role == Role::driven)
        driven_body.push_back(static_cast<std::uint32_t>(b));
    }
}
} // namespace geohybrid::coupling
