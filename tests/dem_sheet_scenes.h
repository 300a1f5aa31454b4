#pragma once
// The spar sheet tests' building blocks (test_dem_sheet.cc, test_dem_sheet_interface.cc,
// test_dem_sheet_system.cc): a linear contact law, a sheet's parameters, a straight chain of nodes.
#include "dem/dem_system.h"

#include <cstddef>
#include <vector>

namespace geohybrid::testing::dem_sheet_scenes
{
inline dem::ContactParameters contact_law(double kn, double friction_deg, double restitution = 1.0)
{
  dem::ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = 0.5 * kn;
  c.friction_angle_deg = friction_deg;
  c.restitution = restitution;
  return c;
}

inline dem::SheetParameters sheet_parameters(double J, double areal_mass, const dem::ContactParameters &interface)
{
  dem::SheetParameters s;
  s.axial_stiffness = J;
  s.thickness = 1.0e-3;
  s.areal_mass = areal_mass;
  s.interface = interface;
  return s;
}

/// Nodes from a to b in n equal segments.
inline std::vector<dem::Vec2> straight_nodes(const dem::Vec2 &a, const dem::Vec2 &b, std::size_t n)
{
  std::vector<dem::Vec2> nodes;
  for (std::size_t k = 0; k <= n; ++k)
    nodes.push_back(a + (static_cast<double>(k) / static_cast<double>(n)) * (b - a));
  return nodes;
}
} // namespace geohybrid::testing::dem_sheet_scenes
