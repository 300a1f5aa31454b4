// The explicit dynamic solver: the P-wave speed of an elastic bar, the static answer of the
// implicit solver reached by a damped explicit run, the stable step and the refusal of a larger
// one, threads, VTU output, and bad input. Its energy ledger and the coupling's hooks (energy
// weights, undamped DoFs): test_fem_explicit_energy.cc.
#include "fem/explicit_solver.h"
#include "temporary_directory.h"
#include "test_fem_support.h"

#include <deal.II/base/function_lib.h>
#include <deal.II/dofs/dof_tools.h>

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <iostream>

using namespace geohybrid::fem;
using namespace geohybrid::fem::testing;

namespace
{
/// v_x = V sin(pi x / (2 L)): the first mode of a bar fixed at x = 0 and free at x = L.
class FirstModeVelocity : public dealii::Function<dim>
{
public:
  FirstModeVelocity(double amplitude, double length) : dealii::Function<dim>(dim), amplitude_(amplitude), length_(length) {}
  double value(const Point<dim> &x, unsigned int c) const override
  {
    return c == 0 ? amplitude_ * std::sin(pi * x[0] / (2.0 * length_)) : 0.0;
  }

private:
  double amplitude_, length_;
};

/// The mean x-displacement of the DoFs on boundary `id` (the free end of the bar). Collective.
double mean_x_displacement(const ExplicitSolver &solver, const dealii::IndexSet &end_x_dofs)
{
  double sum = 0.0, n = 0.0;
  const auto &owned = solver.space().locally_owned_dofs();
  for (const auto dof : end_x_dofs)
    if (owned.is_element(dof))
      {
        sum += solver.displacement()[dof];
        n += 1.0;
      }
  return dealii::Utilities::MPI::sum(sum, MPI_COMM_WORLD) / dealii::Utilities::MPI::sum(n, MPI_COMM_WORLD);
}

/// The period of the free end's oscillation, from its zero crossings (linear interpolation
/// between steps), for a bar of length 1 m in 100 cells of degree `degree`.
struct BarResult
{
  double period, stable_step, n_steps;
};
BarResult bar_period(unsigned int degree, double E, double rho)
{
  const double L = 1.0, h = 0.01;
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, degree == 1 ? 100 : 50, 1, Point<dim>(0, 0), Point<dim>(L, degree == 1 ? h : 2 * h));
  BoundaryConditions bc;
  // Fixed end, and rollers above and below: a 1D bar (every node is on the top or bottom face).
  bc.displacements = {{left, true, true, nullptr}, {bottom, false, true, nullptr}, {top, false, true, nullptr}};
  ExplicitSettings settings;
  settings.element_degree = degree;
  settings.density = rho;
  ExplicitSolver solver(mesh, elastic_soil(E, 0.0), bc, settings);
  solver.set_initial_velocity(FirstModeVelocity(0.01, L));
  const dealii::IndexSet end_x_dofs = dealii::DoFTools::extract_boundary_dofs(
    solver.space().dof_handler(), dealii::ComponentMask(std::vector<bool>{true, false}), {right});

  const double c = std::sqrt(E / rho), expected_period = 4.0 * L / c;
  std::vector<double> crossings;
  double previous = mean_x_displacement(solver, end_x_dofs), previous_time = 0.0;
  while (solver.time() < 2.3 * expected_period)
    {
      solver.step();
      const double now = mean_x_displacement(solver, end_x_dofs);
      if (solver.n_steps() > 1 && (previous > 0.0) != (now > 0.0))
        crossings.push_back(previous_time + (solver.time() - previous_time) * previous / (previous - now));
      previous = now;
      previous_time = solver.time();
    }
  EXPECT_EQ(crossings.size(), 4u); // T/2, T, 3T/2, 2T
  return {(crossings.back() - crossings.front()) / (0.5 * (crossings.size() - 1)), solver.stable_time_step(),
          static_cast<double>(solver.n_steps())};
}

/// The explicit solver's settings for the layer under its weight, damped locally (0.7).
ExplicitSettings damped_layer_settings(const Layer &layer, unsigned int degree = 1)
{
  ExplicitSettings settings;
  settings.element_degree = degree;
  settings.density = layer.density;
  settings.gravity = QuasiStaticSettings::gravity_down();
  settings.damping.local = 0.7;
  return settings;
}
} // namespace

// Central differences with a lumped mass on a bar (nu = 0 in plane strain: the P-wave modulus is E)
// set vibrating in its first mode: period 4 L / c with c = sqrt(E / rho).
TEST(ExplicitSolver, BarVibratesWithThePWaveSpeed)
{
  const double E = 10e6, rho = 2000.0, c = std::sqrt(E / rho), L = 1.0;
  for (const unsigned int degree : {1u, 2u})
    {
      const BarResult bar = bar_period(degree, E, rho);
      const double measured_speed = 4.0 * L / bar.period;
      std::cout << "Q" << degree << " bar: wave speed " << measured_speed << " m/s against sqrt(E/rho) = " << c
                << " m/s (relative error " << (measured_speed - c) / c << "), stable step " << bar.stable_step
                << " s (h/c = " << 0.01 / c << " s), " << bar.n_steps << " steps" << std::endl;
      EXPECT_NEAR(measured_speed, c, 0.01 * c);
    }
}

// Mass-proportional damping alpha on the same bar: the free end's amplitude decays as
// exp(-alpha t / 2), here measured between two maxima one damped period apart.
TEST(ExplicitSolver, MassProportionalDampingDecaysAsExpMinusAlphaTOverTwo)
{
  const double E = 10e6, rho = 2000.0, L = 1.0, alpha = 20.0;
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 100, 1, Point<dim>(0, 0), Point<dim>(L, 0.01));
  BoundaryConditions bc;
  bc.displacements = {{left, true, true, nullptr}, {bottom, false, true, nullptr}, {top, false, true, nullptr}};
  ExplicitSettings settings;
  settings.density = rho;
  settings.damping.mass_proportional = alpha;
  ExplicitSolver solver(mesh, elastic_soil(E, 0.0), bc, settings);
  solver.set_initial_velocity(FirstModeVelocity(0.01, L));
  const dealii::IndexSet end_x_dofs = dealii::DoFTools::extract_boundary_dofs(
    solver.space().dof_handler(), dealii::ComponentMask(std::vector<bool>{true, false}), {right});
  // Maxima of u(L, t), refined by a parabola through the three samples around each.
  std::vector<std::pair<double, double>> maxima; // (time, value)
  double u_2 = 0.0, u_1 = mean_x_displacement(solver, end_x_dofs);
  const double period = 4.0 * L / std::sqrt(E / rho);
  while (solver.time() < 2.2 * period)
    {
      solver.step();
      const double u = mean_x_displacement(solver, end_x_dofs), dt = solver.time_step();
      if (solver.n_steps() > 2 && u_1 > u_2 && u_1 >= u)
        {
          const double curvature = u - 2 * u_1 + u_2, slope = 0.5 * (u - u_2);
          maxima.emplace_back(solver.time() - dt - dt * slope / curvature, u_1 - 0.5 * slope * slope / curvature);
        }
      u_2 = u_1;
      u_1 = u;
    }
  ASSERT_GE(maxima.size(), 2u);
  const double measured = -2.0 * std::log(maxima[1].second / maxima[0].second) / (maxima[1].first - maxima[0].first);
  std::cout << std::setprecision(8) << "mass-proportional damping: decay rate " << measured << " 1/s against alpha = " << alpha << " 1/s"
            << std::endl;
  EXPECT_NEAR(measured, alpha, 0.01 * alpha);
}

// The stable step of the Q1 bar is the 1D bound h / c times the safety factor when the cells are
// long in the other direction (the element's largest frequency is then its axial one), and a
// larger user step is refused with the parameter's name.
TEST(ExplicitSolver, StableStepIsTheCourantBoundAndLargerStepsAreRefused)
{
  const double E = 10e6, rho = 2000.0, c = std::sqrt(E / rho), h = 0.01;
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 10, 1, Point<dim>(0, 0), Point<dim>(10 * h, 0.5));
  BoundaryConditions bc;
  bc.displacements = {{left, true, true, nullptr}};
  ExplicitSettings settings;
  settings.density = rho;
  settings.safety_factor = 0.9;
  const ExplicitSolver solver(mesh, elastic_soil(E, 0.0), bc, settings);
  // Thin cells (h x 50 h): the axial mode dominates; its frequency is 2 c / h up to the small
  // coupling with the transverse direction.
  EXPECT_NEAR(solver.critical_time_step(), h / c, 0.01 * h / c);
  EXPECT_DOUBLE_EQ(solver.time_step(), 0.9 * solver.critical_time_step());

  settings.time_step = 1.01 * solver.stable_time_step();
  try
    {
      ExplicitSolver too_large(mesh, elastic_soil(E, 0.0), bc, settings);
      FAIL() << "a step above the stable one was accepted";
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("'time step'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("stable step"), std::string::npos) << e.what();
    }
  settings.time_step = 0.99 * solver.stable_time_step();
  EXPECT_NO_THROW(ExplicitSolver(mesh, elastic_soil(E, 0.0), bc, settings));
}

TEST(ExplicitSolver, BadSettingsNameTheParameter)
{
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 2, 2, Point<dim>(0, 0), Point<dim>(1, 1));
  BoundaryConditions bc;
  bc.displacements = {{bottom, true, true, nullptr}};
  auto message = [&](const ExplicitSettings &s) {
    try
      {
        ExplicitSolver solver(mesh, elastic_soil(), bc, s);
      }
    catch (const std::invalid_argument &e)
      {
        return std::string(e.what());
      }
    return std::string("accepted");
  };
  ExplicitSettings s;
  EXPECT_NE(message(s).find("'density'"), std::string::npos); // zero density: no dynamics
  s.density = 2000.0;
  s.damping.local = 1.0;
  EXPECT_NE(message(s).find("'local damping'"), std::string::npos);
  s.damping.local = 0.7;
  s.damping.mass_proportional = -1.0;
  EXPECT_NE(message(s).find("'mass-proportional damping'"), std::string::npos);
  s.damping.mass_proportional = 0.0;
  s.safety_factor = 1.5;
  EXPECT_NE(message(s).find("'safety factor'"), std::string::npos);
  s.safety_factor = 0.8;
  EXPECT_EQ(message(s), "accepted");
  bc.displacements = {{7, true, true, nullptr}};
  EXPECT_NE(message(s).find("boundary id 7"), std::string::npos);
}

// A layer under its own weight and a strip load, both applied at once, comes to rest under local
// damping at the implicit solver's static displacement (Q1 and Q2, the same mesh and DoFs).
TEST(ExplicitSolver, DampedRunReachesTheImplicitStaticSolution)
{
  for (const unsigned int degree : {1u, 2u})
    {
      const Layer layer;
      Mesh mesh(MPI_COMM_WORLD);
      make_layer_mesh(mesh, layer, degree, 16);
      const BoundaryConditions bc = strip_loaded_layer(layer, 50e3);
      const SoilModel soil = elastic_soil(layer.E, layer.nu);

      QuasiStaticSettings implicit_settings = layer.settings(degree);
      implicit_settings.stepping.increment = 1.0;
      QuasiStaticSolver implicit(mesh, soil, bc, implicit_settings);
      implicit.advance_to(1.0);

      ExplicitSolver solver(mesh, soil, bc, damped_layer_settings(layer, degree));
      const auto start = std::chrono::steady_clock::now();
      while (solver.n_steps() < 20000 && (solver.n_steps() < 10 || solver.out_of_balance_ratio() > 1e-9))
        solver.step();
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

      const auto &owned = solver.space().locally_owned_dofs();
      double difference = 0.0, largest = 0.0;
      for (const auto i : owned)
        {
          difference = std::max(difference, std::abs(solver.displacement()[i] - implicit.displacement()[i]));
          largest = std::max(largest, std::abs(implicit.displacement()[i]));
        }
      difference = dealii::Utilities::MPI::max(difference, MPI_COMM_WORLD);
      largest = dealii::Utilities::MPI::max(largest, MPI_COMM_WORLD);
      const auto reaction_explicit = solver.boundary_reaction(bottom), reaction_implicit = implicit.boundary_reaction(bottom);
      std::cout << "Q" << degree << " damped explicit: " << solver.n_steps() << " steps of " << solver.time_step()
                << " s to out-of-balance ratio " << solver.out_of_balance_ratio() << ", max |u - u_implicit| "
                << difference << " m of max |u| " << largest << " m; base reaction " << reaction_explicit[1]
                << " N/m (implicit " << reaction_implicit[1] << "); "
                << 1e6 * seconds / (solver.n_steps() * mesh.n_active_cells()) << " us per step per cell" << std::endl;
      EXPECT_LT(solver.out_of_balance_ratio(), 1e-9);
      EXPECT_LT(difference, 1e-6 * largest);
      EXPECT_NEAR(reaction_explicit[1], reaction_implicit[1], 1e-6 * std::abs(reaction_implicit[1]));
    }
}

// The cells' internal force on two threads: the same numbers to the bit as on one (the cells are
// coloured, each DoF sums its cells colour by colour), on a Mohr-Coulomb layer yielding under a
// strip load, Q1 and Q2.
TEST(ExplicitSolver, TwoThreadsGiveTheSameBitsAsOne)
{
  for (const unsigned int degree : {1u, 2u})
    {
      const Layer layer;
      Mesh mesh(MPI_COMM_WORLD);
      make_layer_mesh(mesh, layer, degree, 24);
      const BoundaryConditions bc = strip_loaded_layer(layer, 400e3);
      const SoilModel soil = mohr_coulomb_soil(30.0, 5e3, 0.0, layer.E, layer.nu);
      std::vector<ExplicitSolver::Vector> displacements;
      std::vector<double> plastic;
      for (const unsigned int threads : {1u, 2u})
        {
          ExplicitSettings settings = damped_layer_settings(layer, degree);
          settings.n_threads = threads;
          ExplicitSolver solver(mesh, soil, bc, settings);
          for (unsigned int n = 0; n < 400; ++n)
            solver.step();
          displacements.emplace_back(solver.displacement());
          double largest_plastic = 0.0;
          for (const auto &cell : solver.space().dof_handler().active_cell_iterators())
            if (cell->is_locally_owned())
              for (const auto &point : solver.material_points().at(cell))
                largest_plastic = std::max(largest_plastic, point->plastic_strain.norm());
          plastic.push_back(largest_plastic);
        }
      std::cout << "Q" << degree << ": largest plastic strain " << plastic[0] << std::endl;
      EXPECT_GT(plastic[0], 1e-6); // the layer yields: the return mapping runs on both threads
      EXPECT_EQ(plastic[0], plastic[1]);
      for (const auto i : displacements[0].locally_owned_elements())
        ASSERT_EQ(displacements[0][i], displacements[1][i]) << "DoF " << i << ", Q" << degree;
    }
}

// The explicit solver writes its state for ParaView: a PVTU record and this rank's piece, with the
// displacement and the stresses (the values are base64 data; write_soil_vtu is shared with the
// implicit solver).
TEST(ExplicitSolver, WritesTheDisplacementToVtu)
{
  geohybrid::testing::TemporaryDirectory directory("fem_explicit_vtu");
  const Layer layer;
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 8, 4, Point<dim>(0, 0), Point<dim>(layer.width, layer.height));
  ExplicitSolver solver(mesh, elastic_soil(layer.E, layer.nu), layer.supports(), damped_layer_settings(layer));
  for (unsigned int i = 0; i < 50; ++i)
    solver.step();
  const std::string record = solver.write_vtu(directory.path.string(), "layer", 3);
  EXPECT_EQ(record, "layer_0003.pvtu");
  std::ifstream vtu(directory.path / "layer_0003.0.vtu");
  ASSERT_TRUE(vtu.good());
  std::stringstream text;
  text << vtu.rdbuf();
  EXPECT_NE(text.str().find("Name=\"displacement\""), std::string::npos);
  EXPECT_NE(text.str().find("Name=\"sigma_yy\""), std::string::npos);
}
