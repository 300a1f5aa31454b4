#pragma once
// What every run does around its physics: a fresh output directory, the resolved parameter file,
// a progress report (a bar with ETA on a terminal, plain lines in a log), and a summary written
// last and atomically, so a directory with summary.json is a finished run.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace dealii
{
class ParameterHandler;
}

namespace geohybrid::apps
{
/// Reads an input file (.prm or .json) into `prm`. Throws std::runtime_error with deal.II's
/// message trimmed to what the user needs (file, line, entry, expected pattern).
void parse_input_file(dealii::ParameterHandler &prm, const std::string &input_file);

/// Creates the directory (and parents), removing a stale summary.json from an earlier run.
std::filesystem::path prepare_output_directory(const std::string &directory);

/// Writes every parameter, resolved, as DIRECTORY/parameters.prm.
void write_resolved_parameters(const dealii::ParameterHandler &prm, const std::filesystem::path &directory);

/// A flat JSON object of numbers and strings, written through a temporary file and a rename.
class Summary
{
public:
  void set(const std::string &key, double value);
  void set(const std::string &key, const std::string &value);
  void write(const std::filesystem::path &file) const;

private:
  std::map<std::string, std::string> entries_; // key -> JSON literal
};

class ProgressReport
{
public:
  ProgressReport(std::string label, double end);
  /// Reports progress at `now` (same unit as end); cheap when nothing needs printing.
  void update(double now);
  void finish();

private:
  std::string label_;
  double end_;
  bool terminal_;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point start_, last_print_;
};
} // namespace geohybrid::apps
