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
  std::vector<std::uint32_t> disc_i, disc_j;
  std::vector<ContactState> state;

  // Results of the last force evaluation.
  std::vector<double> force_x, force_y;      ///< force on disc i [N/m]
  std::vector<double> torque_i, torque_j;    ///< moments about each body's centre of mass [N]
  std::vector<double> elastic_normal_force;  ///< kn * overlap (0 when apart) [N/m]
  std::vector<double> friction_work;         ///< energy dissipated by slip in the last step [J/m]
  std::vector<double> viscous_work;          ///< energy dissipated by the dashpot in the last step [J/m]

  // Body -> contacts adjacency (CSR), rebuilt with the list: entry = 2 * pair + (body is j).
  std::vector<std::uint32_t> body_offset;
  std::vector<std::uint32_t> body_entry;
  std::vector<std::uint32_t> adjacency_scratch; ///< reused by build_body_adjacency()

  std::size_t size() const { return disc_i.size(); }
  void resize_results();
};

/// (Re)builds the body -> contact adjacency of `pairs` from its pair list.
void build_body_adjacency(const ParticleSet &particles, PairContacts &pairs);

/// Discs near one wall, with their contact history (same role as PairContacts for walls).
struct WallContacts
{
  std::vector<std::uint32_t> disc;
  std::vector<ContactState> state;
  std::vector<double> force_x, force_y;     ///< force on the disc [N/m]
  std::vector<double> elastic_normal_force; ///< [N/m]
  std::vector<double> friction_work, viscous_work; ///< [J/m]
};

/// Cell-list broad phase. Owns its scratch arrays so that a rebuild does not allocate once the
/// arrays have grown to the size of the problem.
class NeighbourSearch
{
public:
  /// Rebuilds `pairs` (keeping the history of pairs present before) for discs closer than
  /// r_i + r_j + skin; discs of the same body never form a pair.
  void rebuild_pairs(const ParticleSet &particles, double skin, int n_threads, PairContacts &pairs);

  /// Rebuilds the list of discs within r + skin of the wall, keeping history.
  void rebuild_wall(const ParticleSet &particles, const Wall &wall, double skin, WallContacts &contacts);

private:
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
