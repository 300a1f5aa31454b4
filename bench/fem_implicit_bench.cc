// Wall time of the implicit continuum pull-out (fem/quasi_static_pullout.h) on a tank mesh of
// meshes/, refined globally: the run-out sheet of the INSA tank (L = 1 m, H = 0.4 m, GT230) in
// Mohr-Coulomb sand, pulled to a head displacement. Run by bench/run_fem_implicit_bench; prints
// key=value lines (rank 0) for the script.
//
// Usage: fem_implicit_bench MESH.msh REFINEMENTS FINAL_DISPLACEMENT_M INCREMENT_M
#include "fem/quasi_static_pullout.h"
#include "fem/tank_mesh.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <ctime>
#include <cstdlib>
#include <iostream>
#include <string>

using namespace geohybrid::fem;

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  if (argc != 5)
    {
      if (root)
        std::cerr << "usage: fem_implicit_bench MESH.msh REFINEMENTS FINAL_DISPLACEMENT_M INCREMENT_M\n";
      return 2;
    }
  try
    {
      const auto start = std::chrono::steady_clock::now();
      dealii::parallel::distributed::Triangulation<dim> mesh(MPI_COMM_WORLD);
      read_tank_mesh(mesh, argv[1], {tank_boundary::back_wall, tank_boundary::front_wall, tank_boundary::bottom,
                                     tank_boundary::top},
                     std::stoul(argv[2]));

      QuasiStaticPulloutParameters p;
      // The run-out of the reference paper (section 4.3): L = 1 m, H = 0.4 m, GT230 (J = 2104 kN/m),
      // delta = 25.6 deg; sand 1: phi = 38.4 deg and E = 20 MPa (section 4.2), c = 1 kPa (Table 1),
      // gamma = 15.2 kN/m^3 (Table 1). Assumed: nu = 0.3, psi = 10 deg, K0 = 1 - sin(phi).
      p.pullout.sheet_length = 1.0;
      p.pullout.sheet_depth = 0.4;
      p.pullout.sheet_node_spacing = 0.0125;
      if (const char *spacing = std::getenv("FEM_BENCH_NODE_SPACING"))
        p.pullout.sheet_node_spacing = std::stod(spacing); // about half the cell size: fem/README.md
      p.pullout.soil.kind = SoilModelKind::mohr_coulomb;
      p.pullout.soil.young_modulus = 20e6;
      p.pullout.soil.poisson_ratio = 0.3;
      p.pullout.soil.strength = {38.4, 1e3, 10.0};
      if (const char *kind = std::getenv("FEM_BENCH_SOIL"); kind != nullptr && std::string(kind) == "elastic")
        p.pullout.soil.kind = SoilModelKind::linear_elastic; // to tell the soil's share of the cost
      p.pullout.soil_density = 15.2e3 / 9.81;
      p.pullout.element_degree = 1;
      p.pullout.final_displacement = std::stod(argv[3]);
      p.displacement_increment = std::stod(argv[4]);
      p.pullout.output_interval = p.displacement_increment;
      p.minimum_increment = 1e-3 * p.displacement_increment;
      if (const char *rtol = std::getenv("FEM_BENCH_NEWTON_RTOL"))
        p.newton.relative_tolerance = std::stod(rtol);
      if (const char *n = std::getenv("FEM_BENCH_MAX_NEWTON"))
        p.newton.max_iterations = std::stoul(n);
      // Newton's convergence is checked on the true residual, so the Krylov solves need not go
      // to 1e-10: 1e-6 cut the GMRES iterations by 40 % at the same Newton iterations (4,608
      // cells, 2 mm).
      p.linear_solver.relative_tolerance = 1e-6;
      // The pull-out's default is the sparse direct solver (MUMPS); GMRES + BoomerAMG on request.
      if (const char *method = std::getenv("FEM_BENCH_LINEAR"); method != nullptr && std::string(method) == "krylov")
        p.linear_solver.method = LinearSolverSettings::Method::krylov;
      if (const char *rtol = std::getenv("FEM_BENCH_LINEAR_RTOL"))
        p.linear_solver.relative_tolerance = std::stod(rtol);
      // To measure what the predictor and the line search bring (fem/quasi_static_solver.h).
      if (const char *steps = std::getenv("FEM_BENCH_LINE_SEARCH_STEPS"))
        p.newton.max_line_search_steps = std::stoul(steps);
      if (const char *predictor = std::getenv("FEM_BENCH_PREDICTOR"); predictor != nullptr && std::string(predictor) == "linear")
        p.newton.extrapolate_predictor = false;
      QuasiStaticPullout problem(mesh, p, "implicit pull-out bench");
      const auto set_up = std::chrono::steady_clock::now();
      const std::clock_t cpu_start = std::clock();
      // "As far as it goes": a step that cannot converge ends the run; the curve up to the last
      // converged output point is still reported, with where and why it stopped.
      std::string stopped;
      // One line per curve point as it comes (rank 0), so that a run cut short still tells how
      // far it went and at what cost.
      const auto observe = [&](const PulloutCurvePoint &point) {
        const double cpu = dealii::Utilities::MPI::sum(double(std::clock() - cpu_start) / CLOCKS_PER_SEC, MPI_COMM_WORLD);
        unsigned int n_newton = 0, n_krylov = 0;
        for (const auto &step : problem.report().steps)
          {
            n_newton += step.n_iterations;
            n_krylov += step.n_linear_iterations;
          }
        if (root)
          std::cout << "progress: head " << 1e3 * point.head_displacement << " mm, T " << point.head_tension
                    << " N/m, wall " << std::chrono::duration<double>(std::chrono::steady_clock::now() - set_up).count()
                    << " s, CPU (all ranks) " << cpu << " s, Newton " << n_newton << ", Krylov " << n_krylov
                    << ", cutbacks " << problem.report().n_cutbacks() << std::endl;
      };
      try
        {
          problem.run(observe);
        }
      catch (const ConvergenceFailure &failure)
        {
          stopped = failure.what();
        }
      const PulloutResult &r = problem.result();
      const auto end = std::chrono::steady_clock::now();
      // CPU seconds of the pull summed over the ranks: on a shared machine the wall time measures
      // the sharing as much as the code.
      const double cpu_seconds =
        dealii::Utilities::MPI::sum(double(std::clock() - cpu_start) / CLOCKS_PER_SEC, MPI_COMM_WORLD);

      unsigned int newton = 0, krylov = 0, max_newton = 0, backtracks = 0;
      for (const auto &s : problem.report().steps)
        {
          newton += s.n_iterations;
          krylov += s.n_linear_iterations;
          backtracks += s.n_backtracks;
          max_newton = std::max(max_newton, s.n_iterations);
        }
      if (root)
        {
          std::cout << "ranks=" << dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) << "\n"
                    << "cells=" << mesh.n_global_active_cells() << "\n"
                    << "dofs=" << problem.solver().space().dof_handler().n_dofs() << "\n"
                    << "load_steps=" << r.n_steps << "\n"
                    << "cutbacks=" << problem.report().n_cutbacks() << "\n"
                    << "newton_iterations=" << newton << "\n"
                    << "max_newton_iterations_per_step=" << max_newton << "\n"
                    << "krylov_iterations=" << krylov << "\n"
                    << "line_search_backtracks=" << backtracks << "\n"
                    << "newton_relative_tolerance=" << p.newton.relative_tolerance << "\n"
                    << "linear_relative_tolerance=" << p.linear_solver.relative_tolerance << "\n"
                    << "stopped=" << (stopped.empty() ? "no" : stopped) << "\n"
                    << "setup_wall_s=" << std::chrono::duration<double>(set_up - start).count() << "\n"
                    << "run_wall_s=" << std::chrono::duration<double>(end - set_up).count() << "\n"
                    << "run_cpu_s_all_ranks=" << cpu_seconds << "\n"
                    << "total_wall_s=" << std::chrono::duration<double>(end - start).count() << "\n"
                    << "head_displacement_m=" << r.curve.back().head_displacement << "\n"
                    << "head_tension_end_N_per_m=" << r.curve.back().head_tension << "\n"
                    << "max_head_tension_N_per_m=" << r.max_head_tension << "\n"
                    << "sigma_v_at_sheet_Pa=" << r.vertical_stress_at_sheet << "\n"
                    << "curve_mm_N_per_m=";
          for (const auto &point : r.curve)
            std::cout << " " << 1e3 * point.head_displacement << ":" << point.head_tension;
          std::cout << std::endl;
          std::cout << "newton_per_step=";
          for (const auto &step : problem.report().steps)
            std::cout << " " << step.n_iterations;
          std::cout << std::endl;
          if (std::getenv("FEM_BENCH_VERBOSE"))
            for (const auto &step : problem.report().steps)
              {
                std::cout << "step to " << step.time << " m:";
                for (const double r : step.relative_residuals)
                  std::cout << " " << r;
                std::cout << std::endl;
              }
          for (const auto &cutback : problem.report().cutbacks)
            std::cout << "cutback: " << cutback.from_time << " -> " << cutback.to_time << " m after "
                      << cutback.n_iterations << " iterations: " << cutback.reason << "\n";
        }
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "fem_implicit_bench: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
