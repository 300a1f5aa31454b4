#pragma once
// A truss sheet lying in the soil, tied to it by a zero-thickness Mohr-Coulomb interface on each of
// its two faces, for the explicit solver (forces only).
//
// Each sheet node k stands for a length L_k of sheet (truss_sheet.h). It sits at the reference
// point X_k inside a soil cell (found once with GridTools::find_all_active_cells_around_point; the
// soil's shape functions N_i(X_k) are stored), and its relative displacement to the soil there,
// g = u_k - sum_i N_i u_i, is split along the sheet's unit tangent t and normal n:
// - normal: a penalty spring per face, F_n = -2 k_n (g.n) L_k n, ties the sheet to the soil
//   (soil on both faces: no opening);
// - shear: an elastic-perfectly-plastic slider per face with the Mohr-Coulomb limit
//   |tau| <= c_i + max(0, -sigma_nn) tan(delta), sigma_nn = n.sigma.n the soil's normal stress on
//   the sheet's plane (the mean over the quadrature points of the cell holding X_k; tension
//   positive, so -sigma_nn is the confining pressure). tau is updated incrementally from the
//   tangential slip increment and committed every step; F_t = -2 tau L_k t.
// The soil receives -F at X_k through the N_i. At full sliding, a sheet of length L under a
// uniform sigma_v holds T_max = 2 (c_i + sigma_v tan(delta)) L.
//
// The sheet is replicated on every MPI rank (hundreds of nodes): the rank that owns the cell of
// node k (for a node on cell edges, the cell with the smallest CellId) computes its interface force,
// one MPI sum per step shares them, and every rank then integrates the sheet's nodes identically.
#include "fem/displacement_space.h"
#include "fem/material_point_history.h"
#include "fem/truss_sheet.h"

#include <deal.II/lac/la_parallel_vector.h>

#include <functional>
#include <string>
#include <vector>

namespace geohybrid::fem
{
/// Where a sheet node sits in the soil, on the rank that computes its interface: the soil cell,
/// the soil's shape functions there, and the cell's DoFs.
struct SheetSoilPoint
{
  bool owned = false; ///< this rank computes the node's interface
  dealii::DoFHandler<dim>::active_cell_iterator cell;
  std::vector<double> shape_values;                       ///< N_i(X_k) of the cell's DoFs
  std::vector<unsigned int> components;                   ///< the component of each cell DoF
  std::vector<dealii::types::global_dof_index> dof_indices;
};

/// Locates every node of `sheet` in `space`'s mesh. A node on a cell edge or vertex touches
/// several cells, and the soil stress (sigma_nn) is that of one of them: the one with the smallest
/// CellId, whatever the partition, and its owner takes the node, so that results do not depend
/// on the number of ranks. Throws std::invalid_argument naming `where` if a node lies outside the
/// mesh. Collective.
std::vector<SheetSoilPoint> locate_sheet_in_soil(const DisplacementSpace &space, const TrussSheet &sheet,
                                                 const std::string &where);

/// The soil's normal stress n.sigma.n on the sheet's plane at a node: the mean over the committed
/// stresses of the quadrature points of its cell (tension positive) [Pa].
double sheet_normal_stress(MaterialPointHistory &material_points, const SheetSoilPoint &point,
                           const dealii::Tensor<1, dim> &normal);

/// A node of the sheet held at a displacement d(t) (the clamp of a pull-out test).
struct SheetClamp
{
  std::size_t node = 0;
  std::function<dealii::Tensor<1, dim>(double time)> displacement; ///< [m]
};

class EmbeddedSheet
{
public:
  using Vector = dealii::LinearAlgebra::distributed::Vector<double>;
  using Force = dealii::Tensor<1, dim>;

  /// Locates every node in `space`'s mesh. Throws std::invalid_argument naming `where` if a node
  /// lies outside the mesh or the clamp's node does not exist. Collective.
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

  const std::vector<Force> &displacements() const { return displacement_; } ///< [m]
  std::vector<double> axial_forces() const { return sheet_.axial_forces(displacement_); } ///< [N/m]
  /// The force clamp `c` applies to its node to hold it, inertia neglected [N/m].
  Force clamp_force(std::size_t c) const;
  /// The force the interface exerts on the whole sheet (sum over the nodes), last step: at
  /// equilibrium, minus the clamps' forces [N/m].
  Force interface_resultant() const;
  /// Shear stress on each face at node k, last step [Pa].
  double interface_shear_stress(std::size_t k) const { return shear_stress_[k]; }

private:
  const DisplacementSpace &space_;
  TrussSheet sheet_;
  std::vector<SheetClamp> clamps_;
  std::vector<bool> clamped_;
  std::vector<SheetSoilPoint> soil_points_;
  std::vector<Force> displacement_, velocity_, truss_force_, interface_force_;
  std::vector<Force> committed_gap_; ///< relative displacement at the last step (owner only)
  std::vector<double> shear_stress_; ///< tau per face (shared)
};
} // namespace geohybrid::fem
