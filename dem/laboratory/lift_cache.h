#pragma once
// The lifts of a tank fill below its first sheet are the same in every case of one tank and seed:
// the run-outs and wrap-arounds of one depth, every B and geosynthetic, every interface angle a
// calibration tries. Grown and settled once, such a lift is kept in a directory and taken from it
// by any fill that starts it from the same state with the same settings, bit for bit the lift
// that fill would have made (issue 23, part 3: the first lift is a third of a fill's steps).
//
// The key is a hash of everything the lift's growth and settling read: the particles as placed
// (the lifts below them included, each with its velocity, forces and sizes), the fill's spec but
// its sheet (not laid yet below the first sheet) and its threads (results do not depend on them),
// the lift's REDF spec, levels and lid, and the code's numbers version.
#include "dem/particles.h"
#include "sample_preparation.h"
#include "tank_filling.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace geohybrid::dem
{
std::uint64_t lift_cache_key(const TankFillingSpec &spec, std::size_t layer_index, const RedfSpec &redf,
                             const TankLayer &layer, double lid_level, const ParticleSet &placed);

/// DIRECTORY/lift_<key as 16 hexadecimal digits>.h5
std::filesystem::path lift_cache_file(const std::filesystem::path &directory, std::uint64_t key);

/// Writes the settled system and the lift's record to `file` (through a temporary file of this
/// process, renamed: two fills writing the same lift leave one whole file). Throws
/// std::runtime_error naming the file.
void save_lift(const DemSystem &settled, const TankLayer &layer, std::uint64_t key, const std::filesystem::path &file);

/// The settled system's state and the lift's record from `file`, or nothing if there is no such
/// file. Throws std::runtime_error naming the file if it cannot be read or holds another key.
std::optional<DemSystemState> load_lift(const std::filesystem::path &file, std::uint64_t key, TankLayer &layer);
} // namespace geohybrid::dem
