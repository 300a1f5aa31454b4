#pragma once
// Helpers shared by the files of DemSystem's implementation (dem_system*.cc); not part of its
// interface.
#include "particles.h"

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <utility>

namespace geohybrid::dem::detail
{
/// The bodies of the calling thread in every body loop of a step: a fixed split of [0, nb) into
/// one contiguous range per thread of the team (all of it outside a parallel region).
inline std::pair<std::size_t, std::size_t> thread_bodies(std::size_t nb)
{
  const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
  const std::size_t n = static_cast<std::size_t>(omp_get_num_threads());
  return {nb * t / n, nb * (t + 1) / n};
}

inline double largest_disc_radius(const ParticleSet &p)
{
  double largest = 0.0;
  for (const double r : p.disc_radius)
    largest = std::max(largest, r);
  return largest;
}
} // namespace geohybrid::dem::detail
