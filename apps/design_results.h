#pragma once
// The results of `geohybrid design`, in its output directory:
//
// design.csv, one row per value tried, in the order tried:
//   step, <entry>_m (B_m or L_m), T_max_kN_per_m (the mean over the runs at that value),
//   T_max_std_kN_per_m (sample standard deviation, 0 for one run), T_max_min_kN_per_m,
//   T_max_max_kN_per_m, n_runs, criterion_kN_per_m (mean - k std), target_kN_per_m,
//   met (yes, no, or empty when a run failed), directory (the value's sweep), message
//
// design.png: T_max against the value (each value's mean, its min - max, the criterion
// mean - k std), with the target as a line, and the answer if one was found.
//
// summary.json, written last: the answer (null if none), the outcome in words, the criterion,
// the bracket, and each value tried with its figures.
#include "apps/design_definition.h"
#include "apps/spread.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace geohybrid::apps
{
/// One value tried: a sweep over the seeds.
struct DesignStep
{
  double value = 0.0;               ///< as run (design_value_text read back)
  std::string text;                 ///< design_value_text(value)
  std::string directory;            ///< the sweep's directory under the output directory ("B_0.3")
  std::vector<double> T_max_kN;     ///< of the runs that finished
  std::size_t n_runs = 0;           ///< the sweep's members
  std::string message;              ///< the runs that failed, if any
  bool complete() const { return !T_max_kN.empty() && T_max_kN.size() == n_runs; }
  Spread spread() const { return spread_of(T_max_kN); } ///< only when T_max_kN is not empty
  double criterion_kN(double k) const { return spread().mean - k * spread().std; }
};

/// What the design found, in words and figures.
struct DesignAnswer
{
  std::string outcome;              ///< found, not reached, met at the minimum, decreasing, runs failed
  std::string message;              ///< one plain sentence
  std::optional<double> answer;     ///< the smallest value found to meet the criterion
  std::optional<double> highest_failing; ///< the highest value tried that does not
  std::vector<std::string> warnings;     ///< T_max falling where it should rise, ...
};

/// Whether `step` meets the design's criterion (a step with a failed run meets nothing).
bool meets_criterion(const DesignDefinition &design, const DesignStep &step);

/// T_max's mean falling from one tried value to a higher one: one warning per fall, with both
/// values' means and spreads (the design assumes T_max rises with the value).
std::vector<std::string> monotonicity_warnings(const DesignDefinition &design, const std::vector<DesignStep> &steps);

/// Writes design.csv (above). Throws std::runtime_error naming the file if it cannot.
void write_design_table(const DesignDefinition &design, const std::vector<DesignStep> &steps,
                        const std::filesystem::path &csv);

/// design.png from design.csv; false (said on stderr) if gnuplot is missing or fails.
bool plot_design(const DesignDefinition &design, const DesignAnswer &answer, bool with_seeds,
                 const std::filesystem::path &csv, const std::filesystem::path &png);

/// Writes summary.json (above).
void write_design_summary(const DesignDefinition &design, const std::vector<DesignStep> &steps,
                          const DesignAnswer &answer, double seconds, const std::filesystem::path &file);
} // namespace geohybrid::apps
