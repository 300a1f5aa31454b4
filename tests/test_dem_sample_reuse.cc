// A prepared sample given other contact laws (dem/laboratory/sample_reuse.h): the laws are in
// force, the time step follows the stiffest law, and the sample is back in equilibrium at its
// stress.
#include "dem/laboratory/sample_preparation.h"
#include "dem/laboratory/sample_reuse.h"
#include "dem/measurements.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace geohybrid::dem;

namespace
{
RedfSpec small_sample()
{
  RedfSpec s;
  s.n_particles = 80;
  s.shape = ParticleShape::disc;
  s.width = 0.04;
  s.height = 0.04;
  s.target_porosity = 0.2;
  s.porosity_tolerance = 0.01;
  s.target_stress = 20e3;
  s.particle_contact.normal_stiffness = 7e7;
  s.particle_contact.shear_stiffness = 3.5e7;
  s.particle_contact.friction_angle_deg = 20.0;
  s.wall_contact = s.particle_contact;
  s.wall_contact.friction_angle_deg = 0.0;
  s.seed = 5;
  return s;
}
} // namespace

TEST(SampleReuse, NewLawsInEquilibriumAtTheStress)
{
  const RedfSpec spec = small_sample();
  RedfSample sample = make_redf_sample(spec);
  const double old_step = sample.system.time_step();
  const double old_critical = sample.system.critical_time_step();
  DemSystem system = sample.system; // the prepared sample stays as it was
  ContactParameters particle = spec.particle_contact, wall = spec.wall_contact;
  particle.normal_stiffness *= 4.0; // sqrt(m / k): the critical step halves
  particle.shear_stiffness *= 4.0;
  particle.friction_angle_deg = 30.0;
  wall.normal_stiffness *= 4.0;
  wall.shear_stiffness *= 4.0;
  const std::uint64_t steps = change_contact_laws(system, sample.box, particle, wall, spec.target_stress);
  EXPECT_GT(steps, 0u);
  EXPECT_EQ(system.particle_law().normal_stiffness(), 4.0 * 7e7);
  EXPECT_NEAR(system.particle_law().friction_coefficient(), std::tan(30.0 * pi / 180.0), 1e-15);
  for (const Wall &w : system.walls())
    EXPECT_EQ(w.law.normal_stiffness(), 4.0 * 7e7);
  EXPECT_NEAR(system.critical_time_step(), 0.5 * old_critical, 1e-12 * old_critical);
  EXPECT_NEAR(system.time_step(), system.settings().time_step_safety * system.critical_time_step(), 1e-18);
  EXPECT_LT(system.time_step(), old_step);
  EXPECT_NEAR(sample.box.horizontal_stress(system), spec.target_stress, 0.02 * spec.target_stress);
  EXPECT_NEAR(sample.box.vertical_stress(system), spec.target_stress, 0.02 * spec.target_stress);
  EXPECT_LT(unbalanced_force_ratio(system), 1e-3);
  // Stiffer contacts at the same stress overlap less: the porosity rises a little, no more.
  const double porosity = 1.0 - total_solid_area(system.particles()) / sample.box.area(system);
  EXPECT_NEAR(porosity, sample.result.porosity, 0.01);
  // The original is untouched.
  EXPECT_EQ(sample.system.particle_law().normal_stiffness(), 7e7);

  EXPECT_THROW(change_contact_laws(system, sample.box, particle, wall, 0.0), std::invalid_argument);
  particle.normal_stiffness = -1.0;
  EXPECT_THROW(change_contact_laws(system, sample.box, particle, wall, 20e3), std::invalid_argument);
}
