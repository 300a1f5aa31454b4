// SnapshotWriter: the HDF5 file of the snapshots and the .xdmf that lists them. What a snapshot
// holds is gathered in snapshot_contents.cc, its XDMF text written in snapshot_xdmf.cc.
#include "snapshot_writer.h"

#include "hdf5_handles.h"
#include "hdf5_writable_file.h"
#include "snapshot_contents.h"
#include "snapshot_xdmf.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace geohybrid::dem
{
namespace
{
using hdf5::check;
using hdf5::create_group;
using hdf5::Handle;
using hdf5::write_attribute;
using hdf5::write_dataset;
using snapshot_detail::ContactLines;
using snapshot_detail::SheetGeometry;
using snapshot_detail::SnapshotCounts;

/// How failures name the file: "DEM snapshot file '...'".
std::string describe(const std::filesystem::path &file) { return "DEM snapshot file '" + file.string() + "'"; }

[[noreturn]] void fail(const std::filesystem::path &file, const std::string &what)
{
  hdf5::fail(describe(file), what);
}

template <typename Allocator>
void write_doubles(hid_t parent, const char *name, const std::vector<double, Allocator> &v, hsize_t columns,
                   const std::string &where)
{
  std::vector<hsize_t> dims{v.size() / columns};
  if (columns > 1)
    dims.push_back(columns);
  write_dataset(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, v.data(), where);
}

void write_int64s(hid_t parent, const char *name, const std::vector<std::int64_t> &v, hsize_t columns,
                  const std::string &where)
{
  std::vector<hsize_t> dims{v.size() / columns};
  if (columns > 1)
    dims.push_back(columns);
  write_dataset(parent, name, H5T_STD_I64LE, H5T_NATIVE_INT64, dims, v.data(), where);
}

void write_int32s(hid_t parent, const char *name, const std::vector<std::int32_t> &v, const std::string &where)
{
  write_dataset(parent, name, H5T_STD_I32LE, H5T_NATIVE_INT32, {v.size()}, v.data(), where);
}

void write_count(hid_t parent, const char *name, std::uint64_t value, const std::string &where)
{
  write_attribute(parent, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value, where);
}

void write_lines(hid_t group, const ContactLines &lines, const std::string &where)
{
  write_doubles(group, "points", lines.points, 3, where);
  write_int64s(group, "connectivity", lines.connectivity, 2, where);
  write_doubles(group, "normal_force", lines.normal_force, 1, where);
  write_doubles(group, "tangential_force", lines.tangential_force, 1, where);
  write_doubles(group, "force_magnitude", lines.force_magnitude, 1, where);
  write_int32s(group, "bonded", lines.bonded, where);
}

std::string snapshot_name(std::size_t index)
{
  char name[32];
  std::snprintf(name, sizeof(name), "snapshot_%06zu", index);
  return name;
}

/// True if `path` (relative to `parent`, components separated by '/') exists, checking each
/// component in turn (H5Lexists fails on a missing intermediate group).
bool link_exists(hid_t parent, const std::string &path)
{
  for (std::size_t end = path.find('/');; end = path.find('/', end + 1))
    {
      const std::string prefix = path.substr(0, end);
      if (H5Lexists(parent, prefix.c_str(), H5P_DEFAULT) <= 0)
        return false;
      if (end == std::string::npos)
        return true;
    }
}
} // namespace

SnapshotWriter::SnapshotWriter(const std::filesystem::path &directory, const std::string &basename)
  : SnapshotWriter(directory, basename, true)
{}

SnapshotWriter::SnapshotWriter(const std::filesystem::path &directory, const std::string &basename, bool create)
  : h5_path_(directory / (basename + ".h5")), xdmf_path_(directory / (basename + ".xdmf")),
    h5_name_(basename + ".h5")
{
  if (basename.empty())
    throw std::runtime_error("DEM snapshot writer: empty file name in directory '" + directory.string() + "'");
  std::error_code error;
  if (!directory.empty())
    std::filesystem::create_directories(directory, error);
  if (error)
    fail(h5_path_, "cannot create directory '" + directory.string() + "': " + error.message());
  if (create)
    create_empty_files();
}

void SnapshotWriter::create_empty_files()
{
  const std::string where = describe(h5_path_);
  hdf5::SilenceErrors silence;
  hdf5::WritableFile::create(h5_path_, where).close();
  xdmf_entries_.clear();
  write_xdmf();
}

SnapshotWriter SnapshotWriter::resume(const std::filesystem::path &directory, const std::string &basename,
                                      double keep_until_time)
{
  SnapshotWriter writer(directory, basename, false);
  std::error_code error;
  if (!std::filesystem::exists(writer.h5_path_, error))
    {
      writer.create_empty_files();
      return writer;
    }
  const std::string where = describe(writer.h5_path_);
  {
    hdf5::SilenceErrors silence;
    std::optional<hdf5::WritableFile> reopened;
    try
      {
        reopened.emplace(hdf5::WritableFile::open(writer.h5_path_, where));
      }
    catch (const std::runtime_error &e)
      {
        throw std::runtime_error(std::string(e.what()) +
                                 "; move it away to start a new snapshot file from the resumed time on");
      }
    hdf5::WritableFile &file = *reopened;
    bool keeping = true;
    for (std::size_t index = 0;; ++index)
      {
        const std::string name = snapshot_name(index);
        if (H5Lexists(file.get(), name.c_str(), H5P_DEFAULT) <= 0)
          break;
        if (keeping)
          {
            Handle group = hdf5::open_group(file.get(), name, where);
            double time = 0.0;
            SnapshotCounts counts;
            // A snapshot is complete when its attributes and last dataset are there.
            const bool complete = H5Aexists(group.get(), "time") > 0 && H5Aexists(group.get(), "n_discs") > 0 &&
                                  H5Aexists(group.get(), "n_contacts") > 0 &&
                                  H5Aexists(group.get(), "n_wall_contacts") > 0 &&
                                  link_exists(group.get(), "wall_contacts/wall_index");
            if (complete)
              {
                hdf5::read_attribute(group.get(), "time", H5T_NATIVE_DOUBLE, &time, where);
                hdf5::read_attribute(group.get(), "n_discs", H5T_NATIVE_UINT64, &counts.n_discs, where);
                hdf5::read_attribute(group.get(), "n_contacts", H5T_NATIVE_UINT64, &counts.n_contacts, where);
                hdf5::read_attribute(group.get(), "n_wall_contacts", H5T_NATIVE_UINT64, &counts.n_wall_contacts, where);
                // Files written before sheets existed have no sheet counts: none.
                for (auto [attribute, value] : {std::pair{"n_sheet_nodes", &counts.n_sheet_nodes},
                                                std::pair{"n_sheet_segments", &counts.n_sheet_segments},
                                                std::pair{"n_sheet_contacts", &counts.n_sheet_contacts}})
                  if (H5Aexists(group.get(), attribute) > 0)
                    hdf5::read_attribute(group.get(), attribute, H5T_NATIVE_UINT64, value, where);
              }
            keeping = complete && time <= keep_until_time;
            if (keeping)
              {
                writer.xdmf_entries_.push_back(snapshot_detail::xdmf_entry(writer.h5_name_, name, time, counts));
                continue;
              }
          }
        // Snapshots are in time order: this one and all later ones go.
        check(H5Ldelete(file.get(), name.c_str(), H5P_DEFAULT), where, "removing " + name);
      }
    file.close();
  }
  writer.write_xdmf();
  return writer;
}

void SnapshotWriter::write(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  const std::size_t n = p.n_discs_total();

  // Gather everything first, so that the file is open only while writing.
  std::vector<double> position(3 * n), velocity(3 * n), rotation(n);
  std::vector<std::int64_t> cluster_id(n), connectivity(n);
  for (std::size_t d = 0; d < n; ++d)
    {
      const std::uint32_t b = p.disc_body[d];
      const Vec2 lever(p.disc_x[d] - p.x[b], p.disc_y[d] - p.y[b]);
      const Vec2 v = Vec2(p.vx[b], p.vy[b]) + spin_velocity(p.omega[b], lever);
      position[3 * d] = p.disc_x[d];
      position[3 * d + 1] = p.disc_y[d];
      position[3 * d + 2] = 0.0;
      velocity[3 * d] = v.x();
      velocity[3 * d + 1] = v.y();
      velocity[3 * d + 2] = 0.0;
      rotation[d] = p.rotation[b];
      cluster_id[d] = p.body_id[b];
      connectivity[d] = static_cast<std::int64_t>(d);
    }
  const ContactLines pairs = snapshot_detail::pair_lines(system);
  const ContactLines walls = snapshot_detail::wall_lines(system);
  const ContactLines sheet_contacts = snapshot_detail::sheet_contact_lines(system);
  const SheetGeometry sheets = snapshot_detail::sheet_geometry(system);
  SnapshotCounts counts;
  counts.n_discs = n;
  counts.n_contacts = pairs.size();
  counts.n_wall_contacts = walls.size();
  counts.n_sheet_nodes = sheets.n_nodes();
  counts.n_sheet_segments = sheets.n_segments();
  counts.n_sheet_contacts = sheet_contacts.size();

  const std::string name = snapshot_name(n_snapshots());
  const std::string where = describe(h5_path_);
  {
    hdf5::SilenceErrors silence;
    hdf5::WritableFile file = hdf5::WritableFile::open(h5_path_, where);
    // A snapshot that failed half-way earlier may have left its group behind: replace it.
    if (H5Lexists(file.get(), name.c_str(), H5P_DEFAULT) > 0)
      check(H5Ldelete(file.get(), name.c_str(), H5P_DEFAULT), where, "removing the incomplete group " + name);
    {
      Handle snapshot = create_group(file.get(), name, where);
      const double time = system.time();
      write_attribute(snapshot.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &time, where);
      write_count(snapshot.get(), "step", system.step_count(), where);
      write_count(snapshot.get(), "n_discs", n, where);
      write_count(snapshot.get(), "n_bodies", p.n_bodies(), where);
      write_count(snapshot.get(), "n_contacts", pairs.size(), where);
      write_count(snapshot.get(), "n_wall_contacts", walls.size(), where);
      write_count(snapshot.get(), "n_sheet_nodes", counts.n_sheet_nodes, where);
      write_count(snapshot.get(), "n_sheet_segments", counts.n_sheet_segments, where);
      write_count(snapshot.get(), "n_sheet_contacts", counts.n_sheet_contacts, where);
      {
        Handle g = create_group(snapshot.get(), "particles", where);
        write_doubles(g.get(), "position", position, 3, where);
        write_int64s(g.get(), "connectivity", connectivity, 1, where);
        write_doubles(g.get(), "radius", p.disc_radius, 1, where);
        write_doubles(g.get(), "velocity", velocity, 3, where);
        write_int64s(g.get(), "cluster_id", cluster_id, 1, where);
        write_doubles(g.get(), "rotation", rotation, 1, where);
      }
      {
        Handle g = create_group(snapshot.get(), "contacts", where);
        write_lines(g.get(), pairs, where);
      }
      {
        Handle g = create_group(snapshot.get(), "sheets", where);
        write_doubles(g.get(), "position", sheets.position, 3, where);
        write_doubles(g.get(), "velocity", sheets.velocity, 3, where);
        write_int32s(g.get(), "sheet_index", sheets.sheet_index, where);
        write_int64s(g.get(), "connectivity", sheets.connectivity, 2, where);
        write_doubles(g.get(), "tension", sheets.tension, 1, where);
        write_doubles(g.get(), "strain", sheets.strain, 1, where);
      }
      {
        Handle g = create_group(snapshot.get(), "sheet_contacts", where);
        write_lines(g.get(), sheet_contacts, where);
        write_int32s(g.get(), "wall_index", sheet_contacts.wall_index, where);
      }
      // Written last: its presence marks a complete snapshot (resume()).
      {
        Handle g = create_group(snapshot.get(), "wall_contacts", where);
        write_lines(g.get(), walls, where);
        write_int32s(g.get(), "wall_index", walls.wall_index, where);
      }
    }
    file.close(); // a snapshot is listed in the .xdmf only once its file is complete on the disk
  }

  xdmf_entries_.push_back(snapshot_detail::xdmf_entry(h5_name_, name, system.time(), counts));
  try
    {
      write_xdmf();
    }
  catch (...)
    {
      xdmf_entries_.pop_back(); // keep n_snapshots() equal to what the .xdmf lists
      throw;
    }
}

void SnapshotWriter::write_xdmf() const
{
  // Write a temporary file and rename it over the old one, so that a reader never sees half a file.
  std::filesystem::path temporary = xdmf_path_;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    if (!out)
      fail(xdmf_path_, "cannot create '" + temporary.string() + "'");
    out << "<?xml version=\"1.0\" ?>\n"
        << "<Xdmf Version=\"3.0\">\n"
        << "  <Domain>\n";
    if (!xdmf_entries_.empty())
      {
        out << "    <Grid Name=\"dem\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
        for (const std::string &entry : xdmf_entries_)
          out << entry;
        out << "    </Grid>\n";
      }
    out << "  </Domain>\n"
        << "</Xdmf>\n";
    out.close();
    if (!out)
      fail(xdmf_path_, "writing '" + temporary.string() + "' failed");
  }
  std::error_code error;
  std::filesystem::rename(temporary, xdmf_path_, error);
  if (error)
    fail(xdmf_path_, "cannot replace it with '" + temporary.string() + "': " + error.message());
}
} // namespace geohybrid::dem
