#pragma once
// coupling_diagnostics.csv of the hybrid pull-out (apps/pullout_hybrid_mode.h): the coupling's
// diagnostics at each point of the curve (issue 6: "diagnostics every output step"), and their
// extremes for the summary. Its rows are kept as numbers, so that a checkpoint can hold them and
// a resumed run write them again as they were.
#include "apps/summary.h"

#include "coupling/coupled_stepper.h"
#include "dem/io/checkpoint.h"
#include "dem/laboratory/pullout_tank.h"

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <optional>
#include <vector>

namespace geohybrid::coupling
{
class HybridPullOut;
} // namespace geohybrid::coupling

namespace geohybrid::apps
{
class DiagnosticsFile
{
public:
  static constexpr std::size_t n_columns = 23;

  /// Creates DIRECTORY/coupling_diagnostics.csv with its header.
  explicit DiagnosticsFile(const std::filesystem::path &directory);

  /// The balance is measured from `start`: the diagnostics at the pull's first point.
  void set_start(const coupling::CouplingDiagnostics &start) { start_ = start; }

  /// The row of `point` (just recorded), written and flushed at once.
  void add(const dem::PullPoint &point, coupling::HybridPullOut &hybrid);

  std::size_t n_rows() const { return rows_.size() / n_columns; }

  /// Keeps the rows and the extremes in `command` (for a checkpoint).
  void store(dem::CommandState &command) const;

  /// A resumed run: the rows `saved` holds written again, the extremes taken back.
  void restore(const dem::CommandState &saved);

  /// The extremes and the balance's definition into `summary`.
  void finish(Summary &summary);

private:
  /// At every row, as the curve files (PulloutOutput): a killed run keeps its rows, a full disk
  /// stops the run naming the file.
  void flush();
  void write_row(const double *row);

  std::filesystem::path path_;
  std::ofstream file_;
  std::vector<double> rows_;
  double largest_imbalance_ = 0.0, largest_force_ = 0.0;
  std::optional<coupling::CouplingDiagnostics> start_;
  double balance_error_ = 0.0, largest_balance_error_ = 0.0;
};
} // namespace geohybrid::apps
