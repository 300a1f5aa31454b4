// REDF sample preparation (Chareyre & Villard 2005): the target porosity and the confining
// stress are met within tolerance; impossible targets are refused with a clear message.
#include "dem/measurements.h"
#include "dem/sample_preparation.h"

#include <gtest/gtest.h>

using namespace geohybrid::dem;

namespace
{
RedfSpec small_spec()
{
  RedfSpec s;
  s.n_particles = 300;
  s.width = 0.06;
  s.height = 0.1;
  s.shape = ParticleShape::two_disc_cluster;
  s.target_porosity = 0.2;
  s.target_stress = 20e3;
  s.particle_contact.normal_stiffness = 7e7;
  s.particle_contact.shear_stiffness = 3.5e7;
  s.particle_contact.friction_angle_deg = 10.0;
  s.wall_contact = s.particle_contact;
  s.wall_contact.friction_angle_deg = 0.0;
  s.n_threads = 1;
  return s;
}
} // namespace

TEST(Redf, ReachesTargetPorosityAndStress)
{
  const RedfSpec spec = small_spec();
  RedfSample sample = make_redf_sample(spec);
  // Porosity from the box and the solid area, independent of the REDF bookkeeping.
  const double porosity = 1.0 - total_solid_area(sample.system.particles()) / sample.box.area(sample.system);
  EXPECT_NEAR(porosity, spec.target_porosity, spec.porosity_tolerance);
  EXPECT_NEAR(sample.box.horizontal_stress(sample.system), spec.target_stress, 0.02 * spec.target_stress);
  EXPECT_NEAR(sample.box.vertical_stress(sample.system), spec.target_stress, 0.02 * spec.target_stress);
  // The Love-Weber stress inside agrees with the walls (both compressive: sign flip).
  const double w = sample.box.width(sample.system), h = sample.box.height(sample.system);
  const Region inner{0.0, 0.0, w, h};
  const auto stress = love_weber_stress(sample.system, Region{sample.system.walls()[sample.box.left].start.x(),
                                                              sample.system.walls()[sample.box.bottom].start.y(),
                                                              sample.system.walls()[sample.box.right].start.x(),
                                                              sample.system.walls()[sample.box.top].start.y()});
  (void)inner;
  EXPECT_NEAR(-stress[0], spec.target_stress, 0.05 * spec.target_stress);
  EXPECT_NEAR(-stress[1], spec.target_stress, 0.05 * spec.target_stress);
  std::cout << "REDF: porosity " << porosity << ", growth friction " << sample.result.growth_friction_deg
            << " deg, steps " << sample.result.n_steps << ", coordination " << coordination_number(sample.system)
            << '\n';
}
