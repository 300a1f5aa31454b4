#pragma once
// Smoothed-aggregation algebraic multigrid for the soil's tangent that knows what a displacement
// field is: PETSc's GAMG given the rigid-body modes of the plane (two translations and the
// rotation) as its near null space.
//
// Why: BoomerAMG (the default of QuasiStaticSolver) is scalar AMG. On a vector problem it
// coarsens the x and y displacements as if they were unrelated unknowns, so the coarse levels
// cannot represent a rigid rotation, the slowest-converging error of elasticity, and the Krylov
// iteration counts grow with the mesh (fem/README.md: 246 CG iterations on a 6,402-DoF Q2 mesh,
// 70-100 GMRES iterations per solve on the 9,300-DoF tank). Smoothed aggregation interpolates the
// modes the user gives exactly on every level (Vanek, Mandel & Brezina 1996); with the rigid-body
// modes that is the standard choice for elasticity (PETSc manual, PCGAMG, and
// MatNullSpaceCreateRigidBody).
//
// The modes are built from every DoF's position (the soil's support points, the sheet's nodes) as
// laid, and orthonormalised as PETSc asks. Options from the PETSc options database (-pc_gamg_...)
// still apply, read at set-up.
#include "fem/displacement_space.h"

#include <deal.II/lac/petsc_precondition.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <array>
#include <vector>

namespace geohybrid::fem
{
/// The plane's three rigid-body modes (translation in x, in y, rotation about the centroid) on
/// the DoFs of `space` and, after them, of extra nodes (node k's x and y at n_soil + 2k and
/// n_soil + 2k + 1, as the implicit sheet numbers them; positions `extra_nodes`, every rank
/// passing all of them); orthonormal in the Euclidean inner product, laid out like vectors with
/// `owned_dofs`. Collective.
std::array<dealii::PETScWrappers::MPI::Vector, 3>
rigid_body_modes(const DisplacementSpace &space, const dealii::IndexSet &owned_dofs,
                 const std::vector<dealii::Point<dim>> &extra_nodes = {});

struct RigidBodyAMGSettings
{
  /// Drop connections weaker than this (relative) when aggregating; PETSc's default for GAMG is
  /// 0, which aggregates along every coupling [-].
  double threshold = 0.0;
};

/// PETSc's GAMG (smoothed aggregation, one smoothing step of the prolongator) with `modes` as the
/// near null space of `matrix`, to precondition CG or GMRES like any deal.II PETSc preconditioner.
/// The matrix and the modes must outlive it.
class RigidBodyAMG : public dealii::PETScWrappers::PreconditionBase
{
public:
  RigidBodyAMG(const dealii::PETScWrappers::MPI::SparseMatrix &matrix,
               const std::array<dealii::PETScWrappers::MPI::Vector, 3> &modes,
               const RigidBodyAMGSettings &settings = {});
};
} // namespace geohybrid::fem
