#pragma once
// The soil's fields in a pull-out test, as the reference paper shows them (section 4.4): the
// displacement of the grains between the start of the pull and a later head displacement
// (Figure 10), the uplift of the soil surface along the tank (Figure 11), and the contact-force
// network (Figure 12). Plain rows, for CSV files and plots (apps/), computed from the particles
// at the start of the pull and now. The HDF5/XDMF form of the same state is a SnapshotWriter
// snapshot (dem/io/snapshot_writer.h: velocities and contact forces per snapshot).
#include "dem/dem_system.h"

#include <cstdint>
#include <vector>

namespace geohybrid::dem
{
/// One grain (body) now and at the start [m, m/s].
struct GrainDisplacement
{
  std::int64_t body_id = 0;
  double x0 = 0.0, y0 = 0.0; ///< centre of mass at the start
  double x = 0.0, y = 0.0;   ///< now
  double dx = 0.0, dy = 0.0; ///< x - x0, y - y0
  double vx = 0.0, vy = 0.0; ///< velocity now
};

/// Every body of `now` with its displacement since `start` (the same system earlier: bodies in
/// the same order). Throws std::invalid_argument if the two sets do not hold the same bodies.
std::vector<GrainDisplacement> grain_displacements(const ParticleSet &start, const ParticleSet &now);

/// One point of the soil surface: the highest grain of a strip of the surface at the start.
struct SurfacePoint
{
  std::int64_t body_id = 0;
  double x0 = 0.0;      ///< its centre's x at the start [m]
  double top0 = 0.0;    ///< the top of its highest disc at the start: the surface there [m]
  double uplift = 0.0;  ///< vertical displacement of its centre since the start (up > 0) [m]
};

/// The surface of `start` in strips of width `strip` over [0, width] (x of the bodies' centres):
/// in each strip the body whose highest disc reaches highest, and how far it has risen in `now`.
/// Strips without a body are left out; ordered by x. Throws std::invalid_argument for a
/// non-positive strip or width, or sets that do not match.
std::vector<SurfacePoint> surface_uplift(const ParticleSet &start, const ParticleSet &now, double width, double strip);

/// One touching contact between two discs: the line joining their centres and its elastic normal
/// force kn * overlap (compression > 0) [m, N/m].
struct ForceChain
{
  double x1 = 0.0, y1 = 0.0, x2 = 0.0, y2 = 0.0;
  double normal_force = 0.0;
};

/// The contact-force network of `system` now: every touching disc-disc contact, in list order.
std::vector<ForceChain> contact_force_network(const DemSystem &system);
} // namespace geohybrid::dem
