#pragma once
// The geosynthetic as a chain of tension-only spar elements (Chareyre & Villard 2005, the model
// of the reference paper, section 4.2), written once. A segment of rest length l0 and current
// length l carries
//
//   T = J (l - l0) / l0   when l > l0,   T = 0   when l <= l0 (no compression, no bending),
//
// J the tensile stiffness per metre of width [N/m] (GT230: 2104 kN/m). 2D, per metre of width.
// Three places evaluate it: the DEM's spar sheet (dem/spar_sheet.h), the continuum's truss
// (fem/truss_sheet.h) and the segment joining the two (coupling/sheet_crossing.h). Lengths in;
// tensions, stiffnesses and energies out. It knows no vector type, particle or mesh, so that dem/
// and fem/ can both include it (tests/CMakeLists.txt checks that it includes only the standard
// library).
//
// Two roundings of T. The DEM sheet and the crossing compute J (l - l0) / l0; the continuum's
// truss computes J max(0, l / l0 - 1), from the strain its Newton tangent is written in. They
// differ in the last bits, and results are kept the same bit for bit (a validation campaign's
// committed numbers depend on them), so both stay: tension() and tension_at_strain(). Making them
// one would change numbers (apps/parameters_hash.h: numbers_version).
#include <algorithm>
#include <cstddef>

namespace geohybrid::geosynthetic
{
struct TensionOnlyChain
{
  double axial_stiffness; ///< J per metre of width [N/m]

  /// Whether a segment is stretched: only then does it carry a force (slack or folded, none).
  static bool is_taut(double length, double rest_length) { return length > rest_length; }

  /// T = J (l - l0) / l0 when taut, else 0 [N/m].
  double tension(double length, double rest_length) const
  {
    return is_taut(length, rest_length) ? axial_stiffness * (length - rest_length) / rest_length : 0.0;
  }

  /// The strain l / l0 - 1 (negative when slack) [-].
  static double strain(double length, double rest_length) { return length / rest_length - 1.0; }
  /// T = J max(0, strain): the continuum's rounding of tension() (see the header) [N/m].
  double tension_at_strain(double strain) const { return axial_stiffness * std::max(0.0, strain); }

  /// J / l0: a taut segment as an axial spring [N/m^2].
  double spring_stiffness(double rest_length) const { return axial_stiffness / rest_length; }

  /// The stiffness node k of a chain of n_nodes meets, for its stable step: `other_stiffness` (its
  /// contacts, its interface) plus J / l0 of each segment it ends (one at an end of the chain).
  /// rest_lengths[s] is l0 of segment s, which joins nodes s and s + 1. Summed in that order.
  double node_stiffness(const double *rest_lengths, std::size_t n_nodes, std::size_t k, double other_stiffness) const
  {
    double stiffness = other_stiffness;
    if (k > 0)
      stiffness += spring_stiffness(rest_lengths[k - 1]);
    if (k + 1 < n_nodes)
      stiffness += spring_stiffness(rest_lengths[k]);
    return stiffness;
  }

  /// The energy stored in a segment: 1/2 (J / l0) (l - l0)^2 when taut, else 0 [J/m].
  double elastic_energy(double length, double rest_length) const
  {
    const double stretch = length - rest_length;
    return stretch > 0.0 ? 0.5 * axial_stiffness / rest_length * stretch * stretch : 0.0;
  }
};
} // namespace geohybrid::geosynthetic
