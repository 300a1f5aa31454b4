#pragma once
// The geosynthetic as one chain across the two models (issue 6: "the sheet is one spar chain
// crossing the interface ... each node has exactly one owner"). From the clamp, its first nodes
// are a DEM SparSheet in the particles' core, touched by the grains; the rest of the chain is an
// EmbeddedSheet in the continuum, held by its Mohr-Coulomb interface (fem/sheet_interface.h).
// The segment between the DEM sheet's last node c and the continuum sheet's first node belongs
// to neither model and is carried here, the same tension-only spar as every other segment
// (geosynthetic::TensionOnlyChain, the DEM sheet's J):
//   T = J (l - l0) / l0 for l > l0, 0 when slack,
// pulling both end nodes towards each other. Each end node keeps half of its mass (the DEM node
// keeps the half of the segment it had: SparSheet::keep_first_nodes; the continuum's first node
// gets it added, EmbeddedSheet::add_node_mass), so both become ordinary interior nodes of the
// chain: a node between two segments is softer for its mass than an end node, whose stiffness
// the two models' stable steps already count (provided the crossing segment is not much shorter
// than its neighbours: checked).
//
// Timing (coupled_stepper.h): the continuum steps first, to t_{n+1}; the DEM then drifts its
// nodes to t_{n+1} and, before its sheets' forces and kick, calls this (DemSystem's sheet force
// hook): T is evaluated with both ends at t_{n+1}, added to node c's force, and its opposite to
// the continuum sheet's first node for the continuum's next step, as every coupling force is.
#include "dem/spar_sheet.h"
#include "fem/sheet_interface.h"

namespace geohybrid::coupling
{
class SheetCrossing
{
public:
  /// Joins node `dem_node` (the last) of DEM sheet `dem_sheet_index` to node 0 of
  /// `continuum_sheet` by a segment of rest length `rest_length` [m] and the DEM sheet's J. Adds
  /// half the segment's inertial mass to the continuum sheet's node 0. Throws
  /// std::invalid_argument if the DEM node is not the sheet's last, the rest length is not
  /// positive or is under 0.9 x the shorter neighbouring segment, or the sheets' J differ.
  SheetCrossing(const dem::SparSheet &dem_sheet, std::size_t dem_sheet_index, fem::EmbeddedSheet &continuum_sheet,
                double rest_length);

  /// Evaluates T at the nodes' current positions and adds its forces to DEM node c (fx, fy) and
  /// to the continuum sheet's node 0 (for its next step).
  void apply(dem::SparSheet &dem_sheet, fem::EmbeddedSheet &continuum_sheet);

  std::size_t dem_sheet_index() const { return dem_sheet_index_; }
  std::size_t dem_node() const { return dem_node_; }
  double rest_length() const { return rest_length_; }
  /// T of the last apply() [N/m].
  double tension() const { return tension_; }
  /// 1/2 (J / l0) (l - l0)^2 of the last apply() when taut [J/m].
  double energy() const { return energy_; }

private:
  std::size_t dem_sheet_index_, dem_node_;
  double rest_length_;
  geosynthetic::TensionOnlyChain chain_;
  double tension_ = 0.0, energy_ = 0.0;
};
} // namespace geohybrid::coupling
