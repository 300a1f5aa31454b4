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

#include <functional>
#include <memory>
#include <string>

namespace geohybrid::fem
{
struct QuasiStaticPulloutParameters
{
  PulloutProblemParameters pullout;     ///< tank, soil, sheet, final displacement, output interval
  double displacement_increment = 0.5e-3; ///< head displacement per load step, the largest used, > 0 [m]
  double minimum_increment = 1e-6;      ///< a step that fails at this size stops the run, > 0 [m]
  /// A relative residual of 1e-6 of the forces (QuasiStaticSolver's measure: max(|f_int|, |f_ext|),
  /// reactions included) changes the head tension by far less than a curve shows; the solver's
  /// default of 1e-8 costs one to two more Newton iterations per step at a plastic front.
  /// While the slip front and the plastic zone spread (the first 2-3 mm of the INSA run-out in
  /// Mohr-Coulomb sand) the line-searched Newton takes 12-21 iterations per 1 mm step, its
  /// residual falling steadily: 40 iterations let those steps finish instead of being halved and
  /// redone (5,760 cells, 6 mm: 3 cutbacks at 20, none at 40; bench/RESULTS.md).
  NewtonSettings newton = pullout_newton_settings();
  LinearSolverSettings linear_solver = pullout_linear_solver_settings();

  static NewtonSettings pullout_newton_settings()
  {
    NewtonSettings settings;
    settings.relative_tolerance = 1e-6;
    settings.max_iterations = 40;
    return settings;
  }
  /// The sparse direct solver: the tank is 2D and small enough to factorise at every iteration,
  /// and a sliding sheet over a yielded soil makes the Krylov solves slow or fail (5,760 cells,
  /// 6 mm: 7.7 s against 59 s with GMRES + BoomerAMG, which failed once after 5,000 iterations).
  static LinearSolverSettings pullout_linear_solver_settings()
  {
    LinearSolverSettings settings;
    settings.method = LinearSolverSettings::Method::sparse_direct;
    return settings;
  }
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

  /// Called at every point of the curve (a converged state) with the point; the solver then holds
  /// that state (sheet_displacements(), sheet()).
  using CurveObserver = std::function<void(const PulloutCurvePoint &)>;

  /// Pulls the clamp to the final displacement, one curve point per output interval. Throws
  /// ConvergenceFailure (with the last converged head displacement) if a step cannot converge.
  /// Collective; every rank returns the same curve (and calls `observer` alike).
  /// PulloutResult::time_step and sheet_mass_scaling are 0 (no time, no inertia); n_steps counts
  /// the converged load steps.
  PulloutResult run(const CurveObserver &observer = {});

  /// Distance of each sheet node from the clamp (node 0) along the sheet, as laid [m].
  const std::vector<double> &arc_lengths() const { return arc_lengths_; }

  /// The curve so far: all of it after run() returns; after a ConvergenceFailure, up to the last
  /// converged output point (the run-out's "as far as it goes").
  const PulloutResult &result() const { return result_; }
  /// Newton iterations, Krylov iterations and residuals of every load step of run() (after a
  /// ConvergenceFailure, without the output interval that failed).
  const LoadSteppingReport &report() const { return report_; }
  const QuasiStaticSolver &solver() const { return *solver_; }
  QuasiStaticSolver &solver() { return *solver_; } ///< e.g. for its material points

private:
  QuasiStaticPulloutParameters parameters_;
  double tank_length_ = 0.0, tank_height_ = 0.0, x_front_ = 0.0, y_top_ = 0.0;
  GeostaticStress geostatic_;
  std::unique_ptr<QuasiStaticSolver> solver_;
  std::size_t clamp_node_ = 0;
  std::vector<double> arc_lengths_;
  double geostatic_limit_ = 0.0;
  unsigned int n_cells_ = 0;
  LoadSteppingReport report_;
  PulloutResult result_;
};
} // namespace geohybrid::fem
