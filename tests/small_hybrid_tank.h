#pragma once
// The small hybrid pull-out tank of the coupling tests (test_coupling_hybrid_pullout.cc,
// test_coupling_particle_box.cc): one set-up, so that both build the same tank.
#include "coupling/hybrid_pullout.h"

#include <cstddef>

namespace geohybrid::coupling::testing
{
/// 0.4 m x 0.2 m, the sheet 0.25 m long at 0.1 m depth, `n_particles` two-disc clusters of sizes
/// 0.8 to 1 in the whole tank in two lifts at porosity 0.25, seed 3, the soft contacts of the DEM
/// pull-out tests (kn = 1e7 N/m/m, ks = kn / 2); the continuum linear elastic (E = 5 MPa,
/// nu = 0.3); particles within `margin` of the sheet. The coupling method and the box's lifts are
/// each test's.
inline HybridPullOutSpec small_hybrid_tank(std::size_t n_particles, double margin)
{
  HybridPullOutSpec s;
  dem::PullOutTankSpec &t = s.tank;
  t.geometry.tank_length = 0.4;
  t.geometry.fill_height = 0.2;
  t.geometry.cover = 0.1;
  t.geometry.anchorage_length = 0.25;
  t.geometry.clamp_offset = 0.01;
  t.max_segment_length = 0.01;
  t.filling.n_layers = 2;
  t.filling.n_particles = n_particles;
  t.filling.size_distribution = dem::SizeDistribution::uniform(0.8);
  t.filling.target_porosity = 0.25;
  t.filling.growth_stress = 5e3;
  t.filling.equilibrium_unbalanced_ratio = 1e-3;
  t.filling.seed = 3;
  for (dem::ContactParameters *c : {&t.filling.particle_contact, &t.sheet.interface})
    {
      c->normal_stiffness = 1e7;
      c->shear_stiffness = 0.5e7;
    }
  s.region.margin = margin;
  s.continuum.soil.kind = fem::SoilModelKind::linear_elastic;
  s.continuum.soil.young_modulus = 5e6;
  s.continuum.soil.poisson_ratio = 0.3;
  return s;
}
} // namespace geohybrid::coupling::testing
