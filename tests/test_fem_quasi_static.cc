// The implicit quasi-static solver against closed forms: patch tests on distorted Q1 and Q2
// meshes, the Lame thick cylinder and its convergence, a Mohr-Coulomb biaxial element test, the
// collapse load found by step cutback, a geostatic layer with K0 and a surcharge, and bad input.
#include "fem/quasi_static_solver.h"
#include "temporary_directory.h"

#include <deal.II/base/function_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
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
// Boundary ids of a colorized rectangle.
constexpr dealii::types::boundary_id left = 0, right = 1, bottom = 2, top = 3;

SoilModel elastic_soil(double E = 50e6, double nu = 0.3)
{
  SoilParameters p;
  p.kind = SoilModelKind::linear_elastic;
  p.young_modulus = E;
  p.poisson_ratio = nu;
  return SoilModel(p);
}

SoilModel mohr_coulomb_soil(double phi, double c, double psi, double E = 20e6, double nu = 0.3)
{
  SoilParameters p;
  p.kind = SoilModelKind::mohr_coulomb;
  p.young_modulus = E;
  p.poisson_ratio = nu;
  p.strength = {phi, c, psi};
  return SoilModel(p);
}

void make_rectangle(Mesh &mesh, unsigned int nx, unsigned int ny, const Point<dim> &p1, const Point<dim> &p2)
{
  dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {nx, ny}, p1, p2, true);
}

/// A deterministic pseudo-random number in [-1, 1] from a vertex position: the same on every rank.
double hash(const Point<dim> &p)
{
  const double s = std::sin(12.9898 * p[0] + 78.233 * p[1]) * 43758.5453;
  return 2.0 * (s - std::floor(s)) - 1.0;
}

/// u(x, t) = t (u0 + G x): a linear displacement field, growing with the pseudo-time.
class LinearDisplacement : public dealii::Function<dim>
{
public:
  LinearDisplacement() : dealii::Function<dim>(dim) {}
  double value(const Point<dim> &x, unsigned int c) const override
  {
    const double u0[2] = {1e-3, -2e-3};
    const double G[2][2] = {{2e-3, -1e-3}, {3e-3, -4e-3}};
    return get_time() * (u0[c] + G[c][0] * x[0] + G[c][1] * x[1]);
  }
};

/// f(t) = a + b t, a constant in space (a pressure or a displacement component).
class LinearInTime : public dealii::Function<dim>
{
public:
  LinearInTime(double a, double b, unsigned int n_components = 1, unsigned int component = 0)
    : dealii::Function<dim>(n_components), a_(a), b_(b), component_(component) {}
  double value(const Point<dim> &, unsigned int c) const override
  {
    return c == component_ ? a_ + b_ * get_time() : 0.0;
  }

private:
  double a_, b_;
  unsigned int component_;
};

double max_abs_difference(const dealii::PETScWrappers::MPI::Vector &a, const dealii::PETScWrappers::MPI::Vector &b,
                          const dealii::IndexSet &owned)
{
  double m = 0.0;
  for (const auto i : owned)
    m = std::max(m, std::abs(a[i] - b[i]));
  return dealii::Utilities::MPI::max(m, MPI_COMM_WORLD);
}

QuasiStaticSettings exact_settings(unsigned int degree)
{
  QuasiStaticSettings s;
  s.element_degree = degree;
  s.newton.relative_tolerance = 1e-12;
  s.linear_solver.relative_tolerance = 1e-13;
  s.stepping.increment = 1.0;
  return s;
}
} // namespace

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
};

LameErrors solve_lame(unsigned int degree, unsigned int refinements)
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
          static_cast<unsigned int>(solver.space().dof_handler().n_dofs())};
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

namespace
{
/// A unit square of Mohr-Coulomb soil at sigma_xx = sigma_yy = -p0 (sigma_zz = -2 nu p0, as left by
/// elastic in-plane confinement), left side on rollers, bottom on rollers, the right side under
/// the confining pressure p0, and the top either driven down (displacement control) or loaded by
/// a growing pressure (load control). The state stays uniform, so every quadrature point must
/// follow the material-point solution.
struct ElementTest
{
  double p0 = 100e3, phi = 30.0, c = 10e3, psi = 10.0, nu = 0.3;
  double limit_ratio() const
  {
    const double s = std::sin(phi * pi / 180.0);
    return (1 + s) / (1 - s) + 2 * c * std::cos(phi * pi / 180.0) / (1 - s) / p0;
  }
  StressTensor confinement() const
  {
    StressTensor s;
    s[0][0] = s[1][1] = -p0;
    s[2][2] = -2 * nu * p0;
    return s;
  }
};
} // namespace

TEST(QuasiStatic, MohrCoulombElementTestReachesTheLimit)
{
  const ElementTest test;
  for (const unsigned int degree : {1u, 2u})
    {
      Mesh mesh(MPI_COMM_WORLD);
      make_rectangle(mesh, 2, 2, Point<dim>(0, 0), Point<dim>(1, 1));
      BoundaryConditions bc;
      bc.displacements = {{left, true, false, nullptr}, {bottom, false, true, nullptr},
                          {top, false, true, std::make_shared<LinearInTime>(0.0, -0.02, 2, 1)}};
      bc.pressures = {{right, std::make_shared<dealii::Functions::ConstantFunction<dim>>(test.p0)}};
      QuasiStaticSettings settings;
      settings.element_degree = degree;
      settings.newton.relative_tolerance = 1e-11;
      settings.stepping.increment = 0.1;
      QuasiStaticSolver solver(mesh, mohr_coulomb_soil(test.phi, test.c, test.psi, 20e6, test.nu), bc, settings);
      solver.set_initial_stress([&](const Point<dim> &) { return test.confinement(); }, "confinement");
      const auto report = solver.advance_to(1.0);
      std::ostringstream iterations;
      for (const auto &s : report.steps)
        iterations << " " << s.n_iterations;
      std::cout << "element test Q" << degree << ": Newton iterations per step:" << iterations.str() << std::endl;
      for (const auto &s : report.steps)
        {
          std::cout << "  t = " << s.time << ": relative residuals";
          for (const double r : s.relative_residuals)
            std::cout << " " << r;
          std::cout << std::endl;
        }
      double max_ratio_error = 0.0, max_lateral_error = 0.0;
      unsigned int n_plastic = 0, n_points = 0;
      solver.material_points().for_each_cell([&](const auto &, auto &points) {
        for (const auto &p : points)
          {
            max_ratio_error = std::max(max_ratio_error, std::abs(p->stress[1][1] / p->stress[0][0] / test.limit_ratio() - 1));
            max_lateral_error = std::max(max_lateral_error, std::abs(p->stress[0][0] / test.p0 + 1));
            n_plastic += p->region == ReturnRegion::surface;
            ++n_points;
          }
      });
      EXPECT_LT(max_ratio_error, 1e-8) << "Q" << degree;
      EXPECT_LT(max_lateral_error, 1e-8) << "Q" << degree;
      EXPECT_EQ(n_plastic, n_points) << "Q" << degree;
      // The top support carries sigma_yy over the unit width.
      EXPECT_NEAR(solver.boundary_reaction(top)[1], -test.limit_ratio() * test.p0, 1e-7 * test.p0) << "Q" << degree;
      for (const auto &s : report.steps)
        EXPECT_LE(s.n_iterations, 4u) << "Q" << degree << " at t = " << s.time;
    }
}

// Under load control the same element collapses when the axial stress reaches the Mohr-Coulomb
// limit: beyond it there is no equilibrium, the solver halves the increment until the minimum and
// stops with an error that says so, having converged up to within two minimum increments of the
// collapse time t* = (limit - 1) p0 / q_rate.
TEST(QuasiStatic, LoadControlStopsAtTheCollapseLoadAfterCutbacks)
{
  const ElementTest test;
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 2, 2, Point<dim>(0, 0), Point<dim>(1, 1));
  const double q_rate = 1.5 * (test.limit_ratio() - 1) * test.p0; // collapse at t* = 2/3
  BoundaryConditions bc;
  bc.displacements = {{left, true, false, nullptr}, {bottom, false, true, nullptr}};
  bc.pressures = {{right, std::make_shared<dealii::Functions::ConstantFunction<dim>>(test.p0)},
                  {top, std::make_shared<LinearInTime>(test.p0, q_rate)}};
  QuasiStaticSettings settings;
  settings.element_degree = 1;
  settings.newton.max_iterations = 12;
  settings.stepping.increment = 0.1;
  settings.stepping.minimum_increment = 1e-3;
  QuasiStaticSolver solver(mesh, mohr_coulomb_soil(test.phi, test.c, test.psi, 20e6, test.nu), bc, settings);
  solver.set_initial_stress([&](const Point<dim> &) { return test.confinement(); }, "confinement");
  try
    {
      solver.advance_to(1.0);
      ADD_FAILURE() << "the load beyond collapse was carried";
    }
  catch (const ConvergenceFailure &e)
    {
      const double collapse_time = 1.0 / 1.5;
      EXPECT_LE(e.last_converged_time(), collapse_time);
      EXPECT_GE(e.last_converged_time(), collapse_time - 2 * settings.stepping.minimum_increment);
      EXPECT_EQ(solver.time(), e.last_converged_time());
      EXPECT_NE(std::string(e.what()).find("collapse"), std::string::npos) << e.what();
      std::cout << "collapse: " << e.what() << std::endl;
    }
}

namespace
{
/// A 2 m x 1 m layer of soil (density 2000 kg/m^3) on a fixed base between smooth walls.
struct Layer
{
  double width = 2.0, height = 1.0, density = 2000.0, g = 9.81, E = 20e6, nu = 0.3, phi = 30.0;
  double unit_weight() const { return density * g; }
  BoundaryConditions supports() const
  {
    BoundaryConditions bc;
    bc.displacements = {{left, true, false, nullptr}, {right, true, false, nullptr}, {bottom, true, true, nullptr}};
    return bc;
  }
  GeostaticStress geostatic() const
  {
    GeostaticStress g0;
    g0.surface_elevation = height;
    g0.unit_weight = unit_weight();
    g0.k0 = 1 - std::sin(phi * pi / 180.0);
    return g0;
  }
  QuasiStaticSettings settings(unsigned int degree) const
  {
    QuasiStaticSettings s;
    s.element_degree = degree;
    s.density = density;
    s.newton.relative_tolerance = 1e-12;
    s.linear_solver.relative_tolerance = 1e-13;
    s.stepping.increment = 0.5;
    return s;
  }
};
} // namespace

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

// Bad input stops before anything is solved, naming what is wrong.
TEST(QuasiStatic, BadInputIsRefusedByName)
{
  auto expect_message = [](const std::function<void()> &f, const std::string &part) {
    try
      {
        f();
        ADD_FAILURE() << "accepted; expected an error mentioning " << part;
      }
    catch (const std::invalid_argument &e)
      {
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      }
  };
  const Layer layer;
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 2, 1, Point<dim>(0, 0), Point<dim>(2, 1));
  const SoilModel soil = mohr_coulomb_soil(30, 0, 0);

  BoundaryConditions unknown = layer.supports();
  unknown.displacements.push_back({7, true, true, nullptr});
  expect_message([&] { QuasiStaticSolver(mesh, soil, unknown, layer.settings(1)); }, "boundary id 7");
  BoundaryConditions wrong_components = layer.supports();
  wrong_components.pressures = {{top, std::make_shared<LinearInTime>(0.0, 1.0, 2)}};
  expect_message([&] { QuasiStaticSolver(mesh, soil, wrong_components, layer.settings(1)); }, "components");

  auto settings = layer.settings(1);
  settings.density = -1.0;
  expect_message([&] { QuasiStaticSolver(mesh, soil, layer.supports(), settings); }, "'density'");
  settings = layer.settings(1);
  settings.stepping.minimum_increment = 2 * settings.stepping.increment;
  expect_message([&] { QuasiStaticSolver(mesh, soil, layer.supports(), settings); }, "'minimum load increment'");
  settings = layer.settings(3);
  expect_message([&] { QuasiStaticSolver(mesh, soil, layer.supports(), settings); }, "'element degree'");

  // K0 = 4 puts sigma_h / sigma_v beyond the passive limit (1 + sin 30)/(1 - sin 30) = 3.
  QuasiStaticSolver solver(mesh, soil, layer.supports(), layer.settings(1));
  GeostaticStress too_high = layer.geostatic();
  too_high.k0 = 4.0;
  expect_message([&] { solver.set_initial_stress(too_high); }, "K0 = 4");
  too_high.k0 = -0.5;
  expect_message([&] { solver.set_initial_stress(too_high); }, "'K0'");

  // Material parameters are checked where the soil is built, before any solver exists.
  SoilParameters p;
  p.young_modulus = -5e6;
  expect_message([&] { SoilModel bad(p, "soil of the tank"); }, "'Young's modulus'");
  p.young_modulus = 5e6;
  p.strength.friction_angle_deg = 90.0;
  expect_message([&] { SoilModel bad(p, "soil of the tank"); }, "'friction angle'");
  p.strength.friction_angle_deg = 0.0;
  expect_message([&] { SoilModel bad(p, "soil of the tank"); }, "'friction angle'");
}

// The output is a VTU piece per rank plus a PVTU record with the fields ParaView needs.
TEST(QuasiStatic, WritesVtuForParaView)
{
  const geohybrid::testing::TemporaryDirectory directory("fem_vtu");
  const Layer layer;
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 4, 2, Point<dim>(0, 0), Point<dim>(layer.width, layer.height));
  QuasiStaticSolver solver(mesh, mohr_coulomb_soil(layer.phi, 0, 0), layer.supports(), layer.settings(2));
  solver.set_initial_stress(layer.geostatic());
  const std::string record = solver.write_vtu(directory.path.string(), "soil", 3);
  EXPECT_EQ(record, "soil_0003.pvtu");
  std::ifstream pvtu(directory.path / record);
  std::stringstream text;
  text << pvtu.rdbuf();
  EXPECT_NE(text.str().find("soil_0003.0.vtu"), std::string::npos);
  std::ifstream vtu(directory.path / "soil_0003.0.vtu");
  std::stringstream piece;
  piece << vtu.rdbuf();
  for (const char *field : {"displacement", "sigma_yy", "mean_pressure", "plastic_shear_strain", "yielded_fraction"})
    EXPECT_NE(piece.str().find(std::string("Name=\"") + field + "\""), std::string::npos) << field;
}
