#pragma once
// A fingerprint of a run's physics: the 64-bit FNV-1a hash of its resolved parameters that differ
// from their declared defaults, with the entries that only steer the run (where it writes, its
// threads, when it checkpoints or stops) left out. An entry added with a default that keeps the
// numbers as they were leaves every hash as it was, so committed validation runs stay matched to
// their inputs; a change of a default that changes numbers must raise `numbers_version`. Two inputs with the same hash make the same numbers, however they were written
// (comments, includes, order, alignment); summary.json keeps it as `parameters_hash`, so that a
// result can be matched to the input that made it (bench/run_validation skips a run whose
// committed summary holds its input's hash, and resumes a checkpoint only of the same input).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
class ParameterHandler;
}

namespace geohybrid::apps
{
/// FNV-1a, 64 bits (offset basis 0xcbf29ce484222325, prime 0x100000001b3), of the bytes of `text`.
std::uint64_t fnv1a_64(const std::string &text);

/// Raised when a default changes the numbers of an input that does not set that entry.
inline constexpr const char *numbers_version = "geohybrid numbers 2";

/// Every entry of `prm` as ("Subsection/.../entry", value), in ParameterHandler's order
/// (alphabetical within a subsection): the paths set_parameter() takes.
std::vector<std::pair<std::string, std::string>> parameter_entries(const dealii::ParameterHandler &prm);

/// numbers_version, then the entries of `prm` whose values differ from those of `defaults` (the
/// same declarations, nothing parsed), one line "Subsection/.../entry = value" each, in
/// ParameterHandler's order (alphabetical within a subsection), leaving out the entries whose
/// paths ("checkpoint interval", "Filling/seed") are in `excluded`: what the hash is taken of.
std::string canonical_parameters(const dealii::ParameterHandler &prm, const dealii::ParameterHandler &defaults,
                                 const std::vector<std::string> &excluded);

/// fnv1a_64 of canonical_parameters(prm, defaults, excluded), as 16 lowercase hexadecimal digits.
std::string parameters_hash(const dealii::ParameterHandler &prm, const dealii::ParameterHandler &defaults,
                            const std::vector<std::string> &excluded);

/// The entries of `geohybrid pullout` that cannot change its numbers, the one list of them: the
/// output directory; the threads (the particles' results are the same, bit for bit, on any
/// count); the checkpoint interval and 'stop after steps' (a stopped run resumed is the straight
/// run, bit for bit). They are left out of its hash, and a run may be resumed with other values.
const std::vector<std::string> &pullout_run_control_entries();

/// parameters_hash of a pull-out's resolved input without pullout_run_control_entries().
std::string pullout_parameters_hash(const dealii::ParameterHandler &prm);
} // namespace geohybrid::apps
