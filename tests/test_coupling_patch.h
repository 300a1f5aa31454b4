#pragma once
// A coupled patch for the coupling tests: a hexagonal lattice of bonded equal discs (the particle
// region, x < a + w) and a Q1 mesh of the matching plane-strain continuum (x >= a), overlapping in
// a band a < x < a + w, four particle spacings and two cells wide.
#include "coupling/coupled_stepper.h"
#include "coupling/hexagonal_lattice.h"
#include "fem/constitutive/soil_model.h"
#include "test_coupling_support.h"

#include <deal.II/grid/grid_generator.h>

#include <memory>

namespace geohybrid::coupling::testing
{
struct PatchGeometry
{
  double radius = 0.005;
  double overlap = 1e-9;             ///< initial overlap of neighbours, fraction of the spacing [-]
  double kn = 1e8, ks = 0.5e8;       ///< [N/m/m]
  double density = 2650.0;           ///< of the discs [kg/m^3]
  unsigned int rows = 12;
  double band_start = 5.3;           ///< a, in spacings
  double band_width = 4.0;           ///< w, in spacings
  double continuum_end = 13.3;       ///< right edge of the mesh, in spacings
  unsigned int cells_x = 4, cells_y = 5;

  double spacing() const { return 2.0 * radius * (1.0 - overlap); }
  double row_height() const { return spacing() * std::sqrt(3.0) / 2.0; }
};

/// A disc's id from its place in the lattice (column i, row j): the same disc in two patches.
inline std::int64_t lattice_id(unsigned int i, unsigned int j) { return 100000 * static_cast<std::int64_t>(j) + i; }

/// The discs of the particle region: rows of the lattice, cut one spacing past the band's
/// continuum edge (the last ones are driven by the continuum).
inline dem::ParticleSet patch_particles(const PatchGeometry &g)
{
  dem::ParticleSet p;
  const double d = g.spacing(), x_end = (g.band_start + g.band_width + 1.0) * d;
  for (unsigned int j = 0; j < g.rows; ++j)
    for (unsigned int i = 0;; ++i)
      {
        const double x = i * d + (j % 2) * 0.5 * d;
        if (x >= x_end)
          break;
        p.add_disc(Vec2(x, j * g.row_height()), g.radius, g.density, lattice_id(i, j));
      }
  return p;
}

struct CoupledPatch
{
  using Mesh = dealii::parallel::distributed::Triangulation<fem::dim>;
  PatchGeometry geometry;
  std::unique_ptr<Mesh> mesh;
  std::unique_ptr<fem::ExplicitSolver> continuum;
  std::unique_ptr<dem::DemSystem> particles;
  std::unique_ptr<CoupledStepper> stepper;
};

/// Bonded contacts (tension carried, strengths far above the forces of a small strain).
inline dem::LinearContactLaw bonded_lattice_law(double kn, double ks)
{
  dem::ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = ks;
  c.friction_angle_deg = 30.0;
  c.tensile_strength = 1e6;
  c.shear_strength = 1e6;
  return dem::LinearContactLaw(c);
}

inline fem::SoilModel matching_soil(const PatchGeometry &g)
{
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(g.kn, g.ks);
  fem::SoilParameters s;
  s.kind = fem::SoilModelKind::linear_elastic;
  s.young_modulus = m.young_modulus_plane_strain;
  s.poisson_ratio = m.poisson_ratio_plane_strain;
  return fem::SoilModel(s);
}

inline std::unique_ptr<CoupledPatch::Mesh> patch_mesh(const PatchGeometry &g)
{
  auto mesh = std::make_unique<CoupledPatch::Mesh>(MPI_COMM_WORLD);
  const double d = g.spacing(), h = g.row_height();
  dealii::GridGenerator::subdivided_hyper_rectangle(*mesh, {g.cells_x, g.cells_y},
                                                    dealii::Point<2>(g.band_start * d, -0.5 * h),
                                                    dealii::Point<2>(g.continuum_end * d, (g.rows - 0.5) * h), true);
  return mesh;
}

inline fem::ExplicitSettings patch_continuum_settings(const PatchGeometry &g)
{
  fem::ExplicitSettings s;
  s.element_degree = 1;
  s.density = g.density * hexagonal_lattice_moduli(g.kn, g.ks).density_factor;
  return s;
}
/// The patch at rest (bonded lattice, continuum unstressed) coupled by `method`; `settings` for
/// the continuum (damping, to test its refusal).
inline CoupledPatch coupled_patch_at_rest(const CouplingMethod &method, const PatchGeometry &geometry = {},
                                          dem::DemSettings particle_settings = undamped_settings(),
                                          fem::ExplicitSettings continuum_settings = {})
{
  CoupledPatch patch;
  patch.geometry = geometry;
  const PatchGeometry &g = patch.geometry;
  patch.particles = std::make_unique<dem::DemSystem>(patch_particles(g), bonded_lattice_law(g.kn, g.ks), particle_settings);
  patch.particles->initialise_forces();
  patch.particles->bond_touching_contacts();
  patch.mesh = patch_mesh(g);
  fem::ExplicitSettings settings = patch_continuum_settings(g);
  settings.damping = continuum_settings.damping;
  patch.continuum = std::make_unique<fem::ExplicitSolver>(*patch.mesh, matching_soil(g), fem::BoundaryConditions{}, settings);
  const double d = g.spacing();
  const OverlapBand band(Vec2(g.band_start * d, 0.0), Vec2(1.0, 0.0), g.band_width * d);
  patch.stepper = std::make_unique<CoupledStepper>(*patch.particles, *patch.continuum, band, method);
  return patch;
}
} // namespace geohybrid::coupling::testing
