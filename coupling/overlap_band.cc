#include "overlap_band.h"

#include <cmath>
#include <stdexcept>

namespace geohybrid::coupling
{
OverlapBand::OverlapBand(const Vec2 &particle_edge_point, const Vec2 &normal_into_continuum, double width)
  : origin_(particle_edge_point), normal_(normal_into_continuum), width_(width)
{
  if (!(width > 0.0) || !std::isfinite(width))
    throw std::invalid_argument("overlap band: parameter 'band width' = " + std::to_string(width) +
                                " m must be positive and finite");
  const double length = normal_.norm();
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument("overlap band: parameter 'band normal' must be a non-zero, finite vector");
  if (!origin_.allFinite())
    throw std::invalid_argument("overlap band: parameter 'band origin' must be finite");
  normal_ /= length;
}

dem::EnergyWeights OverlapBand::energy_weights(const dem::ParticleSet &particles) const
{
  dem::EnergyWeights weights;
  weights.band_width = width_;
  weights.body_band_coordinate.resize(particles.n_bodies());
  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    weights.body_band_coordinate[b] = coordinate(Vec2(particles.x[b], particles.y[b]));
  return weights;
}
} // namespace geohybrid::coupling
