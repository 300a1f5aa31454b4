#pragma once
// The coupled patch the coupling's benchmarks run on (and its tests, and `geohybrid coupling-test`):
// a hexagonal lattice of bonded equal discs (the particle region, x < a + w) and a Q1 mesh of the
// matching plane-strain continuum (x >= a, hexagonal_lattice.h), overlapping in a straight band
// a < x < a + w. Lengths of the layout are counted in particle spacings d, so that one description
// serves the patch test's small patch and the wave's long strip.
#include "coupling/coupled_stepper.h"
#include "dem/dem_system.h"
#include "fem/constitutive/soil_model.h"
#include "fem/explicit_solver.h"

#include <deal.II/distributed/tria.h>

#include <cmath>
#include <cstdint>
#include <memory>

namespace geohybrid::coupling::benchmarks
{
struct PatchGeometry
{
  double radius = 0.005;             ///< of the discs [m]
  double overlap = 1e-9;             ///< initial overlap of neighbours, fraction of the spacing [-]
  double kn = 1e8, ks = 0.5e8;       ///< contact stiffnesses [N/m/m]
  double density = 2650.0;           ///< of the discs [kg/m^3]
  unsigned int rows = 12;
  double band_start = 5.3;           ///< a, in spacings
  double band_width = 4.0;           ///< w, in spacings
  double continuum_end = 13.3;       ///< right edge of the mesh, in spacings
  unsigned int cells_x = 4, cells_y = 5;

  double spacing() const { return 2.0 * radius * (1.0 - overlap); } ///< d [m]
  double row_height() const { return spacing() * std::sqrt(3.0) / 2.0; } ///< [m]
};

/// A disc's id from its place in the lattice (column i, row j): the same disc in two patches.
inline std::int64_t lattice_id(unsigned int i, unsigned int j) { return 100000 * static_cast<std::int64_t>(j) + i; }

/// The discs of the particle region: rows of the lattice, cut one spacing past the band's
/// continuum edge (the last ones are driven by the continuum).
dem::ParticleSet patch_particles(const PatchGeometry &g);

/// Bonded contacts (tension carried, strengths far above the forces of a small strain).
dem::LinearContactLaw bonded_lattice_law(double kn, double ks);

/// The plane-strain linear elastic continuum with the lattice's moduli.
fem::SoilModel matching_soil(const PatchGeometry &g);

using PatchMesh = dealii::parallel::distributed::Triangulation<fem::dim>;
/// The continuum's rectangle, from the band's particle edge to `continuum_end`, the lattice's
/// height (half a row beyond the first and last rows), cells_x by cells_y cells.
std::unique_ptr<PatchMesh> patch_mesh(const PatchGeometry &g);

/// Q1, the density that matches the lattice's mass per area.
fem::ExplicitSettings patch_continuum_settings(const PatchGeometry &g);

/// No gravity, no damping (the coupling refuses damping), one thread; `time_step` 0 for the
/// automatic step [s].
dem::DemSettings undamped_settings(double time_step = 0.0);

/// The particles, the mesh, the continuum and the stepper that ties them (which refers to the
/// others: the struct is moved as a whole, its parts stay where they are).
struct CoupledPatch
{
  PatchGeometry geometry;
  std::unique_ptr<PatchMesh> mesh;
  std::unique_ptr<fem::ExplicitSolver> continuum;
  std::unique_ptr<dem::DemSystem> particles;
  std::unique_ptr<CoupledStepper> stepper;
};

/// The band between the particle region and the continuum of `g`.
OverlapBand patch_band(const PatchGeometry &g);

/// The patch at rest (bonded lattice, continuum unstressed) coupled by `method`; `settings` for
/// the continuum (its damping, to test its refusal, and its threads); `rate` the continuum's step (multi-rate).
CoupledPatch coupled_patch_at_rest(const CouplingMethod &method, const PatchGeometry &geometry = {},
                                   const dem::DemSettings &particle_settings = undamped_settings(),
                                   const fem::ExplicitSettings &continuum_settings = {},
                                   const MultiRate &rate = {});
} // namespace geohybrid::coupling::benchmarks
