#pragma once
// Plain structure-of-arrays storage for rigid bodies (discs or two-disc clusters) and the discs
// they are made of. Body b owns discs [first_disc[b], first_disc[b] + n_discs[b]). The arrays are
// public on purpose: the force loops read them directly; ParticleSet only keeps them consistent.
#include "conventions.h"
#include "soa_vector.h"

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

  /// Scales every body's size by `factor` about its centre of mass: radii and disc offsets by
  /// factor, mass by factor^2, inertia by factor^4 (same density). Used by radius expansion.
  void scale_sizes(double factor);

  /// Makes body b immovable (infinite mass and inertia).
  void fix_body(std::size_t b);

  /// Recomputes disc world positions from body positions and rotations, on n_threads threads.
  /// With reference positions (one per disc), also returns the largest squared displacement
  /// from them, measured in the same pass (max is exact: the same on any number of threads).
  double update_disc_positions(int n_threads = 1, const SoaVector<double> *reference_x = nullptr,
                               const SoaVector<double> *reference_y = nullptr);

  /// Solid area of body b [m^2 per m]: mass / density is not stored, so this is from geometry.
  double body_area(std::size_t b) const;

  void reserve(std::size_t n_bodies, std::size_t n_discs);
};

/// The same bodies renumbered so that bodies close in space are close in memory: bodies are
/// ordered by the cell of side `cell_size` holding their centre of mass, cells visited in Morton
/// (Z) order, ties kept in the original order. Everything of a body travels with it (id, state,
/// mass, its discs). The contact loop then finds a neighbour's data in cache: on the 40,000-disc
/// benchmark a randomly numbered packing runs 35 % slower than a sorted one (bench/RESULTS.md).
/// Generators that place particles at random (REDF, tank filling) sort before building a system.
ParticleSet spatially_sorted(const ParticleSet &particles, double cell_size);

/// Mass properties of the union of two overlapping discs, per unit density and thickness.
struct TwoDiscGeometry
{
  double area;                 ///< [m^2]
  double centroid_from_large;  ///< distance from the large disc centre along the axis [m]
  double polar_moment;         ///< second polar moment of area about the centroid [m^4]
};
TwoDiscGeometry two_disc_geometry(double r_large, double r_small, double spacing);
} // namespace geohybrid::dem
