#pragma once
// The pull-out test of a geosynthetic sheet in continuum soil, solved with the implicit
// quasi-static solver (fem/quasi_static_solver.h with the sheet of fem/implicit_sheet.h): the
// same tank, soil, sheet and output as the explicit PulloutProblem (fem/pullout_problem.h), so
// that the application can offer both solvers on one input file.
//
// The set-up is that of PulloutProblem: geostatic stress under gravity and the surcharge, fixed
// bottom, smooth walls, the sheet at depth H from the front wall back over L, its node at the
// front wall the clamp. The pull is quasi-static: the pseudo-time is the head displacement [m],
// advanced in load steps of `displacement_increment` (Newton on the consistent tangent, halved on
// non-convergence); each output point is a converged state (no averaging, no inertia, no
// damping), and the head tension is the clamp's reaction. The explicit solver's pull rate, local
// damping, safety factor and sheet mass scaling have no meaning here and are not used.
#include "fem/pullout_problem.h"
#include "fem/quasi_static_solver.h"

#include <memory>
#include <string>

namespace geohybrid::fem
{
struct QuasiStaticPulloutParameters
{
  PulloutProblemParameters pullout;     ///< tank, soil, sheet, final displacement, output interval
  double displacement_increment = 0.5e-3; ///< head displacement per load step, the largest used, > 0 [m]
  double minimum_increment = 1e-6;      ///< a step that fails at this size stops the run, > 0 [m]
  NewtonSettings newton;
  LinearSolverSettings linear_solver;

  /// Throws std::invalid_argument naming `where` and the parameter.
  void validate(const std::string &where) const;
};

class QuasiStaticPullout
{
public:
  /// `mesh` is the tank (boundary ids 1 to 4, fem/tank_mesh.h) and must outlive the problem.
  /// Throws std::invalid_argument naming `where` and the parameter for bad input or a sheet that
  /// does not fit the tank. Collective.
  QuasiStaticPullout(const dealii::parallel::distributed::Triangulation<dim> &mesh,
                     const QuasiStaticPulloutParameters &parameters, const std::string &where = "implicit pull-out");

  /// Pulls the clamp to the final displacement, one curve point per output interval. Throws
  /// ConvergenceFailure (with the last converged head displacement) if a step cannot converge.
  /// Collective; every rank returns the same curve. PulloutResult::time_step and
  /// sheet_mass_scaling are 0 (no time, no inertia); n_steps counts the converged load steps.
  PulloutResult run();

  /// Newton iterations, Krylov iterations and residuals of every load step of run().
  const LoadSteppingReport &report() const { return report_; }
  const QuasiStaticSolver &solver() const { return *solver_; }
  QuasiStaticSolver &solver() { return *solver_; } ///< e.g. for its material points

private:
  QuasiStaticPulloutParameters parameters_;
  double tank_length_ = 0.0, tank_height_ = 0.0, x_front_ = 0.0, y_top_ = 0.0;
  GeostaticStress geostatic_;
  std::unique_ptr<QuasiStaticSolver> solver_;
  std::size_t clamp_node_ = 0;
  LoadSteppingReport report_;
};
} // namespace geohybrid::fem
