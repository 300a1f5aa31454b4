#pragma once
// The set-up of method 3's benchmarks (the non-overlapping interface, interface_wall.h): a
// hexagonal lattice of bonded equal discs standing on the matching plane-strain continuum below a
// straight interface y = 0, and the interface springs that match the lattice. The tests
// (tests/test_coupling_interface*.cc) and `geohybrid coupling-test` build it here.
#include "apps/coupling_benchmarks/coupled_patch.h"
#include "apps/coupling_benchmarks/coupling_benchmarks.h"
#include "coupling/coupling_method.h"

#include <memory>

namespace geohybrid::coupling::benchmarks
{
/// The boundary id of the continuum's top edge y = 0, the interface (subdivided_hyper_rectangle,
/// colorized: y = max is 3).
constexpr dealii::types::boundary_id standing_lattice_interface_id = 3;

/// A hexagonal lattice of `columns` x `rows` bonded discs (radius, kn, ks, density and overlap of
/// `g`; spacing d) standing on the matching Q1 continuum below y = 0: `cells_down` cells, each one
/// spacing wide and `cell_height` spacings high. The bottom row's centres are at y = r less the
/// overlap with which the interface carries the lattice's prestress (the vertical force
/// sqrt(3) kn delta0 of the two diagonal contacts the bottom row lacks, delta0 = 2 r - d), and its
/// discs sit midway between the interface's nodes (discs at x = i d, nodes at (k - 1/2) d), so
/// that each node carries half of two discs (sum_c N_I = 1). Disc (i, j) has id lattice_id(i, j).
struct StandingLattice
{
  PatchGeometry g; ///< the lattice's parameters (its band entries are not used)
  unsigned int columns = 0, rows = 0, cells_down = 0;
  double cell_height = 1.0; ///< in spacings
  InterfaceCoupling interface;
  std::unique_ptr<PatchMesh> mesh;
  std::unique_ptr<fem::ExplicitSolver> continuum;
  std::unique_ptr<dem::DemSystem> particles;  ///< made by the scenario (held, strained, or at rest)
  std::unique_ptr<CoupledStepper> stepper;    ///< made last: it refers to the others

  double bottom_row() const; ///< y of the bottom row's centres [m]
  /// The lattice's discs; `extra_rows_below` (even: the rows' stagger is kept) extends it down
  /// past the interface (the reference run of the wave), the rows above keeping their ids
  /// shifted by that many rows: disc (i, j) of the coupled lattice is (i, j + extra_rows_below).
  dem::ParticleSet discs(unsigned int extra_rows_below = 0) const;
};

/// The continuum of the standing lattice (no particles yet). Throws std::invalid_argument if
/// `interface` does not name standing_lattice_interface_id (the benchmark's mesh is its own).
StandingLattice standing_lattice(const PatchGeometry &g, unsigned int columns, unsigned int rows,
                                 unsigned int cells_down, const InterfaceCoupling &interface, double cell_height = 1.0);

/// The interface springs that stand for the material between the bottom row's centres and the
/// edge (a gap r carrying a length d of interface): kn = (lambda + 2 mu) d / r (a uniaxial strain
/// eps_yy then gives each disc exactly the traction sigma_yy d), ks = mu d / r, each times its
/// factor (1: "matched"), on the standing lattice's interface; no dashpot, no bond [-, -, deg].
InterfaceCoupling matched_interface(const PatchGeometry &g, double normal_factor = 1.0, double shear_factor = 1.0,
                                    double friction_angle_deg = 30.0);

/// The standing strip of the wave and the energy run (StripSpec's `length`, `pulse_width` and
/// `cell_size`; its band width is not used): 6 columns, enough rows for `length` spacings of
/// lattice, the continuum `length` spacings deep in cells `cell_size` spacings high; the discs
/// bonded and at rest, coupled by `interface`; `time_step` 0 for the coupled stable step [s].
StandingLattice standing_strip(const StripSpec &spec, const InterfaceCoupling &interface, const PatchGeometry &g = {},
                               double time_step = 0.0);
/// Rows of the strip's lattice, and the (even) number of rows the reference lattice adds below
/// the interface in place of the continuum.
unsigned int standing_strip_rows(const StripSpec &spec);
unsigned int standing_strip_rows_below(const StripSpec &spec);
} // namespace geohybrid::coupling::benchmarks
