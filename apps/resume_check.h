#pragma once
// A checkpoint keeps the input that made it (its entries that differ from their defaults), so
// that --resume with an input that would make other numbers is refused, naming what differs,
// instead of continuing into a run that parameters.prm would then describe wrongly. Only a
// command's run-control entries (where it writes, its threads, when it checkpoints or stops, for
// `geohybrid dem` its end time and output intervals) may change on resuming.
#include "dem/io/checkpoint.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace dealii
{
class ParameterHandler;
}

namespace geohybrid::apps
{
/// The key of dem::CommandState::texts under which a checkpoint keeps its input.
inline constexpr const char *checkpoint_input_key = "input";

/// Stores the input of the run, canonical_parameters(prm, defaults, {}), in `command`.
void store_input(const dealii::ParameterHandler &prm, const dealii::ParameterHandler &defaults,
                 dem::CommandState &command);

/// The entries of `prm` whose values differ from those of the input that `saved` keeps, but
/// those in `may_differ` (an entry's path, or a subsection's ending in '/': all its entries),
/// each as "'entry' = now (checkpoint: then)", joined by "; "; empty if none differs, nullopt if
/// `saved` keeps no input (written before checkpoints kept it).
std::optional<std::string> differing_entries(const dem::CommandState &saved, const dealii::ParameterHandler &prm,
                                             const dealii::ParameterHandler &defaults,
                                             const std::vector<std::string> &may_differ);

/// Refuses (std::invalid_argument) to resume from `checkpoint`, whose command state is `saved`,
/// with the input `prm` (read from `where`) if an entry not in `may_differ` has another value
/// than in the run that wrote it: the message names each such entry with both values (an entry
/// absent from a record is at its default, read from `defaults`), the file, and the entries that
/// may differ. A checkpoint written before checkpoints kept their input is accepted unchecked,
/// and `command` ("geohybrid pullout") says so on the terminal.
void check_resumed_input(const dem::CommandState &saved, const dealii::ParameterHandler &prm,
                         const dealii::ParameterHandler &defaults, const std::vector<std::string> &may_differ,
                         const std::filesystem::path &checkpoint, const std::string &where,
                         const std::string &command);

/// The entries of `geohybrid dem` that may change on resuming (its docs): the output directory,
/// the threads (the same numbers on any count), the checkpoint interval, the end time (to go on
/// further) and the output and snapshot intervals (the files continue on the new grid).
const std::vector<std::string> &dem_resume_entries();

/// The entries of `geohybrid pullout` that may change when resuming a checkpoint whose pull has
/// not started (the filled tank, filled_tank.h5 copied as checkpoint.h5): its run-control
/// entries, the pull rate and the grains' and the sheet's damping while pulling, which the filled
/// tank does not depend on (bench/run_pullout_rate_check pulls one tank at several rates).
const std::vector<std::string> &pullout_filled_tank_resume_entries();

/// store_input() of a pull-out's input.
void store_pullout_input(const dealii::ParameterHandler &prm, dem::CommandState &command);

/// Refuses to resume the run of `prm` (read from `where`) from the pull-out checkpoint `file`
/// (checkpoint.h5, or hybrid mode's filled_box.h5) if its input differs: check_resumed_input()
/// on its command state, with pullout_run_control_entries(), or
/// pullout_filled_tank_resume_entries() while its pull has not started. Reads the command state
/// only; throws std::runtime_error naming the file and `where` if it cannot be read.
void check_pullout_checkpoint(const std::filesystem::path &file, const dealii::ParameterHandler &prm,
                              const std::string &where);
/// Whether `directory` holds a pull-out run of the same physics as `prm` (its parameters.prm
/// hashes as `prm`, apps/parameters_hash.h): a --resume that finds no checkpoint there starts
/// that run again in its own directory; one of another run's is refused as a fresh run is.
bool holds_same_pullout_run(const std::filesystem::path &directory, const dealii::ParameterHandler &prm);
} // namespace geohybrid::apps
