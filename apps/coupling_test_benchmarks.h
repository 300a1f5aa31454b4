#pragma once
// The three benchmarks of `geohybrid coupling-test` for the method the input chooses: methods 1
// and 2 on a lattice and a continuum overlapping in a band (coupling/benchmark_patch.h), method 3
// on a lattice standing on the continuum (coupling/standing_lattice.h); the same three figures,
// each with its definition for that method.
#include "coupling_test_command.h"

#include <cstddef>
#include <functional>
#include <string>

namespace geohybrid::apps
{
struct BenchmarkFigures
{
  double ghost_discs = 0.0, ghost_nodes = 0.0; ///< the patch test's ghost forces, relative [-]
  std::size_t n_particles = 0, n_cells = 0;    ///< of the patch test
  coupling::benchmarks::WaveRecord wave;
  coupling::benchmarks::EnergyRecord energy;
  std::string ghost_definition, wave_definition, energy_definition; ///< for the summary
};

/// Runs one benchmark (`what`: its name for messages); the command's wraps errors with the input.
using BenchmarkRunning = std::function<void(const char *what, const std::function<void()> &run)>;

/// The patch test (on in.patch_strain), the wave and the energy run of in.method.
BenchmarkFigures run_benchmarks(const CouplingTestInput &in, const BenchmarkRunning &running);
} // namespace geohybrid::apps
