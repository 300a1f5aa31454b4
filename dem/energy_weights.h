#pragma once
// Energy weights of the particles in a bridging (overlap) band, the DEM side of the bridging
// domain method (Xiao & Belytschko 2004, Comput. Methods Appl. Mech. Engrg. 193:1645-1669).
//
// In the band the total energy is shared: the continuum carries w(x) of it and the particles
// 1 - w(x), with w going linearly from 0 on the band's DEM edge to 1 on its continuum edge. Here the
// band is straight: w depends on one coordinate s across it (s = 0 on the DEM edge, s = width on the
// continuum edge), so w(s) = clamp(s / width, 0, 1) and along a straight segment s varies linearly.
//
// - A body's mass and moment of inertia are scaled by its weight 1 - w(s_b) at its centre.
// - A contact's force (and its energy and dissipation) is scaled by the mean of 1 - w along its
//   branch, the segment between the two bodies' centres. Under a uniform strain the contact forces
//   of a lattice carry the stress along the branches; weighting each branch by the integral of the
//   weight along it is what makes the particles' share of the virtual work the integral of
//   (1 - w) sigma : grad(delta u), which the continuum's share w sigma : grad(delta u) completes
//   (the patch test of the coupled model).
//
// The coordinates are those of the reference configuration and stay fixed: the weights of a body
// and of a contact are then constants, the weighted forces derive from the weighted energy, and an
// undamped run conserves it (small strain in the band, as the bridging domain method assumes).
// coupling/ computes the coordinates (it owns the band's geometry); dem/ only applies them.
#include "soa_vector.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace geohybrid::dem
{
/// The continuum's share of the energy at a band coordinate measured in band widths, clamp(t, 0, 1).
inline double continuum_share(double t) { return std::min(1.0, std::max(0.0, t)); }

/// The exact mean of clamp(t, 0, 1) along the segment from t = a to t = b (band widths), i.e. the
/// integral of the piecewise linear weight along the segment over its length. The segment is cut at
/// the kinks t = 0 and t = 1; on each piece the weight is linear, so its mean is its value at the
/// piece's midpoint (no difference of antiderivatives: no cancellation for short segments).
inline double mean_continuum_share(double a, double b)
{
  const double span = b - a;
  if (span == 0.0)
    return continuum_share(a);
  // Parameters (0..1 along the segment) of the two kinks, sorted and clipped to the segment.
  double k0 = (0.0 - a) / span, k1 = (1.0 - a) / span;
  if (k0 > k1)
    std::swap(k0, k1);
  k0 = std::min(1.0, std::max(0.0, k0));
  k1 = std::min(1.0, std::max(0.0, k1));
  const auto piece = [&](double p0, double p1) { return (p1 - p0) * continuum_share(a + 0.5 * (p0 + p1) * span); };
  return piece(0.0, k0) + piece(k0, k1) + piece(k1, 1.0);
}

/// Per body, its coordinate across the band (reference configuration) and the band's width.
struct EnergyWeights
{
  SoaVector<double> body_band_coordinate; ///< s_b [m]: 0 on the band's DEM edge, `band_width` on its continuum edge
  double band_width = 0.0;                ///< [m], > 0

  /// The particles' share 1 - w at body b's centre.
  double body_weight(std::size_t b) const { return 1.0 - continuum_share(body_band_coordinate[b] / band_width); }
  /// The particles' share averaged along the branch from body i's centre to body j's.
  double contact_weight(std::size_t i, std::size_t j) const
  {
    const double s_i = body_band_coordinate[i], s_j = body_band_coordinate[j];
    // Both ends on the DEM side of the band (most of a hybrid's contacts): the branch lies there
    // too, the mean below is exactly 0; skipping it changes no bit.
    if (s_i <= 0.0 && s_j <= 0.0)
      return 1.0;
    return 1.0 - mean_continuum_share(s_i / band_width, s_j / band_width);
  }
  /// The largest weight a contact of body b can have when its branch is at most `reach` long.
  double largest_contact_weight(std::size_t b, double reach) const
  {
    return 1.0 - continuum_share((body_band_coordinate[b] - reach) / band_width);
  }
};
} // namespace geohybrid::dem
