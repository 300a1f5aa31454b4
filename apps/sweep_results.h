#pragma once
// The results of `geohybrid sweep`: sweep.csv and sweep.png in its output directory.
//
// sweep.csv has one row per member ("member"), then one per value of the entries other than the
// seed ("over seeds": the mean of the members' T_max over their seeds, min, max and the sample
// standard deviation, empty for fewer than two). Its columns:
//
//   row, status, T_max_kN_per_m, T_max_min_kN_per_m, T_max_max_kN_per_m, T_max_std_kN_per_m,
//   n_seeds, one column per swept entry (its path: Anchorage/B, ..., Filling/seed), member, message
//
// A member's status is finished (run now), kept (finished earlier with the same parameters_hash),
// failed (message: why), stopped (by a signal, while it ran) or not run (a signal stopped the
// sweep before it started). An "over seeds" row's is
// "all N seeds", "K of N seeds", "one run" (no seed swept) or "no result"; its seed column lists the seeds it averages, its
// message the members that failed. The numbers come first, so that the columns a plot reads do
// not move with a value that holds a comma (such a field is quoted).
//
// sweep.png: T_max against the first swept entry (its values must be numbers): each member's as a
// point, the mean over the seeds as a line, their min - max as error bars; one curve per value of
// the other entries.
#include "apps/sweep_definition.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace geohybrid::apps
{
struct MemberOutcome
{
  std::string status = "not run"; ///< finished, kept, failed, stopped, not run
  std::string message;            ///< why it failed
  std::optional<double> T_max_kN; ///< its summary.json's T_max_kN_per_m [kN/m]
};

/// Writes `csv` (as above) for the members of `sweep` and their outcomes, in the members' order.
/// Throws std::runtime_error naming the file if it cannot be written.
void write_sweep_table(const SweepDefinition &sweep, const std::vector<MemberOutcome> &outcomes,
                       const std::filesystem::path &csv);

/// sweep.png from the table `csv` written by write_sweep_table. Returns false (and says why on
/// stderr) if the first entry's values are not all numbers or gnuplot is missing or fails.
bool plot_sweep(const SweepDefinition &sweep, const std::filesystem::path &csv, const std::filesystem::path &png);

/// A CSV field, quoted if it holds a comma, a quote or a line break (a line break becomes a space).
std::string csv_field(const std::string &text);

/// The fields of a CSV line as csv_field writes them (quotes removed, "" read as ").
std::vector<std::string> csv_fields(const std::string &line);
} // namespace geohybrid::apps
