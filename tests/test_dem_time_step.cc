// The time step of DemSystem: the critical step is stable for the densest packings of discs and of
// clusters, the automatic step is the safety factor of the system with its walls; and the refusal
// of bad input (contact parameters, a step above the stable limit, thread counts).
#include "dem/dem_system.h"
#include "dem/laboratory/sample_preparation.h"
#include "dem_system_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace geohybrid::dem;
using namespace geohybrid::testing::dem_system_scenes;

// Contact parameters are checked where they enter, with a message naming the parameter.
TEST(BadInput, ContactParametersRefused)
{
  const auto message_of = [](const ContactParameters &c) -> std::string {
    try
      {
        LinearContactLaw law_(c);
      }
    catch (const std::invalid_argument &e)
      {
        return e.what();
      }
    return "";
  };
  ContactParameters c = law(20.0, 0.5);
  EXPECT_NO_THROW(c.validate("test"));

  ContactParameters bad = c;
  bad.normal_stiffness = -1.0e6;
  EXPECT_THROW(bad.validate("test"), std::invalid_argument);
  EXPECT_NE(message_of(bad).find("normal stiffness"), std::string::npos) << message_of(bad);

  for (double angle : {90.0, 95.0, -1.0})
    {
      bad = c;
      bad.friction_angle_deg = angle;
      EXPECT_THROW(bad.validate("test"), std::invalid_argument) << angle;
      EXPECT_NE(message_of(bad).find("friction angle"), std::string::npos) << message_of(bad);
    }
  bad.friction_angle_deg = 89.9; // just below 90 is allowed
  EXPECT_NO_THROW(bad.validate("test"));

  for (double e : {0.0, -0.5, 1.01})
    {
      bad = c;
      bad.restitution = e;
      EXPECT_THROW(bad.validate("test"), std::invalid_argument) << e;
      EXPECT_NE(message_of(bad).find("restitution"), std::string::npos) << message_of(bad);
    }
  bad.restitution = 1.0; // the end of (0, 1] is allowed
  EXPECT_NO_THROW(bad.validate("test"));
  // validate names its caller.
  bad.normal_stiffness = 0.0;
  try
    {
      bad.validate("wall 'floor'");
      ADD_FAILURE() << "zero normal stiffness accepted";
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("wall 'floor'"), std::string::npos) << e.what();
    }
}

// The critical step is a bound for the densest packing: a hexagonal packing of equal discs, all
// in contact (6 each), frictional, without damping, keeps its energy at dt = critical_time_step()
// over thousands of steps, for ks = kn (rotation limits) and ks = kn / 2. (Measured with the
// refusal disabled: the same packing blows up at 1.1 x this step, and at 0.7 sqrt(m / kn), the
// single-contact estimate used before.)
TEST(TimeStep, CriticalStepStableForAHexagonalPacking)
{
  for (const double shear_ratio : {1.0, 0.5})
    {
      ParticleSet p;
      const double spacing = 2.0 * r_max * (1.0 - 1e-3); // every neighbour pair overlaps a little
      for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 20; ++i)
          {
            const std::size_t b =
              p.add_disc(Vec2((i + 0.5 * (j % 2)) * spacing, j * spacing * std::sqrt(3.0) / 2.0), r_max, density);
            p.vx[b] = 1e-3 * std::sin(7.1 * i + 3.3 * j); // excite every mode
            p.vy[b] = 1e-3 * std::cos(1.7 * i + 5.3 * j);
          }
      DemSettings s;
      s.gravity = Vec2::Zero();
      s.local_damping = 0.0;
      s.time_step_safety = 1.0;
      ContactParameters c = law(60.0, 1.0);
      c.shear_stiffness = shear_ratio * kn;
      // Strong bonds hold the lattice together (the overlaps would otherwise push it apart), so
      // that every disc keeps its six contacts and the lattice vibrates about its rest state.
      c.tensile_strength = c.shear_strength = 0.1 * kn * r_max;
      c.bond_new_contacts = true;
      DemSystem system(p, LinearContactLaw(c), s);
      ASSERT_EQ(system.time_step(), system.critical_time_step());
      system.initialise_forces();
      ASSERT_GT(system.n_touching_pairs(), 1100u); // 20 x 20 hexagonal: 1123 neighbour pairs
      const double e0 = system.energy().total();
      system.run_steps(4000);
      EXPECT_NEAR(system.energy().total(), e0, 1e-2 * e0) << "ks / kn = " << shear_ratio;
      EXPECT_EQ(system.n_broken_bonds(), 0u);
    }
}

// Sand is a packing of two-disc clusters, whose rotational stiffness the critical step estimates
// from contacts spread evenly round each disc (not a strict bound): a dense REDF packing under
// 100 kPa, its walls fixed, undamped, every body kicked, keeps its stored energy at the critical
// step (friction may only take some away) and all its contacts, for ks = kn / 2 and ks = kn.
// (Measured on 400 clusters with the refusal disabled: stable at 1.6 x, blown up at 2 x.)
TEST(TimeStep, CriticalStepStableForAClusterPacking)
{
  for (const double shear_ratio : {0.5, 1.0})
    {
      RedfSpec spec;
      spec.width = 0.06;
      spec.height = 0.06;
      spec.n_particles = 100;
      spec.particle_contact = law(30.0, 1.0);
      spec.particle_contact.normal_stiffness = 7e7;
      spec.particle_contact.shear_stiffness = shear_ratio * 7e7;
      spec.wall_contact = spec.particle_contact;
      spec.wall_contact.friction_angle_deg = 0.0;
      spec.target_stress = 1e5;
      const RedfSample sample = make_redf_sample(spec);
      DemSettings s = sample.system.settings();
      s.local_damping = 0.0;
      s.gravity = Vec2::Zero();
      s.time_step_safety = 1.0;
      DemSystem system(sample.system.particles(), LinearContactLaw(spec.particle_contact), s);
      for (Wall wall : sample.system.walls())
        {
          wall.control = WallControl::prescribed_velocity;
          wall.velocity = Vec2::Zero();
          system.add_wall(wall);
        }
      ASSERT_EQ(system.time_step(), system.critical_time_step());
      ParticleSet &p = system.particles();
      for (std::size_t b = 0; b < p.n_bodies(); ++b)
        {
          p.vx[b] = 1e-3 * std::sin(7.1 * b);
          p.vy[b] = 1e-3 * std::cos(3.3 * b);
          p.omega[b] = 0.3 * std::sin(1.7 * b);
        }
      system.initialise_forces();
      const std::size_t touching = system.n_touching_pairs();
      ASSERT_GT(touching, 2 * p.n_bodies()); // dense: coordination above 4
      const auto stored_energy = [&] { return system.energy().kinetic + system.energy().elastic; };
      const double e0 = stored_energy();
      system.run_steps(3000);
      EXPECT_LT(stored_energy(), 1.001 * e0) << "ks / kn = " << shear_ratio;
      EXPECT_GT(stored_energy(), 0.9 * e0) << "ks / kn = " << shear_ratio;
      // Kicked grains may slide off a contact or two; a blow-up loses most (at 2 x: a third).
      EXPECT_GT(system.n_touching_pairs(), 0.9 * touching) << "ks / kn = " << shear_ratio;
    }
}

// A step above the critical one is refused, naming the stable limit (its value in the message);
// the critical step itself is accepted. A thread count of 0 is refused.
TEST(BadInput, TimeStepAndThreads)
{
  ParticleSet p;
  p.add_disc(Vec2(0.0, 0.0), r_max, density);
  p.add_disc(Vec2(3.0 * r_max, 0.0), 0.7 * r_max, density);
  DemSettings s;
  const LinearContactLaw contact(law(20.0, 0.5));
  DemSystem system(p, contact, s);
  // Independent value of the limit: the lighter disc, m = rho pi r^2, with 6 contacts: in
  // translation omega^2 = 6 (kn + ks) / m = 9 kn / m for ks = kn / 2, in rotation
  // omega^2 = 2 * 6 ks r^2 / (m r^2 / 2) = 12 kn / m, the higher; dt = 2 / omega.
  const double m = density * pi * 0.49 * r_max * r_max;
  const double dt_crit = 2.0 / std::sqrt(12.0 * kn / m);
  EXPECT_NEAR(system.critical_time_step(), dt_crit, 1e-12 * dt_crit);
  EXPECT_NO_THROW(system.set_time_step(system.critical_time_step()));
  EXPECT_EQ(system.time_step(), system.critical_time_step());
  try
    {
      system.set_time_step(1.01 * dt_crit);
      ADD_FAILURE() << "a step above the critical one was accepted";
    }
  catch (const std::invalid_argument &e)
    {
      std::ostringstream limit;
      limit << system.critical_time_step();
      const std::string what = e.what();
      EXPECT_NE(what.find("stable limit"), std::string::npos) << what;
      EXPECT_NE(what.find(limit.str()), std::string::npos) << what << " (limit " << limit.str() << ")";
    }
  EXPECT_EQ(system.time_step(), system.critical_time_step()); // unchanged by the refusal
  EXPECT_THROW(system.set_time_step(0.0), std::invalid_argument);
  EXPECT_THROW(system.set_time_step(-1e-6), std::invalid_argument);

  s.time_step = 2.0 * dt_crit; // a user step in the settings is checked too
  EXPECT_THROW(DemSystem(p, contact, s), std::invalid_argument);

  DemSettings no_threads;
  no_threads.n_threads = 0;
  EXPECT_THROW(DemSystem(p, contact, no_threads), std::invalid_argument);
  no_threads.n_threads = -2;
  EXPECT_THROW(DemSystem(p, contact, no_threads), std::invalid_argument);
}

// One definition of the automatic step: the safety factor times the critical step of the system
// as it is, walls included. Walls twice as stiff as the grains lower the critical step by sqrt(2)
// (omega^2 scales with kn + ks); the step follows, to exactly the safety factor of the new limit.
// (Before, the step fixed with the grains alone was kept while it stayed below the new limit:
// 0.5 x the grains' critical step, 0.71 of the system's; the run printed one figure and a refused
// user step named the other.)
TEST(TimeStep, AutomaticStepIsTheSafetyFactorOfTheSystemWithItsWalls)
{
  DemSettings s;
  s.time_step_safety = 0.5;
  DemSystem system(grid_sample(6, 4, 0.1), LinearContactLaw(law(20.0, 1.0)), s);
  const double grains_only = system.critical_time_step();
  EXPECT_EQ(system.time_step(), 0.5 * grains_only);
  ContactParameters stiff = law(20.0, 1.0);
  stiff.normal_stiffness *= 2.0;
  stiff.shear_stiffness *= 2.0;
  add_box(system, 6 * 2.5 * r_max, 4 * 2.5 * r_max, LinearContactLaw(stiff));
  EXPECT_NEAR(system.critical_time_step(), grains_only / std::sqrt(2.0), 1e-12 * grains_only);
  EXPECT_EQ(system.time_step(), 0.5 * system.critical_time_step());
  // A step the user chooses between the two limits is refused, naming the walls' limit.
  s.time_step = 0.9 * grains_only;
  DemSystem chosen(grid_sample(6, 4, 0.1), LinearContactLaw(law(20.0, 1.0)), s);
  try
    {
      add_box(chosen, 6 * 2.5 * r_max, 4 * 2.5 * r_max, LinearContactLaw(stiff));
      ADD_FAILURE() << "a step above the walls' limit was accepted";
    }
  catch (const std::invalid_argument &e)
    {
      std::ostringstream limit;
      limit << system.critical_time_step();
      EXPECT_NE(std::string(e.what()).find("stable limit " + limit.str()), std::string::npos) << e.what();
    }
}
