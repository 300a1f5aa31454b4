// The geosynthetic sheet in the continuum: the tension-only truss (elongation T L / J, nothing in
// compression or rigid rotation), and a sheet pulled out of an elastic block pressed from above,
// whose interface limit is T_max = 2 sigma_v tan(delta) L (both faces).
#include "fem/explicit_solver.h"
#include "fem/truss_sheet.h"
#include "test_fem_support.h"

#include <deal.II/base/function_lib.h>

#include <gtest/gtest.h>

#include <iostream>

using namespace geohybrid::fem;
using namespace geohybrid::fem::testing;
using Force = dealii::Tensor<1, dim>;

TEST(TrussSheet, ElongatesByTLOverJAndCarriesNothingInCompression)
{
  TrussSheetParameters parameters;
  parameters.axial_stiffness = 687e3; // GT75
  const double L = 0.4, angle = 0.5, delta = 2e-3;
  const Force axis({std::cos(angle), std::sin(angle)});
  const TrussSheet sheet({Point<dim>(0.1, 0.2), Point<dim>(0.1, 0.2) + L * axis}, parameters);
  EXPECT_DOUBLE_EQ(sheet.tributary_length(0), 0.5 * L);

  // Stretched along its axis by delta: T = J delta / L, pulling the nodes together.
  std::vector<Force> u{Force(), delta * axis};
  EXPECT_NEAR(sheet.axial_forces(u)[0], 687e3 * delta / L, 1e-9 * 687e3 * delta / L);
  const auto forces = sheet.nodal_forces(u);
  EXPECT_NEAR((forces[0] - 687e3 * delta / L * axis).norm(), 0.0, 1e-9);
  EXPECT_NEAR((forces[1] + forces[0]).norm(), 0.0, 1e-12);

  // Shortened: slack, no force.
  u[1] = -delta * axis;
  EXPECT_EQ(sheet.axial_forces(u)[0], 0.0);
  EXPECT_EQ(sheet.nodal_forces(u)[1].norm(), 0.0);

  // A rigid rotation by 30 degrees about node 0 does not stretch it.
  const double r = pi / 6;
  const Force rotated({std::cos(angle + r), std::sin(angle + r)});
  u[1] = L * (rotated - axis);
  EXPECT_LT(sheet.axial_forces(u)[0], 1e-9 * 687e3);

  TrussSheetParameters bad = parameters;
  bad.axial_stiffness = -1.0;
  EXPECT_THROW(TrussSheet({Point<dim>(0, 0), Point<dim>(1, 0)}, bad), std::invalid_argument);
  try
    {
      TrussSheet({Point<dim>(0, 0), Point<dim>(0, 0)}, parameters, "sheet 'GT75'");
      FAIL();
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("sheet 'GT75'"), std::string::npos) << e.what();
    }
}

namespace
{
/// A 0.6 m x 0.4 m elastic block, pressed by sigma_v on top, on a fixed base between smooth walls,
/// at its (uniform) initial stress, with a sheet across it from wall to wall at mid-height of a row
/// of cells, clamped at the left wall. The shear the sheet puts into the soil changes sigma_yy
/// along it, but with smooth walls at both of its ends the vertical equilibrium of the soil above
/// any level still gives a mean sigma_yy of -sigma_v over the sheet's length, and the interface
/// limit is linear in sigma_n: the pull-out force is 2 sigma_v tan(delta) L however the stress
/// redistributes (a sheet ending inside the soil would not have that property: its end carries
/// shear into the soil beyond it, and the mean normal stress on it is not sigma_v).
struct PulloutBlock
{
  double sigma_v = 50e3, length = 0.6, E = 20e6, nu = 0.3, y_sheet = 0.175;
  Mesh mesh{MPI_COMM_WORLD};
  std::unique_ptr<ExplicitSolver> solver;

  explicit PulloutBlock(double pull_rate, double mass_scaling)
  {
    make_rectangle(mesh, 12, 8, Point<dim>(0, 0), Point<dim>(length, 0.4));
    BoundaryConditions bc;
    bc.displacements = {{bottom, true, true, nullptr}, {left, true, false, nullptr}, {right, true, false, nullptr}};
    bc.pressures = {{top, std::make_shared<dealii::Functions::ConstantFunction<dim>>(sigma_v)}};
    ExplicitSettings settings;
    settings.density = 2000.0;
    settings.damping.local = 0.7;
    solver = std::make_unique<ExplicitSolver>(mesh, elastic_soil(E, nu), bc, settings);
    const double k0 = nu / (1 - nu);
    solver->set_initial_stress(
      [&](const Point<dim> &) {
        StressTensor s;
        s[1][1] = -sigma_v;
        s[0][0] = s[2][2] = -k0 * sigma_v;
        return s;
      },
      "the uniform stress under the surcharge");
    TrussSheetParameters sheet;
    sheet.mass_scaling = mass_scaling;
    std::vector<Point<dim>> nodes;
    for (unsigned int k = 0; k <= 24; ++k)
      nodes.emplace_back(length * k / 24.0, y_sheet);
    solver->attach_sheet(TrussSheet(nodes, sheet),
                         {{0, [pull_rate](double t) { return Force({-pull_rate * t, 0.0}); }}});
  }
};
} // namespace

TEST(SheetInterface, UnstableSheetNodesAskForMassScaling)
{
  try
    {
      PulloutBlock block(0.01, 1.0);
      FAIL() << "an unstable sheet was accepted";
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("'mass scaling'"), std::string::npos) << e.what();
    }
}

// Pulled 12 mm at 4 mm/s with local damping: the clamp force rises while the sheet stretches and
// the interface yields from the clamp inwards, then stays at 2 sigma_v tan(delta) L. The
// resistance of the interface (the sum of its forces on the sheet) sits at that limit; the clamp
// force carries besides the dynamics of the mass-scaled sheet (the local damping resists the
// sheet's steady sliding whenever its nodes oscillate), +-2 % from step to step, so it is compared
// as its mean over the sliding phase.
TEST(SheetInterface, PulloutReachesTheInterfaceLimit)
{
  PulloutBlock block(0.004, 3000.0);
  const double expected = 2.0 * block.sigma_v * std::tan(degrees_to_radians(25.6)) * block.length;
  const auto &sheet = *block.solver->sheet();
  std::vector<double> forces;
  double clamp_sum = 0.0, resistance_sum = 0.0, n_sliding = 0.0;
  for (unsigned int stage = 1; stage <= 10; ++stage)
    {
      while (block.solver->time() < 0.3 * stage - 1e-9)
        {
          block.solver->step();
          if (stage > 6) // from 7.2 mm on: sliding everywhere
            {
              clamp_sum += -sheet.clamp_force(0)[0];
              resistance_sum += sheet.interface_resultant()[0];
              n_sliding += 1.0;
            }
        }
      forces.push_back(-sheet.clamp_force(0)[0]);
    }
  const double mean_clamp = clamp_sum / n_sliding, mean_resistance = resistance_sum / n_sliding;
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::cout << "pull-out: clamp force every 1.2 mm:";
      for (const double f : forces)
        std::cout << " " << f;
      std::cout << " N/m; mean over the sliding phase " << mean_clamp << " N/m, interface resistance "
                << mean_resistance << " N/m; T_max = 2 sigma_v tan(delta) L = " << expected << " N/m; "
                << block.solver->n_steps() << " steps; far-end slip " << sheet.displacements().back()[0] << " m"
                << std::endl;
    }
  EXPECT_NEAR(mean_resistance, expected, 0.02 * expected);
  EXPECT_NEAR(mean_clamp, expected, 0.02 * expected);
  // Before sliding (2.4 mm), the force is well below the limit: the test sees the rise, not only
  // a constant.
  EXPECT_LT(forces[1], 0.8 * expected);
  // Sliding everywhere: the far end moved.
  EXPECT_LT(sheet.displacements().back()[0], -1e-3);
  // The first segment carries the clamp force, less node 0's share of the interface.
  EXPECT_NEAR(sheet.axial_forces()[0], forces.back(), 0.05 * expected);
}
