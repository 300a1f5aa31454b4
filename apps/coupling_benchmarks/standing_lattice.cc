#include "standing_lattice.h"

#include "apps/coupling_benchmarks/hexagonal_lattice.h"

#include <deal.II/grid/grid_generator.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace geohybrid::coupling::benchmarks
{
double StandingLattice::bottom_row() const
{
  return g.radius - std::sqrt(3.0) * g.kn * (2.0 * g.radius - g.spacing()) / interface.contact.normal_stiffness;
}

dem::ParticleSet StandingLattice::discs(unsigned int extra_rows_below) const
{
  dem::ParticleSet p;
  // Row k counted from the bottom row: the coupled lattice's discs sit at the same coordinates,
  // to the last bit, in the extended one (the wave's reference starts with no difference).
  const double d = g.spacing(), h = g.row_height();
  for (unsigned int j = 0; j < rows + extra_rows_below; ++j)
    for (unsigned int i = 0; i < columns; ++i)
      {
        const double k = static_cast<double>(j) - static_cast<double>(extra_rows_below);
        p.add_disc(Vec2(i * d + (j % 2) * 0.5 * d, bottom_row() + k * h), g.radius, g.density, lattice_id(i, j));
      }
  return p;
}

StandingLattice standing_lattice(const PatchGeometry &g, unsigned int columns, unsigned int rows,
                                 unsigned int cells_down, const InterfaceCoupling &interface, double cell_height)
{
  if (interface.boundary_id != standing_lattice_interface_id)
    throw std::invalid_argument("standing lattice: the interface's boundary id is " +
                                std::to_string(interface.boundary_id) + ", the benchmark mesh's interface (y = 0) is " +
                                std::to_string(standing_lattice_interface_id));
  StandingLattice s;
  s.g = g;
  s.columns = columns;
  s.rows = rows;
  s.cells_down = cells_down;
  s.cell_height = cell_height;
  s.interface = interface;
  s.mesh = std::make_unique<PatchMesh>(MPI_COMM_WORLD);
  const double d = g.spacing();
  dealii::GridGenerator::subdivided_hyper_rectangle(*s.mesh, {columns, cells_down},
                                                    dealii::Point<2>(-0.5 * d, -1.0 * cells_down * cell_height * d),
                                                    dealii::Point<2>((columns - 0.5) * d, 0.0), true);
  s.continuum = std::make_unique<fem::ExplicitSolver>(*s.mesh, matching_soil(g), fem::BoundaryConditions{},
                                                      patch_continuum_settings(g));
  return s;
}

InterfaceCoupling matched_interface(const PatchGeometry &g, double normal_factor, double shear_factor,
                                    double friction_angle_deg)
{
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(g.kn, g.ks);
  InterfaceCoupling c;
  c.boundary_id = standing_lattice_interface_id;
  c.contact.normal_stiffness = normal_factor * (m.lame_lambda + 2.0 * m.shear_modulus) * g.spacing() / g.radius;
  c.contact.shear_stiffness = shear_factor * m.shear_modulus * g.spacing() / g.radius;
  c.contact.friction_angle_deg = friction_angle_deg;
  return c;
}

unsigned int standing_strip_rows(const StripSpec &spec)
{
  return static_cast<unsigned int>(std::ceil(spec.length * 2.0 / std::sqrt(3.0))); // rows h = sqrt(3) / 2 d apart
}

unsigned int standing_strip_rows_below(const StripSpec &spec)
{
  return 2 * static_cast<unsigned int>(std::lround(spec.length / std::sqrt(3.0)));
}

StandingLattice standing_strip(const StripSpec &spec, const InterfaceCoupling &interface, const PatchGeometry &g,
                               double time_step)
{
  const auto cells_down = static_cast<unsigned int>(std::max(1L, std::lround(spec.length / spec.cell_size)));
  StandingLattice s = standing_lattice(g, 6, standing_strip_rows(spec), cells_down, interface,
                                       spec.length / cells_down);
  s.particles = std::make_unique<dem::DemSystem>(s.discs(), bonded_lattice_law(g.kn, g.ks), undamped_settings(time_step));
  s.particles->initialise_forces();
  s.particles->bond_touching_contacts();
  s.stepper = std::make_unique<CoupledStepper>(*s.particles, *s.continuum, s.interface);
  return s;
}
} // namespace geohybrid::coupling::benchmarks
