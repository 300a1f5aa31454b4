#pragma once
// Shared set-up of the tests of method 3 (the non-overlapping interface): the interface's contact
// laws. The lattice standing on the continuum and its scenarios are library code
// (apps/coupling_benchmarks/standing_lattice.h, apps/coupling_benchmarks/coupling_benchmarks.h), shared with
// `geohybrid coupling-test`.
#include "apps/coupling_benchmarks/standing_lattice.h"
#include "test_coupling_patch.h"

namespace geohybrid::coupling::testing
{
using Mesh = dealii::parallel::distributed::Triangulation<fem::dim>;
constexpr dealii::types::boundary_id top = standing_lattice_interface_id; // colorized: y = max

inline fem::SoilModel elastic_soil(double young_modulus, double poisson_ratio)
{
  fem::SoilParameters s;
  s.kind = fem::SoilModelKind::linear_elastic;
  s.young_modulus = young_modulus;
  s.poisson_ratio = poisson_ratio;
  return fem::SoilModel(s);
}

inline InterfaceCoupling interface_law(double kn, double ks, double friction_angle_deg)
{
  InterfaceCoupling c;
  c.boundary_id = top;
  c.contact.normal_stiffness = kn;
  c.contact.shear_stiffness = ks;
  c.contact.friction_angle_deg = friction_angle_deg;
  return c;
}

/// The project's default for a wall: the particles' own kn and ks.
inline InterfaceCoupling particles_law_interface(const PatchGeometry &g) { return interface_law(g.kn, g.ks, 30.0); }
} // namespace geohybrid::coupling::testing
