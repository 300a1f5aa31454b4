// The implicit quasi-static solver with Mohr-Coulomb soil: a biaxial element test reaching the
// limit, the collapse load found by step cutback; and the solver's input checks and VTU output.
#include "temporary_directory.h"
#include "test_fem_support.h"

#include <deal.II/base/function_lib.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace geohybrid::fem;
using namespace geohybrid::fem::testing;

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
      // The solver still holds the last equilibrium: the top carries the load of that time.
      const double top_load = test.p0 + q_rate * solver.time();
      EXPECT_NEAR(solver.boundary_reaction(bottom)[1], top_load, 1e-6 * top_load);
      EXPECT_NE(std::string(e.what()).find("collapse"), std::string::npos) << e.what();
      std::cout << "collapse: " << e.what() << std::endl;
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
