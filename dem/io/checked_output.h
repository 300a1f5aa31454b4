#pragma once
// Text outputs (CSV tables, parameter files, plot scripts) checked where their records end, so
// that a write that fails (a full disk: ENOSPC; a file-size limit: EFBIG) stops the run with one
// error naming the file, instead of leaving a file cut short that looks complete. Every command's
// text files go through these two checks (apps/ and dem/ alike; the HDF5 files have their own,
// dem/io/hdf5_writable_file.h).
//
// Why a flush: an std::ofstream keeps what it is given in its buffer (some kilobytes) and writes
// it later. `if (!out)` after the last row sees a failed write only if the buffer overflowed; a
// file shorter than the buffer fails in the destructor, where nobody looks.
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

namespace geohybrid::dem
{
/// "cannot write FILE (is the disk full, or the directory not writable?)".
std::string write_failure_message(const std::filesystem::path &file);

/// Flushes `out`, the stream of `file`; throws std::runtime_error(write_failure_message(file)) if
/// this or an earlier write to it failed (or it never opened). For a file written row by row: at
/// each record, so that a full disk stops the run there and a run killed later keeps its rows.
void flush_checked(std::ostream &out, const std::filesystem::path &file);

/// Closes `out`, the stream of `file`; throws as flush_checked() does. For a file written at once.
void close_checked(std::ofstream &out, const std::filesystem::path &file);

/// Writes `contents` as `file`, whole or not at all: through FILE.tmp and a rename. For a file
/// whose presence says something (summary.json: the run finished; a calibration's fragment, which
/// an input includes). On failure the temporary is removed and std::runtime_error names `file`
/// (write_failure_message), or the rename that failed.
void write_whole_file(const std::filesystem::path &file, const std::string &contents);
} // namespace geohybrid::dem
