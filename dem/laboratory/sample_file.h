#pragma once
// REDF samples saved to a file and read back, so that one sample - the costly part of a biaxial
// campaign - serves many tests: the three confinements of a campaign, and later campaigns with
// other test settings. The seed is part of what is stored: a sample is named by how it was made.
//
// The file is a DEM checkpoint (dem/io/checkpoint.h: the complete DemSystemState, doubles stored
// exactly) with one more group, so a reloaded sample continues bit for bit as the one in memory
// would:
//
//   /redf_sample   attributes: format = "geohybrid REDF sample", format_version (uint32);
//                  the RedfSpec it was made from under its C++ names (n_particles, seed and
//                  max_steps uint64, shape "disc" or "two-disc cluster"; n_threads is not stored:
//                  results do not depend on it); groups particle_contact and wall_contact (the
//                  ContactParameters, as in a checkpoint's law groups); the RedfResult as
//                  result_<name>; the DemSettings of the sample's system as settings_<name>
//                  (settings_gravity_x, settings_gravity_y; track_energy uint8; n_threads not
//                  stored); the box's wall indices box_left, box_right, box_bottom, box_top
//                  (uint64)
#include "sample_preparation.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::dem
{
/// Version of the /redf_sample layout above; read_sample_file() refuses any other.
constexpr std::uint32_t sample_file_format_version = 2; // 2: size distributions (classes) instead of a size ratio

/// A REDF sample as values: how it was made and the complete state of its system.
struct StoredSample
{
  RedfSpec spec;
  RedfResult result;
  DemSettings settings; ///< the settings its DemSystem was built with
  RectangularBox box;
  DemSystemState state;
};

/// Takes the state of a sample made by make_redf_sample(spec).
StoredSample store_sample(const RedfSample &sample, const RedfSpec &spec);

/// A sample in the stored state, its DemSystem on `n_threads` threads. Each call gives an
/// independent copy that continues exactly as the stored sample's system would have.
RedfSample restore_sample(const StoredSample &stored, int n_threads);

/// Writes the sample to `file` (its directory is created if needed) through FILE.partial and a
/// rename, so an interrupted write never leaves a truncated sample under the name. Throws
/// std::runtime_error naming the file on failure.
void write_sample_file(const StoredSample &sample, const std::filesystem::path &file);

/// Reads a file written by write_sample_file(). Throws std::runtime_error naming the file if it
/// is missing, not a REDF sample file (for example a plain DEM checkpoint), of another format
/// version, damaged or inconsistent.
StoredSample read_sample_file(const std::filesystem::path &file);

/// The generation settings in which two specs differ, one "name: stored value, wanted value" item
/// each; empty when `wanted` would make the `stored` sample. The thread count and the step limit
/// do not count: they do not change the sample.
std::vector<std::string> sample_spec_differences(const RedfSpec &stored, const RedfSpec &wanted);
} // namespace geohybrid::dem
