#include "overlap_band.h"

#include <cmath>
#include <stdexcept>

namespace geohybrid::coupling
{
namespace
{
void check_width(double width)
{
  if (!(width > 0.0) || !std::isfinite(width))
    throw std::invalid_argument("overlap band: parameter 'band width' = " + std::to_string(width) +
                                " m must be positive and finite");
}
} // namespace

OverlapBand::OverlapBand(std::vector<Side> sides, double width) : sides_(std::move(sides)), width_(width)
{
  check_width(width);
}

OverlapBand::OverlapBand(const Vec2 &particle_edge_point, const Vec2 &normal_into_continuum, double width)
  : OverlapBand(std::vector<Side>{Side{particle_edge_point, normal_into_continuum}}, width)
{
  Vec2 &normal = sides_[0].outward_normal;
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument("overlap band: parameter 'band normal' must be a non-zero, finite vector");
  if (!particle_edge_point.allFinite())
    throw std::invalid_argument("overlap band: parameter 'band origin' must be finite");
  normal /= length;
}

OverlapBand OverlapBand::around_convex_region(const std::vector<Vec2> &dem_region, double width)
{
  const std::string where = "overlap band: parameter 'DEM region' ";
  const std::size_t n = dem_region.size();
  if (n < 3)
    throw std::invalid_argument(where + "has " + std::to_string(n) + " vertices; a polygon needs at least 3");
  for (const Vec2 &v : dem_region)
    if (!v.allFinite())
      throw std::invalid_argument(where + "has a vertex that is not finite");
  std::vector<Side> sides;
  double turning = 0.0; // the sum of the exterior angles: 2 pi for a convex polygon that winds once
  for (std::size_t i = 0; i < n; ++i)
    {
      const Vec2 &p = dem_region[i];
      const Vec2 edge = dem_region[(i + 1) % n] - p, next = dem_region[(i + 2) % n] - dem_region[(i + 1) % n];
      const double length = edge.norm();
      if (!(length > 0.0) || !std::isfinite(length) || !(next.norm() > 0.0))
        throw std::invalid_argument(where + "has two equal consecutive vertices (a side of zero length) at vertex " +
                                    std::to_string((i + 1) % n));
      // A left turn at every vertex (counter-clockwise and convex); a straight angle is refused too
      // (a degenerate vertex: its two sides would be one).
      const double turn = dem::cross(edge, next);
      if (!(turn > 1e-12 * length * next.norm()))
        throw std::invalid_argument(where + "must be convex, with its vertices counter-clockwise: it turns " +
                                    (turn < 0.0 ? "right" : "straight on") + " at vertex " +
                                    std::to_string((i + 1) % n));
      turning += std::atan2(turn, edge.dot(next));
      sides.push_back(Side{p, Vec2(edge.y(), -edge.x()) / length}); // the outward normal of a CCW side
    }
  if (std::abs(turning - 2.0 * std::acos(-1.0)) > 1e-9)
    throw std::invalid_argument(where + "winds round more than once (a star polygon): it is not convex");
  return OverlapBand(std::move(sides), width);
}

double OverlapBand::branch_particle_weight(const Vec2 &a, const Vec2 &b) const
{
  // s(a + t (b - a)) = max over the sides of s_e(t), each affine in t: a convex piecewise linear
  // function of t. Walk its upper envelope from t = 0 to 1; on each piece s is linear and
  // dem::mean_continuum_share is exact. A straight band is one piece, the same arithmetic as
  // EnergyWeights::contact_weight.
  const std::size_t n = sides_.size();
  const auto at_a = [&](std::size_t e) { return sides_[e].coordinate(a); };
  const auto at_b = [&](std::size_t e) { return sides_[e].coordinate(b); };
  // The side's value at t, exact at the two ends (a + 1 (b - a) need not round to b).
  const auto value = [&](std::size_t e, double t) {
    return t == 0.0 ? at_a(e) : t == 1.0 ? at_b(e) : at_a(e) + t * (at_b(e) - at_a(e));
  };
  const auto slope = [&](std::size_t e) { return at_b(e) - at_a(e); };

  // The largest side at t = 0; of equal ones the steepest (it stays the largest after 0).
  std::size_t current = 0;
  for (std::size_t e = 1; e < n; ++e)
    if (at_a(e) > at_a(current) || (at_a(e) == at_a(current) && slope(e) > slope(current)))
      current = e;
  double start = 0.0, mean = 0.0;
  while (true)
    {
      // The next side to overtake the current one: of the steeper ones, the first to cross it.
      std::size_t next = n;
      double crossing = 1.0;
      for (std::size_t e = 0; e < n; ++e)
        if (slope(e) > slope(current))
          {
            const double t = (at_a(current) - at_a(e)) / (slope(e) - slope(current));
            if (t < crossing || (t == crossing && next < n && slope(e) > slope(next)))
              next = e, crossing = t;
          }
      const double end = next == n ? 1.0 : std::max(start, crossing); // round-off: never backwards
      if (end > start)
        mean += (end - start) * dem::mean_continuum_share(value(current, start) / width_, value(current, end) / width_);
      if (next == n)
        break;
      current = next, start = end; // the slope grows at each switch: at most n pieces
    }
  return 1.0 - mean;
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
double OverlapBand::driven_from(double driven_below_weight) const
{
  if (!(driven_below_weight >= 0.0 && driven_below_weight < 1.0))
    throw std::invalid_argument("overlap band: parameter 'driven below weight' = " +
                                std::to_string(driven_below_weight) + " must lie in [0, 1)");
  return (1.0 - driven_below_weight) * width_;
}
} // namespace geohybrid::coupling
