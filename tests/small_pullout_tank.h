#pragma once
// The small DEM pull-out tank of the DEM tests (test_dem_pullout.cc, test_dem_lift_cache.cc):
// one set-up, so that both fill the same tank.
#include "dem/laboratory/pullout_tank.h"

namespace geohybrid::testing
{
/// A small tank: 0.16 m long, 0.1 m of soil in two lifts, a simple run-out L = 0.1 m under
/// H = 0.05 m, 400 two-disc clusters of sizes 0.8 to 1 (about 7 mm: seven grains per lift),
/// porosity 0.25 (lifts this thin cannot hold particles for 0.2: REDF refuses grains wider than a
/// fifth of the lift), Table 5's friction (10 degrees). The contacts (grains and interface) are
/// softer than Table 5's, kn = 1e7 N/m/m, ks = kn / 2: no check here depends on the stiffness
/// (under the 1 kPa of this tank the overlaps stay below 1e-4 of a grain), and the stable step is
/// 2.6 times longer, which brings the fill from 14 s to 3 s of CPU (measured, seed 3). With these
/// softer contacts and the 20 kPa growth stress of the full tank, a grain of seed 3 was squeezed
/// through the slot while the upper lift grew; at 5 kPa none is (seeds 3 and 4).
inline dem::PullOutTankSpec small_pullout_tank(int n_threads = 1)
{
  dem::PullOutTankSpec s;
  s.geometry.tank_length = 0.16;
  s.geometry.fill_height = 0.1;
  s.geometry.cover = 0.05;
  s.geometry.anchorage_length = 0.1;
  s.geometry.clamp_offset = 0.01;
  s.max_segment_length = 0.01;
  s.filling.n_layers = 2;
  s.filling.n_particles = 400;
  s.filling.size_distribution = dem::SizeDistribution::uniform(0.8);
  s.filling.target_porosity = 0.25;
  s.filling.growth_stress = 5e3; // above the fill's weight on the base, 1.4 kPa (tank_filling.h)
  s.filling.equilibrium_unbalanced_ratio = 1e-3;
  s.filling.seed = 3;
  s.filling.n_threads = n_threads;
  for (dem::ContactParameters *c : {&s.filling.particle_contact, &s.sheet.interface})
    {
      c->normal_stiffness = 1e7;
      c->shear_stiffness = 0.5e7;
    }
  return s;
}
} // namespace geohybrid::testing
