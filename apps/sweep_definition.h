#pragma once
// The input of `geohybrid sweep FILE.prm`: a pull-out input (the base) and the entries to vary,
// named as in the base input, each with its values:
//
//   set base input       = wraparound.prm     # beside the sweep file, or from the working directory
//   set output directory = output/sweep_B
//   set combination      = grid               # grid: every combination; list: the k-th values together
//   subsection Sweep
//     subsection Anchorage
//       set B = 0.125, 0.25, 0.5, 0.75
//     end
//     subsection Filling
//       set seed = 1, 2, 3
//     end
//   end
//
// subsection Sweep mirrors the pull-out's entries (declare_pullout_parameters), each a list of
// values, empty = not swept; values are separated by commas, or by semicolons when an entry's
// value is itself a list ('Pull/tension profiles at = 0.006, 0.06; 0.01', and '0.006, 0.02;' for
// one such value). An entry of one value is a plain override of the base input. Each value is checked
// against the entry's own pattern when the sweep is read. 'Filling/seed' is the replicate
// dimension: it is crossed with the other entries in either combination, and sweep.csv averages
// over it (apps/sweep_results.h). The run-control entries (pullout_run_control_entries(),
// apps/parameters_hash.h: output directory, threads, ...) are not swept: they change no number.
#include "apps/pullout_command.h"

#include <deal.II/base/parameter_handler.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
/// The replicate entry of a sweep.
inline const std::string sweep_seed_entry = "Filling/seed";

struct SweptEntry
{
  std::string path;                ///< "Anchorage/B"
  std::vector<std::string> values; ///< in the order given
};

struct SweepMember
{
  std::size_t index = 0;        ///< 0-based, in the sweep's order (rank index % n_ranks runs it)
  /// Its directory's name under the output directory, from the entries of several values and the
  /// seed: "B_0.125_seed_1".
  std::string name;
  ParameterOverrides values;    ///< (path, value) of every swept entry, in SweepDefinition::entries' order
};

struct SweepDefinition
{
  std::string input_file;                 ///< the sweep file
  std::string base_input;                 ///< the pull-out input every member runs
  std::filesystem::path output_directory; ///< the members' directories, sweep.csv, sweep.png
  bool grid = true;
  /// The swept entries: those of several values, then those of one (an override of the base
  /// input: 'mode = fem'), each in ParameterHandler's order, then Filling/seed if swept. The
  /// first is the x axis of sweep.png.
  std::vector<SweptEntry> entries;
  /// Members ordered so that each value of the entries but the first and the seed is one block,
  /// the first entry's values within it, the seeds innermost: a block is one curve of sweep.png.
  std::vector<SweepMember> members;
  bool sweeps_seeds() const { return !entries.empty() && entries.back().path == sweep_seed_entry; }
  /// The entries other than the seed.
  std::size_t n_varied() const { return entries.size() - (sweeps_seeds() ? 1 : 0); }
};

void declare_sweep_parameters(dealii::ParameterHandler &prm);

/// The pull-out's entries a sweep may vary (or a design's 'Overrides' set): all but its run-control
/// entries, as "Anchorage/B".
std::vector<std::string> sweepable_entries();

/// Declares each of sweepable_entries() in prm's current subsection (its own subsections nested
/// there), as text, empty by default; its doc is `head` + " of the pull-out's entry '...' (...)" + `tail`.
void declare_pullout_entry_texts(dealii::ParameterHandler &prm, const std::string &head, const std::string &tail);

/// A base input named in `input_file`, resolved like an 'include': beside that file first, then as given.
std::string resolve_base_input(const std::string &input_file, const std::string &base);

/// Reads `input_file` into `prm` (declared by declare_sweep_parameters) and makes its members.
/// Throws std::runtime_error naming the file and the entry for: no entry swept, a value that its
/// entry's pattern refuses, list entries of different lengths, a base input that cannot be read.
SweepDefinition parse_sweep(const std::string &input_file, dealii::ParameterHandler &prm);

/// The same for a `prm` already read or set (`geohybrid design` makes each step's sweep so);
/// `input_file` names it in errors and places its base input.
SweepDefinition make_sweep(const std::string &input_file, const dealii::ParameterHandler &prm);

/// The base input with the member's values and `output_directory` set, as its run reads it.
void read_member_input(const SweepDefinition &sweep, const SweepMember &member, dealii::ParameterHandler &prm);

/// The member's overrides for run_pullout_command: its values and its output directory.
ParameterOverrides member_overrides(const SweepDefinition &sweep, const SweepMember &member);
} // namespace geohybrid::apps
