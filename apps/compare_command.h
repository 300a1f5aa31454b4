#pragma once
// `geohybrid compare DIR1 DIR2 ... [--output FILE.png]`: the pull-out curves of several result
// directories (DEM, continuum, hybrid; any runs of `geohybrid pullout`) laid over each other in
// one PNG, so that discrete and continuum answers to the same test can be read side by side.
//
// Each directory must hold the pull-out output contract (issue 4): `pullout_curve.csv` with the
// header `head_displacement_m,head_tension_kN_per_m`, and `summary.json` with `mode` and
// `T_max_kN_per_m`. Nothing is computed: the command reads, checks and plots.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
/// What `compare` reads of one result directory.
struct PulloutRunRecord
{
  std::filesystem::path directory;
  std::string mode;                 ///< summary.json "mode": dem, fem or hybrid
  double max_head_tension_kN = 0.0; ///< summary.json "T_max_kN_per_m" [kN/m]
  std::vector<std::string> warnings; ///< summary.json "warnings" (none in a summary older than them)
  std::size_t n_points = 0;         ///< rows of pullout_curve.csv
  /// Its first two columns, row by row: head displacement [m], head tension [kN/m].
  std::vector<std::array<double, 2>> curve;
};

/// Reads and checks `directory`. Throws std::runtime_error naming the directory and the file if
/// pullout_curve.csv or summary.json is missing, the CSV's header does not start with the
/// contract's two columns (more may follow, as in the curve averaged over seeds) or a row does not
/// start with two numbers, or summary.json lacks "mode" or "T_max_kN_per_m".
PulloutRunRecord read_pullout_run(const std::filesystem::path &directory);

/// Overlays the curves of `directories` in `png` (legend: directory name and mode). Returns the
/// records read; throws as read_pullout_run, or naming `png` if it is not a .png or gnuplot fails.
std::vector<PulloutRunRecord> compare_pullout_runs(const std::vector<std::filesystem::path> &directories,
                                                   const std::filesystem::path &png);

/// The command line after `compare`: directories and an optional `--output FILE.png` (default
/// pullout_comparison.png in the working directory). Prints a table of the runs. Returns the exit
/// code; throws std::runtime_error for bad arguments or results.
int run_compare_command(const std::vector<std::string> &arguments);
} // namespace geohybrid::apps
