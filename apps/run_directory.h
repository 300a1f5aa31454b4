#pragma once
// What every run does around its physics: a fresh output directory, the resolved parameter file,
// a progress report (a bar with ETA on a terminal, plain lines in a log), and a summary written
// last and atomically, so a directory with summary.json is a finished run.
#include "apps/summary.h"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace dealii
{
class ParameterHandler;
}

namespace geohybrid::apps
{
/// `value` with `digits` significant digits in the C locale (a decimal point whatever the user's
/// locale), for messages, parameter files and summaries.
std::string number(double value, int digits = 12);

/// Reads an input file (.prm or .json) into `prm`. Throws std::runtime_error with deal.II's
/// message trimmed to what the user needs (file, line, entry, expected pattern).
void parse_input_file(dealii::ParameterHandler &prm, const std::string &input_file);

/// Sets the entry at `path` ("subsection/.../entry", e.g. "Filling/seed") to `value`, as if the
/// input file had said so (the entry's pattern is checked by ParameterHandler).
void set_parameter(dealii::ParameterHandler &prm, const std::string &path, const std::string &value);

/// The value of the entry at `path`, as set_parameter() names it; throws if it is not declared.
std::string get_parameter(const dealii::ParameterHandler &prm, const std::string &path);

/// Creates the directory (and parents) for a run, or for a run that continues the one there
/// (`resume`: its files are kept, but a stale summary.json is removed). A directory that holds
/// another run's files is refused, or cleared with --overwrite (apps/output_guard.h).
std::filesystem::path prepare_output_directory(const std::string &directory, bool resume);

/// Writes every parameter, resolved, as DIRECTORY/parameters.prm.
void write_resolved_parameters(const dealii::ParameterHandler &prm, const std::filesystem::path &directory);

/// Opens a CSV file of time-ordered rows (first column: time [s]) for writing.
/// A fresh run (no keep_until_time) creates it holding `header` (given without a newline).
/// A resumed run keeps the header and the rows whose time is <= *keep_until_time, stopping at the
/// first row that is later, incomplete (no final newline) or malformed (another number of fields
/// than the header), rewrites the file with them through a temporary file and a rename, and
/// opens it for appending; a missing file is created as for a fresh run.
/// Throws std::runtime_error naming the file if it cannot be read or written, or if its header
/// is not `header` (the columns changed since the earlier run). The caller checks its rows where
/// they are recorded (dem::flush_checked, dem/io/checked_output.h).
std::ofstream open_csv_rows(const std::filesystem::path &file, const std::string &header,
                            std::optional<double> keep_until_time);

/// Says when a wall-clock interval has passed since it last said so (or since construction).
class WallClockInterval
{
public:
  /// An interval of 0 s (or less) is never due.
  explicit WallClockInterval(double seconds);
  /// True at most once per interval; cheap to call every step.
  bool due();

private:
  std::chrono::steady_clock::duration interval_;
  std::chrono::steady_clock::time_point last_;
  bool enabled_;
};

class ProgressReport
{
public:
  ProgressReport(std::string label, double end);
  /// Reports progress at `now` (same unit as end); cheap when nothing needs printing.
  void update(double now);
  /// The end reached: the bar at 100 %.
  void finish();
  /// A run that failed: the bar's line ended where it stands (not at 100 %).
  void stop();

private:
  std::string label_;
  double end_;
  bool terminal_;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point start_, last_print_;
};
} // namespace geohybrid::apps
