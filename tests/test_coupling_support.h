#pragma once
// Shared set-up of the coupling tests: hexagonal lattices of equal discs and their contact law.
#include "apps/coupling_benchmarks/coupled_patch.h"
#include "dem/dem_system.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace geohybrid::coupling::testing
{
// The benchmarks' set-up (undamped_settings, the coupled patch) is library code, shared with
// `geohybrid coupling-test`.
using namespace geohybrid::coupling::benchmarks;

/// A hexagonal lattice of `columns` x `rows` equal discs of radius r, rows along x, centres
/// `spacing` apart (spacing < 2 r: every neighbour pair overlaps by 2 r - spacing), the first
/// disc at `corner`. Odd rows are shifted by half a spacing.
inline dem::ParticleSet hexagonal_lattice(unsigned int columns, unsigned int rows, double radius, double spacing,
                                          double density, const dem::Vec2 &corner = dem::Vec2(0.0, 0.0))
{
  dem::ParticleSet p;
  const double row_height = spacing * std::sqrt(3.0) / 2.0;
  for (unsigned int j = 0; j < rows; ++j)
    for (unsigned int i = 0; i < columns; ++i)
      p.add_disc(corner + dem::Vec2(i * spacing + (j % 2) * 0.5 * spacing, j * row_height), radius, density,
                 static_cast<std::int64_t>(j * columns + i));
  return p;
}

/// A frictionless-enough linear law (Coulomb limit far above the forces of a small strain).
inline dem::LinearContactLaw lattice_law(double kn, double ks)
{
  dem::ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = ks;
  c.friction_angle_deg = 60.0;
  c.restitution = 1.0;
  return dem::LinearContactLaw(c);
}

/// The message of the std::invalid_argument that `make()` throws, or "no exception".
template <typename Make>
std::string invalid_argument_message(Make make)
{
  try
    {
      make();
    }
  catch (const std::invalid_argument &e)
    {
      return std::string(e.what());
    }
  return std::string("no exception");
}

} // namespace geohybrid::coupling::testing
