#pragma once
// `geohybrid report DIR1 DIR2 ... [--output FILE.html]`: one self-contained HTML page (every image
// inlined as a base64 data URI: the page is one file) of result directories, one section each.
//
// A run's directory (it holds summary.json: a pull-out of any mode, a `--seeds` ensemble, or any
// other command's run) gives: its curves (pullout_curve.png, or the curve plotted from
// pullout_curve.csv if the PNG is missing; time_series.png, biaxial.png), its field images
// (grain_displacements_*, force_network_*, surface_uplift.png) and other PNGs, the comparison with
// the paper when its input is a case of Tables 3, 4 or 6 (apps/paper_experiments.h), the summary's
// figures and warnings, and its input: the entries off their defaults, and the whole parameters.prm.
//
// A sweep's directory (it holds sweep.csv, apps/sweep_results.h) gives sweep.png, the table of
// T_max over the seeds per value (with the paper's values for the values that are its cases),
// the table of the members and the sweep's input, sweep.prm.
//
// A design's directory (it holds design.csv, apps/design_results.h; it has a summary.json too, so
// it is told apart first) gives the outcome and the answer in words, design.png, the table of the
// values tried, the warnings, the input (design.prm, design_base.prm) and, collapsed, each value's
// sweep section (apps/report_design.h).
#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
/// Writes the page of `directories` to `html`. Throws std::runtime_error naming a directory that
/// is neither a run's, a sweep's nor a design's, or `html` if it cannot be written.
void write_report(const std::vector<std::filesystem::path> &directories, const std::filesystem::path &html);

/// The command line after `report`: directories and an optional `--output FILE.html` (default
/// report.html in the working directory). Returns the exit code; throws for bad arguments.
int run_report_command(const std::vector<std::string> &arguments);

namespace report
{
/// The section of a sweep's directory (above), its titles as `heading` elements ("h3"; "h4" when
/// it is one value of a design's section).
std::string sweep_section(const std::filesystem::path &directory, const std::string &heading = "h3");
} // namespace report
} // namespace geohybrid::apps
