#pragma once
// Making particle sets: a loose lattice for gravity deposition, and reading/writing the particle
// CSV format of `geohybrid dem` (x, y, radius, vx, vy, omega, optional cluster_id).
#include "particles.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace geohybrid::dem
{
enum class ParticleShape
{
  disc,
  two_disc_cluster ///< discs of diameters d and ratio * d (0.9 in the reference paper)
};

struct LooseLatticeSpec
{
  std::size_t n_particles = 1000;
  double x_min = 0.0, x_max = 1.0; ///< the particles' centres stay inside, one radius from the edge
  double y_min = 0.0;              ///< bottom of the first row
  double radius_min = 1.5e-3, radius_max = 2.5e-3; ///< of the large disc, uniform [m]
  double density = 2650.0;         ///< [kg/m^3]
  ParticleShape shape = ParticleShape::disc;
  double cluster_diameter_ratio = 0.9;   ///< small / large diameter
  double cluster_spacing = 0.95;         ///< centre spacing / large diameter; 0.95 = touching
  double gap = 0.1;                      ///< free space between lattice sites / largest extent
  std::uint64_t seed = 1;
};

/// Places particles row by row on a square lattice wide enough for the largest particle, with
/// random sizes and orientations from `seed` (same seed, same set on any machine).
ParticleSet make_loose_lattice(const LooseLatticeSpec &spec);
/// Top of the lattice that make_loose_lattice() builds [m].
double loose_lattice_height(const LooseLatticeSpec &spec);

/// Reads particles from CSV. Rows sharing a cluster_id >= 0 form one rigid two-disc cluster.
/// Throws std::runtime_error naming the file and line for a malformed row, a non-positive radius,
/// a cluster of more than two discs, or two particles overlapping by more than
/// `overlap_tolerance` times the smaller radius.
ParticleSet read_particle_csv(const std::filesystem::path &file, double density, double overlap_tolerance);

/// Writes the particle CSV (one row per disc, cluster_id = body id for clusters, -1 for discs),
/// the format read_particle_csv() reads.
void write_particle_csv(const ParticleSet &particles, const std::filesystem::path &file);

/// Deterministic uniform number in [0, 1) from a 64-bit generator state (SplitMix64), so that
/// samples do not depend on the standard library's distributions.
class UniformRandom
{
public:
  explicit UniformRandom(std::uint64_t seed) : state_(seed) {}
  double operator()()
  {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z = z ^ (z >> 31);
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  double uniform(double a, double b) { return a + (b - a) * (*this)(); }

private:
  std::uint64_t state_;
};
} // namespace geohybrid::dem
