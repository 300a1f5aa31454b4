// The implicit quasi-static solver against closed forms of linear elasticity: patch tests on
// distorted Q1 and Q2 meshes, the Lame thick cylinder and its convergence, a geostatic layer with
// K0 in equilibrium with gravity, and a surcharge on it (oedometer).
#include "test_fem_support.h"

#include <deal.II/base/function_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>

using namespace geohybrid::fem;
using namespace geohybrid::fem::testing;

// A linear displacement field lies in the Q1 and Q2 spaces on any mesh of straight-sided
// quadrilaterals, so prescribing it on the boundary must give it back exactly inside, with the
// uniform stress C : eps at every quadrature point, however distorted the cells are.
TEST(QuasiStatic, PatchTestOnDistortedMeshIsExact)
{
  for (const unsigned int degree : {1u, 2u})
    {
      Mesh mesh(MPI_COMM_WORLD);
      make_rectangle(mesh, 5, 4, Point<dim>(0, 0), Point<dim>(2, 1));
      dealii::GridTools::transform(
        [](const Point<dim> &p) {
          const bool interior = p[0] > 1e-9 && p[0] < 2 - 1e-9 && p[1] > 1e-9 && p[1] < 1 - 1e-9;
          return interior ? Point<dim>(p[0] + 0.12 * hash(p), p[1] + 0.08 * hash(Point<dim>(p[1], p[0]))) : p;
        },
        mesh);
      auto exact = std::make_shared<LinearDisplacement>();
      BoundaryConditions bc;
      for (const auto id : {left, right, bottom, top})
        bc.displacements.push_back({id, true, true, exact});
      const SoilModel soil = elastic_soil();
      QuasiStaticSolver solver(mesh, soil, bc, exact_settings(degree));
      const auto report = solver.advance_to(1.0);
      EXPECT_EQ(report.steps.size(), 1u);
      // Linear problem: the first solve gives the answer; the second only confirms it to the
      // tight tolerance the round-off of an AMG-preconditioned Krylov solve allows.
      EXPECT_LE(report.steps[0].n_iterations, 2u);
      std::cout << "patch test Q" << degree << ": relative residuals";
      for (const double r : report.steps[0].relative_residuals)
        std::cout << " " << r;
      std::cout << std::endl;

      dealii::PETScWrappers::MPI::Vector interpolated(solver.space().locally_owned_dofs(), MPI_COMM_WORLD);
      exact->set_time(1.0);
      dealii::VectorTools::interpolate(solver.space().mapping(), solver.space().dof_handler(), *exact, interpolated);
      const double error = max_abs_difference(solver.displacement(), interpolated, solver.space().locally_owned_dofs());
      EXPECT_LT(error, 1e-10 * 1e-2) << "Q" << degree; // |u| ~ 1e-2 m
      std::cout << "patch test Q" << degree << ": max nodal error " << error << " m" << std::endl;

      // eps = sym(G); sigma = lambda tr(eps) I + 2 G eps, sigma_zz = lambda tr(eps)
      const double E = 50e6, nu = 0.3, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
      const double exx = 2e-3, eyy = -4e-3, exy = 0.5 * (-1e-3 + 3e-3);
      double stress_error = 0.0;
      solver.material_points().for_each_cell([&](const auto &, auto &points) {
        for (const auto &p : points)
          {
            stress_error = std::max(stress_error, std::abs(p->stress[0][0] - (lambda * (exx + eyy) + 2 * mu * exx)));
            stress_error = std::max(stress_error, std::abs(p->stress[1][1] - (lambda * (exx + eyy) + 2 * mu * eyy)));
            stress_error = std::max(stress_error, std::abs(p->stress[0][1] - 2 * mu * exy));
            stress_error = std::max(stress_error, std::abs(p->stress[2][2] - lambda * (exx + eyy)));
          }
      });
      EXPECT_LT(stress_error, 1e-8 * E * 4e-3) << "Q" << degree;
    }
}

// The extrapolated predictor (NewtonSettings::extrapolate_predictor): in a linear problem under
// proportional loading the last step's increment, scaled, is the next step's exact answer, so the
// second to fourth of four steps converge on it without a linear solve (relative residual below
// the 1e-12 tolerance at the predictor) and the field is the exact linear one; with the linear
// predictor every step needs its solves.
TEST(QuasiStatic, ExtrapolatedPredictorIsExactUnderProportionalLinearLoading)
{
  for (const bool extrapolate : {true, false})
    {
      SCOPED_TRACE(extrapolate ? "extrapolated predictor" : "linear predictor");
      Mesh mesh(MPI_COMM_WORLD);
      make_rectangle(mesh, 5, 4, Point<dim>(0, 0), Point<dim>(2, 1));
      auto exact = std::make_shared<LinearDisplacement>();
      BoundaryConditions bc;
      for (const auto id : {left, right, bottom, top})
        bc.displacements.push_back({id, true, true, exact});
      QuasiStaticSettings settings = exact_settings(1);
      settings.stepping.increment = 0.25;
      settings.newton.extrapolate_predictor = extrapolate;
      QuasiStaticSolver solver(mesh, elastic_soil(), bc, settings);
      const auto report = solver.advance_to(1.0);
      ASSERT_EQ(report.steps.size(), 4u);
      EXPECT_GE(report.steps[0].n_iterations, 1u);
      for (std::size_t k = 1; k < 4; ++k)
        if (extrapolate)
          {
            EXPECT_EQ(report.steps[k].n_iterations, 0u) << "step " << k;
            EXPECT_LT(report.steps[k].relative_residuals.front(), 1e-12) << "step " << k;
          }
        else
          EXPECT_GE(report.steps[k].n_iterations, 1u) << "step " << k;
      dealii::PETScWrappers::MPI::Vector interpolated(solver.space().locally_owned_dofs(), MPI_COMM_WORLD);
      exact->set_time(1.0);
      dealii::VectorTools::interpolate(solver.space().mapping(), solver.space().dof_handler(), *exact, interpolated);
      EXPECT_LT(max_abs_difference(solver.displacement(), interpolated, solver.space().locally_owned_dofs()),
                1e-10 * 1e-2); // |u| ~ 1e-2 m
    }
}

// The same field with displacements on the left and right sides only and the tractions sigma n
// on the bottom and top: the traction assembly is exact too, and so are the support reactions,
// sigma n times the side's length (f_int - f_ext at a support's DoFs; the corner nodes shared with
// a loaded side keep only the support's share).
TEST(QuasiStatic, PatchTestWithTractionsGivesExactReactions)
{
  const double E = 50e6, nu = 0.3, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const double exx = 2e-3, eyy = -4e-3, exy = 1e-3; // sym of the gradient in LinearDisplacement
  const double sxx = lambda * (exx + eyy) + 2 * mu * exx, syy = lambda * (exx + eyy) + 2 * mu * eyy, sxy = 2 * mu * exy;
  for (const unsigned int degree : {1u, 2u})
    {
      Mesh mesh(MPI_COMM_WORLD);
      make_rectangle(mesh, 4, 3, Point<dim>(0, 0), Point<dim>(2, 1));
      auto exact = std::make_shared<LinearDisplacement>();
      BoundaryConditions bc;
      bc.displacements = {{left, true, true, exact}, {right, true, true, exact}};
      // t = t_pseudo * sigma n: on the bottom n = (0, -1), on the top n = (0, 1).
      bc.tractions = {{bottom, std::make_shared<LinearInTime>(0.0, -sxy, 2, 0)},
                      {top, std::make_shared<LinearInTime>(0.0, sxy, 2, 0)}};
      // LinearInTime carries one non-zero component; the y components come from a second load.
      bc.tractions.push_back({bottom, std::make_shared<LinearInTime>(0.0, -syy, 2, 1)});
      bc.tractions.push_back({top, std::make_shared<LinearInTime>(0.0, syy, 2, 1)});
      QuasiStaticSolver solver(mesh, elastic_soil(E, nu), bc, exact_settings(degree));
      solver.advance_to(1.0);
      dealii::PETScWrappers::MPI::Vector interpolated(solver.space().locally_owned_dofs(), MPI_COMM_WORLD);
      exact->set_time(1.0);
      dealii::VectorTools::interpolate(solver.space().mapping(), solver.space().dof_handler(), *exact, interpolated);
      EXPECT_LT(max_abs_difference(solver.displacement(), interpolated, solver.space().locally_owned_dofs()), 1e-12)
        << "Q" << degree;
      const auto r_left = solver.boundary_reaction(left), r_right = solver.boundary_reaction(right);
      const double scale = 1e-9 * std::abs(syy);
      EXPECT_NEAR(r_left[0], -sxx, scale) << "Q" << degree;
      EXPECT_NEAR(r_left[1], -sxy, scale) << "Q" << degree;
      EXPECT_NEAR(r_right[0], sxx, scale) << "Q" << degree;
      EXPECT_NEAR(r_right[1], sxy, scale) << "Q" << degree;
    }
}

namespace
{
// Lame's thick cylinder in plane strain: inner radius a under pressure p, outer radius b free.
//   sigma_rr = A - B / r^2,  sigma_tt = A + B / r^2,  A = p a^2 / (b^2 - a^2),  B = A b^2,
//   u_r = (1 + nu) / E (A (1 - 2 nu) r + B / r).
struct LameCylinder
{
  double a = 1.0, b = 2.0, p = 100e3, E = 50e6, nu = 0.3;
  double A() const { return p * a * a / (b * b - a * a); }
  double B() const { return A() * b * b; }
  double radial_displacement(double r) const { return (1 + nu) / E * (A() * (1 - 2 * nu) * r + B() / r); }
  StressTensor stress(const Point<dim> &x) const
  {
    const double r = x.norm(), c = x[0] / r, s = x[1] / r;
    const double srr = A() - B() / (r * r), stt = A() + B() / (r * r);
    StressTensor sigma;
    sigma[0][0] = srr * c * c + stt * s * s;
    sigma[1][1] = srr * s * s + stt * c * c;
    sigma[0][1] = (srr - stt) * s * c;
    sigma[2][2] = nu * (srr + stt);
    return sigma;
  }
};

class LameDisplacement : public dealii::Function<dim>
{
public:
  explicit LameDisplacement(const LameCylinder &c) : dealii::Function<dim>(dim), cylinder_(c) {}
  double value(const Point<dim> &x, unsigned int c) const override
  {
    return cylinder_.radial_displacement(x.norm()) * x[c] / x.norm();
  }

private:
  LameCylinder cylinder_;
};

struct LameErrors
{
  double displacement_l2; ///< |u_h - u|_L2 / |u|_L2
  double stress_max;      ///< max over quadrature points of |sigma_h - sigma| / p
  unsigned int n_dofs;
  unsigned int n_linear_iterations = 0;
};

LameErrors solve_lame(unsigned int degree, unsigned int refinements,
                      LinearSolverSettings::Preconditioner preconditioner = LinearSolverSettings::Preconditioner::boomer_amg,
                      LinearSolverSettings::Method method = LinearSolverSettings::Method::krylov)
{
  const LameCylinder cylinder;
  Mesh mesh(MPI_COMM_WORLD);
  // Colorized quarter annulus: 0 inner, 1 outer, 2 on x = 0, 3 on y = 0.
  dealii::GridGenerator::quarter_hyper_shell(mesh, Point<dim>(), cylinder.a, cylinder.b, 0, true);
  mesh.refine_global(refinements);
  BoundaryConditions bc;
  bc.displacements = {{2, true, false, nullptr}, {3, false, true, nullptr}}; // symmetry planes
  bc.pressures = {{0, std::make_shared<LinearInTime>(0.0, cylinder.p)}};
  QuasiStaticSettings settings = exact_settings(degree);
  settings.linear_solver.preconditioner = preconditioner;
  settings.linear_solver.method = method;
  QuasiStaticSolver solver(mesh, elastic_soil(cylinder.E, cylinder.nu), bc, settings);
  const auto report = solver.advance_to(1.0);
  std::cout << "  (" << report.steps[0].n_linear_iterations << " CG iterations)";

  const LameDisplacement exact(cylinder);
  dealii::Vector<float> cell_errors(mesh.n_active_cells());
  const dealii::QGauss<dim> quadrature(degree + 3);
  dealii::VectorTools::integrate_difference(solver.space().mapping(), solver.space().dof_handler(), solver.displacement(),
                                            exact, cell_errors, quadrature, dealii::VectorTools::L2_norm);
  const double error = dealii::VectorTools::compute_global_error(mesh, cell_errors, dealii::VectorTools::L2_norm);
  dealii::PETScWrappers::MPI::Vector zero(solver.space().locally_owned_dofs(), solver.space().locally_relevant_dofs(),
                                          MPI_COMM_WORLD);
  dealii::VectorTools::integrate_difference(solver.space().mapping(), solver.space().dof_handler(), zero, exact,
                                            cell_errors, quadrature, dealii::VectorTools::L2_norm);
  const double norm = dealii::VectorTools::compute_global_error(mesh, cell_errors, dealii::VectorTools::L2_norm);

  dealii::FEValues<dim> fe_values(solver.space().mapping(), solver.space().fe(), solver.space().cell_quadrature(),
                                  dealii::update_quadrature_points);
  double stress_error = 0.0;
  for (const auto &cell : solver.space().dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        const auto points = solver.material_points().at(cell);
        for (unsigned int q = 0; q < points.size(); ++q)
          stress_error = std::max(stress_error, (points[q]->stress - cylinder.stress(fe_values.quadrature_point(q))).norm());
      }
  return {error / norm, dealii::Utilities::MPI::max(stress_error, MPI_COMM_WORLD) / cylinder.p,
          static_cast<unsigned int>(solver.space().dof_handler().n_dofs()), report.steps[0].n_linear_iterations};
}
} // namespace

// The displacement error in L2 falls as h^2 for Q1 and h^3 for Q2 (the Q2 mapping follows the
// circular boundaries to the same order); the stresses at the Gauss points converge too.
TEST(QuasiStatic, LameCylinderConvergesToTheClosedForm)
{
  for (const unsigned int degree : {1u, 2u})
    {
      std::vector<LameErrors> errors;
      for (unsigned int r = 2; r <= 4; ++r)
        {
          const auto start = std::chrono::steady_clock::now();
          errors.push_back(solve_lame(degree, r));
          const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          std::cout << "Lame Q" << degree << " refinement " << r << ": " << errors.back().n_dofs << " DoFs, L2 error "
                    << errors.back().displacement_l2 << ", max stress error / p " << errors.back().stress_max << " ("
                    << seconds << " s)" << std::endl;
        }
      const double expected_ratio = degree == 1 ? 4.0 : 8.0;
      for (unsigned int i = 1; i < errors.size(); ++i)
        {
          const double ratio = errors[i - 1].displacement_l2 / errors[i].displacement_l2;
          EXPECT_GT(ratio, 0.85 * expected_ratio) << "Q" << degree << " refinement " << i + 2;
          EXPECT_LT(ratio, 1.15 * expected_ratio) << "Q" << degree << " refinement " << i + 2;
          EXPECT_LT(errors[i].stress_max, errors[i - 1].stress_max) << "Q" << degree;
        }
      // Measured at refinement 4 (1666 DoFs for Q1, 6402 for Q2): 5.3e-4 and 3.4e-6 in L2; largest
      // Gauss-point stress error 0.094 p and 0.0024 p, at the inner boundary.
      EXPECT_LT(errors.back().displacement_l2, degree == 1 ? 6e-4 : 4e-6) << "Q" << degree;
      EXPECT_LT(errors.back().stress_max, degree == 1 ? 0.11 : 3e-3) << "Q" << degree;
    }
}


// GAMG with the rigid-body modes (fem/rigid_body_amg.h) solves the same system to the same
// answer as BoomerAMG, in fewer Krylov iterations, and its count grows less with refinement.
// Measured (Q2, CG to 1e-13): refinement 4 (6,402 DoFs) BoomerAMG 246 iterations, GAMG 79;
// refinement 5 (25,090 DoFs) 483 and 87; the L2 errors agree to 6 digits.
TEST(QuasiStatic, RigidBodyAMGSolvesTheLameCylinderInFewerIterations)
{
  using P = LinearSolverSettings::Preconditioner;
  for (const unsigned int r : {4u, 5u})
    {
      const LameErrors boomer = solve_lame(2, r, P::boomer_amg), gamg = solve_lame(2, r, P::rigid_body_amg);
      std::cout << "Lame Q2 refinement " << r << ": " << boomer.n_dofs << " DoFs, CG iterations BoomerAMG "
                << boomer.n_linear_iterations << ", GAMG with rigid-body modes " << gamg.n_linear_iterations
                << "; L2 errors " << boomer.displacement_l2 << ", " << gamg.displacement_l2 << std::endl;
      EXPECT_NEAR(gamg.displacement_l2, boomer.displacement_l2, 1e-3 * boomer.displacement_l2) << r;
      EXPECT_LT(gamg.n_linear_iterations, boomer.n_linear_iterations / 2) << r;
    }
}

// The sparse direct solver (MUMPS) solves the same system to the same answer, in one
// factorisation per Newton iteration (the elastic cylinder: one iteration).
TEST(QuasiStatic, SparseDirectSolverSolvesTheLameCylinderAsTheKrylovSolver)
{
  using P = LinearSolverSettings::Preconditioner;
  using M = LinearSolverSettings::Method;
  for (const unsigned int degree : {1u, 2u})
    {
      const LameErrors krylov = solve_lame(degree, 4), direct = solve_lame(degree, 4, P::boomer_amg, M::sparse_direct);
      std::cout << "Lame Q" << degree << " refinement 4: L2 error Krylov " << krylov.displacement_l2 << ", direct "
                << direct.displacement_l2 << "; max stress error / p " << krylov.stress_max << ", "
                << direct.stress_max << std::endl;
      // CG to 1e-13 against an LU factorisation: the discretisation errors agree to round-off.
      EXPECT_NEAR(direct.displacement_l2, krylov.displacement_l2, 1e-8 * krylov.displacement_l2) << degree;
      EXPECT_NEAR(direct.stress_max, krylov.stress_max, 1e-8 * krylov.stress_max) << degree;
      EXPECT_EQ(direct.n_linear_iterations, 1u) << degree;
    }
}

// The K0 stress is in equilibrium with gravity between smooth walls: starting from it, nothing
// moves (the first out-of-balance force is round-off), and the supports carry the weight and the
// lateral thrust K0 gamma H^2 / 2.
TEST(QuasiStatic, GeostaticStateIsInEquilibriumWithGravity)
{
  const Layer layer;
  for (const unsigned int degree : {1u, 2u})
    {
      Mesh mesh(MPI_COMM_WORLD);
      make_rectangle(mesh, 4, 2, Point<dim>(0, 0), Point<dim>(layer.width, layer.height));
      QuasiStaticSolver solver(mesh, mohr_coulomb_soil(layer.phi, 0, 0, layer.E, layer.nu), layer.supports(),
                               layer.settings(degree));
      solver.set_initial_stress(layer.geostatic());
      const auto report = solver.advance_to(1.0);
      for (const auto &s : report.steps)
        {
          EXPECT_EQ(s.n_iterations, 0u) << "Q" << degree;
          EXPECT_LT(s.relative_residuals.front(), 1e-13) << "Q" << degree;
        }
      EXPECT_LT(solver.displacement().linfty_norm(), 1e-15) << "Q" << degree;
      const double weight = layer.unit_weight() * layer.width * layer.height;
      EXPECT_NEAR(solver.boundary_reaction(bottom)[1], weight, 1e-10 * weight) << "Q" << degree;
      const double thrust = layer.geostatic().k0 * layer.unit_weight() * layer.height * layer.height / 2;
      EXPECT_NEAR(solver.boundary_reaction(left)[0], thrust, 1e-10 * thrust) << "Q" << degree;
      EXPECT_NEAR(solver.boundary_reaction(right)[0], -thrust, 1e-10 * thrust) << "Q" << degree;
    }
}

// A surcharge q on the geostatic layer compresses it in one dimension (oedometer): the elastic
// increment is u_y = -q y / M, M = E (1 - nu) / ((1 + nu)(1 - 2 nu)), the vertical stress grows by
// q everywhere and the horizontal by nu / (1 - nu) q, all within the yield surface.
TEST(QuasiStatic, SurchargeOnGeostaticLayerIsOedometric)
{
  const Layer layer;
  const double q = 10e3, M = layer.E * (1 - layer.nu) / ((1 + layer.nu) * (1 - 2 * layer.nu));
  for (const unsigned int degree : {1u, 2u})
    {
      Mesh mesh(MPI_COMM_WORLD);
      make_rectangle(mesh, 4, 2, Point<dim>(0, 0), Point<dim>(layer.width, layer.height));
      BoundaryConditions bc = layer.supports();
      bc.pressures = {{top, std::make_shared<LinearInTime>(0.0, q)}};
      QuasiStaticSolver solver(mesh, mohr_coulomb_soil(layer.phi, 0, 0, layer.E, layer.nu), bc, layer.settings(degree));
      solver.set_initial_stress(layer.geostatic());
      solver.advance_to(1.0);

      const dealii::VectorFunctionFromScalarFunctionObject<dim> exact([&](const Point<dim> &x) { return -q * x[1] / M; },
                                                                      1, dim);
      dealii::PETScWrappers::MPI::Vector interpolated(solver.space().locally_owned_dofs(), MPI_COMM_WORLD);
      dealii::VectorTools::interpolate(solver.space().mapping(), solver.space().dof_handler(), exact, interpolated);
      EXPECT_LT(max_abs_difference(solver.displacement(), interpolated, solver.space().locally_owned_dofs()),
                1e-9 * q / M)
        << "Q" << degree;

      dealii::FEValues<dim> fe_values(solver.space().mapping(), solver.space().fe(), solver.space().cell_quadrature(),
                                      dealii::update_quadrature_points);
      double stress_error = 0.0;
      bool all_elastic = true;
      for (const auto &cell : solver.space().dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            const auto points = solver.material_points().at(cell);
            for (unsigned int k = 0; k < points.size(); ++k)
              {
                const auto &x = fe_values.quadrature_point(k);
                const double sv = -(q + layer.unit_weight() * (layer.height - x[1]));
                const double sh = layer.geostatic().k0 * (sv + q) - layer.nu / (1 - layer.nu) * q;
                stress_error = std::max({stress_error, std::abs(points[k]->stress[1][1] - sv),
                                         std::abs(points[k]->stress[0][0] - sh), std::abs(points[k]->stress[2][2] - sh)});
                all_elastic = all_elastic && points[k]->region == ReturnRegion::elastic;
              }
          }
      EXPECT_LT(stress_error, 1e-9 * q) << "Q" << degree;
      EXPECT_TRUE(all_elastic);
      const double load = layer.unit_weight() * layer.width * layer.height + q * layer.width;
      EXPECT_NEAR(solver.boundary_reaction(bottom)[1], load, 1e-9 * load) << "Q" << degree;
    }
}

