#include "pullout_fem_mode.h"

#include "apps/parameters_hash.h"
#include "interrupt.h"
#include "rank_error.h"
#include "run_health.h"

#include "apps/pullout_output.h"
#include "apps/run_directory.h"

#include "fem/pullout_problem.h"
#include "fem/quasi_static_pullout.h"
#include "fem/tank_mesh.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace geohybrid::apps
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_continuum_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Continuum");
  prm.declare_entry("mesh file", "", Patterns::Anything(),
                    "fem mode only: a gmsh 2.2 .msh of the tank (e.g. meshes/insa_tank_runout.msh: quadrilaterals, "
                    "walls tagged 1 bottom, 2 front, 3 top, 4 back), relative to the working directory; its extent "
                    "must be 'Tank/length' x 'Tank/fill height'. Empty: a generated rectangle of that size with "
                    "cells of 'cell size' [-]");
  prm.declare_entry("cell size", "0.025", Patterns::Double(1e-4, 1.0),
                    "fem mode only (hybrid: 'Hybrid/cell size'), generated mesh: the cells' size; the sheet's lower part (and a wrap-around's "
                    "return and upper part) runs through the middle of a row (column) of cells, so the interface "
                    "reads the soil's stress at the sheet's level [m]");
  prm.declare_entry("sheet node spacing", "0.0125", Patterns::Double(1e-4, 1.0),
                    "fem mode only (dem mode: 'Sheet/segment length'): the truss elements' length at most; keep it "
                    "at about half the cell size: more nodes per cell tie each cell to more penalty springs, and the "
                    "mass-scaled sheet's pull becomes noisy and overshoots (5 nodes per cell: +56 % on a 0.6 m x "
                    "0.4 m tank, 2 per cell: +8 %) [m]");
  prm.declare_entry("solver", "explicit", Patterns::Selection("explicit|implicit"),
                    "fem mode only: 'explicit' (central differences with local damping, the clamp pulled at "
                    "'Pull/rate'; the solver the hybrid runs in lockstep with the DEM) or 'implicit' (quasi-static "
                    "load steps of 'displacement increment', Newton on the consistent tangent with PETSc's "
                    "linear solvers: no rate, no damping, no mass scaling; simple run-out only) [-]");
  prm.declare_entry("displacement increment", "0.5e-3", Patterns::Double(1e-7, 1.0),
                    "fem mode, implicit solver only: the head displacement of a load step, the largest used (halved "
                    "on non-convergence, grown back after); at most 'Pull/record interval' [m]");
  prm.declare_entry("linear solver", "direct", Patterns::Selection("direct|Krylov"),
                    "fem mode, implicit solver only: 'direct' (MUMPS LU through PETSc, each rank factorising the whole matrix, so that runs repeat bit for bit; "
                    "robust while the sheet slides over yielded soil) or 'Krylov' (CG or GMRES with the "
                    "'preconditioner' below; less memory on very large meshes) [-]");
  prm.declare_entry("preconditioner", "BoomerAMG", Patterns::Selection("BoomerAMG|GAMG"),
                    "fem mode, implicit solver with 'linear solver' = Krylov only: hypre's BoomerAMG (scalar) or "
                    "PETSc's GAMG given the rigid-body modes (fem/rigid_body_amg.h) [-]");
  prm.declare_entry("element degree", "1", Patterns::Integer(1, 2),
                    "fem mode only: 1 (Q1, cheaper per step and per stable step) or 2 (Q2) [-]");
  prm.declare_entry("soil model", "Mohr-Coulomb", Patterns::Selection("linear elastic|Mohr-Coulomb|Drucker-Prager"),
                    "fem and hybrid modes: the continuum's constitutive law (Drucker-Prager is matched to Mohr-Coulomb in "
                    "plane strain) [-]");
  prm.declare_entry("Young modulus", "20e6", Patterns::Double(1e3, 1e12),
                    "fem and hybrid modes: E; sand 1: 20 MPa from the triaxial tests at 10-50 kPa (section 4.2) [Pa]");
  prm.declare_entry("Poisson ratio", "0.3", Patterns::Double(0.0, 0.49),
                    "fem and hybrid modes: nu (not measured in the paper: 0.3, a usual value for sand) [-]");
  prm.declare_entry("friction angle", "38.4", Patterns::Double(0.1, 89.9),
                    "fem and hybrid modes: phi of the Mohr-Coulomb and Drucker-Prager soils; sand 1: 38.4 degrees "
                    "(triaxial tests, section 4.2) [deg]");
  prm.declare_entry("cohesion", "0", Patterns::Double(0.0, 1e9), "fem and hybrid modes: c; sand 1: none [Pa]");
  prm.declare_entry("dilatancy angle", "8.4", Patterns::Double(0.0, 89.9),
                    "fem and hybrid modes: psi, at most phi; the paper gives none: 8.4 = phi - 30 degrees is Bolton's "
                    "(1986) estimate for a dense sand, a choice [deg]");
  prm.declare_entry("K0", "0", Patterns::Double(0.0, 10.0),
                    "fem and hybrid modes: sigma_h / sigma_v of the geostatic state; 0 takes 1 - sin(phi) (Jaky) for the "
                    "plastic soils and nu / (1 - nu) for the elastic one [-]");
  prm.declare_entry("local damping", "0.3", Patterns::Double(0.0, 0.99),
                    "fem and hybrid modes: local (Cundall) damping of the continuum (fem: of soil and sheet; 0.3 "
                    "rather than PFC's 0.7 because it drags the sliding sheet, fem/pullout_problem.h; hybrid: of the "
                    "continuum only, the particles and the sheet keep 'Filling/local damping' and 'Pull/sheet local "
                    "damping') [-]");
  prm.declare_entry("safety factor", "0.8", Patterns::Double(0.01, 1.0),
                    "fem mode only: the time step over the soil's critical step [-]");
  prm.declare_entry("interface cohesion", "0", Patterns::Double(0.0, 1e9),
                    "fem mode, and hybrid mode's sheet past the DEM region: c_i of the sheet's interface, tau <= c_i + sigma_n tan(delta) with delta "
                    "'Sheet/Interface/friction angle' (the other Sheet/Interface entries are the DEM's) [Pa]");
  prm.declare_entry("interface normal stiffness", "1e8", Patterns::Double(1.0, 1e14),
                    "fem mode, and hybrid mode's sheet past the DEM region: the penalty tying each face of the sheet to the soil (keep it below about E / "
                    "cell size) [Pa/m]");
  prm.declare_entry("interface shear stiffness", "1e8", Patterns::Double(1.0, 1e14),
                    "fem mode, and hybrid mode's sheet past the DEM region: the interface's elastic slip stiffness per face before sliding [Pa/m]");
  prm.declare_entry("sheet mass scaling", "0", Patterns::Double(0.0, 1e12),
                    "fem mode only: factor on the sheet nodes' inertial mass, at least 1; 0 takes 8 times the "
                    "smallest that keeps them stable at the soil's step [-]");
  prm.declare_entry("snapshot interval", "0", Patterns::Double(0.0, 10.0),
                    "fem mode only: head displacement between VTU snapshots of the soil in OUTPUT/snapshots; "
                    "0 = none [m]");
  prm.leave_subsection();
}

ContinuumSoilInput parse_continuum_soil(ParameterHandler &prm)
{
  ContinuumSoilInput c;
  prm.enter_subsection("Continuum");
  c.soil.kind = fem::soil_model_kind_from_string(prm.get("soil model"));
  c.soil.young_modulus = prm.get_double("Young modulus");
  c.soil.poisson_ratio = prm.get_double("Poisson ratio");
  c.soil.strength.friction_angle_deg = prm.get_double("friction angle");
  c.soil.strength.cohesion = prm.get_double("cohesion");
  c.soil.strength.dilatancy_angle_deg = prm.get_double("dilatancy angle");
  c.k0 = prm.get_double("K0");
  c.local_damping = prm.get_double("local damping");
  prm.leave_subsection();
  return c;
}

namespace
{
struct ContinuumInput
{
  fem::PulloutProblemParameters problem;
  bool implicit_solver = false;
  bool krylov = false;                    ///< implicit solver: Krylov instead of the sparse direct solver
  bool rigid_body_amg = false;            ///< implicit solver, Krylov: GAMG with the rigid-body modes
  double displacement_increment = 0.5e-3; ///< implicit solver: the load step's head displacement [m]
  std::string mesh_file;
  double cell_size = 0.025;
  double snapshot_interval = 0.0;
};

/// The shared sections mapped onto the continuum's problem, and subsection Continuum.
ContinuumInput parse_continuum(ParameterHandler &prm, const PullOutInput &in, const std::string &where)
{
  ContinuumInput c;
  fem::PulloutProblemParameters &p = c.problem;
  const dem::PullOutGeometry &g = in.tank.geometry;
  p.sheet_length = g.anchorage_length;
  p.sheet_depth = g.cover;
  // The wrap-around as the DEM lays it (dem/laboratory/pullout_tank.cc): up D1 from the lower
  // part's end, then B back towards the front wall; H = D1 + D2 is checked with the geometry.
  p.wrap_around = g.anchorage == dem::Anchorage::wrap_around;
  if (p.wrap_around)
    {
      p.return_height = g.return_height;
      p.upper_length = g.upper_length;
    }
  p.soil_density = in.tank.unit_weight / p.gravity;
  p.sheet.axial_stiffness = in.tank.sheet.axial_stiffness;
  p.sheet.areal_mass = in.tank.sheet.areal_mass;
  p.sheet.interface.friction_angle_deg = in.tank.sheet.interface.friction_angle_deg;
  p.pull_rate = in.pull.rate;
  p.final_displacement = in.pull.final_displacement;
  p.output_interval = in.pull.record_interval;
  p.ramp_displacement = in.pull.ramp_displacement;

  prm.enter_subsection("Continuum");
  c.mesh_file = prm.get("mesh file");
  c.cell_size = prm.get_double("cell size");
  c.implicit_solver = prm.get("solver") == "implicit";
  c.krylov = prm.get("linear solver") == "Krylov";
  c.rigid_body_amg = prm.get("preconditioner") == "GAMG";
  c.displacement_increment = prm.get_double("displacement increment");
  p.sheet_node_spacing = prm.get_double("sheet node spacing");
  p.element_degree = static_cast<unsigned int>(prm.get_integer("element degree"));
  p.safety_factor = prm.get_double("safety factor");
  p.sheet.interface.cohesion = prm.get_double("interface cohesion");
  p.sheet.interface.normal_stiffness = prm.get_double("interface normal stiffness");
  p.sheet.interface.shear_stiffness = prm.get_double("interface shear stiffness");
  const double scaling = prm.get_double("sheet mass scaling");
  c.snapshot_interval = prm.get_double("snapshot interval");
  prm.leave_subsection();
  const ContinuumSoilInput soil = parse_continuum_soil(prm);
  p.soil = soil.soil;
  p.k0 = soil.k0;
  p.local_damping = soil.local_damping;
  if (scaling != 0.0 && scaling < 1.0)
    throw std::invalid_argument(where + ": 'Continuum/sheet mass scaling' = " + number(scaling) +
                                " must be 0 (automatic) or at least 1 [-]");
  p.automatic_mass_scaling = scaling == 0.0;
  p.sheet.mass_scaling = std::max(1.0, scaling);
  if (c.implicit_solver && c.displacement_increment > p.output_interval)
    throw std::invalid_argument(where + ": 'Continuum/displacement increment' = " + number(c.displacement_increment) +
                                " m must be at most 'Pull/record interval' = " + number(p.output_interval) +
                                " m (every point of the curve is a converged load step)");
  return c;
}

/// The tank's mesh: read and checked against the Tank's size, or generated.
void make_mesh(dealii::parallel::distributed::Triangulation<fem::dim> &mesh, const ContinuumInput &c,
               const dem::PullOutGeometry &g, const std::string &where)
{
  if (c.mesh_file.empty())
    {
      fem::make_pullout_tank_mesh(mesh, g.tank_length, g.fill_height, c.cell_size, c.problem,
                                  where + ", subsection Continuum");
      return;
    }
  try
    {
      fem::read_tank_mesh(mesh, c.mesh_file);
    }
  catch (const std::invalid_argument &e)
    {
      throw std::invalid_argument(where + ": 'Continuum/mesh file' = '" + c.mesh_file + "': " + e.what());
    }
  const auto [lo, hi] = fem::mesh_extent(mesh);
  const auto check = [&](double expected, double actual, const char *entry, const char *what) {
    if (std::abs(expected - actual) > 1e-6 * expected)
      throw std::invalid_argument(where + ": '" + entry + "' = " + number(expected) + " m does not match the mesh file '" +
                                  c.mesh_file + "', whose soil is " + number(actual) + " m " + what +
                                  " (make them agree, or leave 'Continuum/mesh file' empty for a generated mesh)");
  };
  check(g.tank_length, hi[0] - lo[0], "Tank/length", "long");
  check(g.fill_height, hi[1] - lo[1], "Tank/fill height", "high");
}

} // namespace

int run_pullout_fem_mode(ParameterHandler &prm, const PullOutInput &in, const std::string &where, MPI_Comm comm,
                         bool check_only)
{
  const auto start_time = std::chrono::steady_clock::now();
  const auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  };
  const bool writer = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  const dem::PullOutGeometry &g = in.tank.geometry;
  ContinuumInput c = parse_continuum(prm, in, where);
  const std::filesystem::path out = prm.get("output directory");
  if (out.empty())
    throw std::invalid_argument(where + ": parameter 'output directory' is empty");
  if (c.snapshot_interval > 0.0)
    {
      c.problem.snapshot_directory = (out / "snapshots").string();
      c.problem.snapshot_interval = c.snapshot_interval;
    }

  if (c.implicit_solver && g.anchorage == dem::Anchorage::wrap_around)
    throw std::invalid_argument(where + ": 'Continuum/solver' = implicit takes a simple run-out only: its sheet lies "
                                        "straight (fem/quasi_static_pullout.h); use 'set solver = explicit' for the "
                                        "wrap-around");

  // Everything that can be refused is checked here, before a file is written: the mesh, and the
  // problem of the chosen solver (parameters, the sheet in the tank).
  dealii::parallel::distributed::Triangulation<fem::dim> mesh(comm);
  make_mesh(mesh, c, g, where);
  const std::string problem_where = c.mesh_file.empty() ? where : where + ", mesh file '" + c.mesh_file + "'";
  std::optional<fem::PulloutProblem> explicit_problem;
  std::optional<fem::QuasiStaticPullout> implicit_problem;
  if (c.implicit_solver)
    {
      fem::QuasiStaticPulloutParameters q;
      q.pullout = c.problem;
      q.displacement_increment = c.displacement_increment;
      q.minimum_increment = std::min(q.minimum_increment, c.displacement_increment);
      if (c.krylov)
        q.linear_solver.method = fem::LinearSolverSettings::Method::krylov;
      if (c.rigid_body_amg)
        q.linear_solver.preconditioner = fem::LinearSolverSettings::Preconditioner::rigid_body_amg;
      implicit_problem.emplace(mesh, q, problem_where);
    }
  else
    explicit_problem.emplace(mesh, c.problem, problem_where);
  if (check_only)
    return 0;

  std::optional<PulloutOutput> output;
  on_rank_zero(comm, [&] {
    prepare_output_directory(out.string(), false);
    write_resolved_parameters(prm, out);
    if (!c.problem.snapshot_directory.empty())
      std::filesystem::create_directories(c.problem.snapshot_directory);
    output.emplace(out, g.sheet_width, in.profiles_at);
  });
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  if (writer)
    {
      std::cout << "geohybrid pullout: " << anchorage_description(g) << "; mode fem: " << mesh.n_global_active_cells() << " Q"
                << c.problem.element_degree << " cells (" << (c.mesh_file.empty() ? "generated" : c.mesh_file)
                << "), " << fem::to_string(c.problem.soil.kind) << " soil, ";
      if (c.implicit_solver)
        std::cout << "implicit solver, load steps of " << number(1e3 * c.displacement_increment, 4) << " mm";
      else
        std::cout << "explicit solver, time step " << number(explicit_problem->solver().time_step(), 4) << " s";
      std::cout << ", " << n_ranks << " MPI rank" << (n_ranks > 1 ? "s" : "") << std::endl;
    }

  // The pull; rank 0 records every point of the curve as it comes, with the sheet as it is then.
  std::optional<ProgressReport> progress;
  if (writer)
    progress.emplace("pulling", in.pull.final_displacement);
  const std::vector<double> &arc_lengths =
    c.implicit_solver ? implicit_problem->arc_lengths() : explicit_problem->arc_lengths();
  const std::size_t end = c.implicit_solver ? arc_lengths.size() - 1 : explicit_problem->lower_part_end(),
                    middle = end / 2;
  const auto record = [&](const fem::PulloutCurvePoint &point, const fem::TrussSheet &sheet,
                          const std::vector<dealii::Tensor<1, fem::dim>> &u) {
    // Rank 0 writes; a failed write (a full disk) stops every rank, not only the writer.
    on_rank_zero(comm, [&] {
      // The clamp (node 0) is the sheet's first node inside the tank: it sits on the front wall.
      output->add_point(point.head_displacement, point.head_tension, {{u[0][0], u[middle][0], u[end][0]}});
      // A profile is the sheet now, at the clamp's displacement now (with the explicit solver the
      // curve's point is the mean over its interval).
      if (output->profile_due(u[0][0]))
        {
          const std::vector<double> T = sheet.axial_forces(u);
          std::vector<SheetTensionRow> rows;
          for (std::size_t k = 0; k < T.size(); ++k)
            {
              const auto x = 0.5 * (sheet.node(k) + u[k] + sheet.node(k + 1) + u[k + 1]);
              rows.push_back({k, 0.5 * (arc_lengths[k] + arc_lengths[k + 1]), x[0], x[1], T[k]});
            }
          output->add_profile(u[0][0], rows);
        }
      progress->update(point.head_displacement);
    });
    // A signal (interrupt.h) is looked at here, at each point of the curve, by every rank at
    // once (each may have received it at another step): they stop together, the curve so far
    // written. No checkpoint: this mode has none.
    if (const int signal = dealii::Utilities::MPI::max(interrupt_signal(), comm); signal != 0)
      throw Interrupted(signal,
                        "at " + number(1e3 * point.head_displacement, 4) + " mm of the pull: the curve so far is in " +
                          out.string() + ", no summary.json (fem mode writes no checkpoints)",
                        false);
  };
  fem::PulloutResult result;
  if (c.implicit_solver)
    try
      {
        const fem::QuasiStaticSolver &solver = implicit_problem->solver();
        result = implicit_problem->run([&](const fem::PulloutCurvePoint &point) {
          record(point, solver.sheet()->sheet(), solver.sheet_displacements());
        });
      }
    catch (const fem::ConvergenceFailure &failure)
      {
        // The curve up to the last converged point is kept, without summary.json: the directory
        // does not look like a finished run (apps/run_directory.h).
        on_rank_zero(comm, [&] {
          progress->stop(); // where it stopped, not 100 %
          output->finish("FEM (implicit, stopped)", in.references, in.pull.final_displacement);
        });
        throw std::runtime_error(where + ": the implicit solver stopped at head displacement " +
                                 number(1e3 * failure.last_converged_time(), 4) +
                                 " mm (the curve up to there is in " + out.string() +
                                 ", no summary.json: the run did not finish): " + failure.what());
      }
  else
    result = explicit_problem->run([&](const fem::PulloutCurvePoint &point, const fem::EmbeddedSheet &sheet) {
      record(point, sheet.sheet(), sheet.displacements());
    });
  // The answer against the interface's limit (apps/run_health.h), on every rank: each holds the
  // result, so all stop together.
  std::vector<std::string> warnings = in.warnings;
  if (auto w = check_fem_tension(result.max_head_tension, result.geostatic_interface_limit))
    warnings.push_back(*w);

  on_rank_zero(comm, [&] {
    progress->finish();
    output->finish(c.implicit_solver ? "FEM (implicit)" : "FEM", in.references, in.pull.final_displacement);
    const double wall_time = seconds(), T_max = output->max_head_tension();
    Summary summary;
    output->fill_summary(summary, "fem", anchorage_name(g), in.references);
    summary.set("n_particles", 0.0);
    summary.set("n_cells", static_cast<double>(result.n_cells));
    summary.set("element_degree", static_cast<double>(c.problem.element_degree));
    summary.set("soil_model", fem::to_string(c.problem.soil.kind));
    summary.set("mesh", c.mesh_file.empty() ? "generated, cell size " + number(c.cell_size) + " m" : c.mesh_file);
    summary.set("n_sheet_nodes", static_cast<double>(arc_lengths.size()));
    summary.set("solver", c.implicit_solver ? "implicit" : "explicit");
    summary.set("sigma_v_at_sheet_Pa", result.vertical_stress_at_sheet);
    summary.set("gamma_H_Pa", in.tank.unit_weight * g.cover);
    summary.set("geostatic_interface_limit_kN_per_m", result.geostatic_interface_limit / 1e3);
    summary.set("T_max_over_geostatic_interface_limit", T_max / result.geostatic_interface_limit);
    summary.set("time_step_s", result.time_step);
    summary.set("n_steps", static_cast<double>(result.n_steps));
    summary.set("sheet_mass_scaling", result.sheet_mass_scaling);
    if (c.implicit_solver)
      {
        // The implicit solver's cost: load steps (n_steps), Newton iterations (linear solves) and
        // Krylov iterations summed over them, and the steps that had to be halved.
        unsigned int n_newton = 0, n_krylov = 0;
        for (const fem::StepRecord &step : implicit_problem->report().steps)
          {
            n_newton += step.n_iterations;
            n_krylov += step.n_linear_iterations;
          }
        summary.set("linear_solver", c.krylov ? "Krylov" : "direct");
        summary.set("n_newton_iterations", static_cast<double>(n_newton));
        // With the direct solver each Newton iteration is one solve and counts one.
        summary.set("n_krylov_iterations", static_cast<double>(n_krylov));
        summary.set("n_cutbacks", static_cast<double>(implicit_problem->report().n_cutbacks()));
      }
    summary.set("n_mpi_ranks", static_cast<double>(n_ranks));
    summary.set("wall_time_s", wall_time);
    summary.set("parameters_hash", pullout_parameters_hash(prm));
    report_warnings(warnings, "geohybrid pullout", summary, std::cerr);
    summary.write(out / "summary.json");
    std::cout << "geohybrid pullout: T_max = " << number(T_max / 1e3, 4) << " kN/m ("
              << number(T_max * g.sheet_width / 1e3, 4) << " kN for b = " << number(g.sheet_width, 3) << " m) at "
              << number(1e3 * output->head_displacement_at_max(), 3) << " mm; geostatic interface limit "
              << number(result.geostatic_interface_limit / 1e3, 4) << " kN/m"
              << experiment_text(in.references) << "; " << result.n_steps << " steps, " << number(wall_time, 4)
              << " s\n" << demonstration_lines(in.references) << "results in " << out.string() << '\n';
  });
  return 0;
}
} // namespace geohybrid::apps
