#pragma once
// The section of `geohybrid report`'s page (apps/report_command.h) for the output directory of
// `geohybrid design` (apps/design_results.h): the outcome and the answer in words from
// summary.json, design.png, the table of the values tried from design.csv, the warnings, the
// resolved input, and each value's sweep as the report shows a sweep, collapsed.
#include <filesystem>
#include <string>

namespace geohybrid::apps::report
{
/// Whether `directory` is a design's: it holds design.csv (it also holds a summary.json, as a
/// run's directory does, so this is asked first).
bool is_design_directory(const std::filesystem::path &directory);

/// The section's HTML; `id` is the section's anchor, which the values' sweeps extend to anchors
/// of their own. Throws std::runtime_error naming design.csv if it is not a design's table.
std::string design_section(const std::filesystem::path &directory, const std::string &id);
} // namespace geohybrid::apps::report
