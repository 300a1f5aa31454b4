// The explicit dynamic solver: the P-wave speed of an elastic bar, the static answer of the
// implicit solver reached by a damped explicit run, the stable step and the refusal of a larger
// one, and bad input.
#include "fem/explicit_solver.h"
#include "temporary_directory.h"
#include "test_fem_support.h"

#include <deal.II/base/function_lib.h>
#include <deal.II/dofs/dof_tools.h>
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

/// A load of `pressure` on the top face for x < `width`.
class StripPressure : public dealii::Function<dim>
{
public:
  StripPressure(double pressure, double width) : dealii::Function<dim>(1), pressure_(pressure), width_(width) {}
  double value(const Point<dim> &x, unsigned int) const override { return x[0] < width_ ? pressure_ : 0.0; }

private:
  double pressure_, width_;
};
/// The layer's mesh: `nx_q1` x nx_q1 / 2 Q1 cells, or half as many Q2 cells (the same nodes).
void make_layer_mesh(Mesh &mesh, const Layer &layer, unsigned int degree, unsigned int nx_q1)
{
  const unsigned int nx = degree == 1 ? nx_q1 : nx_q1 / 2;
  make_rectangle(mesh, nx, nx / 2, Point<dim>(0, 0), Point<dim>(layer.width, layer.height));
}

/// The layer's supports with `pressure` on the top face over x < 0.5 m [Pa].
BoundaryConditions strip_loaded_layer(const Layer &layer, double pressure)
{
  BoundaryConditions bc = layer.supports();
  bc.pressures = {{top, std::make_shared<StripPressure>(pressure, 0.5)}};
  return bc;
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

// The coupling's hooks (issue 6): an energy weight w(x) multiplies the lumped mass and the
// internal force at every quadrature point. A uniform weight halves both and leaves the stable
// step as it was; a weight that reaches 0 on a whole cell leaves its nodes without mass (refused).
// An initial displacement u = G x gives the internal force of the uniform stress C : G.
// Damping leaves exempt DoFs alone (a coupling's tied nodes): a free block falls from rest under
// gravity with local and mass-proportional damping; with every DoF exempt it falls freely (v = g t
// at the half steps, central differences being exact for a constant force), with none it falls slower.
TEST(ExplicitSolver, UndampedDofsFallFreely)
{
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 2, 2, Point<dim>(0, 0), Point<dim>(0.2, 0.2));
  ExplicitSettings settings;
  settings.density = 2000.0;
  settings.gravity[1] = -9.81;
  settings.damping.local = 0.7;
  settings.damping.mass_proportional = 50.0;
  ExplicitSolver exempt(mesh, elastic_soil(10e6, 0.25), BoundaryConditions{}, settings);
  ExplicitSolver damped(mesh, elastic_soil(10e6, 0.25), BoundaryConditions{}, settings);
  std::vector<unsigned int> all(exempt.velocity().locally_owned_size());
  for (unsigned int i = 0; i < all.size(); ++i)
    all[i] = i;
  exempt.set_undamped_dofs(all);
  for (int n = 0; n < 50; ++n)
    {
      exempt.step();
      damped.step();
    }
  const double t = exempt.time() - 0.5 * exempt.time_step(); // of the half-step velocity
  // The x-DoFs stay at rest; the most negative velocity is a y-DoF's (all equal for a free fall).
  double vy_exempt = 0.0, vy_damped = 0.0;
  for (unsigned int i = 0; i < all.size(); ++i)
    {
      vy_exempt = std::min(vy_exempt, exempt.velocity().local_element(i));
      vy_damped = std::min(vy_damped, damped.velocity().local_element(i));
    }
  EXPECT_NEAR(vy_exempt, -9.81 * t, 1e-10);
  EXPECT_GT(vy_damped, -0.5 * 9.81 * t);
  // The energy ledger: no strain and no damping on the exempt block, so the weight's work is the
  // kinetic energy gained, 1/2 m (g t)^2; damped, the damping takes its share and it still closes.
  const double closed_form = 0.5 * (2000.0 * 0.2 * 0.2) * 9.81 * t * 9.81 * t;
  const ExplicitEnergyLedger free = exempt.energy_ledger(), slowed = damped.energy_ledger();
  EXPECT_NEAR(free.kinetic, closed_form, 1e-10 * closed_form);
  EXPECT_NEAR(free.gravity_work, closed_form, 1e-10 * closed_form);
  EXPECT_EQ(free.damping_work, 0.0);
  EXPECT_LT(std::abs(free.internal_work), 1e-10 * closed_form);
  EXPECT_GT(slowed.damping_work, 0.1 * slowed.gravity_work);
  EXPECT_LT(slowed.kinetic, 0.5 * closed_form);
  EXPECT_LT(std::abs(slowed.balance()), 1e-12 * slowed.gravity_work);
  EXPECT_THROW(exempt.set_undamped_dofs({static_cast<unsigned int>(all.size())}), std::invalid_argument);
}

// The energy ledger (ExplicitEnergyLedger) against closed forms. A linear elastic layer loaded from
// rest, without initial stress, by constant forces (its weight, a strip pressure and a point force
// added through add_external_force at every step) and damped to rest:
// - the internal work is the elastic energy 1/2 u . f_int, whatever the path (the physics);
// - a constant force's work is f . (u_N + u_N-1) / 2 - f . u_1 / 4: the telescoped sum of
//   f . dt (v_n-1/2 + v_n+1/2) / 2 over the steps, the first a half step from rest. It is f . u_N
//   but for the start-up term, large here (the point force kicks its node by u_1 = 0.27 u_N in the
//   first step: 7 % of its work), O(dt^2) for a smooth load;
// - the damping took the rest, and the terms add up to round-off.
TEST(ExplicitSolver, EnergyLedgerOfALayerDampedToRest)
{
  const Layer layer;
  Mesh mesh(MPI_COMM_WORLD);
  make_layer_mesh(mesh, layer, 1, 16);
  ExplicitSettings settings;
  settings.density = layer.density;
  settings.gravity = QuasiStaticSettings::gravity_down();
  settings.damping.local = 0.5;
  settings.damping.mass_proportional = 20.0;
  ExplicitSolver solver(mesh, elastic_soil(layer.E, layer.nu), strip_loaded_layer(layer, 50e3), settings);
  // The point force: 20 kN/m pulling up one y DoF of the top face (free: the sides hold x only).
  const auto &owned = solver.space().locally_owned_dofs();
  unsigned int loaded = 0;
  {
    const dealii::IndexSet top_y = dealii::DoFTools::extract_boundary_dofs(
      solver.space().dof_handler(), dealii::ComponentMask(std::vector<bool>{false, true}), {top});
    loaded = owned.index_within_set(*top_y.begin());
    ASSERT_FALSE(solver.is_constrained(loaded));
  }
  const double point_force = 20e3;
  ExplicitSolver::Vector u_first, u_before_last;
  for (;;)
    {
      // Added for the next step, which the out-of-balance ratio then sees too.
      solver.add_external_force(loaded, point_force);
      if (solver.n_steps() >= 20000 || (solver.n_steps() >= 10 && solver.out_of_balance_ratio() < 1e-10))
        break;
      u_before_last = solver.displacement();
      solver.step();
      if (solver.n_steps() == 1)
        u_first = solver.displacement();
    }
  ASSERT_LT(solver.out_of_balance_ratio(), 1e-10);

  // Closed forms: the body force is g times the lumped mass (row sums of the consistent mass with
  // rho g constant); the pressure's nodal load is f_ext - rho g - the point force.
  const auto &u = solver.displacement(), &M = solver.lumped_mass(), &f_ext = solver.external_force(),
             &f_int = solver.internal_force();
  const dealii::IndexSet y_dofs = dealii::DoFTools::extract_dofs(solver.space().dof_handler(),
                                                                 dealii::ComponentMask(std::vector<bool>{false, true}));
  const auto path = [&](unsigned int i) {
    return 0.5 * (u.local_element(i) + u_before_last.local_element(i)) - 0.25 * u_first.local_element(i);
  };
  double gravity_work = 0.0, load_work = 0.0, elastic = 0.0;
  for (unsigned int i = 0; i < u.locally_owned_size(); ++i)
    {
      if (solver.is_constrained(i))
        continue;
      const double body = y_dofs.is_element(owned.nth_index_in_set(i)) ? -layer.g * M.local_element(i) : 0.0;
      const double load = f_ext.local_element(i) - body - (i == loaded ? point_force : 0.0);
      gravity_work += body * path(i);
      load_work += load * path(i);
      elastic += 0.5 * u.local_element(i) * f_int.local_element(i);
    }
  const double added_work = point_force * path(loaded);
  const ExplicitEnergyLedger ledger = solver.energy_ledger();
  const double supplied = ledger.gravity_work + ledger.load_work + ledger.added_force_work;
  std::cout << "layer damped to rest in " << solver.n_steps() << " steps: gravity work " << ledger.gravity_work
            << " J/m (closed form " << gravity_work << "), load " << ledger.load_work << " (" << load_work
            << "), point force " << ledger.added_force_work << " (" << added_work << "; f u_N "
            << point_force * u.local_element(loaded) << "), internal " << ledger.internal_work << " (1/2 u.f_int "
            << elastic << "), damping " << ledger.damping_work << ", kinetic " << ledger.kinetic << ", balance "
            << ledger.balance() << std::endl;
  EXPECT_GT(ledger.gravity_work, 0.0);
  EXPECT_GT(ledger.load_work, 0.0);
  EXPECT_GT(ledger.added_force_work, 0.0);
  EXPECT_NEAR(ledger.gravity_work, gravity_work, 1e-9 * gravity_work);
  EXPECT_NEAR(ledger.load_work, load_work, 1e-9 * load_work);
  EXPECT_NEAR(ledger.added_force_work, added_work, 1e-9 * added_work);
  EXPECT_NEAR(ledger.internal_work, elastic, 1e-6 * elastic);
  EXPECT_GT(ledger.damping_work, 0.3 * supplied);
  EXPECT_EQ(ledger.initial_kinetic, 0.0);
  EXPECT_LT(ledger.kinetic, 1e-15 * supplied);
  EXPECT_LT(std::abs(ledger.balance()), 1e-12 * supplied);
}

TEST(ExplicitSolver, EnergyWeightScalesMassAndInternalForce)
{
  const double E = 10e6, nu = 0.25, rho = 2000.0;
  Mesh mesh(MPI_COMM_WORLD);
  make_rectangle(mesh, 4, 3, Point<dim>(0, 0), Point<dim>(0.4, 0.3));
  ExplicitSettings settings;
  settings.density = rho;
  ExplicitSolver plain(mesh, elastic_soil(E, nu), BoundaryConditions{}, settings);
  ExplicitSolver half(mesh, elastic_soil(E, nu), BoundaryConditions{}, settings);
  half.set_energy_weight([](const Point<dim> &) { return 0.5; });
  EXPECT_NEAR(half.critical_time_step(), plain.critical_time_step(), 1e-12 * plain.critical_time_step());
  class Affine : public dealii::Function<dim>
  {
  public:
    Affine() : dealii::Function<dim>(dim) {}
    double value(const Point<dim> &x, unsigned int c) const override
    {
      return c == 0 ? 1e-4 * x[0] + 2e-4 * x[1] : -3e-4 * x[1];
    }
  };
  plain.set_initial_displacement(Affine());
  half.set_initial_displacement(Affine());
  double largest = 0.0;
  for (unsigned int i = 0; i < plain.lumped_mass().locally_owned_size(); ++i)
    {
      EXPECT_NEAR(half.lumped_mass().local_element(i), 0.5 * plain.lumped_mass().local_element(i),
                  1e-14 * plain.lumped_mass().local_element(i));
      EXPECT_NEAR(half.internal_force().local_element(i), 0.5 * plain.internal_force().local_element(i),
                  1e-12 * std::abs(plain.internal_force().local_element(i)) + 1e-9);
      largest = std::max(largest, std::abs(plain.internal_force().local_element(i)));
    }
  // Uniform stress: the forces are tractions on the boundary only; the corner force of the x-DoF
  // at the origin is -(sigma_xx h_y + sigma_xy h_x) / 2 with h = 0.1 m (the integral of dN/dx over
  // its cell is -h_y / 2).
  ASSERT_GT(largest, 0.0);
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const double exx = 1e-4, eyy = -3e-4, exy = 1e-4;
  const double sxx = lambda * (exx + eyy) + 2 * mu * exx, sxy = 2 * mu * exy;
  const auto &dofs = plain.space().dof_handler();
  for (const auto &cell : dofs.active_cell_iterators())
    for (unsigned int v = 0; v < 4; ++v)
      if (cell->vertex(v).norm() < 1e-12)
        {
          const auto dof = cell->vertex_dof_index(v, 0);
          EXPECT_NEAR(plain.internal_force()[dof], -(sxx * 0.1 + sxy * 0.1) / 2.0, 1e-9 * (std::abs(sxx) + std::abs(sxy)));
        }
  ExplicitSolver cut(mesh, elastic_soil(E, nu), BoundaryConditions{}, settings);
  EXPECT_THROW(cut.set_energy_weight([](const Point<dim> &x) { return x[0] < 0.1 ? 0.0 : 1.0; }), std::invalid_argument);
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

      ExplicitSettings settings;
      settings.element_degree = degree;
      settings.density = layer.density;
      settings.gravity = QuasiStaticSettings::gravity_down();
      settings.damping.local = 0.7;
      ExplicitSolver solver(mesh, soil, bc, settings);
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
          ExplicitSettings settings;
          settings.element_degree = degree;
          settings.density = layer.density;
          settings.gravity = QuasiStaticSettings::gravity_down();
          settings.damping.local = 0.7;
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
  ExplicitSettings settings;
  settings.density = layer.density;
  settings.gravity = QuasiStaticSettings::gravity_down();
  settings.damping.local = 0.7;
  ExplicitSolver solver(mesh, elastic_soil(layer.E, layer.nu), layer.supports(), settings);
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
