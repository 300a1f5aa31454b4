#pragma once
// Checkpoints of a DemSystem: its complete DemSystemState in one HDF5 file, so that a long run can
// be continued exactly (bit for bit) after a stop or a crash. The construction inputs (particle
// contact law, DemSettings) are not stored: the reader builds a DemSystem from the same input,
// then calls DemSystem::restore_state(read_checkpoint(file)). Walls are stored whole (geometry,
// contact law, control), so the saved walls replace those the system was built with.
//
// Each stored state is described once, as a list of its fields with their names in the file
// (checkpoint_fields.h), which the writer (checkpoint_writer.h) and the reader
// (checkpoint_reader.h) both walk; this file's functions handle the files themselves.
//
// HDF5 layout, format version 2 (doubles as IEEE 754 binary64, so values round-trip exactly;
// booleans as uint8; "n x 2" datasets hold (x, y) rows). Version 1 files (no sheets, no sheet
// energy terms) are still read, as a state without sheets:
//
//   /                 attributes: format = "geohybrid DEM checkpoint", format_version (uint32),
//                     time, time_step, skin (double), step_count, n_rebuilds, n_broken_bonds
//                     (uint64), rebuild_needed (uint8)
//   /energy           attributes: the EnergyBudget terms (double), by their C++ names (version 1:
//                     without sheet_kinetic, sheet_elastic, interface_friction_dissipated)
//   /particles/*      every ParticleSet array under its C++ name (body_id int64; first_disc,
//                     n_discs, disc_body uint32; the others double)
//   /pairs/*          disc_i, disc_j (uint32); the ContactState fields tangential_force,
//                     bonded, touching, dashpot_force; force_x, force_y, torque_i, torque_j,
//                     elastic_normal_force, friction_work, viscous_work
//   /walls            attribute count; /walls/wall_NNNNNN per wall: attributes name, control
//                     ("prescribed_velocity" or "servo_stress"), n_contacts (uint64),
//                     servo_target_stress, servo_relaxation, servo_max_speed; datasets start,
//                     end, velocity, force_from_particles (2 doubles); group law with the
//                     ContactParameters as attributes (bond_new_contacts uint8)
//   /wall_contacts    attribute count; /wall_contacts/wall_NNNNNN: disc (uint32), the ContactState
//                     fields, force_x, force_y, elastic_normal_force, friction_work, viscous_work
//   /verlet           disc_x_at_rebuild, disc_y_at_rebuild, wall_start_at_rebuild (n x 2)
//   /wall_force_previous   n x 2
//   /damping          fx, fy, torque
//   /sheets           (version 2) attribute count; /sheets/sheet_NNNNNN per sheet: attributes name,
//                     axial_stiffness, thickness, areal_mass, mass_scaling; group interface (the
//                     interface ContactParameters, as a wall's law); datasets x, y, vx, vy, fx, fy,
//                     mass, inverse_mass, gravitational_mass, damping_fx, damping_fy, reaction_x,
//                     reaction_y, load_x, load_y (per node), rest_length, tension (per segment);
//                     contacts/: disc, segment (uint32), the ContactState fields, position,
//                     overlap, counted (uint8), force_x, force_y, elastic_normal_force,
//                     friction_work, viscous_work, node_x_at_rebuild, node_y_at_rebuild;
//                     wall_contacts/ attribute count, wall_NNNNNN: node (uint32), the ContactState
//                     fields, force_x, force_y, elastic_normal_force, friction_work, viscous_work
//   /command          (optional, any version) what a command keeps beside the DEM state to go on
//                     with its own work (CommandState): attribute name; datasets reals/<key>
//                     (double) and counts/<key> (uint64); attributes real_keys, count_keys (the
//                     keys, one a line); optionally group texts with one string attribute per
//                     key and attribute text_keys (files written before it have none)
#include "dem/dem_system.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace geohybrid::dem
{
/// Version of the layout above; read_checkpoint() reads it and the earlier ones, refuses others.
constexpr std::uint32_t checkpoint_format_version = 2;

/// What a command stores with the DEM state to continue its own work exactly: a pull-out's
/// loop and the rows it has recorded, the description of its filled tank. Named arrays of
/// doubles and counts (round-tripped exactly); `name` says which command wrote them.
struct CommandState
{
  std::string name;
  std::map<std::string, std::vector<double>> reals;
  std::map<std::string, std::vector<std::uint64_t>> counts;
  /// Short texts (each under 64 KB), such as the input that made the run.
  std::map<std::string, std::string> texts;

  /// The array under `key`; throws std::runtime_error naming the key if there is none or if it
  /// does not hold `size` values (size 0: any).
  const std::vector<double> &real(const std::string &key, std::size_t size = 0) const;
  const std::vector<std::uint64_t> &count(const std::string &key, std::size_t size = 0) const;
};

/// Writes `state` to `file` through FILE.tmp in the same directory: the temporary file is
/// written, flushed to the disk (fsync) and renamed over `file`, so a crash at any moment leaves
/// either the previous checkpoint or the new one, never a partial file. Throws
/// std::runtime_error naming the file on failure (the previous checkpoint is then untouched).
void write_checkpoint(const DemSystemState &state, const std::filesystem::path &file);
/// The same with a command's state in /command.
void write_checkpoint(const DemSystemState &state, const CommandState &command, const std::filesystem::path &file);

/// Reads a checkpoint written by write_checkpoint(). Throws std::runtime_error naming the file if
/// it is missing, not a DEM checkpoint, of another format version, damaged, or inconsistent
/// (array lengths or indices that do not fit together).
DemSystemState read_checkpoint(const std::filesystem::path &file);
/// The same, and the command's state into `command` (its name empty if the file has none).
DemSystemState read_checkpoint(const std::filesystem::path &file, CommandState &command);
/// The command's state alone (its name empty if the file has none), checked as read_checkpoint()
/// checks the file, without reading the DEM state: to look at a checkpoint before using it.
CommandState read_checkpoint_command(const std::filesystem::path &file);
} // namespace geohybrid::dem
