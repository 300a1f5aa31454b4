#pragma once
// The truss sheet in the implicit solver: the sheet's nodes carry their own displacement DoFs,
// numbered after the soil's (the last MPI rank owns them, so that PETSc's contiguous ownership
// ranges still hold), and two kinds of small elements couple them:
// - truss segments (fem/truss_sheet.h: tension-only, T = J (l - l0)/l0, tangent zero when slack,
//   but 1e-3 J / l0 along a slack segment in the Newton matrix: slack_segment_stiffness_fraction),
//   between the DoFs of two consecutive nodes;
// - interface elements (fem/sheet_interface_law.h, both faces), between the DoFs of node k and
//   the soil DoFs of the cell that holds it: the relative displacement g = u_k - sum_i N_i(X_k) u_i
//   drives a normal penalty spring and a Coulomb slider per face. The slider is integrated from
//   the last converged step's shear stress with the slip since then, so a Newton iterate never
//   changes the history (as the soil's material points), and its tangent (k_s sticking, 0 sliding)
//   is the consistent one.
// The interface's normal stress sigma_nn is that of the soil's last converged step (the mean over
// the cell of the node, as in the explicit solver, fem/sheet_interface.h): within a load step the
// slider's limit is fixed, which keeps the tangent symmetric (CG for elastic soil). The limit
// therefore lags the soil's stress by one load step.
//
// The element set is the same for every partition: node k's interface is computed by the owner of
// its cell (locate_sheet_in_soil), the truss by the owner of the sheet's DoFs.
#include "fem/material_point_history.h"
#include "fem/sheet_interface.h"
#include "fem/sheet_interface_law.h"

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <string>
#include <vector>

namespace geohybrid::fem
{
class ImplicitSheet
{
public:
  using Force = dealii::Tensor<1, dim>;
  using DofIndex = dealii::types::global_dof_index;

  /// One element's contribution: its DoFs, its tangent and its internal (resisting) force.
  struct LocalElement
  {
    std::vector<DofIndex> dofs;
    dealii::FullMatrix<double> tangent;
    dealii::Vector<double> internal_force;
  };

  /// The fraction of its taut axial stiffness J / l0 that a slack segment keeps in the Newton
  /// matrix (its force stays zero): without it a sliding node between slack segments makes the
  /// matrix singular at an iterate (ImplicitSheet::for_each_element) [-].
  static constexpr double slack_segment_stiffness_fraction = 1e-3;

  /// The sheet's DoFs are first_dof, first_dof + 1, ... (node k, component c at first_dof + 2k + c).
  /// Throws std::invalid_argument naming `where` for a clamp on a missing node or a node outside
  /// the mesh. Collective.
  ImplicitSheet(const DisplacementSpace &space, const TrussSheet &sheet, std::vector<SheetClamp> clamps,
                DofIndex first_dof, const std::string &where);

  const TrussSheet &sheet() const { return sheet_; }
  unsigned int n_dofs() const { return dim * sheet_.n_nodes(); }
  DofIndex dof(std::size_t node, unsigned int component) const { return first_dof_ + dim * node + component; }
  /// True on the rank that owns the sheet's DoFs (the last one).
  bool owns_dofs() const { return owns_dofs_; }

  /// Calls `visit` with the DoFs of every element this rank assembles (for the sparsity pattern).
  void for_each_coupling(const std::function<void(const std::vector<DofIndex> &)> &visit) const;

  /// Calls `add` with every element this rank assembles, for the total displacement
  /// `displacement + increment` (both ghosted, the sheet's DoFs included) and the soil's committed
  /// stresses; keeps the sliders' trial shear stresses for commit().
  void for_each_element(const dealii::PETScWrappers::MPI::Vector &displacement,
                        const dealii::PETScWrappers::MPI::Vector &increment, MaterialPointHistory &material_points,
                        const std::function<void(const LocalElement &)> &add);

  /// Constrains the clamped nodes' DoFs: to the increment d(time) - u (u from `displacement`, the
  /// converged state) if `displacement` is given, else homogeneously.
  void add_clamp_constraints(dealii::AffineConstraints<double> &constraints, double time,
                             const dealii::PETScWrappers::MPI::Vector *displacement) const;

  /// The last assembled trial state becomes the committed one (end of a converged step). Collective.
  void commit();

  /// The nodes' displacements in `displacement` (ghosted) [m].
  std::vector<Force> node_displacements(const dealii::PETScWrappers::MPI::Vector &displacement) const;
  /// Committed shear stress on each face at node k [Pa] (every rank).
  double interface_shear_stress(std::size_t k) const { return shear_stress_[k]; }

private:
  const DisplacementSpace &space_;
  TrussSheet sheet_;
  SheetInterfaceLaw law_;
  std::vector<SheetClamp> clamps_;
  DofIndex first_dof_;
  bool owns_dofs_ = false;
  std::vector<SheetSoilPoint> soil_points_;
  std::vector<double> trial_shear_stress_; ///< of the last assembly, on the node's owner
  std::vector<double> shear_stress_;       ///< committed, on every rank
  std::vector<bool> trial_sliding_, sliding_; ///< of the last assembly / committed, on the node's owner
};
} // namespace geohybrid::fem
