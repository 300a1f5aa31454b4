#pragma once
// Plain structure-of-arrays storage for rigid bodies (discs or two-disc clusters) and the discs
// they are made of. Body b owns discs [first_disc[b], first_disc[b] + n_discs[b]). The arrays are
// public on purpose: the force loops read them directly; ParticleSet only keeps them consistent.
#include "conventions.h"
#include "soa_vector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace geohybrid::dem
{
struct ParticleSet
{
  // ---- bodies -------------------------------------------------------------------------------
  SoaVector<std::int64_t> body_id;    ///< the user's id (CSV id or generation order)
  SoaVector<double> x, y;             ///< centre of mass [m]
  SoaVector<double> rotation;         ///< angle about +z [rad]
  SoaVector<double> vx, vy;           ///< [m/s]
  SoaVector<double> omega;            ///< angular velocity about +z [rad/s]
  SoaVector<double> fx, fy, torque;   ///< resultant of the last force evaluation [N/m, N]
  SoaVector<double> mass, inertia;    ///< [kg/m], [kg m]
  SoaVector<double> inverse_mass, inverse_inertia; ///< 0 for a fixed body
  SoaVector<std::uint32_t> first_disc, n_discs;

  // ---- discs --------------------------------------------------------------------------------
  SoaVector<std::uint32_t> disc_body;        ///< owning body
  SoaVector<double> disc_radius;             ///< [m]
  SoaVector<double> disc_offset_x, disc_offset_y; ///< centre in the body frame [m]
  SoaVector<double> disc_x, disc_y;          ///< centre in the world frame [m]

  std::size_t n_bodies() const { return x.size(); }
  std::size_t n_discs_total() const { return disc_radius.size(); }

  /// Adds a single disc of the given density [kg/m^3]; returns the body index.
  std::size_t add_disc(const Vec2 &centre, double radius, double density, std::int64_t id = -1);

  /// Adds a rigid cluster of two discs (radii r_large and r_small, centres `spacing` apart) whose
  /// axis makes `angle` with +x; the mass properties subtract the lens where the discs overlap.
  std::size_t add_two_disc_cluster(const Vec2 &centre_of_mass, double r_large, double r_small,
                                   double spacing, double angle, double density,
                                   std::int64_t id = -1);

  /// Scales the size of every body from `first_body` on by `factor` about its centre of mass:
  /// radii and disc offsets by factor, mass by factor^2, inertia by factor^4 (same density), and
  /// places their discs. Used by radius expansion (a tank's lift grows the bodies above the ones
  /// already settled, which keep their sizes).
  void scale_sizes(double factor, std::size_t first_body = 0);

  /// Makes body b immovable (infinite mass and inertia).
  void fix_body(std::size_t b);

  /// Recomputes disc world positions from body positions and rotations, on n_threads threads.
  /// With reference positions (one per disc), also returns the largest squared displacement
  /// from them, measured in the same pass (max is exact: the same on any number of threads).
  double update_disc_positions(int n_threads = 1, const SoaVector<double> *reference_x = nullptr,
                               const SoaVector<double> *reference_y = nullptr);

  /// Places the discs of body b from its position and rotation (what update_disc_positions()
  /// does for every body). With reference positions (one per disc), returns the largest squared
  /// displacement of those discs from them; 0 otherwise.
  inline double place_discs(std::size_t b, const double *reference_x, const double *reference_y);

  /// The largest squared displacement of body b's discs, as they stand, from the reference
  /// positions (0 without them): what place_discs() returns for a body that has not moved.
  inline double disc_move2(std::size_t b, const double *reference_x, const double *reference_y) const;

  /// True if every body is one disc at its centre of mass and body b owns disc b: the disc
  /// centres are then copies of the body centres.
  bool single_centred_discs() const;

  /// Solid area of body b [m^2 per m]: mass / density is not stored, so this is from geometry.
  double body_area(std::size_t b) const;

  void reserve(std::size_t n_bodies, std::size_t n_discs);
};

inline double ParticleSet::place_discs(std::size_t b, const double *reference_x, const double *reference_y)
{
  // A loop over bodies, so that a cluster's rotation is turned into cos and sin once for all
  // its discs (sincos is the dearest operation here: a third of a cluster system's step when
  // taken per disc). A single disc at its body's centre of mass needs no rotation at all.
  double max_move2 = 0.0;
  const std::uint32_t begin = first_disc[b], end = begin + n_discs[b];
  if (end == begin + 1 && disc_offset_x[begin] == 0.0 && disc_offset_y[begin] == 0.0)
    {
      const double xb = x[b], yb = y[b];
      disc_x[begin] = xb;
      disc_y[begin] = yb;
      if (reference_x)
        {
          const double dx = xb - reference_x[begin], dy = yb - reference_y[begin];
          max_move2 = dx * dx + dy * dy;
        }
      return max_move2;
    }
  const double c = std::cos(rotation[b]), s = std::sin(rotation[b]);
  for (std::uint32_t d = begin; d < end; ++d)
    {
      const double ox = disc_offset_x[d], oy = disc_offset_y[d];
      disc_x[d] = x[b] + c * ox - s * oy;
      disc_y[d] = y[b] + s * ox + c * oy;
    }
  return disc_move2(b, reference_x, reference_y);
}

inline double ParticleSet::disc_move2(std::size_t b, const double *reference_x, const double *reference_y) const
{
  double max_move2 = 0.0;
  if (reference_x)
    for (std::uint32_t d = first_disc[b]; d < first_disc[b] + n_discs[b]; ++d)
      {
        const double dx = disc_x[d] - reference_x[d], dy = disc_y[d] - reference_y[d];
        max_move2 = std::max(max_move2, dx * dx + dy * dy);
      }
  return max_move2;
}

/// The same bodies renumbered so that bodies close in space are close in memory: bodies are
/// ordered by the cell of side `cell_size` holding their centre of mass, cells visited in Morton
/// (Z) order, ties kept in the original order. Everything of a body travels with it (id, state,
/// mass, its discs). The contact loop then finds a neighbour's data in cache: on the 40,000-disc
/// benchmark a randomly numbered packing runs 35 % slower than a sorted one (bench/RESULTS.md).
/// Generators that place particles at random (REDF, tank filling) sort before building a system.
ParticleSet spatially_sorted(const ParticleSet &particles, double cell_size);

/// The listed bodies of `particles`, in that order, each with everything it has (id, state,
/// mass, its discs).
ParticleSet bodies_of(const ParticleSet &particles, const std::vector<std::uint32_t> &bodies);

/// Mass properties of the union of two overlapping discs, per unit density and thickness.
struct TwoDiscGeometry
{
  double area;                 ///< [m^2]
  double centroid_from_large;  ///< distance from the large disc centre along the axis [m]
  double polar_moment;         ///< second polar moment of area about the centroid [m^4]
};
TwoDiscGeometry two_disc_geometry(double r_large, double r_small, double spacing);
} // namespace geohybrid::dem
