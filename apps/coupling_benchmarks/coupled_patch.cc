#include "coupled_patch.h"

#include "apps/coupling_benchmarks/hexagonal_lattice.h"

#include <deal.II/grid/grid_generator.h>

namespace geohybrid::coupling::benchmarks
{
dem::ParticleSet patch_particles(const PatchGeometry &g)
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

dem::LinearContactLaw bonded_lattice_law(double kn, double ks)
{
  dem::ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = ks;
  c.friction_angle_deg = 30.0;
  c.tensile_strength = 1e6;
  c.shear_strength = 1e6;
  return dem::LinearContactLaw(c);
}

fem::SoilModel matching_soil(const PatchGeometry &g)
{
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(g.kn, g.ks);
  fem::SoilParameters s;
  s.kind = fem::SoilModelKind::linear_elastic;
  s.young_modulus = m.young_modulus_plane_strain;
  s.poisson_ratio = m.poisson_ratio_plane_strain;
  return fem::SoilModel(s);
}

std::unique_ptr<PatchMesh> patch_mesh(const PatchGeometry &g)
{
  auto mesh = std::make_unique<PatchMesh>(MPI_COMM_WORLD);
  const double d = g.spacing(), h = g.row_height();
  dealii::GridGenerator::subdivided_hyper_rectangle(*mesh, {g.cells_x, g.cells_y},
                                                    dealii::Point<2>(g.band_start * d, -0.5 * h),
                                                    dealii::Point<2>(g.continuum_end * d, (g.rows - 0.5) * h), true);
  return mesh;
}

fem::ExplicitSettings patch_continuum_settings(const PatchGeometry &g)
{
  fem::ExplicitSettings s;
  s.element_degree = 1;
  s.density = g.density * hexagonal_lattice_moduli(g.kn, g.ks).density_factor;
  return s;
}

dem::DemSettings undamped_settings(double time_step)
{
  dem::DemSettings s;
  s.gravity = dem::Vec2(0.0, 0.0);
  s.local_damping = 0.0;
  s.time_step = time_step;
  s.n_threads = 1;
  return s;
}

OverlapBand patch_band(const PatchGeometry &g)
{
  const double d = g.spacing();
  return OverlapBand(Vec2(g.band_start * d, 0.0), Vec2(1.0, 0.0), g.band_width * d);
}

CoupledPatch coupled_patch_at_rest(const CouplingMethod &method, const PatchGeometry &geometry,
                                   const dem::DemSettings &particle_settings,
                                   const fem::ExplicitSettings &continuum_settings, const MultiRate &rate)
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
  settings.n_threads = continuum_settings.n_threads;
  patch.continuum = std::make_unique<fem::ExplicitSolver>(*patch.mesh, matching_soil(g), fem::BoundaryConditions{}, settings);
  patch.stepper =
    std::make_unique<CoupledStepper>(*patch.particles, *patch.continuum, patch_band(g), method, BandTreatment{}, rate);
  return patch;
}
} // namespace geohybrid::coupling::benchmarks
