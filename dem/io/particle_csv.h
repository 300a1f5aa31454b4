#pragma once
// The particle CSV format of `geohybrid dem`: one row per disc, x, y, radius, vx, vy, omega and an
// optional cluster_id (the rows of one two-disc cluster share it; -1 or none for a lone disc).
// The initial particles of a scene are read from it, the final ones written to it.
#include "dem/particles.h"

#include <filesystem>

namespace geohybrid::dem
{
/// Reads particles from CSV. Rows sharing a cluster_id >= 0 form one rigid two-disc cluster.
/// Throws std::runtime_error naming the file and line for a malformed row, a non-positive radius,
/// a cluster of more than two discs, or two particles overlapping by more than
/// `overlap_tolerance` times the smaller radius.
ParticleSet read_particle_csv(const std::filesystem::path &file, double density, double overlap_tolerance);

/// Writes the particle CSV (one row per disc, cluster_id = body id for clusters, -1 for discs),
/// the format read_particle_csv() reads. Throws std::runtime_error naming the file if a write
/// fails (checked_output.h).
void write_particle_csv(const ParticleSet &particles, const std::filesystem::path &file);
} // namespace geohybrid::dem
