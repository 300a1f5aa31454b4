// The continuum on two MPI ranks (ctest runs this file with mpirun -np 2): a nonlinear footing
// problem solved on a mesh distributed over both ranks gives the same displacements, stresses and
// footing force as the same problem solved whole on each rank alone; the Lame cylinder keeps its
// accuracy; the VTU output has one piece per rank.
#include "fem/explicit_solver.h"
#include "fem/pullout_problem.h"
#include "fem/quasi_static_solver.h"
#include "test_fem_support.h"
#include "temporary_directory.h"

#include <deal.II/base/function_lib.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace geohybrid::fem;
using dealii::Point;
using Mesh = dealii::parallel::distributed::Triangulation<dim>;

namespace
{
constexpr dealii::types::boundary_id left = 0, right = 1, bottom = 2, footing = 4;

/// u_y = -rate t on the footing.
class FootingSettlement : public dealii::Function<dim>
{
public:
  explicit FootingSettlement(double rate) : dealii::Function<dim>(dim), rate_(rate) {}
  double value(const Point<dim> &, unsigned int c) const override { return c == 1 ? -rate_ * get_time() : 0.0; }

private:
  double rate_;
};

/// A 2 m x 1 m Mohr-Coulomb layer at its geostatic stress, between smooth walls on a rough base,
/// with a rough rigid footing 0.5 m wide at the top-left corner pushed 5 mm down in 4 steps: a
/// plastic zone grows under the footing (about a quarter of the points yield), and the
/// non-associated flow needs GMRES.
struct FootingProblem
{
  explicit FootingProblem(MPI_Comm comm) : mesh(comm)
  {
    dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {8, 4}, Point<dim>(0, 0), Point<dim>(2, 1), true);
    for (const auto &cell : mesh.cell_iterators_on_level(0))
      for (const auto face : cell->face_indices())
        if (cell->face(face)->at_boundary() && cell->face(face)->boundary_id() == 3 && cell->face(face)->center()[0] < 0.5)
          cell->face(face)->set_boundary_id(footing);
    mesh.refine_global(1);
    SoilParameters soil;
    soil.young_modulus = 20e6;
    soil.poisson_ratio = 0.3;
    soil.strength = {30.0, 5e3, 10.0};
    BoundaryConditions bc;
    bc.displacements = {{left, true, false, nullptr}, {right, true, false, nullptr}, {bottom, true, true, nullptr},
                        {footing, true, true, std::make_shared<FootingSettlement>(0.005)}};
    QuasiStaticSettings settings;
    settings.element_degree = 2;
    settings.density = 2000.0;
    settings.newton.relative_tolerance = 1e-11;
    settings.linear_solver.relative_tolerance = 1e-12;
    settings.stepping.increment = 0.25;
    solver = std::make_unique<QuasiStaticSolver>(mesh, SoilModel(soil), bc, settings);
    GeostaticStress geostatic;
    geostatic.surface_elevation = 1.0;
    geostatic.unit_weight = 2000.0 * 9.81;
    geostatic.k0 = 1 - std::sin(30.0 * pi / 180.0);
    solver->set_initial_stress(geostatic);
  }
  Mesh mesh;
  std::unique_ptr<QuasiStaticSolver> solver;
};
} // namespace

TEST(Mpi, DistributedSolutionMatchesTheWholeProblemOnOneRank)
{
  ASSERT_EQ(dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD), 2u) << "run with mpirun -np 2";
  auto start = std::chrono::steady_clock::now();
  FootingProblem distributed(MPI_COMM_WORLD);
  const auto report = distributed.solver->advance_to(1.0);
  const double distributed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  start = std::chrono::steady_clock::now();
  FootingProblem whole(MPI_COMM_SELF);
  whole.solver->advance_to(1.0);
  const double whole_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Both ranks own part of the mesh.
  EXPECT_GT(distributed.mesh.n_locally_owned_active_cells(), 0u);
  EXPECT_LT(distributed.mesh.n_locally_owned_active_cells(), whole.mesh.n_active_cells());

  const auto force_distributed = distributed.solver->boundary_reaction(footing);
  const auto force_whole = whole.solver->boundary_reaction(footing);
  EXPECT_NEAR(force_distributed[1], force_whole[1], 1e-8 * std::abs(force_whole[1]));
  EXPECT_NEAR(force_distributed[0], force_whole[0], 1e-8 * std::abs(force_whole[1]));

  // Cell by cell (the same CellId on both meshes): DoF values and quadrature-point stresses.
  const auto &dofs_d = distributed.solver->space().dof_handler();
  const auto &dofs_w = whole.solver->space().dof_handler();
  const unsigned int n = dofs_d.get_fe().n_dofs_per_cell();
  std::vector<dealii::types::global_dof_index> indices_d(n), indices_w(n);
  double displacement_difference = 0.0, stress_difference = 0.0, largest_displacement = 0.0, largest_stress = 0.0;
  unsigned int n_yielded = 0;
  for (const auto &cell_d : dofs_d.active_cell_iterators())
    if (cell_d->is_locally_owned())
      {
        const auto tria_cell_w = whole.mesh.create_cell_iterator(cell_d->id());
        const dealii::DoFHandler<dim>::active_cell_iterator cell_w(&whole.mesh, tria_cell_w->level(), tria_cell_w->index(), &dofs_w);
        cell_d->get_dof_indices(indices_d);
        cell_w->get_dof_indices(indices_w);
        for (unsigned int i = 0; i < n; ++i)
          {
            const double ud = distributed.solver->displacement()[indices_d[i]];
            const double uw = whole.solver->displacement()[indices_w[i]];
            displacement_difference = std::max(displacement_difference, std::abs(ud - uw));
            largest_displacement = std::max(largest_displacement, std::abs(uw));
          }
        const auto points_d = distributed.solver->material_points().at(cell_d);
        const auto points_w = whole.solver->material_points().at(tria_cell_w);
        for (unsigned int q = 0; q < points_d.size(); ++q)
          {
            stress_difference = std::max(stress_difference, (points_d[q]->stress - points_w[q]->stress).norm());
            largest_stress = std::max(largest_stress, points_w[q]->stress.norm());
            n_yielded += points_d[q]->region != ReturnRegion::elastic;
          }
      }
  displacement_difference = dealii::Utilities::MPI::max(displacement_difference, MPI_COMM_WORLD);
  largest_displacement = dealii::Utilities::MPI::max(largest_displacement, MPI_COMM_WORLD);
  stress_difference = dealii::Utilities::MPI::max(stress_difference, MPI_COMM_WORLD);
  largest_stress = dealii::Utilities::MPI::max(largest_stress, MPI_COMM_WORLD);
  n_yielded = dealii::Utilities::MPI::sum(n_yielded, MPI_COMM_WORLD);
  EXPECT_LT(displacement_difference, 1e-8 * largest_displacement);
  EXPECT_LT(stress_difference, 1e-8 * largest_stress);
  EXPECT_GT(n_yielded, 10u); // the comparison covers plastic states, not only elastic ones
  EXPECT_NEAR(largest_displacement, 0.005, 1e-12); // the footing's settlement is the largest motion

  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::cout << "footing: force " << force_distributed << " N/m (whole " << force_whole << "), max |du| "
                << displacement_difference << " m, max |dsigma| " << stress_difference << " Pa, " << n_yielded
                << " yielded points; 2 ranks " << distributed_seconds << " s, 1 rank " << whole_seconds << " s; Newton";
      for (const auto &s : report.steps)
        std::cout << " " << s.n_iterations << " (" << s.n_linear_iterations << " GMRES)";
      std::cout << std::endl;
    }
}

// The Lame cylinder on two ranks (Q2, 1666 DoFs) keeps the L2 error of the serial run, 2.67e-5.
TEST(Mpi, LameCylinderOnTwoRanks)
{
  const double a = 1.0, b = 2.0, p = 100e3, E = 50e6, nu = 0.3, A = p * a * a / (b * b - a * a), B = A * b * b;
  Mesh mesh(MPI_COMM_WORLD);
  dealii::GridGenerator::quarter_hyper_shell(mesh, Point<dim>(), a, b, 0, true);
  mesh.refine_global(3);
  SoilParameters soil;
  soil.kind = SoilModelKind::linear_elastic;
  soil.young_modulus = E;
  soil.poisson_ratio = nu;
  BoundaryConditions bc;
  bc.displacements = {{2, true, false, nullptr}, {3, false, true, nullptr}};
  bc.pressures = {{0, std::make_shared<dealii::Functions::ConstantFunction<dim>>(p)}};
  QuasiStaticSettings settings;
  settings.newton.relative_tolerance = 1e-12;
  settings.linear_solver.relative_tolerance = 1e-13;
  settings.stepping.increment = 1.0;
  QuasiStaticSolver solver(mesh, SoilModel(soil), bc, settings);
  solver.advance_to(1.0);
  const dealii::VectorFunctionFromScalarFunctionObject<dim> ux(
    [&](const Point<dim> &x) { return (1 + nu) / E * (A * (1 - 2 * nu) + B / x.norm_square()) * x[0]; }, 0, dim);
  const dealii::VectorFunctionFromScalarFunctionObject<dim> uy(
    [&](const Point<dim> &x) { return (1 + nu) / E * (A * (1 - 2 * nu) + B / x.norm_square()) * x[1]; }, 1, dim);
  dealii::Vector<float> cells(mesh.n_active_cells());
  double error2 = 0.0, norm2 = 0.0;
  dealii::PETScWrappers::MPI::Vector zero(solver.space().locally_owned_dofs(), solver.space().locally_relevant_dofs(),
                                          MPI_COMM_WORLD);
  for (const auto *exact : {&ux, &uy})
    {
      const dealii::ComponentSelectFunction<dim> select(exact == &ux ? 0 : 1, dim);
      dealii::VectorTools::integrate_difference(solver.space().mapping(), solver.space().dof_handler(),
                                                solver.displacement(), *exact, cells, dealii::QGauss<dim>(5),
                                                dealii::VectorTools::L2_norm, &select);
      error2 += std::pow(dealii::VectorTools::compute_global_error(mesh, cells, dealii::VectorTools::L2_norm), 2);
      dealii::VectorTools::integrate_difference(solver.space().mapping(), solver.space().dof_handler(), zero, *exact,
                                                cells, dealii::QGauss<dim>(5), dealii::VectorTools::L2_norm, &select);
      norm2 += std::pow(dealii::VectorTools::compute_global_error(mesh, cells, dealii::VectorTools::L2_norm), 2);
    }
  const double relative_error = std::sqrt(error2 / norm2);
  EXPECT_NEAR(relative_error, 2.66941e-05, 1e-9);
}

namespace
{
/// The footing problem of FootingProblem run by the explicit solver: the footing pushed 5 mm down
/// in 0.1 s (400 steps), local damping 0.7, so that the soil under it yields while waves travel.
struct ExplicitFootingProblem
{
  explicit ExplicitFootingProblem(MPI_Comm comm) : mesh(comm)
  {
    dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {16, 8}, Point<dim>(0, 0), Point<dim>(2, 1), true);
    for (const auto &cell : mesh.cell_iterators_on_level(0))
      for (const auto face : cell->face_indices())
        if (cell->face(face)->at_boundary() && cell->face(face)->boundary_id() == 3 && cell->face(face)->center()[0] < 0.5)
          cell->face(face)->set_boundary_id(footing);
    mesh.refine_global(1);
    SoilParameters soil;
    soil.young_modulus = 20e6;
    soil.poisson_ratio = 0.3;
    soil.strength = {30.0, 5e3, 10.0};
    BoundaryConditions bc;
    bc.displacements = {{left, true, false, nullptr}, {right, true, false, nullptr}, {bottom, true, true, nullptr},
                        {footing, true, true, std::make_shared<FootingSettlement>(0.05)}};
    ExplicitSettings settings;
    settings.density = 2000.0;
    settings.gravity = QuasiStaticSettings::gravity_down();
    settings.damping.local = 0.7;
    settings.time_step = 2.5e-4;
    solver = std::make_unique<ExplicitSolver>(mesh, SoilModel(soil), bc, settings);
    GeostaticStress geostatic;
    geostatic.surface_elevation = 1.0;
    geostatic.unit_weight = 2000.0 * 9.81;
    geostatic.k0 = 1 - std::sin(30.0 * pi / 180.0);
    solver->set_initial_stress(geostatic);
  }
  Mesh mesh;
  std::unique_ptr<ExplicitSolver> solver;
};
} // namespace

// Explicit dynamics on two ranks: the same displacements and stresses, cell by cell, as the whole
// problem on one rank after 400 steps with plastic flow and local damping (only the order of the
// sums of the ghost contributions differs).
TEST(Mpi, ExplicitSolverGivesTheSameResultOnTwoRanks)
{
  ExplicitFootingProblem distributed(MPI_COMM_WORLD);
  ExplicitFootingProblem whole(MPI_COMM_SELF);
  ASSERT_EQ(distributed.solver->time_step(), 2.5e-4);
  distributed.solver->advance_to(0.1);
  whole.solver->advance_to(0.1);
  EXPECT_EQ(distributed.solver->n_steps(), 400u);
  EXPECT_LT(distributed.mesh.n_locally_owned_active_cells(), whole.mesh.n_active_cells());

  const auto &dofs_d = distributed.solver->space().dof_handler();
  const auto &dofs_w = whole.solver->space().dof_handler();
  const unsigned int n = dofs_d.get_fe().n_dofs_per_cell();
  std::vector<dealii::types::global_dof_index> indices_d(n), indices_w(n);
  double displacement_difference = 0.0, stress_difference = 0.0, largest_displacement = 0.0, largest_stress = 0.0;
  unsigned int n_yielded = 0;
  for (const auto &cell_d : dofs_d.active_cell_iterators())
    if (cell_d->is_locally_owned())
      {
        const auto tria_cell_w = whole.mesh.create_cell_iterator(cell_d->id());
        const dealii::DoFHandler<dim>::active_cell_iterator cell_w(&whole.mesh, tria_cell_w->level(), tria_cell_w->index(), &dofs_w);
        cell_d->get_dof_indices(indices_d);
        cell_w->get_dof_indices(indices_w);
        for (unsigned int i = 0; i < n; ++i)
          {
            const double ud = distributed.solver->displacement()[indices_d[i]];
            const double uw = whole.solver->displacement()[indices_w[i]];
            displacement_difference = std::max(displacement_difference, std::abs(ud - uw));
            largest_displacement = std::max(largest_displacement, std::abs(uw));
          }
        const auto points_d = distributed.solver->material_points().at(cell_d);
        const auto points_w = whole.solver->material_points().at(tria_cell_w);
        for (unsigned int q = 0; q < points_d.size(); ++q)
          {
            stress_difference = std::max(stress_difference, (points_d[q]->stress - points_w[q]->stress).norm());
            largest_stress = std::max(largest_stress, points_w[q]->stress.norm());
            n_yielded += points_d[q]->region != ReturnRegion::elastic;
          }
      }
  displacement_difference = dealii::Utilities::MPI::max(displacement_difference, MPI_COMM_WORLD);
  largest_displacement = dealii::Utilities::MPI::max(largest_displacement, MPI_COMM_WORLD);
  stress_difference = dealii::Utilities::MPI::max(stress_difference, MPI_COMM_WORLD);
  largest_stress = dealii::Utilities::MPI::max(largest_stress, MPI_COMM_WORLD);
  n_yielded = dealii::Utilities::MPI::sum(n_yielded, MPI_COMM_WORLD);
  // Local damping switches with the sign of each DoF's velocity, so a velocity that is zero up to
  // round-off somewhere turns the round-off of the summation order into a (small) jump: measured
  // 1.3e-11 m and 6e-3 Pa; without damping the runs agree to 5e-18 m and 5e-10 Pa.
  EXPECT_LT(displacement_difference, 1e-8 * largest_displacement);
  EXPECT_LT(stress_difference, 1e-7 * largest_stress);
  EXPECT_GT(n_yielded, 10u); // the comparison covers plastic states
  EXPECT_NEAR(largest_displacement, 0.005, 1e-12);
  const auto force_d = distributed.solver->boundary_reaction(footing), force_w = whole.solver->boundary_reaction(footing);
  EXPECT_NEAR(force_d[1], force_w[1], 1e-8 * std::abs(force_w[1]));
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "explicit footing: force " << force_d << " N/m (whole " << force_w << "), max |du| "
              << displacement_difference << " m, max |dsigma| " << stress_difference << " Pa, " << n_yielded
              << " yielded points" << std::endl;
}

namespace
{
/// A sheet across a 0.6 m x 0.4 m elastic block under 50 kPa, pulled 2 mm at its left end (the
/// set-up of test_fem_sheet.cc, undamped), run by the explicit solver on `comm`. Its nodes sit on cell edges
/// every other one, so some of them lie on the partition boundary.
struct ExplicitPullout
{
  explicit ExplicitPullout(MPI_Comm comm) : mesh(comm)
  {
    dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {12, 8}, Point<dim>(0, 0), Point<dim>(0.6, 0.4), true);
    SoilParameters soil;
    soil.kind = SoilModelKind::linear_elastic;
    soil.young_modulus = 20e6;
    soil.poisson_ratio = 0.3;
    BoundaryConditions bc;
    bc.displacements = {{bottom, true, true, nullptr}, {left, true, false, nullptr}, {right, true, false, nullptr}};
    bc.pressures = {{3, std::make_shared<dealii::Functions::ConstantFunction<dim>>(50e3)}};
    ExplicitSettings settings;
    settings.density = 2000.0;
    settings.damping.local = 0.0; // see EmbeddedSheetGivesTheSameResultOnTwoRanks
    solver = std::make_unique<ExplicitSolver>(mesh, SoilModel(soil), bc, settings);
    solver->set_initial_stress(
      [](const Point<dim> &) {
        StressTensor s;
        s[1][1] = -50e3;
        s[0][0] = s[2][2] = -50e3 * 0.3 / 0.7;
        return s;
      },
      "the uniform stress under the surcharge");
    TrussSheetParameters sheet;
    sheet.mass_scaling = 3000.0;
    std::vector<Point<dim>> nodes;
    for (unsigned int k = 0; k <= 24; ++k)
      nodes.emplace_back(0.6 * k / 24.0, 0.175);
    solver->attach_sheet(TrussSheet(nodes, sheet),
                         {{0, [](double t) { return dealii::Tensor<1, dim>({-0.004 * t, 0.0}); }}});
  }
  Mesh mesh;
  std::unique_ptr<ExplicitSolver> solver;
};
} // namespace

// The sheet is replicated on each rank and its interface forces are computed by the owner of each
// node's cell: on two ranks the clamp force and the nodes' displacements are those of one rank, to
// round-off (measured 1e-15 m) in undamped dynamics. With local damping 0.7 they differ by 3e-4
// (6e-7 m of 2 mm, 9 N/m of 18 kN/m): the damping force's switch with the sign of each node's
// velocity and the slider's stick/slip switch amplify the round-off of the summation order, so
// that comparison would test the chaos, not the replication.
TEST(Mpi, EmbeddedSheetGivesTheSameResultOnTwoRanks)
{
  ExplicitPullout distributed(MPI_COMM_WORLD);
  ExplicitPullout whole(MPI_COMM_SELF);
  EXPECT_LT(distributed.mesh.n_locally_owned_active_cells(), whole.mesh.n_active_cells());
  distributed.solver->advance_to(0.5);
  whole.solver->advance_to(0.5);
  const auto &sheet_d = *distributed.solver->sheet(), &sheet_w = *whole.solver->sheet();
  const double force_d = -sheet_d.clamp_force(0)[0], force_w = -sheet_w.clamp_force(0)[0];
  double difference = 0.0;
  for (std::size_t k = 0; k < sheet_w.displacements().size(); ++k)
    difference = std::max(difference, (sheet_d.displacements()[k] - sheet_w.displacements()[k]).norm());
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "explicit pull-out: clamp force " << force_d << " N/m (whole " << force_w
              << "), max node |du| " << difference << " m" << std::endl;
  EXPECT_GT(force_w, 5e3); // the sheet is loaded
  EXPECT_NEAR(force_d, force_w, 1e-10 * force_w);
  EXPECT_LT(difference, 1e-11);
}

// The wrap-around of tests/test_fem_pullout.cc (0.8 m x 0.6 m elastic tank, 50 mm cells, local
// damping 0.3), pulled 8 mm: its return crosses the boundary between the two ranks' cells (rows
// 0-5 and 6-11), and its nodes change cells and owners as they slide. Every rank follows every
// soil point and the owner is the rank of the cell with the smallest CellId, so 2 ranks give the
// 1-rank run but for the round-off that the damping's and the slider's switches amplify: the
// documented 3e-4 of T_max for the damped sheet (fem/README.md). Measured: 7.6e-5 of T_max, the soil
// points to 3.7e-7 m. (Undamped, unlike the run-out, which agrees to 4e-10, the wrap-around's two
// runs part from round-off at once and reach 0.6 % of T_max by 8 mm; not understood, see README.)
TEST(Mpi, WrapAroundSlidesRoundItsCornersAlikeOnTwoRanks)
{
  PulloutProblemParameters p = geohybrid::fem::testing::small_wrap_around_tank(0.004);
  p.final_displacement = 0.008;
  Mesh mesh_distributed(MPI_COMM_WORLD), mesh_whole(MPI_COMM_SELF);
  make_pullout_tank_mesh(mesh_distributed, 0.8, 0.6, 0.05, p, "wrap-around");
  make_pullout_tank_mesh(mesh_whole, 0.8, 0.6, 0.05, p, "wrap-around");
  EXPECT_LT(mesh_distributed.n_locally_owned_active_cells(), mesh_whole.n_active_cells());
  PulloutProblem distributed(mesh_distributed, p), whole(mesh_whole, p);
  const PulloutResult a = distributed.run(), b = whole.run();
  ASSERT_EQ(a.curve.size(), b.curve.size());
  double largest = 0.0, slid = 0.0, s_difference = 0.0;
  for (std::size_t i = 0; i < a.curve.size(); ++i)
    largest = std::max(largest, std::abs(a.curve[i].head_tension - b.curve[i].head_tension));
  const auto &sheet_a = *distributed.solver().sheet(), &sheet_b = *whole.solver().sheet();
  for (std::size_t k = 0; k < sheet_b.sheet().n_nodes(); ++k)
    {
      s_difference = std::max(s_difference, std::abs(sheet_a.soil_point_arc_length(k) - sheet_b.soil_point_arc_length(k)));
      slid = std::max(slid, sheet_b.reference_path().vertex_arc_length(k) - sheet_b.soil_point_arc_length(k));
    }
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "wrap-around on 2 ranks: largest head tension difference " << largest / b.max_head_tension
              << " of T_max " << b.max_head_tension << " N/m; soil points " << s_difference << " m; largest slip "
              << slid << " m" << std::endl;
  EXPECT_GT(slid, 0.005); // the points moved, some across cells
  EXPECT_LT(largest, 3e-4 * b.max_head_tension);
  EXPECT_LT(s_difference, 1e-5);
}

TEST(Mpi, VtuRecordListsOnePiecePerRank)
{
  // Rank 0 chooses the directory; the others use the same one.
  std::unique_ptr<geohybrid::testing::TemporaryDirectory> directory;
  std::string path;
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      directory = std::make_unique<geohybrid::testing::TemporaryDirectory>("fem_mpi_vtu");
      path = directory->path.string();
    }
  path = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, path, 0);
  FootingProblem problem(MPI_COMM_WORLD);
  const std::string record = problem.solver->write_vtu(path, "footing", 0);
  MPI_Barrier(MPI_COMM_WORLD); // each rank writes its own piece: wait for all before reading
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::ifstream pvtu(path + "/" + record);
      std::stringstream text;
      text << pvtu.rdbuf();
      EXPECT_NE(text.str().find("footing_0000.0.vtu"), std::string::npos);
      EXPECT_NE(text.str().find("footing_0000.1.vtu"), std::string::npos);
      EXPECT_TRUE(std::ifstream(path + "/footing_0000.1.vtu").good());
    }
  MPI_Barrier(MPI_COMM_WORLD); // rank 0 removes the directory only after every rank wrote
}
