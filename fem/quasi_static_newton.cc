// One load step of the implicit quasi-static solver (quasi_static_solver.h): Newton's iterations
// from the predictor, each with its linear solve (Krylov with AMG, or sparse direct) and a
// backtracking line search on the out-of-balance force.
#include "quasi_static_solver.h"

#include "fem/redundant_lu.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/petsc_precondition.h>
#include <deal.II/lac/petsc_solver.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace geohybrid::fem
{
namespace
{
struct LinearSolverFailure
{
  std::string message;
};
} // namespace

unsigned int QuasiStaticSolver::solve_linear_system(const dealii::AffineConstraints<double> &constraints)
{
  correction_ = 0.0;
  unsigned int n_iterations = 0;
  const double rhs_norm = newton_rhs_.l2_norm();
  if (rhs_norm > 0.0 && settings_.linear_solver.method == LinearSolverSettings::Method::sparse_direct)
    {
      // One LU factorisation of this iteration's tangent and one solve; it reports one iteration.
      // A whole copy per rank (fem/redundant_lu.h): MUMPS distributed over the ranks gives other
      // last bits on every run.
      try
        {
          solve_redundant_lu(tangent_, correction_, newton_rhs_);
        }
      catch (const std::exception &e)
        {
          throw LinearSolverFailure{std::string("the sparse direct solver (MUMPS) failed: ") + e.what()};
        }
      // PETSc answers a zero pivot with a solution of infinities, not an error.
      if (!std::isfinite(correction_.l2_norm()))
        throw LinearSolverFailure{"the sparse direct solver (MUMPS) met a singular tangent (zero pivot): a part of "
                                  "the body or the sheet with no stiffness at this iterate"};
      n_iterations = 1;
    }
  else if (rhs_norm > 0.0)
    {
      const bool symmetric = soil_.has_symmetric_tangent();
      // PETSc's CG measures the preconditioned residual, whose scale is not the force's, so the
      // stop is a reduction of whatever norm the Krylov method reports (GMRES is right
      // preconditioned and reports the true residual).
      const auto &linear = settings_.linear_solver;
      dealii::ReductionControl control(linear.max_iterations, 1e-300, linear.relative_tolerance);
      const bool rigid_body = linear.preconditioner == LinearSolverSettings::Preconditioner::rigid_body_amg;
      std::unique_ptr<dealii::PETScWrappers::PreconditionBase> amg;
      if (rigid_body)
        amg = std::make_unique<RigidBodyAMG>(tangent_, rigid_body_modes_);
      else
        {
          dealii::PETScWrappers::PreconditionBoomerAMG::AdditionalData amg_data;
          amg_data.symmetric_operator = symmetric;
          amg_data.strong_threshold = linear.amg_strong_threshold;
          amg_data.aggressive_coarsening_num_levels = linear.amg_aggressive_coarsening_levels;
          amg = std::make_unique<dealii::PETScWrappers::PreconditionBoomerAMG>(tangent_, amg_data);
        }
      try
        {
          if (symmetric)
            {
              dealii::PETScWrappers::SolverCG cg(control, space_.communicator());
              cg.solve(tangent_, correction_, newton_rhs_, *amg);
            }
          else
            {
              dealii::PETScWrappers::SolverGMRES gmres(control, space_.communicator(),
                                                       dealii::PETScWrappers::SolverGMRES::AdditionalData(200, true));
              gmres.solve(tangent_, correction_, newton_rhs_, *amg);
            }
        }
      catch (const dealii::SolverControl::NoConvergence &e)
        {
          std::ostringstream message;
          message << "the linear solver (" << (symmetric ? "CG" : "GMRES") << " + " << (rigid_body ? "GAMG" : "BoomerAMG")
                  << ") did not converge: residual "
                  << e.last_residual << " after " << e.last_step << " iterations";
          throw LinearSolverFailure{message.str()};
        }
      n_iterations = control.last_step();
    }
  constraints.distribute(correction_);
  return n_iterations;
}

QuasiStaticSolver::NewtonOutcome QuasiStaticSolver::solve_step(double new_time)
{
  NewtonOutcome outcome;
  const dealii::AffineConstraints<double> first_constraints = step_constraints(new_time);
  double largest_prescribed_increment = 0.0;
  for (const auto &line : first_constraints.get_lines())
    largest_prescribed_increment = std::max(largest_prescribed_increment, std::abs(line.inhomogeneity));
  const bool moves_boundary =
    dealii::Utilities::MPI::max(largest_prescribed_increment, space_.communicator()) > 0.0;

  // The predictor: the last step's increment scaled to this one, with the prescribed DoFs set to
  // their values (the constraints' distribute); then every iteration is a homogeneous correction.
  // Without it the first iteration carries the prescribed increment (inhomogeneous constraints).
  const bool extrapolated = settings_.newton.extrapolate_predictor && last_step_ > 0.0;
  increment_ = 0.0;
  if (extrapolated)
    {
      increment_.add((new_time - time_) / last_step_, last_increment_);
      first_constraints.distribute(increment_);
    }
  const double tolerance_factor = settings_.newton.relative_tolerance;
  const auto converged = [&](double residual, double reference) {
    return residual <= tolerance_factor * reference + settings_.newton.absolute_tolerance;
  };
  increment_relevant_ = increment_;
  const auto &first_iteration_constraints = extrapolated ? homogeneous_constraints_ : first_constraints;
  assemble(new_time, first_iteration_constraints);
  for (unsigned int iteration = 0;; ++iteration)
    {
      const auto &constraints = iteration == 0 ? first_iteration_constraints : homogeneous_constraints_;
      const double residual = residual_.l2_norm();
      const double reference = std::max(internal_force_.l2_norm(), external_force_.l2_norm());
      outcome.relative_residuals.push_back(reference > 0.0 ? residual / reference : residual);
      if (!std::isfinite(residual))
        {
          outcome.failure = "the out-of-balance force is not finite after " + std::to_string(iteration) + " iterations";
          return outcome;
        }
      // With prescribed boundary motion and the linear predictor, the first residual is that of
      // the old displacement; after the extrapolated predictor it is that of the new one.
      if ((iteration > 0 || !moves_boundary || extrapolated) && converged(residual, reference))
        {
          outcome.converged = true;
          outcome.n_iterations = iteration;
          return outcome;
        }
      if (iteration == settings_.newton.max_iterations)
        {
          std::ostringstream message;
          message << "Newton's method did not converge in " << iteration << " iterations: out-of-balance force "
                  << residual << " N/m against forces of " << reference << " N/m (relative "
                  << residual / reference << ", tolerance " << settings_.newton.relative_tolerance << ")";
          outcome.failure = message.str();
          return outcome;
        }
      try
        {
          outcome.n_linear_iterations += solve_linear_system(constraints);
        }
      catch (const LinearSolverFailure &failure)
        {
          outcome.failure = failure.message;
          return outcome;
        }

      // The line search: the residual of the linear predictor's iteration 0 (old displacement,
      // new boundary values) is not comparable with the next, so that correction is taken whole.
      line_search_base_ = increment_;
      const bool search = &constraints == &homogeneous_constraints_;
      double factor = 1.0;
      for (unsigned int backtrack = 0;; ++backtrack)
        {
          increment_ = line_search_base_;
          increment_.add(factor, correction_);
          increment_relevant_ = increment_;
          assemble(new_time, homogeneous_constraints_);
          if (!search || backtrack == settings_.newton.max_line_search_steps)
            break;
          const double trial = residual_.l2_norm();
          const double trial_reference = std::max(internal_force_.l2_norm(), external_force_.l2_norm());
          if (std::isfinite(trial) && (trial <= (1.0 - 1e-4 * factor) * residual || converged(trial, trial_reference)))
            break;
          // phi(a) = |R(a)|^2 with phi(0) = r^2 and phi'(0) = -2 r^2 (a Newton direction): the
          // minimiser of the parabola through phi(factor), safeguarded.
          const double r2 = residual * residual;
          const double t2 = std::isfinite(trial) ? trial * trial : 1e300;
          const double minimiser = r2 * factor * factor / (t2 - r2 + 2.0 * r2 * factor);
          factor = std::clamp(minimiser, 0.1 * factor, 0.5 * factor);
          ++outcome.n_backtracks;
        }
    }
}
} // namespace geohybrid::fem
