#pragma once
// The domain split of a coupled model: a particle (DEM) region and a continuum (FE) region that
// overlap in a band of width w, the bridging zone of the bridging domain method (Xiao &
// Belytschko 2004). The DEM core (particles only) is a convex region bounded by straight sides;
// the band runs along its sides, on their continuum side. With s(x) the band coordinate below:
//   s <= 0         particles only       continuum weight 0, particle weight 1
//   0 < s < w      the overlap band     continuum weight s / w, particle weight 1 - s / w
//   s >= w         continuum only       continuum weight 1, particle weight 0
// The weights sum to one everywhere, so the two models share each point's energy exactly once.
// The band should be several particle diameters and at least one element wide.
//
// Two shapes of core:
// - a straight band: the core is one half-plane, given by a point on its edge and the unit normal
//   that points across the band into the continuum; s = n . (x - origin);
// - a convex polygon (a region around an anchorage, issue 6): s(x) = max over its sides e of
//   n_e . (x - p_e), n_e the side's outward unit normal, p_e a point of it. s <= 0 inside the core;
//   outside it s is the distance to the nearest side where that side's normal points at x (away
//   from the corners); past a corner it is the larger of the two sides' distances, so the band's
//   outer edge has a corner too (a square corner, not a rounded one: the weight stays piecewise
//   linear, which the exact branch mean below needs).
//   A side on or outside a tank wall never has particles or continuum on its other side, so it
//   does nothing: a strip spanning the whole tank is a rectangle wider than the tank (its two
//   sides past the walls idle), a core in a corner of the tank a rectangle past both walls.
//
// The branch weight of a contact (the mean of 1 - w along the segment between two bodies' centres)
// is exact here for both shapes: s along a segment is the upper envelope of the sides' affine
// functions, and the clamped weight is integrated exactly on each of its linear pieces.
// The DEM's pair loop (dem/energy_weights.h, EnergyWeights::contact_weight) only has the two
// bodies' coordinates and takes s linear between them (the chord of the envelope). That is exact
// for a straight band, wherever one side's function is the largest at both ends (away from the
// corners), and for a branch with both ends in the core (s <= 0: by convexity s stays below the
// chord, <= 0). Near a corner the chord lies above the convex s, so the DEM's contact weight is
// too small (never too large), by at most
//     |n_1 - n_2| L / (8 w)   (= 2 sin(theta / 2) L / (8 w) <= L / (4 w)),
// n_1, n_2 the normals of the sides that are the largest at the two ends, theta the angle between
// them, L the branch length: the chord minus a convex function with slope jump K = (n_2 - n_1).(b - a)
// averages at most K / 8, and the clamp is 1-Lipschitz in s / w. A right-angled corner:
// sqrt(2) L / (8 w) = 0.177 L / w (measured, tests/test_coupling_region.cc: the bound is reached by
// a branch across the corner's bisector, inside the band). It only concerns branches within about
// a branch length of the band's corner line.
#include "dem/conventions.h"
#include "dem/energy_weights.h"
#include "dem/particles.h"

#include <algorithm>
#include <string>
#include <vector>

namespace geohybrid::coupling
{
using dem::Vec2;

class OverlapBand
{
public:
  /// A straight band: the core is the half-plane n . (x - particle_edge_point) <= 0. Throws
  /// std::invalid_argument naming 'band width' (not positive and finite), 'band normal' (zero or
  /// not finite; it is normalised) or 'band origin' (not finite).
  OverlapBand(const Vec2 &particle_edge_point, const Vec2 &normal_into_continuum, double width);

  /// The band around a convex polygonal DEM core, its vertices counter-clockwise [m]. Throws
  /// std::invalid_argument naming 'DEM region' (fewer than 3 vertices, a vertex not finite, a
  /// side of zero length, clockwise, not strictly convex, or winding more than once) or 'band
  /// width'.
  static OverlapBand around_convex_region(const std::vector<Vec2> &dem_region, double width);

  double width() const { return width_; }

  /// s [m]: <= 0 in the core, 0 on its boundary, width() on the band's continuum-side edge (see the
  /// header's comment).
  double coordinate(const Vec2 &x) const
  {
    double s = sides_[0].coordinate(x);
    for (std::size_t e = 1; e < sides_.size(); ++e)
      s = std::max(s, sides_[e].coordinate(x));
    return s;
  }
  /// w(x), the continuum's share of the energy at x [-].
  double continuum_weight(const Vec2 &x) const { return dem::continuum_share(coordinate(x) / width_); }
  /// 1 - w(x), the particles' share [-].
  double particle_weight(const Vec2 &x) const { return 1.0 - continuum_weight(x); }
  /// The particles' share averaged along the segment from a to b (a contact's branch), exact [-].
  /// For a straight band the same arithmetic as dem::EnergyWeights::contact_weight.
  double branch_particle_weight(const Vec2 &a, const Vec2 &b) const;
  /// The band coordinate from which particles are driven by the continuum (massless, moved with
  /// it, their contact forces passed to its nodes) rather than tied to it: where the particles'
  /// weight 1 - w falls to `driven_below_weight` in [0, 1) (0: the band's continuum edge, only
  /// the particles past the band). Why drive the lightest band particles: a particle's mass is
  /// weighted at its centre but its contacts by the mean along their branches, which reach
  /// deeper into the particles' side, so near the continuum edge a particle of weight epsilon
  /// keeps contacts of weight ~ L / (2 w) and limits the stable step to ~ sqrt(2 w epsilon / L)
  /// of the particles' own (measured: 1.6e-7 s instead of 4e-5 s on a pull-out tank's band).
  /// Driving those below 0.1 bounds it to about a third; the energy they would carry (below a
  /// tenth of their own) goes to the continuum. Throws std::invalid_argument naming 'driven
  /// below weight' outside [0, 1). [m]
  double driven_from(double driven_below_weight) const;
  /// Strictly inside the band (both models present, 0 < w < 1).
  bool in_band(const Vec2 &x) const
  {
    const double s = coordinate(x);
    return s > 0.0 && s < width_;
  }

  /// The bodies' band coordinates at their current centres of mass, for dem::CouplingAttachment::set_energy_weights.
  dem::EnergyWeights energy_weights(const dem::ParticleSet &particles) const;

private:
  /// One side of the core: the half-plane n . (x - point) <= 0.
  struct Side
  {
    Vec2 point, outward_normal;
    double coordinate(const Vec2 &x) const { return outward_normal.dot(x - point); }
  };
  OverlapBand(std::vector<Side> sides, double width);

  std::vector<Side> sides_; ///< at least one
  double width_;
};
} // namespace geohybrid::coupling
