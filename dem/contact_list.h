#pragma once
// Candidate contacts found by the cell-list broad phase (a Verlet list: pairs closer than the sum
// of radii plus a skin), their history, and the per-step forces, all as structure of arrays.
// Pairs are kept sorted by (disc_i, disc_j) with disc_i < disc_j, so that history can be carried
// from one list to the next by a merge and every loop visits contacts in the same order whatever
// the number of threads.
#include "contact_law.h"
#include "particles.h"
#include "wall.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace geohybrid::dem
{
struct PairContacts
{
  SoaVector<std::uint32_t> disc_i, disc_j;
  SoaVector<ContactState> state;

  // Results of the last force evaluation.
  SoaVector<double> force_x, force_y;      ///< force on disc i [N/m]
  SoaVector<double> torque_i, torque_j;    ///< moments about each body's centre of mass [N]; kept only
                                           ///< for a body completed by its owning chunk (see below)
  SoaVector<double> elastic_normal_force;  ///< kn * overlap (0 when apart) [N/m]
  SoaVector<double> friction_work;         ///< energy dissipated by slip in the last step [J/m]
  SoaVector<double> viscous_work;          ///< energy dissipated by the dashpot in the last step [J/m]

  // Body -> contacts adjacency (CSR), rebuilt with the list: entry = 2 * pair + (body is j).
  SoaVector<std::uint32_t> body_offset;
  SoaVector<std::uint32_t> body_entry;
  SoaVector<std::uint32_t> adjacency_scratch; ///< reused by build_body_adjacency()

  // The force loop runs over n_chunks consecutive ranges of pairs, one per thread. A body belongs
  // to the chunk of its lowest pair, which adds all its forces on that body directly; a body that
  // also has pairs in later chunks ("shared", near a chunk boundary) gets those added afterwards,
  // in pair order, from its CSR entry shared_first_entry on. Each body thus sums its forces in
  // ascending pair order whatever the number of chunks (bit-for-bit the same result on any
  // number of threads), and no two threads ever write to one body.
  //
  // Only the first pairs of a chunk can touch a body owned by an earlier chunk (with the discs
  // numbered in space, those near the chunk's first discs): chunk k checks ownership and stores
  // the moments (torque_i, torque_j) for its pairs [chunk_begin(k), chunk_checked_end[k]) only,
  // and adds the rest straight to both bodies, as the one chunk of a single thread does.
  std::size_t n_chunks = 1;
  SoaVector<std::uint32_t> body_first_pair; ///< lowest pair touching each body (size() if none)
  SoaVector<std::uint32_t> shared_body, shared_first_entry;
  SoaVector<std::uint32_t> chunk_checked_end; ///< per chunk: 1 + its last pair touching a body it does not own
  /// First pair of chunk k (k = n_chunks gives size()).
  std::size_t chunk_begin(std::size_t k) const { return size() * k / n_chunks; }

  std::size_t size() const { return disc_i.size(); }
  void resize_results();
};

/// (Re)builds the body -> contact adjacency of `pairs` from its pair list, and the ownership of
/// bodies by `n_chunks` chunks of pairs (see PairContacts).
void build_body_adjacency(const ParticleSet &particles, PairContacts &pairs, std::size_t n_chunks);

/// Discs near one wall, with their contact history (same role as PairContacts for walls).
struct WallContacts
{
  SoaVector<std::uint32_t> disc;
  SoaVector<ContactState> state;
  SoaVector<double> force_x, force_y;     ///< force on the disc [N/m]
  SoaVector<double> elastic_normal_force; ///< [N/m]
  SoaVector<double> friction_work, viscous_work; ///< [J/m]
};

/// Cell-list broad phase. Owns its scratch arrays so that a rebuild does not allocate once the
/// arrays have grown to the size of the problem.
class NeighbourSearch
{
public:
  /// Rebuilds `pairs` (keeping the history of pairs present before) for discs closer than
  /// r_i + r_j + skin; discs of the same body never form a pair.
  /// With `carry_forces`, a pair present before also keeps its last force (a contact that is
  /// not evaluated again, DemSystem::set_skip_contacts_between_fixed_bodies); otherwise the
  /// forces start at zero.
  void rebuild_pairs(const ParticleSet &particles, double skin, int n_threads, PairContacts &pairs,
                     bool carry_forces = false);

  /// Rebuilds the list of discs within r + skin of the wall, keeping history.
  void rebuild_wall(const ParticleSet &particles, const Wall &wall, double skin, WallContacts &contacts);

  /// Appends to `discs` every disc whose cell, in the grid of the last rebuild_pairs(), meets the
  /// box [lo, hi] (cell by cell, ascending disc index inside a cell): the candidates near an
  /// object inside the box, such as a sheet segment. Every disc whose centre lies in the box is
  /// among them; others may be too.
  void append_discs_near_box(const Vec2 &lo, const Vec2 &hi, std::vector<std::uint32_t> &discs) const;

private:
  // The cell grid of the last rebuild_pairs(): origin, cell size and number of cells per row and
  // column (0 when there were no discs).
  double grid_x0_ = 0.0, grid_y0_ = 0.0, grid_cell_ = 1.0;
  std::size_t grid_ncx_ = 0, grid_ncy_ = 0;
  std::vector<std::uint32_t> cell_start_, cell_disc_, disc_cell_, fill_;
  std::vector<std::vector<std::uint32_t>> thread_i_, thread_j_;
  PairContacts previous_;
  WallContacts previous_wall_;
};

/// Distance from point p to the segment [a, b], and the closest point.
inline double closest_point_on_segment(const Vec2 &p, const Vec2 &a, const Vec2 &b, Vec2 &closest)
{
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  closest = a + t * ab;
  return (p - closest).norm();
}
} // namespace geohybrid::dem
