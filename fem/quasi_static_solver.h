#pragma once
// The implicit quasi-static solver of the soil: equilibrium div(sigma) + rho g = 0 under boundary
// data that vary with a pseudo-time t, solved step by step with Newton's method on the consistent
// tangent of the soil model (as in deal.II's step-42, here with non-associated Mohr-Coulomb).
//
// Each load step t_n -> t_{n+1} solves for the displacement increment du: the first iteration
// applies the increment of the prescribed boundary displacements through inhomogeneous
// constraints (a linear predictor that spreads it into the body), the later ones correct with
// homogeneous constraints until the out-of-balance force is small against the forces in play. A
// step that does not converge is retried with half the increment; below a minimum increment the
// run stops with a ConvergenceFailure that says what failed. Linear systems are PETSc MPI matrices
// solved by CG (symmetric tangent) or GMRES (non-associated flow) with BoomerAMG.
//
// A truss sheet with its Mohr-Coulomb interface may be attached (attach_sheet): its nodes become
// DoFs after the soil's, in the same PETSc system (fem/implicit_sheet.h).
//
// The mesh is a parallel::distributed::Triangulation; everything here is collective on its
// communicator. Results do not depend on the number of ranks beyond the solver tolerances.
#include "fem/boundary_conditions.h"
#include "fem/constitutive/soil_model.h"
#include "fem/displacement_space.h"
#include "fem/geostatic_stress.h"
#include "fem/implicit_sheet.h"
#include "fem/rigid_body_amg.h"
#include "fem/material_point_history.h"

#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace geohybrid::fem
{
struct NewtonSettings
{
  /// Converged when |R| <= relative_tolerance * max(|f_int|, |f_ext|) + absolute_tolerance, where
  /// R is the out-of-balance force on the free DoFs and f_int includes the support reactions.
  double relative_tolerance = 1e-8;          ///< [-]
  double absolute_tolerance = 1e-9;          ///< [N/m]
  unsigned int max_iterations = 20;
  /// Start each step from the last converged step's increment, scaled to the new step size, with
  /// the prescribed DoFs at their new values (the steady sliding of a pull-out repeats itself from
  /// step to step), instead of the linear predictor on the tangent at the start of the step, which
  /// is elastic at every point on the yield surface and over-predicts by 10 to 25 % of the forces.
  /// The first step, and a step after one that moved nothing, use the linear predictor.
  bool extrapolate_predictor = true;
  /// Backtracking on |R|: a Newton correction is scaled down (quadratic interpolation, kept in
  /// [0.1, 0.5] of the last factor) until |R| falls by at least 1e-4 of the factor, at most this
  /// many times; the last factor tried is taken. 0: full Newton steps.
  unsigned int max_line_search_steps = 4;
};

/// CG (symmetric tangent) or right-preconditioned GMRES (non-associated flow) with BoomerAMG, or
/// a sparse direct LU factorisation (MUMPS through PETSc, a whole copy per rank: redundant_lu.h).
/// Scalar AMG on vector elasticity coarsens poorly with hypre's defaults; a strong threshold of
/// 0.7 and one level of aggressive coarsening measured 2 to 8 times faster on 2D Q1 and Q2
/// elasticity (66,000 DoFs) than the default 0.25 without.
struct LinearSolverSettings
{
  /// Krylov (CG or GMRES with the preconditioner below) or sparse direct (MUMPS). A 2D tangent
  /// factorises cheaply (nested dissection: fill ~ n log n), and a direct solve does not care how
  /// ill-conditioned the tangent is: a pull-out's interface nodes that slide (no stiffness along
  /// the sheet) and soil points at the Mohr-Coulomb apex (zero tangent) make the Krylov solves
  /// slow or fail while the slip front spreads (bench/RESULTS.md, "Continuum, implicit pull-out").
  enum class Method
  {
    krylov,
    sparse_direct
  };
  Method method = Method::krylov;
  /// Krylov only: BoomerAMG (hypre, scalar) or RigidBodyAMG (PETSc's GAMG with the plane's
  /// rigid-body modes, fem/rigid_body_amg.h).
  enum class Preconditioner
  {
    boomer_amg,
    rigid_body_amg
  };
  Preconditioner preconditioner = Preconditioner::boomer_amg;
  double relative_tolerance = 1e-10; ///< stop when the reported residual fell by this factor [-]
  unsigned int max_iterations = 5000;
  double amg_strong_threshold = 0.7;
  unsigned int amg_aggressive_coarsening_levels = 1;
};

struct LoadSteppingSettings
{
  double increment = 0.1;          ///< pseudo-time increment tried first, and the largest used [-]
  double minimum_increment = 1e-4; ///< a step that fails at this size stops the run [-]
};

struct QuasiStaticSettings
{
  unsigned int element_degree = 2;        ///< 1 (Q1) or 2 (Q2)
  double density = 0.0;                   ///< rho, for the body force rho g [kg/m^3]
  dealii::Tensor<1, dim> gravity = gravity_down(); ///< g [m/s^2]
  NewtonSettings newton;
  LinearSolverSettings linear_solver;
  LoadSteppingSettings stepping;

  static dealii::Tensor<1, dim> gravity_down()
  {
    dealii::Tensor<1, dim> g;
    g[1] = -9.81;
    return g;
  }
  /// Throws std::invalid_argument naming `where` and the parameter.
  void validate(const std::string &where) const;
};

struct StepRecord
{
  double time;                          ///< t at the end of the step
  double increment;                     ///< its pseudo-time increment
  unsigned int n_iterations;            ///< linear solves of its Newton iterations
  unsigned int n_linear_iterations;     ///< Krylov iterations, summed over those solves
  std::vector<double> relative_residuals; ///< |R| / max(|f_int|, |f_ext|), per iteration
  unsigned int n_backtracks = 0;        ///< line-search reductions (extra assemblies) in the step
};

/// A step that did not converge and was retried with half its increment.
struct CutbackRecord
{
  double from_time, to_time;   ///< the step that failed
  unsigned int n_iterations;   ///< Newton iterations spent on it (lost)
  std::string reason;          ///< why it failed
};

struct LoadSteppingReport
{
  std::vector<StepRecord> steps;
  std::vector<CutbackRecord> cutbacks; ///< one per cutback, in order (their iterations are not in steps)
  unsigned int n_cutbacks() const { return static_cast<unsigned int>(cutbacks.size()); }
};

/// The run could not reach the requested time: `what()` names the step, the increment and the
/// reason; `last_converged_time()` is where the solution still holds.
class ConvergenceFailure : public std::runtime_error
{
public:
  ConvergenceFailure(const std::string &message, double last_converged_time)
    : std::runtime_error(message), last_converged_time_(last_converged_time) {}
  double last_converged_time() const { return last_converged_time_; }

private:
  double last_converged_time_;
};

class QuasiStaticSolver
{
public:
  /// The mesh must outlive the solver. Throws std::invalid_argument for bad settings or boundary
  /// conditions that name a boundary id the mesh lacks.
  QuasiStaticSolver(const dealii::parallel::distributed::Triangulation<dim> &mesh, const SoilModel &soil,
                    const BoundaryConditions &boundary_conditions, const QuasiStaticSettings &settings);

  /// Sets the stress at every quadrature point (the displacement stays zero). Throws
  /// std::invalid_argument if it lies outside the yield surface somewhere, naming `description`.
  void set_initial_stress(const std::function<StressTensor(const dealii::Point<dim> &)> &stress,
                          const std::string &description);
  void set_initial_stress(const GeostaticStress &geostatic);

  /// Lays a truss sheet in the soil, tied by its Mohr-Coulomb interface (fem/implicit_sheet.h);
  /// `clamps` prescribe nodes' displacements as functions of the pseudo-time (the clamp of a
  /// pull-out). The sheet's nodes become DoFs of the system after the soil's. Only before the
  /// first step. Throws std::invalid_argument naming the sheet for a node outside the mesh, or
  /// std::logic_error after a step. Collective.
  void attach_sheet(const TrussSheet &sheet, std::vector<SheetClamp> clamps);
  const ImplicitSheet *sheet() const { return sheet_.get(); } ///< nullptr without a sheet
  /// The sheet's nodal displacements at the last converged step (every rank) [m].
  std::vector<dealii::Tensor<1, dim>> sheet_displacements() const;
  /// f_int - f_ext at sheet node k's DoFs, last converged step: at a clamp, the force the clamp
  /// exerts to hold the node (the head tension of a pull-out) [N/m]. Collective.
  dealii::Tensor<1, dim> sheet_node_reaction(std::size_t node) const;

  /// Advances the pseudo-time from time() to `end_time` in steps of at most the settings'
  /// increment, halving it on non-convergence. Throws ConvergenceFailure below the minimum.
  LoadSteppingReport advance_to(double end_time);

  double time() const { return time_; }
  const DisplacementSpace &space() const { return space_; }
  const dealii::PETScWrappers::MPI::Vector &displacement() const { return displacement_; } ///< ghosted [m]
  MaterialPointHistory &material_points() { return material_points_; }

  /// The force the supports and loads of boundary `boundary_id` exert on the soil, summed over its
  /// DoFs: f_int - f_ext there, at the last converged step [N/m]. Collective.
  dealii::Tensor<1, dim> boundary_reaction(dealii::types::boundary_id boundary_id) const;

  /// VTU piece per rank plus a PVTU record, for ParaView; returns the PVTU file name. Collective.
  std::string write_vtu(const std::string &directory, const std::string &basename, unsigned int step);

private:
  struct NewtonOutcome
  {
    bool converged = false;
    unsigned int n_iterations = 0;
    unsigned int n_linear_iterations = 0;
    std::vector<double> relative_residuals;
    unsigned int n_backtracks = 0;
    std::string failure; ///< why it did not converge
  };
  /// Index sets, constraints without values, sparsity pattern, matrix and vectors, for the soil
  /// and (if attached) the sheet.
  void setup_system();
  /// The hanging-node constraints on the relevant DoFs, sheet included.
  dealii::AffineConstraints<double> base_constraints() const;
  NewtonOutcome solve_step(double new_time);
  dealii::AffineConstraints<double> step_constraints(double new_time) const;
  void assemble(double time, const dealii::AffineConstraints<double> &constraints);
  /// Solves for the Newton correction; returns the number of Krylov iterations, or throws
  /// LinearSolverFailure.
  unsigned int solve_linear_system(const dealii::AffineConstraints<double> &constraints);

  SoilModel soil_;
  BoundaryConditions boundary_conditions_;
  QuasiStaticSettings settings_;
  DisplacementSpace space_;
  MaterialPointHistory material_points_;
  std::unique_ptr<ImplicitSheet> sheet_;
  /// The near null space of RigidBodyAMG, on the soil's and the sheet's DoFs (set up with the system).
  std::array<dealii::PETScWrappers::MPI::Vector, 3> rigid_body_modes_;
  dealii::IndexSet owned_dofs_, relevant_dofs_; ///< the soil's, plus the sheet's
  dealii::AffineConstraints<double> homogeneous_constraints_;
  dealii::IndexSet x_component_dofs_;

  dealii::PETScWrappers::MPI::SparseMatrix tangent_;
  dealii::PETScWrappers::MPI::Vector newton_rhs_;     ///< R with the step's constraints applied
  dealii::PETScWrappers::MPI::Vector residual_;       ///< R on the free DoFs only
  dealii::PETScWrappers::MPI::Vector internal_force_; ///< f_int on all DoFs
  dealii::PETScWrappers::MPI::Vector external_force_; ///< f_ext on all DoFs
  dealii::PETScWrappers::MPI::Vector correction_;
  dealii::PETScWrappers::MPI::Vector increment_;          ///< du of the current step (owned)
  dealii::PETScWrappers::MPI::Vector last_increment_;     ///< du of the last converged step (owned)
  dealii::PETScWrappers::MPI::Vector line_search_base_;   ///< du before the current correction
  double last_step_ = 0.0; ///< the pseudo-time increment of last_increment_; 0 before any step
  dealii::PETScWrappers::MPI::Vector increment_relevant_; ///< the same, with ghosts
  dealii::PETScWrappers::MPI::Vector displacement_owned_;
  dealii::PETScWrappers::MPI::Vector displacement_;       ///< u at time_, with ghosts
  double time_ = 0.0;
};
} // namespace geohybrid::fem
