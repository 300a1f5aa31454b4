#pragma once
// The domain split of a coupled model: a particle (DEM) region and a continuum (FE) region that
// overlap in a straight band of width w, the bridging zone of the bridging domain method (Xiao &
// Belytschko 2004). The band is given by a point on its particle-side edge, the unit normal that
// points across it into the continuum, and its width. With s = n . (x - origin):
//   s <= 0         particles only       continuum weight 0, particle weight 1
//   0 < s < w      the overlap band     continuum weight s / w, particle weight 1 - s / w
//   s >= w         continuum only       continuum weight 1, particle weight 0
// The weights sum to one everywhere, so the two models share each point's energy exactly once.
// The band should be several particle diameters and at least one element wide.
//
// A straight band keeps the coordinate linear along every contact's branch, so the branch weight
// (dem/energy_weights.h) is an exact integral. A polygonal DEM region (a band around an anchorage)
// needs a distance function with corners, and is not written yet.
#include "dem/conventions.h"
#include "dem/energy_weights.h"
#include "dem/particles.h"

#include <string>

namespace geohybrid::coupling
{
using dem::Vec2;

class OverlapBand
{
public:
  /// Throws std::invalid_argument naming 'band width' (not positive and finite) or 'band normal'
  /// (zero or not finite; it is normalised).
  OverlapBand(const Vec2 &particle_edge_point, const Vec2 &normal_into_continuum, double width);

  double width() const { return width_; }
  const Vec2 &normal() const { return normal_; }
  const Vec2 &origin() const { return origin_; }

  /// s = n . (x - origin) [m]: 0 on the particle-side edge, width() on the continuum-side edge.
  double coordinate(const Vec2 &x) const { return normal_.dot(x - origin_); }
  /// w(x), the continuum's share of the energy at x [-].
  double continuum_weight(const Vec2 &x) const { return dem::continuum_share(coordinate(x) / width_); }
  /// 1 - w(x), the particles' share [-].
  double particle_weight(const Vec2 &x) const { return 1.0 - continuum_weight(x); }
  /// The particles' share averaged along the segment from a to b (a contact's branch) [-].
  double branch_particle_weight(const Vec2 &a, const Vec2 &b) const
  {
    return 1.0 - dem::mean_continuum_share(coordinate(a) / width_, coordinate(b) / width_);
  }
  /// Strictly inside the band (both models present, 0 < w < 1).
  bool in_band(const Vec2 &x) const
  {
    const double s = coordinate(x);
    return s > 0.0 && s < width_;
  }

  /// The bodies' band coordinates at their current centres of mass, for DemSystem::set_energy_weights.
  dem::EnergyWeights energy_weights(const dem::ParticleSet &particles) const;

private:
  Vec2 origin_, normal_;
  double width_;
};
} // namespace geohybrid::coupling
