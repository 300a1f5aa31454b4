#pragma once
// The scenes of DemSystem's system-level tests (test_dem_system.cc, test_dem_energy.cc,
// test_dem_time_step.cc): one contact law, one grid of discs and clusters, one closed box, so that
// the three programs build the same systems.
#include "dem/dem_system.h"

#include <cstddef>
#include <random>

namespace geohybrid::testing::dem_system_scenes
{
inline constexpr double density = 2650.0, r_max = 0.005, kn = 1.0e6;

inline dem::ContactParameters law(double friction_deg, double restitution)
{
  dem::ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = 0.5 * kn;
  c.friction_angle_deg = friction_deg;
  c.restitution = restitution;
  return c;
}

/// nx x ny discs of radii uniform in [r_low, 1] r_max on a square grid of pitch `pitch` r_max
/// (> 2: no overlaps), with velocity components uniform in [-v, v]. Every `cluster_every`-th body
/// is a two-disc cluster instead (0: discs only). Deterministic: fixed seed.
inline dem::ParticleSet grid_sample(int nx, int ny, double v, int cluster_every = 0, unsigned seed = 42,
                                    double pitch = 2.5, double r_low = 0.7)
{
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> radius(r_low * r_max, r_max), velocity(-v, v),
    angle(-dem::pi, dem::pi);
  pitch *= r_max;
  dem::ParticleSet p;
  int k = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i, ++k)
      {
        const dem::Vec2 centre((i + 0.5) * pitch, (j + 0.5) * pitch);
        std::size_t b;
        if (cluster_every > 0 && k % cluster_every == 0) // within 0.82 r_max of its centre
          b = p.add_two_disc_cluster(centre, 0.6 * r_max, 0.54 * r_max, 0.5 * r_max, angle(generator), density);
        else
          b = p.add_disc(centre, radius(generator), density);
        p.vx[b] = velocity(generator);
        p.vy[b] = velocity(generator);
      }
  return p;
}

/// A closed box [0, width] x [0, height] of four walls whose active sides face inwards; returns
/// the index of the first (the floor; then right, roof, left).
inline std::size_t add_box(dem::DemSystem &system, double width, double height, const dem::LinearContactLaw &wall_law)
{
  using dem::Vec2;
  using dem::Wall;
  const std::size_t floor = system.add_wall(Wall("floor", Vec2(0.0, 0.0), Vec2(width, 0.0), wall_law));
  system.add_wall(Wall("right", Vec2(width, 0.0), Vec2(width, height), wall_law));
  system.add_wall(Wall("roof", Vec2(width, height), Vec2(0.0, height), wall_law));
  system.add_wall(Wall("left", Vec2(0.0, height), Vec2(0.0, 0.0), wall_law));
  return floor;
}
} // namespace geohybrid::testing::dem_system_scenes
