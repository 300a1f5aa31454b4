// The explicit solver's energy ledger (ExplicitEnergyLedger) against closed forms, and the hooks
// a coupling uses (issue 6): energy weights on the mass and the internal force, and DoFs the
// damping leaves alone.
#include "fem/explicit_solver.h"
#include "test_fem_support.h"

#include <deal.II/dofs/dof_tools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace geohybrid::fem;
using namespace geohybrid::fem::testing;

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
