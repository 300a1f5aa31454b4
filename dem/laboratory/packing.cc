#include "packing.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace geohybrid::dem
{
namespace
{
/// Half the largest extent of a particle whose large disc has radius r.
double particle_half_extent(const LooseLatticeSpec &s, double r)
{
  if (s.shape == ParticleShape::disc)
    return r;
  const double spacing = s.cluster_spacing * 2.0 * r;
  return 0.5 * (r + spacing + s.cluster_diameter_ratio * r);
}

double lattice_pitch(const LooseLatticeSpec &s)
{
  return 2.0 * particle_half_extent(s, s.radius_max) * (1.0 + s.gap);
}

std::size_t lattice_columns(const LooseLatticeSpec &s)
{
  const double pitch = lattice_pitch(s);
  const double width = s.x_max - s.x_min;
  if (width < pitch)
    throw std::invalid_argument("loose lattice: the box (width " + std::to_string(width) +
                                " m) is narrower than one particle");
  return static_cast<std::size_t>(std::floor(width / pitch));
}
} // namespace

double loose_lattice_height(const LooseLatticeSpec &s)
{
  const std::size_t columns = lattice_columns(s);
  const std::size_t rows = (s.n_particles + columns - 1) / columns;
  return s.y_min + static_cast<double>(rows) * lattice_pitch(s);
}

ParticleSet make_loose_lattice(const LooseLatticeSpec &s)
{
  if (!(s.radius_min > 0.0) || s.radius_max < s.radius_min)
    throw std::invalid_argument("loose lattice: need 0 < minimum radius <= maximum radius");
  const double pitch = lattice_pitch(s);
  const std::size_t columns = lattice_columns(s);
  // Centre the lattice in the box.
  const double x0 = s.x_min + 0.5 * (s.x_max - s.x_min - static_cast<double>(columns) * pitch) + 0.5 * pitch;
  UniformRandom random(s.seed);
  ParticleSet p;
  p.reserve(s.n_particles, s.shape == ParticleShape::disc ? s.n_particles : 2 * s.n_particles);
  for (std::size_t k = 0; k < s.n_particles; ++k)
    {
      const double x = x0 + static_cast<double>(k % columns) * pitch;
      const double y = s.y_min + (static_cast<double>(k / columns) + 0.5) * pitch;
      const double r = random.uniform(s.radius_min, s.radius_max);
      const double angle = random.uniform(0.0, 2.0 * pi);
      std::size_t b;
      if (s.shape == ParticleShape::disc)
        b = p.add_disc(Vec2(x, y), r, s.density);
      else
        b = p.add_two_disc_cluster(Vec2(x, y), r, s.cluster_diameter_ratio * r,
                                   s.cluster_spacing * 2.0 * r, angle, s.density);
      // A small random velocity breaks the lattice's symmetry.
      const double jitter = 0.01 * std::sqrt(9.81 * r);
      p.vx[b] = random.uniform(-jitter, jitter);
      p.vy[b] = random.uniform(-jitter, jitter);
    }
  return p;
}

SizeDistribution SizeDistribution::uniform(double min_ratio)
{
  if (!(min_ratio > 0.0 && min_ratio <= 1.0))
    throw std::invalid_argument("size distribution: the size ratio (smallest / largest) " + std::to_string(min_ratio) +
                                " must lie in (0, 1]");
  SizeDistribution d;
  d.min_ratio_ = min_ratio;
  return d;
}

SizeDistribution SizeDistribution::fractions(std::vector<SizeClass> classes)
{
  if (classes.empty())
    throw std::invalid_argument("size distribution: the list of size fractions is empty");
  double sum = 0.0;
  for (const SizeClass &c : classes)
    {
      if (!(c.relative_size > 0.0 && std::isfinite(c.relative_size)))
        throw std::invalid_argument("size distribution: size " + std::to_string(c.relative_size) +
                                    " must be positive");
      if (!(c.area_fraction > 0.0 && c.area_fraction <= 1.0))
        throw std::invalid_argument("size distribution: the area fraction " + std::to_string(c.area_fraction) +
                                    " of size " + std::to_string(c.relative_size) + " must lie in (0, 1]");
      sum += c.area_fraction;
    }
  constexpr double sum_tolerance = 1e-3;
  if (std::abs(sum - 1.0) > sum_tolerance)
    {
      std::ostringstream message;
      message << "size distribution: the area fractions sum to " << sum << ", not 1 (within " << sum_tolerance << ")";
      throw std::invalid_argument(message.str());
    }
  std::sort(classes.begin(), classes.end(),
            [](const SizeClass &a, const SizeClass &b) { return a.relative_size > b.relative_size; });
  for (std::size_t k = 1; k < classes.size(); ++k)
    if (classes[k].relative_size == classes[k - 1].relative_size)
      throw std::invalid_argument("size distribution: size " + std::to_string(classes[k].relative_size) +
                                  " is listed twice; give each size once with its total fraction");
  for (SizeClass &c : classes)
    c.area_fraction /= sum;
  SizeDistribution d;
  d.min_ratio_ = classes.back().relative_size / classes.front().relative_size;
  d.classes_ = std::move(classes);
  return d;
}

std::vector<double> SizeDistribution::relative_sizes(std::size_t n, UniformRandom &random) const
{
  std::vector<double> sizes;
  sizes.reserve(n);
  if (is_uniform())
    for (std::size_t k = 0; k < n; ++k)
      sizes.push_back(random.uniform(min_ratio_, 1.0));
  else
    {
      // A class of area fraction f and size s holds a number share f / s^2 (particle area ~ s^2).
      // Whole counts by largest remainder: floor the ideal counts, then give the particles left
      // to the classes with the largest fractional parts (ties to the larger size).
      std::vector<double> ideal(classes_.size());
      double number_weight = 0.0;
      for (const SizeClass &c : classes_)
        number_weight += c.area_fraction / (c.relative_size * c.relative_size);
      std::vector<std::size_t> count(classes_.size());
      std::size_t assigned = 0;
      for (std::size_t i = 0; i < classes_.size(); ++i)
        {
          const SizeClass &c = classes_[i];
          ideal[i] = static_cast<double>(n) * c.area_fraction / (c.relative_size * c.relative_size) / number_weight;
          count[i] = static_cast<std::size_t>(std::floor(ideal[i]));
          assigned += count[i];
        }
      std::vector<std::size_t> order(classes_.size());
      for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return ideal[a] - std::floor(ideal[a]) > ideal[b] - std::floor(ideal[b]);
      });
      for (std::size_t k = 0; assigned < n; ++k, ++assigned)
        ++count[order[k % order.size()]];
      for (std::size_t i = 0; i < classes_.size(); ++i)
        {
          if (count[i] == 0)
            throw std::invalid_argument("size distribution: size " + std::to_string(classes_[i].relative_size) +
                                        " (area fraction " + std::to_string(classes_[i].area_fraction) +
                                        ") gets no particle among " + std::to_string(n) +
                                        "; use more particles or merge it with a neighbouring size");
          sizes.insert(sizes.end(), count[i], classes_[i].relative_size);
        }
    }
  return sizes;
}

std::string SizeDistribution::to_string() const
{
  std::ostringstream out;
  if (is_uniform())
    out << "uniform " << min_ratio_;
  else
    for (std::size_t i = 0; i < classes_.size(); ++i)
      out << (i ? ", " : "") << classes_[i].relative_size << ':' << classes_[i].area_fraction;
  return out.str();
}
} // namespace geohybrid::dem
