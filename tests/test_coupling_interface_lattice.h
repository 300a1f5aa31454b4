#pragma once
// Shared set-up of the tests of method 3 (the non-overlapping interface): a hexagonal lattice
// standing on the matching continuum, the interface's contact laws.
#include "test_coupling_patch.h"

#include <deal.II/grid/grid_generator.h>

#include <memory>

namespace geohybrid::coupling::testing
{
using Mesh = dealii::parallel::distributed::Triangulation<fem::dim>;
constexpr dealii::types::boundary_id top = 3; // subdivided_hyper_rectangle, colorized: y = max

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

/// A hexagonal lattice of `columns` x `rows` bonded discs (the coupling tests' lattice: r = 5 mm,
/// kn = 1e8, ks = 0.5e8 N/m/m) standing on the matching Q1 continuum below y = 0, in square cells
/// of one spacing, `cells_down` deep; its bottom row at y = r less the overlap with which the
/// interface carries the lattice's prestress (the vertical force sqrt(3) kn delta0 of the two
/// diagonal contacts the bottom row lacks, delta0 = 2 r - spacing). The bottom row's discs sit
/// midway between the interface's nodes (x = i d, nodes at (k - 1/2) d).
struct StandingLattice
{
  PatchGeometry g;
  unsigned int columns = 0, rows = 0, cells_down = 0;
  InterfaceCoupling interface;
  std::unique_ptr<Mesh> mesh;
  std::unique_ptr<fem::ExplicitSolver> continuum;
  std::unique_ptr<dem::DemSystem> particles;
  std::unique_ptr<CoupledStepper> stepper;

  double bottom_row() const
  {
    return g.radius - std::sqrt(3.0) * g.kn * (2.0 * g.radius - g.spacing()) / interface.contact.normal_stiffness;
  }
  /// `extra_rows_below` (even: the rows' stagger is kept) extends the lattice down past the interface.
  dem::ParticleSet discs(unsigned int extra_rows_below = 0) const
  {
    return hexagonal_lattice(columns, rows + extra_rows_below, g.radius, g.spacing(), g.density,
                             Vec2(0.0, bottom_row() - extra_rows_below * g.row_height()));
  }
};

/// The interface springs that stand for the material between the bottom row's centres and the
/// edge (a gap r carrying a length d of the interface): kn = (lambda + 2 mu) d / r (a uniaxial
/// strain eps_yy then gives each disc exactly the traction sigma_yy d), ks = mu d / r.
inline InterfaceCoupling matched_interface(const PatchGeometry &g)
{
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(g.kn, g.ks);
  return interface_law((m.lame_lambda + 2.0 * m.shear_modulus) * g.spacing() / g.radius,
                       m.shear_modulus * g.spacing() / g.radius, 30.0);
}
/// The project's default for a wall: the particles' own kn and ks.
inline InterfaceCoupling particles_law_interface(const PatchGeometry &g) { return interface_law(g.kn, g.ks, 30.0); }

inline StandingLattice standing_lattice(unsigned int columns, unsigned int rows, unsigned int cells_down,
                                 const InterfaceCoupling &interface)
{
  StandingLattice s;
  s.columns = columns;
  s.rows = rows;
  s.cells_down = cells_down;
  s.interface = interface;
  s.mesh = std::make_unique<Mesh>(MPI_COMM_WORLD);
  const double d = s.g.spacing();
  dealii::GridGenerator::subdivided_hyper_rectangle(*s.mesh, {columns, cells_down}, dealii::Point<2>(-0.5 * d, -1.0 * cells_down * d),
                                                    dealii::Point<2>((columns - 0.5) * d, 0.0), true);
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(s.g.kn, s.g.ks);
  fem::ExplicitSettings settings;
  settings.density = s.g.density * m.density_factor;
  s.continuum = std::make_unique<fem::ExplicitSolver>(
    *s.mesh, elastic_soil(m.young_modulus_plane_strain, m.poisson_ratio_plane_strain), fem::BoundaryConditions{}, settings);
  return s;
}

} // namespace geohybrid::coupling::testing
