#include "checkpoint.h"

#include "checkpoint_fields.h"
#include "checkpoint_reader.h"
#include "checkpoint_writer.h"
#include "hdf5_handles.h"
#include "hdf5_writable_file.h"

#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <cerrno>
#include <fcntl.h>
#include <unistd.h>

// The files themselves: written whole under a temporary name and renamed, read after checking
// what they are. What they hold is the field lists of checkpoint_fields.h.
namespace geohybrid::dem
{
namespace
{
using checkpoint_fields::Reader;
using checkpoint_fields::Writer;
using hdf5::fail;
using hdf5::Handle;

constexpr const char *format_name = "geohybrid DEM checkpoint";

std::string describe(const std::filesystem::path &file) { return "DEM checkpoint '" + file.string() + "'"; }

/// Flushes a file (or directory) to the disk. A directory that cannot be opened is skipped
/// (`required` false): some file systems do not allow it.
void sync_to_disk(const std::filesystem::path &path, bool required, const std::string &where)
{
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0)
    {
      if (required)
        fail(where, "cannot open '" + path.string() + "' to flush it: " + std::strerror(errno));
      return;
    }
  const int status = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (status != 0 && required)
    fail(where, "flushing '" + path.string() + "' to the disk failed: " + std::strerror(error));
}

/// Lengths and indices that the step loop relies on; a damaged or foreign file fails here rather
/// than by reading out of bounds later.
void check_consistency(const DemSystemState &s, const std::string &where)
{
  const ParticleSet &p = s.particles;
  const std::size_t nb = p.x.size(), nd = p.disc_radius.size();
  const auto require = [&](bool condition, const std::string &what) {
    if (!condition)
      fail(where, "inconsistent content: " + what);
  };
  for (std::size_t size : {p.body_id.size(), p.y.size(), p.rotation.size(), p.vx.size(), p.vy.size(),
                           p.omega.size(), p.fx.size(), p.fy.size(), p.torque.size(), p.mass.size(),
                           p.inertia.size(), p.inverse_mass.size(), p.inverse_inertia.size(),
                           p.first_disc.size(), p.n_discs.size(), s.damping_fx.size(), s.damping_fy.size(),
                           s.damping_torque.size()})
    require(size == nb, "body arrays of different lengths");
  for (std::size_t size : {p.disc_body.size(), p.disc_offset_x.size(), p.disc_offset_y.size(), p.disc_x.size(),
                           p.disc_y.size()})
    require(size == nd, "disc arrays of different lengths");
  for (std::size_t b = 0; b < nb; ++b)
    require(std::uint64_t(p.first_disc[b]) + p.n_discs[b] <= nd, "a body's discs are out of range");
  for (std::uint32_t b : p.disc_body)
    require(b < nb, "a disc's body is out of range");
  if (!s.rebuild_needed)
    require(s.disc_x_at_rebuild.size() == nd && s.disc_y_at_rebuild.size() == nd &&
              s.wall_start_at_rebuild.size() == s.walls.size(),
            "Verlet list reference positions of the wrong length");

  const PairContacts &c = s.pairs;
  const std::size_t n = c.size();
  for (std::size_t size : {c.disc_j.size(), c.state.size(), c.force_x.size(), c.force_y.size(),
                           c.torque_i.size(), c.torque_j.size(), c.elastic_normal_force.size(),
                           c.friction_work.size(), c.viscous_work.size()})
    require(size == n, "pair contact arrays of different lengths");
  for (std::size_t q = 0; q < n; ++q)
    require(c.disc_i[q] < c.disc_j[q] && c.disc_j[q] < nd, "a pair contact's discs are out of range");

  require(s.wall_contacts.size() == s.walls.size() && s.wall_force_previous.size() == s.walls.size(),
          "per-wall arrays of different lengths");
  for (const WallContacts &w : s.wall_contacts)
    {
      const std::size_t m = w.disc.size();
      for (std::size_t size : {w.state.size(), w.force_x.size(), w.force_y.size(), w.elastic_normal_force.size(),
                               w.friction_work.size(), w.viscous_work.size()})
        require(size == m, "wall contact arrays of different lengths");
      for (std::uint32_t d : w.disc)
        require(d < nd, "a wall contact's disc is out of range");
    }

  require(s.sheet_contacts.size() == s.sheets.size(), "sheets and sheet contact lists of different counts");
  for (std::size_t k = 0; k < s.sheets.size(); ++k)
    {
      const SparSheet &sheet = s.sheets[k];
      const SheetContacts &sc = s.sheet_contacts[k];
      const std::size_t n_nodes = sheet.x.size(), n_segments = sheet.rest_length.size();
      require(n_nodes >= 2 && n_segments + 1 == n_nodes, "a sheet's node and segment counts do not match");
      for (std::size_t size : {sheet.y.size(), sheet.vx.size(), sheet.vy.size(), sheet.fx.size(), sheet.fy.size(),
                               sheet.mass.size(), sheet.inverse_mass.size(), sheet.gravitational_mass.size(),
                               sheet.damping_fx.size(), sheet.damping_fy.size(), sheet.reaction_x.size(),
                               sheet.reaction_y.size(), sheet.load_x.size(), sheet.load_y.size()})
        require(size == n_nodes, "sheet node arrays of different lengths");
      require(sheet.tension.size() == n_segments, "sheet segment arrays of different lengths");
      for (double l0 : sheet.rest_length)
        require(l0 > 0.0, "a sheet segment's rest length is not positive");
      const std::size_t m = sc.disc.size();
      for (std::size_t size : {sc.segment.size(), sc.state.size(), sc.position.size(), sc.overlap.size(),
                               sc.counted.size(), sc.force_x.size(), sc.force_y.size(),
                               sc.elastic_normal_force.size(), sc.friction_work.size(), sc.viscous_work.size()})
        require(size == m, "sheet contact arrays of different lengths");
      for (std::size_t q = 0; q < m; ++q)
        require(sc.disc[q] < nd && sc.segment[q] < n_segments, "a sheet contact's disc or segment is out of range");
      if (!s.rebuild_needed)
        require(sc.node_x_at_rebuild.size() == n_nodes && sc.node_y_at_rebuild.size() == n_nodes &&
                  sc.walls.size() == s.walls.size(),
                "sheet reference positions or wall lists of the wrong length");
      for (const SheetWallContacts &w : sc.walls)
        {
          for (std::size_t size : {w.state.size(), w.force_x.size(), w.force_y.size(), w.elastic_normal_force.size(),
                                   w.friction_work.size(), w.viscous_work.size()})
            require(size == w.node.size(), "sheet-wall contact arrays of different lengths");
          for (std::uint32_t node : w.node)
            require(node < n_nodes, "a sheet-wall contact's node is out of range");
        }
    }
}

void write_checkpoint_file(const DemSystemState &state, const CommandState *command, const std::filesystem::path &file)
{
  const std::string where = describe(file);
  std::filesystem::path temporary = file;
  temporary += ".tmp";
  try
    {
      {
        hdf5::SilenceErrors silence;
        hdf5::WritableFile h5 = hdf5::WritableFile::create(temporary, where);
        Writer root(h5.get(), where);
        root.text("format", format_name);
        root.attribute("format_version", checkpoint_format_version);
        checkpoint_fields::visit_fields(state, root);
        if (command)
          root.group("command", [&](Writer &in) { checkpoint_fields::visit_fields(*command, in); });
        h5.close();
      }
      sync_to_disk(temporary, true, where);
    }
  catch (...)
    {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw;
    }
  std::error_code error;
  std::filesystem::rename(temporary, file, error);
  if (error)
    fail(where, "cannot replace it with '" + temporary.string() + "': " + error.message());
  // Make the rename itself durable.
  const std::filesystem::path directory = file.parent_path();
  sync_to_disk(directory.empty() ? std::filesystem::path(".") : directory, false, where);
}

/// With `state` null, only the command's state is read (the file checked as for the whole).
void read_checkpoint_file(const std::filesystem::path &file, DemSystemState *state, CommandState *command)
{
  const std::string where = describe(file);
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    fail(where, "does not exist or is not a file");
  hdf5::SilenceErrors silence;
  Handle fapl = hdf5::file_access(where);
#if H5_VERSION_GE(1, 12, 0)
  const htri_t is_hdf5 = H5Fis_accessible(file.c_str(), fapl.get());
#else
  const htri_t is_hdf5 = H5Fis_hdf5(file.c_str());
#endif
  if (is_hdf5 <= 0)
    fail(where, "is not a readable HDF5 file (damaged or not a checkpoint)");
  Handle h5(H5Fopen(file.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose, where, "opening the file");
  if (H5Aexists(h5.get(), "format") <= 0 || H5Aexists(h5.get(), "format_version") <= 0 ||
      hdf5::read_string_attribute(h5.get(), "format", where) != format_name)
    fail(where, "is not a geohybrid DEM checkpoint");
  std::uint32_t version = 0;
  hdf5::read_attribute(h5.get(), "format_version", H5T_NATIVE_UINT32, &version, where);
  if (version < 1 || version > checkpoint_format_version)
    fail(where, "has checkpoint format version " + std::to_string(version) + "; this program reads versions 1 to " +
                  std::to_string(checkpoint_format_version));
  Reader root(h5.get(), version, where);
  if (state)
    {
      *state = DemSystemState{};
      checkpoint_fields::visit_fields(*state, root);
      check_consistency(*state, where);
    }
  if (command)
    {
      *command = CommandState{};
      if (H5Lexists(h5.get(), "command", H5P_DEFAULT) > 0)
        root.group("command", [&](Reader &in) { checkpoint_fields::visit_fields(*command, in); });
    }
  h5.close(where, "closing the file");
}
} // namespace

void write_checkpoint(const DemSystemState &state, const std::filesystem::path &file)
{
  write_checkpoint_file(state, nullptr, file);
}

void write_checkpoint(const DemSystemState &state, const CommandState &command, const std::filesystem::path &file)
{
  write_checkpoint_file(state, &command, file);
}

DemSystemState read_checkpoint(const std::filesystem::path &file)
{
  DemSystemState state;
  read_checkpoint_file(file, &state, nullptr);
  return state;
}

DemSystemState read_checkpoint(const std::filesystem::path &file, CommandState &command)
{
  DemSystemState state;
  read_checkpoint_file(file, &state, &command);
  return state;
}

CommandState read_checkpoint_command(const std::filesystem::path &file)
{
  CommandState command;
  read_checkpoint_file(file, nullptr, &command);
  return command;
}

namespace
{
template <typename T>
const std::vector<T> &find_array(const std::map<std::string, std::vector<T>> &arrays, const std::string &name,
                                 const std::string &key, std::size_t size)
{
  const auto found = arrays.find(key);
  if (found == arrays.end())
    throw std::runtime_error("checkpoint of '" + name + "': no array '" + key + "'");
  if (size > 0 && found->second.size() != size)
    throw std::runtime_error("checkpoint of '" + name + "': array '" + key + "' holds " +
                             std::to_string(found->second.size()) + " values, expected " + std::to_string(size));
  return found->second;
}
} // namespace

const std::vector<double> &CommandState::real(const std::string &key, std::size_t size) const
{
  return find_array(reals, name, key, size);
}

const std::vector<std::uint64_t> &CommandState::count(const std::string &key, std::size_t size) const
{
  return find_array(counts, name, key, size);
}
} // namespace geohybrid::dem
