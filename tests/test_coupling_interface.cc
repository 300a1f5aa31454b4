// Method 3 of issue 6, the non-overlapping interface (coupling/interface_wall.h): closed-form
// disc-edge contacts, the patch test, the stable step and bad input. The dynamics (waves, energy,
// force balance) are in test_coupling_interface_dynamics.cc.
#include "test_coupling_interface_lattice.h"

#include <deal.II/grid/grid_generator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <unordered_map>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
/// The external force on the x or y DoF of the interface node at `x` [N/m].
double node_force(const fem::ExplicitSolver &continuum, const InterfaceWall &wall, const Vec2 &x, int component)
{
  for (const InterfaceNode &n : wall.nodes())
    if ((n.reference - x).norm() < 1e-12)
      return continuum.external_force().local_element(component == 0 ? n.x_dof : n.y_dof);
  ADD_FAILURE() << "no interface node at " << x.transpose();
  return 0.0;
}

// Closed form: discs pressed on two edges of the interface y = 0, [0, 0.1] and [0.1, 0.2], by a
// known overlap. A disc at xi = 0.3 of the first edge feels kn delta up, and the edge's nodes
// -(1 - xi) kn delta and -xi kn delta; a disc over the shared node is counted once (not by both
// edges); sliding at 0.1 m/s, the tangential force is capped at mu kn delta against the slip, with
// its moment -(r - delta / 2) mu kn delta about the centre, and the slip dissipates.
TEST(InterfaceWall, DiscPressedOnAnEdgeAndSlidingAlongIt)
{
  Mesh mesh(MPI_COMM_WORLD);
  dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {2, 1}, dealii::Point<2>(0.0, -0.05),
                                                    dealii::Point<2>(0.2, 0.0), true);
  fem::ExplicitSettings settings;
  settings.density = 2000.0;
  fem::ExplicitSolver continuum(mesh, elastic_soil(1e8, 0.25), fem::BoundaryConditions{}, settings);
  const double r = 0.01, kn = 1e7, ks = 0.5e7, friction_angle = 20.0, force = 50.0, delta = force / kn;
  dem::ParticleSet p;
  p.add_disc(Vec2(0.03, r - delta), r, 2650.0, 0);
  InterfaceWall wall(interface_law(kn, ks, friction_angle), p, continuum, 0.4 * r);
  ASSERT_EQ(wall.edges().size(), 2u);
  CouplingForceSums sums;
  wall.apply(p, continuum, TieTiming{}, sums);
  EXPECT_NEAR(p.fy[0], force, 1e-9 * force);
  EXPECT_NEAR(p.fx[0], 0.0, 1e-12 * force);
  EXPECT_NEAR(node_force(continuum, wall, Vec2(0.0, 0.0), 1), -0.7 * force, 1e-9 * force);
  EXPECT_NEAR(node_force(continuum, wall, Vec2(0.1, 0.0), 1), -0.3 * force, 1e-9 * force);
  EXPECT_NEAR((sums.on_particles + sums.on_continuum).norm(), 0.0, 1e-14 * force);
  EXPECT_NEAR(wall.elastic_energy(), 0.5 * force * force / kn, 1e-9 * 0.5 * force * force / kn);

  // Over the shared node x = 0.1: one contact, not two.
  dem::ParticleSet on_node;
  on_node.add_disc(Vec2(0.1, r - delta), r, 2650.0, 0);
  InterfaceWall wall2(interface_law(kn, ks, friction_angle), on_node, continuum, 0.4 * r);
  CouplingForceSums sums2;
  wall2.apply(on_node, continuum, TieTiming{}, sums2);
  EXPECT_NEAR(on_node.fy[0], force, 1e-9 * force);
  EXPECT_EQ(wall2.n_touching(), 1u);

  // Sliding: the first evaluation (no drift) sets the contact, the second has slipped vx dt.
  const double dt = 1e-4, vx = 0.1, mu = std::tan(friction_angle * M_PI / 180.0);
  ASSERT_GT(ks * vx * dt, mu * force); // the trial force exceeds the Coulomb limit
  p.vx[0] = vx;
  for (double drift : {0.0, dt})
    {
      p.fx[0] = p.fy[0] = p.torque[0] = 0.0;
      wall.apply(p, continuum, TieTiming{drift, drift}, sums);
    }
  EXPECT_NEAR(p.fx[0], -mu * force, 1e-9 * force);
  EXPECT_NEAR(p.fy[0], force, 1e-9 * force);
  EXPECT_NEAR(p.torque[0], -(r - 0.5 * delta) * mu * force, 1e-9 * force * r);
  // Slip work: limit x (trial - limit) / ks (contact_law.h).
  EXPECT_NEAR(wall.dissipated(), mu * force * (ks * vx * dt - mu * force) / ks, 1e-9 * mu * force * vx * dt);
}

// The patch test of method 3. A single normal spring per disc replaces the two diagonal contacts
// the bottom row lacks, so a uniform strain is carried exactly only if the spring's force follows
// sigma_yy d: with the matched kn = (lambda + 2 mu) d / r the discs and the nodes (each node gets
// half of two discs: sum_c N_I = 1 when the cells are one spacing) are left with
//   r = [sigma_yy - (lambda + 2 mu) eps_yy] d = lambda eps_xx d,
// zero for a uniaxial strain eps_yy and lambda eps_xx / |sigma| otherwise (the interface has no
// Poisson coupling); with the particles' own kn (a wall's), [sigma_yy - kn eps_yy r / d] d.
// Shear (eps_xy) is left out: a new contact's tangential spring starts unloaded.
// Measured (14 x 9 discs on 14 x 6 cells): uniaxial 2.3e-8 (discs) and 1.3e-8 (nodes) of
// |sigma| d (round-off of the strained positions and the prestress's geometric terms, as for
// methods 1 and 2's untied discs); the issue's strain without shear, (1e-7, -0.4e-7): 1.46e-1 on
// both, the closed form; the particles' kn (a wall's law), uniaxial: 6.63e-1, the closed form.
TEST(InterfaceWall, PatchTestGhostForces)
{
  const PatchGeometry g;
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(g.kn, g.ks);
  const PlaneStrain uniaxial{0.0, -1e-7, 0.0};
  const InterfacePatchTestResult exact = interface_patch_test(matched_interface(g), uniaxial);
  const PlaneStrain issue{1e-7, -0.4e-7, 0.0};
  const InterfacePatchTestResult poisson = interface_patch_test(matched_interface(g), issue);
  const InterfacePatchTestResult wall_law = interface_patch_test(particles_law_interface(g), uniaxial);
  std::cout << "interface patch, matched kn: uniaxial discs " << exact.bottom_discs << ", nodes "
            << exact.interface_nodes << "; strain (1e-7, -0.4e-7): discs " << poisson.bottom_discs << ", nodes "
            << poisson.interface_nodes << "; the particles' kn, uniaxial: discs " << wall_law.bottom_discs
            << ", nodes " << wall_law.interface_nodes << std::endl;
  EXPECT_LT(exact.bottom_discs, 1e-6);
  EXPECT_LT(exact.interface_nodes, 1e-6);
  const double poisson_closed_form = m.lame_lambda * issue.xx / poisson.stress;
  EXPECT_NEAR(poisson.bottom_discs, poisson_closed_form, 1e-4 * poisson_closed_form);
  EXPECT_NEAR(poisson.interface_nodes, poisson_closed_form, 1e-4 * poisson_closed_form);
  const double syy = (m.lame_lambda + 2.0 * m.shear_modulus) * uniaxial.yy;
  const double wall_closed_form = std::abs(syy - g.kn * uniaxial.yy * g.radius / g.spacing()) / wall_law.stress;
  EXPECT_NEAR(wall_law.bottom_discs, wall_closed_form, 1e-4 * wall_closed_form);
  EXPECT_NEAR(wall_law.interface_nodes, wall_closed_form, 1e-4 * wall_closed_form);
  // Shear cannot be applied (a contact formed at the strained state has an unloaded tangential spring).
  EXPECT_THROW(interface_patch_test(matched_interface(g), PlaneStrain{1e-7, -0.4e-7, 0.3e-7}), std::invalid_argument);
}
// The stable step: the interface springs' squared frequency (interface_wall.cc) added to the
// larger of the two sides' (Weyl), in closed form for the standing lattice: a disc's row
// 2 x 2 max(kn / m, ks (1/m + r^2 / I)) = 4 max(kn, 3 ks) / m for a solid disc (r^2 / I = 2 / m), a
// node's row 2 max(kn, ks) (1 + 2 d / (2 x 1.8 r)) / M_I; the step is the safety factor x 2 / omega.
TEST(InterfaceWall, StableStepIncludesTheInterfaceSprings)
{
  const PatchGeometry g;
  StandingLattice s = standing_lattice(g, 6, 5, 4, matched_interface(g));
  s.particles = std::make_unique<dem::DemSystem>(s.discs(), bonded_lattice_law(g.kn, g.ks), undamped_settings());
  const double particles_omega = 2.0 / s.particles->critical_time_step();
  const double continuum_omega = 2.0 / s.continuum->critical_time_step();
  s.stepper = std::make_unique<CoupledStepper>(*s.particles, *s.continuum, s.interface);
  const double kn = s.interface.contact.normal_stiffness, mass = g.density * M_PI * g.radius * g.radius;
  const double disc_row = 4.0 * std::max(kn, 3.0 * s.interface.contact.shear_stiffness) / mass;
  double node_row = 0.0;
  for (const InterfaceNode &n : s.stepper->interface_wall()->nodes())
    {
      const bool end = n.reference.x() < 0.0 || n.reference.x() > (s.columns - 1) * g.spacing();
      const double adjacent = (end ? 1.0 : 2.0) * g.spacing();
      node_row = std::max(node_row, 2.0 * kn * (1.0 + adjacent / (2.0 * 1.8 * g.radius)) * n.inverse_mass);
    }
  const double omega2 = std::pow(std::max(particles_omega, continuum_omega), 2) + std::max(disc_row, node_row);
  EXPECT_NEAR(s.stepper->time_step(), 0.8 * 2.0 / std::sqrt(omega2), 1e-12 * s.stepper->time_step());
  EXPECT_LT(s.stepper->time_step(), 0.8 * 2.0 / std::max(particles_omega, continuum_omega));
}

TEST(InterfaceWall, BadInputNamesTheProblem)
{
  const PatchGeometry g;
  StandingLattice s = standing_lattice(g, 6, 5, 4, matched_interface(g));
  s.particles = std::make_unique<dem::DemSystem>(s.discs(), bonded_lattice_law(g.kn, g.ks), undamped_settings());
  InterfaceCoupling bonded = s.interface;
  bonded.contact.tensile_strength = 1.0;
  EXPECT_NE(invalid_argument_message([&] { CoupledStepper(*s.particles, *s.continuum, bonded); }).find("tensile strength"),
            std::string::npos);
  InterfaceCoupling nowhere = s.interface;
  nowhere.boundary_id = 7;
  EXPECT_NE(invalid_argument_message([&] { CoupledStepper(*s.particles, *s.continuum, nowhere); }).find("boundary id"),
            std::string::npos);
  const OverlapBand band(Vec2(0.0, 0.0), Vec2(0.0, -1.0), g.spacing());
  EXPECT_NE(invalid_argument_message([&] { CoupledStepper(*s.particles, *s.continuum, band, CouplingMethod(s.interface)); })
              .find("no overlap band"),
            std::string::npos);
}
} // namespace
