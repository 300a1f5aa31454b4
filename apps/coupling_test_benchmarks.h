#pragma once
// The three benchmarks of `geohybrid coupling-test` for the method the input chooses: methods 1
// and 2 on a lattice and a continuum overlapping in a band (apps/coupling_benchmarks/coupled_patch.h), method 3
// on a lattice standing on the continuum (apps/coupling_benchmarks/standing_lattice.h); the same three figures,
// each with its definition for that method.
#include "coupling_test_command.h"

#include <algorithm>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>

namespace geohybrid::apps
{
struct BenchmarkFigures
{
  /// The ghost forces, relative [-], of the patch test across the lattice's rows (methods 1 and 2:
  /// the band's normal +x, not exact) or of the lattice standing on the continuum (method 3).
  double ghost_discs = 0.0, ghost_nodes = 0.0;
  std::size_t n_particles = 0, n_cells = 0; ///< of that patch test
  /// Methods 1 and 2: the patch test along the rows, where the weights are exact.
  std::optional<coupling::benchmarks::RowPatchTestResult> row_patch;
  /// max_ghost_force_relative: the row patch's largest ghost force where there is one.
  double max_ghost() const { return row_patch ? row_patch->ghost.largest() : std::max(ghost_discs, ghost_nodes); }
  coupling::benchmarks::WaveRecord wave;
  coupling::benchmarks::EnergyRecord energy;
  std::string ghost_definition, wave_definition, energy_definition; ///< for the summary
  /// Method 1 with multi-rate stepping: per ratio of CouplingTestInput::continuum_step_ratios.
  struct MultiRateFigures
  {
    unsigned int ratio = 1;
    coupling::benchmarks::WaveRecord wave;
    coupling::benchmarks::EnergyRecord energy;
  };
  std::vector<MultiRateFigures> multi_rate;
};

/// Runs one benchmark (`what`: its name for messages); the command's wraps errors with the input.
using BenchmarkRunning = std::function<void(const char *what, const std::function<void()> &run)>;

/// The patch tests (on in.patch_strain; methods 1 and 2 also along the rows, on
/// in.row_patch_strain), the wave and the energy run of in.method.
BenchmarkFigures run_benchmarks(const CouplingTestInput &in, const BenchmarkRunning &running);
} // namespace geohybrid::apps
