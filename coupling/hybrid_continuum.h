#pragma once
// The hybrid pull-out's continuum (hybrid_pullout.h): the tank's mesh round the DEM core, and the
// explicit solver on it at the geostatic stress.
//
// The mesh is the tank's in the particle box's frame, with mesh lines on the core's and the band's
// edges: uniform cells over the band and the core's span (each interval divided evenly), growing by
// 1.3 per cell away from them up to the far cell size; the core's cells are then removed
// (continuum_region.h). The continuum runs at the particles' step, so its cells cost as much as
// the particles on a uniform mesh: the far field is coarser.
//
// The solver: Q1, the tank's unit weight under gravity, the continuum's local damping and the
// particles' threads; smooth back and front walls, a fixed base and a free top (only the walls the
// mesh reaches); the soil at rest, sigma_v = gamma (fill - y), sigma_h = K0 sigma_v, u = 0.
#include "coupling/overlap_band.h"
#include "coupling/particle_box.h"
#include "fem/explicit_solver.h"

#include <deal.II/distributed/tria.h>

#include <memory>

namespace geohybrid::coupling
{
struct HybridPullOutSpec;

/// The DEM core's rectangle in the box's frame: the box less, on each shared side, a pad and the
/// band; its other sides lie past the tank's walls [m].
struct DemCore
{
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
};

/// The continuum's mesh (one MPI rank: MPI_COMM_SELF): cells of `cell` [m] over the band (of
/// `band_width` round `core`) and the core's span, growing to `far_cell` away from them, the
/// core's cells removed.
std::unique_ptr<dealii::parallel::distributed::Triangulation<fem::dim>>
hybrid_continuum_mesh(const ParticleBox &box, const dem::PullOutGeometry &tank, const DemCore &core,
                      const OverlapBand &band, double band_width, double cell, double far_cell);

/// The explicit solver of the continuum on `mesh` (box frame), at the geostatic stress of the whole
/// tank (HybridContinuumSpec's soil and K0, the tank's unit weight).
std::unique_ptr<fem::ExplicitSolver>
hybrid_continuum_solver(const dealii::parallel::distributed::Triangulation<fem::dim> &mesh,
                        const HybridPullOutSpec &spec, const ParticleBox &box);
} // namespace geohybrid::coupling
