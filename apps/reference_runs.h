#pragma once
// The full-size runs a pull-out is set beside (issue 23, part 5). A run made small or soft so
// that it takes minutes (the README's main job) is a demonstration of the workflow, not the
// model's answer: its plot and summary show the answer of the same case at full size, read from
// finished runs of it (for example validation/runs/gt230_h040_b025, three seeds), so that nobody
// takes the demonstration's T_max for the model's.
#include "apps/compare_command.h"
#include "apps/spread.h"

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace geohybrid::apps
{
/// Finished pull-out runs of one case, one per seed: the subdirectories seed<k> (the validation
/// campaign's) or seed_<k> (`pullout --seeds`) of a directory, in the order of k.
struct ReferenceRuns
{
  std::filesystem::path directory;
  std::vector<PulloutRunRecord> seeds;
  Spread T_max;                                  ///< over the seeds' T_max [kN/m]
  std::vector<std::array<double, 2>> mean_curve; ///< the seeds' curves averaged row by row [m, kN/m]
  double T_max_of_mean_curve = 0.0;              ///< the paper's reading: the mean curve's maximum [kN/m]
  double clusters = 0.0;                         ///< summary.json "n_particles" of the first seed, 0 if absent
};

/// Reads the runs under `directory`. Throws std::invalid_argument naming `where` (the input file
/// and the entry) if the directory does not exist, holds no seed directory, or a seed's files
/// are missing or malformed (as `geohybrid compare` reads them), or if the seeds' curves do not
/// record at the same head displacements (within half the first seed's first interval).
ReferenceRuns read_reference_runs(const std::filesystem::path &directory, const std::string &where);

/// What a pull-out's curve is set beside: the experiment's T_max, the same case at full size,
/// and, for a demonstration, why it is one.
struct CurveReferences
{
  std::optional<double> experimental_T_max; ///< [N/m]
  std::optional<ReferenceRuns> full_size;
  std::string demonstration; ///< empty: the run is a result; otherwise why it is only a demonstration
};

/// "; experiment 14.2 kN/m" for the end of a run's result line, or "".
std::string experiment_text(const CurveReferences &references);
/// The lines printed after a run's result: that it is a demonstration, and the full-size figure
/// (each ending in a newline), or "".
std::string demonstration_lines(const CurveReferences &references);
} // namespace geohybrid::apps
