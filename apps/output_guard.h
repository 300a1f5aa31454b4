#pragma once
// One run per output directory: a run into a directory that holds another run's files is refused
// unless it continues that run (--resume) or the user asked for them to be replaced
// (--overwrite), so that a directory never shows files of two runs side by side (the field
// images of a first run beside the summary of a second). Only the files geohybrid writes count,
// and only they are removed: a user's own files (an input kept beside the results, a log) stay.
#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
/// Whether `overwrite` (--overwrite, set once by main for the process) lets a fresh run clear an
/// output directory that holds another run's files.
void set_overwrite_output(bool overwrite);
bool overwrite_output();

/// Whether a file or directory of this name in an output directory is one geohybrid writes (any
/// command): summary.json, parameters.prm, checkpoint.h5, the curve and field files, their plot
/// scripts and temporary files, the seed_N directories of --seeds, fem mode's snapshots.
bool is_run_file(const std::string &name);

/// The run files in `directory` (none if it does not exist), sorted, those of its seed_N and
/// snapshots subdirectories included.
std::vector<std::filesystem::path> run_files(const std::filesystem::path &directory);

/// Called before a run writes into `directory`: nothing to do if it holds no run files or if
/// `resume` (the run continues the one there); with overwrite_output(), removes them (and the
/// seed_N and snapshots directories they leave empty); otherwise throws std::runtime_error naming
/// the directory, a few of its files and the three ways on.
void claim_output_directory(const std::filesystem::path &directory, bool resume);
} // namespace geohybrid::apps
