#pragma once
// The small hybrid pull-out tank of the coupling tests (test_coupling_hybrid_pullout.cc,
// test_coupling_particle_box.cc): one set-up, so that both build the same tank.
#include "coupling/hybrid_pullout.h"
#include "small_pullout_tank.h"

#include <cstddef>

namespace geohybrid::coupling::testing
{
/// 0.4 m x 0.2 m, the sheet 0.25 m long at 0.1 m depth, `n_particles` in the whole tank, filled
/// and in contact as the DEM tests' small tank (small_pullout_tank.h: two lifts, porosity 0.25,
/// seed 3, kn = 1e7 N/m/m, ks = kn / 2); the continuum linear elastic (E = 5 MPa,
/// nu = 0.3); particles within `margin` of the sheet. The coupling method and the box's lifts are
/// each test's.
inline HybridPullOutSpec small_hybrid_tank(std::size_t n_particles, double margin)
{
  HybridPullOutSpec s;
  s.tank = geohybrid::testing::small_pullout_tank(); // its fill and contacts, in a larger tank
  dem::PullOutGeometry &g = s.tank.geometry;
  g.tank_length = 0.4;
  g.fill_height = 0.2;
  g.cover = 0.1;
  g.anchorage_length = 0.25;
  s.tank.filling.n_particles = n_particles;
  s.region.margin = margin;
  s.continuum.soil.kind = fem::SoilModelKind::linear_elastic;
  s.continuum.soil.young_modulus = 5e6;
  s.continuum.soil.poisson_ratio = 0.3;
  return s;
}
} // namespace geohybrid::coupling::testing
