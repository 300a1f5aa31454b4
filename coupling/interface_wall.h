#pragma once
// Method 3, the non-overlapping interface (issue 6): the continuum's boundary edges that face the
// particle region are deformable walls. No band, no energy weights: the particles fill their
// region up to the mesh's boundary and touch it.
//
// Each step, for every disc near the interface (candidates from a bin grid, rebuilt when the discs
// and the edges' nodes have together moved more than the skin):
//   - capsule geometry: the closest point P = A + xi (B - A) of the edge [A, B] (current nodes,
//     X + u) to the disc's centre c, xi clamped to [0, 1]; overlap r - |P - c|, normal n from the
//     disc to P (conventions.h: force on the disc, overlap positive in penetration);
//   - the edge's velocity at P, (1 - xi) v_A + xi v_B (the continuum's half-step velocities, as the
//     disc's: both made the drift just done);
//   - the force from the project's LinearContactLaw, the same value type and evaluation as the
//     DEM's walls (dem_system_walls.cc): normal spring, Coulomb-capped incremental tangential spring
//     (Cundall & Strack 1979) with its history kept per (disc, edge) across rebuilds, optional
//     dashpot on the effective mass 1 / (1/m + (1 - xi)^2 / M_A + xi^2 / M_B) (the lumped nodes
//     seen at P: a force f at P accelerates P by sum_I N_I^2 f / M_I);
//   - the disc gets F (and its moment about the body's centre), the edge's nodes -N_I(xi) F with
//     N_A = 1 - xi, N_B = xi: the two sums cancel to round-off (N_A + N_B = 1).
// A disc whose closest point is a node shared by two interface edges is counted once: by the edge
// it projects into ([0, 1) of the parameter), or, at a convex corner where it projects into
// neither, by the edge that starts at that node. (A contact passing from one edge to the next
// loses its tangential history; its spring energy is booked as friction work, as the law does on
// separation.)
//
// Energy: the contacts' elastic energy 1/2 Fn^2 / kn + 1/2 Ft^2 / ks plus the friction and dashpot
// work accumulated; with the particles' and the continuum's energies it closes the balance.
// Stable step: the squared frequency the interface springs add (Gershgorin, squared_frequency_bound).
// Limits: Q1 cells; small strain at the interface (edges binned once: a node moving more than one
// largest disc radius from its reference position is refused); one MPI rank.
#include "coupling/coupling_forces.h"
#include "coupling/coupling_method.h"
#include "dem/particles.h"
#include "fem/explicit_solver.h"

#include <cstdint>
#include <string_view>
#include <vector>

namespace geohybrid::coupling
{
/// A node of the interface: local indices of its x and y DoFs, reference position, 1 / lumped mass
/// (0 for a node with a prescribed displacement: it is infinitely heavy).
struct InterfaceNode
{
  unsigned int x_dof = 0, y_dof = 0;
  Vec2 reference = Vec2::Zero(); ///< [m]
  double inverse_mass = 0.0;     ///< [m/kg]
};

/// A boundary edge from node `start` to node `end`, oriented so that perp(end - start) points out
/// of the continuum, into the particles (the DEM's wall convention); `previous` is the interface
/// edge ending at `start`, -1 if none.
struct InterfaceEdge
{
  std::uint32_t start = 0, end = 0;
  std::int64_t previous = -1;
  bool end_shared = false; ///< another interface edge starts at `end`
};

/// A coupling tie (coupling_tie.h), the one without a band.
class InterfaceWall
{
public:
  static constexpr std::string_view name = InterfaceCoupling::name;

  /// The edges of boundary `parameters.boundary_id` of `continuum`'s mesh (Q1 only) and the bins
  /// for the discs of `particles`; `skin` [m] is the candidates' margin (the DEM's Verlet skin).
  /// Throws std::invalid_argument for bad parameters, Q2 cells, a boundary id without faces, or
  /// more than one MPI rank.
  InterfaceWall(const InterfaceCoupling &parameters, const dem::ParticleSet &particles,
                const fem::ExplicitSolver &continuum, double skin);

  /// Evaluates the disc-edge contacts at the current positions and adds their forces to the
  /// bodies and (as external forces) to the continuum. `timing.drift_time` is the time over which
  /// the velocities just moved both sides (the tangential springs' increment): the step, or 0 at
  /// the first evaluation. Throws std::runtime_error if an interface node moved farther than the
  /// bins allow (large deformation at the interface).
  void apply(dem::ParticleSet &particles, fem::ExplicitSolver &continuum, const TieTiming &timing,
             CouplingForceSums &sums);

  double elastic_energy() const { return elastic_energy_; }  ///< in the touching contacts now [J/m]
  double dissipated() const { return dissipated_; }          ///< friction and dashpot work so far [J/m]
  double energy() const { return elastic_energy_ + dissipated_; }

  /// A bound on the squared frequency the interface springs add to the coupled system [1/s^2]
  /// (block Gershgorin on M^-1 K of the contacts, per node and per disc; see interface_wall.cc).
  /// The continuum's masses are those the wall read when it was made.
  double squared_frequency_bound(const dem::ParticleSet &particles, const fem::ExplicitSolver &continuum) const;

  const std::vector<InterfaceNode> &nodes() const { return nodes_; }
  const std::vector<InterfaceEdge> &edges() const { return edges_; }
  std::size_t n_touching() const { return n_touching_; }
  std::size_t n_candidates() const { return candidate_disc_.size(); }
  std::size_t n_rebuilds() const { return n_rebuilds_; }
  const dem::LinearContactLaw &law() const { return law_; }

private:
  Vec2 node_position(const fem::ExplicitSolver::Vector &u, std::uint32_t node) const
  {
    const InterfaceNode &n = nodes_[node];
    return n.reference + Vec2(u.local_element(n.x_dof), u.local_element(n.y_dof));
  }
  bool candidates_stale(const dem::ParticleSet &particles, const fem::ExplicitSolver::Vector &u) const;
  void rebuild_candidates(const dem::ParticleSet &particles, const fem::ExplicitSolver::Vector &u);

  dem::LinearContactLaw law_;
  std::vector<InterfaceNode> nodes_;
  std::vector<InterfaceEdge> edges_;
  double skin_ = 0.0;
  double largest_radius_ = 0.0, smallest_radius_ = 0.0;
  double node_allowance_ = 0.0; ///< how far a node may move from its reference position [m]

  // Bins: a uniform grid over the interface's reference box, widened by the reach of a disc
  // (largest radius + skin + node allowance); each bin lists the edges whose widened box meets it
  // (compressed rows, built once).
  Vec2 grid_origin_ = Vec2::Zero();
  double bin_size_ = 0.0;
  unsigned int n_bins_x_ = 0, n_bins_y_ = 0;
  std::vector<std::uint32_t> bin_first_edge_, bin_edges_;

  // Candidates, sorted by (disc, edge), with their contact histories; the previous list is kept
  // to carry the histories over a rebuild. Reserved once; rebuilds reuse the capacity.
  std::vector<std::uint32_t> candidate_disc_, candidate_edge_;
  std::vector<dem::ContactState> candidate_state_;
  std::vector<std::uint32_t> previous_disc_, previous_edge_;
  std::vector<dem::ContactState> previous_state_;
  std::vector<double> disc_x_at_rebuild_, disc_y_at_rebuild_; ///< [m]
  std::vector<Vec2> node_displacement_at_rebuild_;            ///< [m]
  bool rebuild_needed_ = true;
  std::size_t n_rebuilds_ = 0, n_touching_ = 0;

  double elastic_energy_ = 0.0, dissipated_ = 0.0;
};
} // namespace geohybrid::coupling
