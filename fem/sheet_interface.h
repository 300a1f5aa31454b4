#pragma once
// A truss sheet lying in the soil, tied to it by a zero-thickness Mohr-Coulomb interface on each of
// its two faces, for the explicit solver (forces only).
//
// Each sheet node k stands for a length L_k of sheet (truss_sheet.h). Large slip: the node is
// compared with the soil at a point of the sheet's reference path (sheet_path.h, the polyline of
// the nodes as laid), at arc length s_k, which follows the node: every step s_k moves to the foot
// of the node on the path displaced with the soil (SheetPath::nearest_point, searched from the
// segment it was on), so a node that slides round a corner of a wrap-around meets the soil of the
// part it has reached, along that part's tangent t and normal n. With P(s) the path's point and
// u_s = sum_i N_i(P(s_k)) u_i the soil's displacement there:
// - normal: a penalty spring per face, F_n = -2 k_n g_n L_k n, g_n = ((X_k + u_k - u_s) - P(s_k)).n
//   the node's distance from the displaced path, ties the sheet to the soil (soil on both faces:
//   no opening);
// - shear: an elastic-perfectly-plastic slider per face with the Mohr-Coulomb limit
//   |tau| <= c_i + max(0, -sigma_nn) tan(delta), sigma_nn = n.sigma.n the soil's normal stress on
//   the sheet's plane (the mean over the quadrature points of the cell holding P(s_k); tension
//   positive, so -sigma_nn is the confining pressure). tau is updated incrementally from the slip
//   of the step, ds = s_k,new - s_k (the distance the node moved along the path relative to the
//   soil) and committed every step; F_t = -2 tau L_k t.
// The soil receives -F at P(s_k) through the N_i. At full sliding, a straight sheet of length L
// under a uniform sigma_v holds T_max = 2 (c_i + sigma_v tan(delta)) L. On a straight sheet this is
// the small-slip tie of a node to its reference point, but for the soil's displacement, shape
// functions and cell taken where the node is rather than where it started (a difference of the
// order of the soil's strain times the slip; the run-out tank's plateau moved by -0.8 %).
//
// At a corner (a vertex of the path where its direction turns) the tension turning round the
// node pushes it into the soil on the inside of the bend: the normal penalty carries that force,
// 2 T sin(theta / 2) for a bend of theta, into the soil through the shape functions at P(s_k), and
// the Coulomb limit of the corner node is that of every node, with the sigma_nn of its cell on the
// normal of the segment its soil point is on. No capstan term is added for the node's own normal
// force: the force is already in the soil's stress (the cell's sigma_nn would count it twice), and
// concentrated on the one node at a sharp corner it would make that node's strength a function of
// the sheet's tension and of the node spacing rather than of the soil's stress. What this leaves
// out, the Euler-Eytelwein friction of a sheet bent round a soil edge (T_out / T_in = exp(theta
// tan(delta)) on a rigid edge), is left to the soil's response to the corner force. On the inside
// of a corner a node has a foot on both parts; it moves to the part it is nearer to when it
// crosses the bisector, so its slip jumps by twice its distance from the parts then (in the
// sliding direction: the slider is at its limit there anyway). Corners are best laid rounded over
// a few segments (PulloutProblem does): at a sharp one the segments beside it cut across it, and
// each node beside it, held along its own part's normal only, balances the tension of the
// inclined segment by its component along that part, so the tension rises across the corner (the
// L-shaped sheet of tests/test_fem_sheet.cc held +57 % over its interface limit with a sharp
// 90 degree corner, +9.2 % with the corner rounded over four segments, about half of which is the
// block's fixed walls raising the normal stress near the clamp).
// A node that passes the path's start (the clamp, pulled out through the front wall) keeps the soil
// at the path's start, as the small-slip tie did.
//
// The sheet is replicated on every MPI rank (hundreds of nodes), and so are the s_k: every rank
// follows every node's point from cell to neighbouring cell (sheet_soil_cells.h: no global search
// in a step; the walk crosses artificial cells too, whose geometry every rank has), the rank that
// owns the cell (for a point on cell edges, the cell with the smallest CellId) computes the
// node's interface force and new s_k, and one MPI sum per step shares them; every rank then
// integrates the sheet's nodes identically. The owner of a node changes with its cell, and does
// not depend on the partition.
#include "fem/displacement_space.h"
#include "fem/material_point_history.h"
#include "fem/sheet_path.h"
#include "fem/sheet_soil_cells.h"
#include "fem/truss_sheet.h"

#include <deal.II/lac/la_parallel_vector.h>

#include <functional>
#include <string>
#include <vector>

namespace geohybrid::fem
{
/// The soil point a node of the explicit sheet has slid to: its arc length on the reference path,
/// the cell holding it (on every rank: it may be a ghost or artificial cell here), and, on the
/// rank that computes its interface, the shape functions there, the cell's DoFs and material
/// points (these change only when the cell does).
struct SlidingSoilPoint
{
  double arc_length = 0.0;   ///< s on the reference path (beyond [0, length]: the clamp pulled out) [m]
  unsigned int segment = 0;  ///< of the reference path
  bool owned = false;        ///< this rank computes the node's interface
  dealii::DoFHandler<dim>::cell_iterator cell;
  std::vector<double> shape_values;                          ///< N_i(P(s)) of the cell's DoFs
  std::vector<dealii::types::global_dof_index> dof_indices; ///< of the cell (owner only)
  std::vector<const MaterialPoint *> material_points;        ///< of the cell (owner only)
};

/// A node of the sheet held at a displacement d(t) (the clamp of a pull-out test).
struct SheetClamp
{
  std::size_t node = 0;
  std::function<dealii::Tensor<1, dim>(double time)> displacement; ///< [m]
};

/// The sheet's own energy ledger since its first advance() [J/m], booked as the soil's
/// (ExplicitEnergyLedger): each force on a free node times du = dt_v (v_n-1/2 + v_n+1/2) / 2, which
/// central differences make add up to the change of the nodes' kinetic energy, so the terms close
/// to round-off. A clamped node has no kinetic energy (inertia neglected, as clamp_force()): the
/// forces on it are booked with its prescribed motion and the clamp supplies their sum. The
/// interface's forces on the soil are in the soil's internal work (ExplicitEnergyLedger); the
/// interface's own energy (its springs and its slip) is interface_work plus that share.
struct SheetEnergyLedger
{
  double kinetic = 0.0;          ///< 1/2 m v.v of the free nodes' half-step velocity, now
  double initial_kinetic = 0.0;  ///< the same before the first advance()
  double truss_work = 0.0;       ///< taken by the truss: its strain energy (tension only, elastic)
  double interface_work = 0.0;   ///< taken by the interface from the sheet's nodes
  double damping_work = 0.0;     ///< dissipated by the mass-proportional and the local damping
  double load_work = 0.0;        ///< of the forces added through add_node_load (a coupling's)
  double clamp_work = 0.0;       ///< supplied by the clamps
  /// Zero to round-off: kinetic energy gained + taken + dissipated - supplied.
  double balance() const
  {
    return kinetic - initial_kinetic + truss_work + interface_work + damping_work - load_work - clamp_work;
  }
};

/// What an EmbeddedSheet changes as it runs, as plain numbers: a checkpoint keeps it to continue
/// the run exactly (the sheet, its path and its clamps are rebuilt from the input). Per node,
/// (x, y) pairs for the vectors.
struct EmbeddedSheetState
{
  std::vector<double> displacement, velocity, truss_force, interface_force, node_load; ///< 2 per node
  std::vector<double> shear_stress, normal_stress, arc_length;                       ///< 1 per node
  std::vector<unsigned int> segment;                                                  ///< of each soil point
  SheetEnergyLedger ledger;
  bool advanced = false;
};

class EmbeddedSheet
{
public:
  using Vector = dealii::LinearAlgebra::distributed::Vector<double>;
  using Force = dealii::Tensor<1, dim>;

  /// Locates every node in `space`'s mesh. Throws std::invalid_argument naming `where` if a node
  /// lies outside the mesh or the clamp's node does not exist. Collective (every rank finds the
  /// same cells from the coarse mesh, which each of them has whole).
  EmbeddedSheet(const DisplacementSpace &space, const TrussSheet &sheet, std::vector<SheetClamp> clamps,
                const std::string &where = "sheet");

  const TrussSheet &sheet() const { return sheet_; }

  /// The largest stable step of the sheet's nodes on their own (truss and interface springs,
  /// Gershgorin bound on the node's frequency) [s].
  double stable_time_step() const;

  /// Interface forces from the soil displacement `soil_displacement` (ghosted) and the soil's
  /// committed stresses; adds the soil's share to `soil_internal_force` (ghosted, the caller
  /// compresses), commits the interface state, and computes the truss forces. Collective.
  void compute_forces(const Vector &soil_displacement, MaterialPointHistory &material_points,
                      Vector &soil_internal_force);

  /// Central-difference update of the nodes to `new_time` (the same scheme and damping as the
  /// soil's): `dt` the new half step, `previous_dt` the last one (0 at the start).
  void advance(double dt, double previous_dt, double mass_proportional_damping, double local_damping,
               double new_time);

  /// Adds `force` [N/m] to node k for the next advance() only: a coupling's force, the segment
  /// that joins this sheet to the rest of its chain in another model (coupling/sheet_crossing.h).
  void add_node_load(std::size_t k, const Force &force) { node_load_.at(k) += force; }
  /// Adds `mass` [kg/m] to node k's inertial mass from now on: half of that joining segment's.
  /// Throws std::invalid_argument for a negative or non-finite mass.
  void add_node_mass(std::size_t k, double mass);
  /// Node k's inertial mass: the truss's (TrussSheet::node_mass) and what was added [kg/m].
  double node_mass(std::size_t k) const { return sheet_.node_mass(k) + added_mass_.at(k); }
  /// The node's current position X_k + u_k [m].
  dealii::Point<dim> node_position(std::size_t k) const { return sheet_.node(k) + displacement_.at(k); }

  const std::vector<Force> &displacements() const { return displacement_; } ///< [m]
  std::vector<double> axial_forces() const { return sheet_.axial_forces(displacement_); } ///< [N/m]
  /// The force clamp `c` applies to its node to hold it, inertia neglected [N/m].
  Force clamp_force(std::size_t c) const;
  /// The force the interface exerts on the whole sheet (sum over the nodes), last step: at
  /// equilibrium, minus the clamps' forces [N/m].
  Force interface_resultant() const;
  /// The force the interface exerts on node k (both faces), last step [N/m].
  const Force &interface_force(std::size_t k) const { return interface_force_[k]; }
  /// Shear stress on each face at node k, last step [Pa].
  double interface_shear_stress(std::size_t k) const { return shear_stress_[k]; }
  /// The soil's sigma_nn at node k's soil point (tension positive) that its Coulomb limit used, last step [Pa].
  double interface_normal_stress(std::size_t k) const { return normal_stress_[k]; }
  /// The arc length on the reference path of the soil point node k has slid to [m].
  double soil_point_arc_length(std::size_t k) const { return soil_points_[k].arc_length; }
  /// The energy ledger since the first advance(), its kinetic energy that of now.
  SheetEnergyLedger energy_ledger() const;

  /// The state between two steps (EmbeddedSheetState).
  EmbeddedSheetState export_state() const;
  /// Takes `state` (of a sheet built from the same input): the soil points are moved to the
  /// stored arc lengths (their cells found again). Throws std::invalid_argument if its sizes do
  /// not fit this sheet. Collective.
  void restore_state(const EmbeddedSheetState &state);
  const SheetPath &reference_path() const { return path_; }

private:
  /// Moves node k's soil point to arc length `s` on `segment`: its cell (walked to from the
  /// last one) and, if this rank owns that cell, the shape functions there.
  void move_soil_point(std::size_t k, double s, unsigned int segment);
  /// Makes this rank's record of node k's cell (and its DoFs and points if owned) current.
  void set_soil_cell(SlidingSoilPoint &p, const dealii::DoFHandler<dim>::cell_iterator &cell,
                     const dealii::Point<dim> &unit_point);

  const DisplacementSpace &space_;
  TrussSheet sheet_;
  SheetPath path_;
  std::vector<SheetClamp> clamps_;
  std::vector<bool> clamped_;
  std::vector<SlidingSoilPoint> soil_points_;
  std::vector<unsigned int> components_; ///< of each cell DoF
  std::vector<Force> displacement_, velocity_, truss_force_, interface_force_;
  std::vector<Force> node_load_;   ///< add_node_load, for the next advance only
  std::vector<double> added_mass_; ///< add_node_mass
  std::vector<double> shear_stress_; ///< tau per face (shared)
  std::vector<double> normal_stress_; ///< sigma_nn per node (shared)
  std::vector<double> shared_;       ///< the per-step MPI sum's buffer
  SheetEnergyLedger ledger_;         ///< the booked terms (its kinetic energy is computed when asked)
  bool advanced_ = false;            ///< advance() was called
};
} // namespace geohybrid::fem
