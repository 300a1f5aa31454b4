#pragma once
// Making particle sets: a loose lattice for gravity deposition, the deterministic random numbers
// samples are drawn with, and the size distribution of generated samples. (Particle CSV files are
// read and written in dem/io/particle_csv.h.)
#include "dem/particles.h"

#include <cstdint>
#include <string>
#include <vector>

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

/// The size distribution of a generated sample, as a shape only: sizes are relative (large-disc
/// radii divided by any reference size), because REDF and tank filling scale them so that the
/// particles fill their region at the target porosity. Two kinds:
///  - uniform(min_ratio): radii uniform in number between min_ratio and 1 (smallest / largest);
///  - fractions({{relative size, area fraction}, ...}): discrete size classes, like a grading
///    curve read at its sieve sizes; each class has one size and its share of the solid area,
///    which in 2D with one density is its share of the mass. A class of the sieve interval
///    [d_i, d_i+1] is best given the interval's mean size.
class SizeDistribution
{
public:
  struct SizeClass
  {
    double relative_size; ///< large-disc radius of the class, relative [-]
    double area_fraction; ///< share of the solid area (= of the mass) [-]
  };

  /// Throws std::invalid_argument unless 0 < min_ratio <= 1.
  static SizeDistribution uniform(double min_ratio);
  /// Throws std::invalid_argument for no class, a size or fraction that is not positive, two
  /// classes of the same size, or fractions that do not sum to 1 within 1e-3 (they are then
  /// rescaled to sum to 1 exactly).
  static SizeDistribution fractions(std::vector<SizeClass> classes);

  bool is_uniform() const { return classes_.empty(); }
  double min_ratio() const { return min_ratio_; } ///< uniform only
  /// The classes by decreasing size (fractions only).
  const std::vector<SizeClass> &classes() const { return classes_; }

  /// n relative sizes. Uniform: n draws from `random`, in the order drawn. Fractions: by
  /// decreasing size (`random` is not used); the number of particles of each class is the
  /// nearest to its area fraction that n allows (largest remainder), so each class's area share
  /// is reproduced within about one particle; throws std::invalid_argument if a class would get
  /// no particle.
  std::vector<double> relative_sizes(std::size_t n, UniformRandom &random) const;

  /// E.g. "uniform 0.5" or "1:0.6, 0.5:0.4".
  std::string to_string() const;

private:
  double min_ratio_ = 1.0;
  std::vector<SizeClass> classes_;
};
} // namespace geohybrid::dem
