#pragma once
// The particles tied to the continuum, as the coupling methods see them, gathered once when the
// coupling is set up (small strain in the band: the lists and the interpolation do not change
// during a run), so that each step reads short index lists.
//
// - Tied particles: those of the overlap band (0 < w < 1) and those within `tie margin` outside
//   its particle-side edge. The margin is the longest branch a contact can have: a particle that
//   close to the band has contacts whose weight, the mean along the branch, is below one while its
//   opposite contacts' is one, so it feels a net weighted force under a uniform strain (a ghost
//   force) unless it too is tied. Those lie just outside the mesh and are tied to the extrapolated
//   shape functions of the nearest cell.
// - Driven particles: those in the continuum-only region (w = 1) past the band's continuum-side
//   edge (and, on request, the band's lightest particles: see OverlapBand::driven_from). They have no mass left, but a contact between one of them and a band particle still
//   carries the weight of the part of its branch inside the band; without them the band's last
//   particles would miss those contacts (a ghost force at that edge). They are fixed bodies moved
//   with the continuum's displacement (x = X + u(X) - u_0(X)), and their contact forces are passed
//   to the continuum's nodes (N_I(X) F): pad particles, as in the quasicontinuum and CADD methods.
#include "coupling/band_points.h"
#include "coupling/overlap_band.h"

#include <cstdint>
#include <vector>

namespace geohybrid::coupling
{
struct BandParticles
{
  double driven_from = 0.0;                ///< band coordinate from which particles are driven [m]
  std::vector<std::uint32_t> body;         ///< DEM body index of each tied particle
  std::vector<Vec2> reference_position;    ///< its centre of mass when tied [m]
  BandPoints points;                       ///< where the reference positions sit in the mesh

  std::vector<std::uint32_t> driven_body;       ///< DEM body index of each driven particle
  std::vector<Vec2> driven_reference_position;  ///< [m]
  BandPoints driven_points;

  /// Tied: the bodies of `particles` with -tie_margin < s < s_d, located in `space`'s mesh
  /// (extrapolated up to tie_margin outside it); driven: those with s >= s_d, where s_d =
  /// band.driven_from(driven_below_weight) (w for 0: only those past the band), located alike
  /// (a grain at a free surface that the box and the continuum share stands a little above the
  /// mesh's top). Throws std::invalid_argument if no particle is tied or one lies farther outside
  /// the mesh.
  BandParticles(const OverlapBand &band, const dem::ParticleSet &particles, const fem::DisplacementSpace &space,
                const BandPoints::Vector &layout, double tie_margin, double driven_below_weight = 0.0);
  std::size_t size() const { return body.size(); }
};
} // namespace geohybrid::coupling
