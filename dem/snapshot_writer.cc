#include "snapshot_writer.h"

#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace geohybrid::dem
{
namespace
{
// ---- HDF5 error handling ------------------------------------------------------------------------

/// Turns off HDF5's printing of its error stack for the lifetime of the guard (the message goes
/// into the exception instead) and restores the previous handler afterwards.
class SilenceHdf5Errors
{
public:
  SilenceHdf5Errors()
  {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~SilenceHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  SilenceHdf5Errors(const SilenceHdf5Errors &) = delete;
  SilenceHdf5Errors &operator=(const SilenceHdf5Errors &) = delete;

private:
  H5E_auto2_t function_ = nullptr;
  void *data_ = nullptr;
};

herr_t collect_error(unsigned n, const H5E_error2_t *error, void *client_data)
{
  auto *text = static_cast<std::string *>(client_data);
  if (error->desc && *error->desc)
    {
      if (!text->empty())
        *text += "; ";
      for (const char *c = error->desc; *c; ++c)
        *text += (*c == '\n' ? ' ' : *c);
      if (error->func_name)
        *text += std::string(" (") + error->func_name + ")";
    }
  return n < 1 ? 0 : 1; // the two innermost entries say what went wrong
}

/// The innermost messages of the current HDF5 error stack.
std::string hdf5_error_text()
{
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, collect_error, &text);
  return text.empty() ? std::string("unknown HDF5 error") : text;
}

[[noreturn]] void fail(const std::filesystem::path &file, const std::string &what)
{
  throw std::runtime_error("DEM snapshot file '" + file.string() + "': " + what);
}

/// An HDF5 identifier that is closed when it goes out of scope.
class Handle
{
public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer, const std::filesystem::path &file, const std::string &what)
    : id_(id), closer_(closer)
  {
    if (id_ < 0)
      fail(file, what + " failed: " + hdf5_error_text());
  }
  ~Handle()
  {
    if (id_ >= 0)
      closer_(id_);
  }
  Handle(Handle &&other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Handle(const Handle &) = delete;
  Handle &operator=(const Handle &) = delete;
  Handle &operator=(Handle &&) = delete;
  hid_t get() const { return id_; }

  /// Closes now, reporting a failure (H5Fclose is where buffered data reach the disk).
  void close(const std::filesystem::path &file, const std::string &what)
  {
    const hid_t id = id_;
    id_ = -1;
    if (closer_(id) < 0)
      fail(file, what + " failed: " + hdf5_error_text());
  }

private:
  hid_t id_;
  Closer closer_;
};

void check(herr_t status, const std::filesystem::path &file, const std::string &what)
{
  if (status < 0)
    fail(file, what + " failed: " + hdf5_error_text());
}

/// File access properties: strong close, and no file locking where the library has it, so that a
/// reader holding the file open for a moment does not make a long run fail.
Handle file_access(const std::filesystem::path &file)
{
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, file, "creating file access properties");
  check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), file, "setting the close degree");
#if H5_VERSION_GE(1, 10, 7)
  check(H5Pset_file_locking(fapl.get(), 0, 1), file, "disabling file locking");
#endif
  return fapl;
}

/// Writes a dataset of the given shape (a first dimension of 0 gives an empty dataset).
void write_dataset(hid_t parent, const char *name, hid_t file_type, hid_t memory_type,
                   const std::vector<hsize_t> &dims, const void *data,
                   const std::filesystem::path &file)
{
  const std::string what = std::string("dataset '") + name + "'";
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, file,
               "creating the dataspace of " + what);
  Handle set(H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose, file, "creating " + what);
  hsize_t n = 1;
  for (hsize_t d : dims)
    n *= d;
  if (n > 0)
    check(H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), file, "writing " + what);
}

void write_doubles(hid_t parent, const char *name, const std::vector<double> &v, hsize_t columns,
                   const std::filesystem::path &file)
{
  std::vector<hsize_t> dims{v.size() / columns};
  if (columns > 1)
    dims.push_back(columns);
  write_dataset(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, v.data(), file);
}

void write_int64s(hid_t parent, const char *name, const std::vector<std::int64_t> &v, hsize_t columns,
                  const std::filesystem::path &file)
{
  std::vector<hsize_t> dims{v.size() / columns};
  if (columns > 1)
    dims.push_back(columns);
  write_dataset(parent, name, H5T_STD_I64LE, H5T_NATIVE_INT64, dims, v.data(), file);
}

void write_int32s(hid_t parent, const char *name, const std::vector<std::int32_t> &v,
                  const std::filesystem::path &file)
{
  write_dataset(parent, name, H5T_STD_I32LE, H5T_NATIVE_INT32, {v.size()}, v.data(), file);
}

void write_attribute(hid_t parent, const char *name, hid_t file_type, hid_t memory_type, const void *value,
                     const std::filesystem::path &file)
{
  const std::string what = std::string("attribute '") + name + "'";
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, file, "creating the dataspace of " + what);
  Handle attribute(H5Acreate2(parent, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                   file, "creating " + what);
  check(H5Awrite(attribute.get(), memory_type, value), file, "writing " + what);
}

void write_count(hid_t parent, const char *name, std::uint64_t value, const std::filesystem::path &file)
{
  write_attribute(parent, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value, file);
}

Handle create_group(hid_t parent, const std::string &name, const std::filesystem::path &file)
{
  return Handle(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, file,
                "creating group '" + name + "'");
}

// ---- data of one snapshot -----------------------------------------------------------------------

/// Lines of a contact network: two points per line and the values attached to each line.
struct ContactLines
{
  std::vector<double> points;                 // 2m x 3
  std::vector<std::int64_t> connectivity;     // m x 2
  std::vector<double> normal_force, tangential_force, force_magnitude;
  std::vector<std::int32_t> bonded, wall_index;

  std::size_t size() const { return normal_force.size(); }

  void add(const Vec2 &a, const Vec2 &b, double fn, double ft, double fx, double fy, bool is_bonded)
  {
    const auto first = static_cast<std::int64_t>(points.size() / 3);
    points.insert(points.end(), {a.x(), a.y(), 0.0, b.x(), b.y(), 0.0});
    connectivity.insert(connectivity.end(), {first, first + 1});
    normal_force.push_back(fn);
    tangential_force.push_back(ft);
    force_magnitude.push_back(std::hypot(fx, fy));
    bonded.push_back(is_bonded ? 1 : 0);
  }
};

double value_or_zero(const std::vector<double> &v, std::size_t q) { return q < v.size() ? v[q] : 0.0; }

ContactLines pair_lines(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  const PairContacts &c = system.pair_contacts();
  ContactLines lines;
  for (std::size_t q = 0; q < c.size(); ++q)
    {
      const ContactState &s = c.state[q];
      if (!s.touching)
        continue;
      const std::uint32_t i = c.disc_i[q], j = c.disc_j[q];
      lines.add(Vec2(p.disc_x[i], p.disc_y[i]), Vec2(p.disc_x[j], p.disc_y[j]),
                value_or_zero(c.elastic_normal_force, q), s.tangential_force, value_or_zero(c.force_x, q),
                value_or_zero(c.force_y, q), s.bonded);
    }
  return lines;
}

ContactLines wall_lines(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  ContactLines lines;
  const auto &all = system.wall_contacts();
  for (std::size_t w = 0; w < all.size() && w < system.walls().size(); ++w)
    {
      const Wall &wall = system.walls()[w];
      const WallContacts &c = all[w];
      for (std::size_t q = 0; q < c.disc.size(); ++q)
        {
          const ContactState &s = c.state[q];
          if (!s.touching)
            continue;
          const std::uint32_t d = c.disc[q];
          const Vec2 centre(p.disc_x[d], p.disc_y[d]);
          Vec2 closest;
          closest_point_on_segment(centre, wall.start, wall.end, closest);
          lines.add(centre, closest, value_or_zero(c.elastic_normal_force, q), s.tangential_force,
                    value_or_zero(c.force_x, q), value_or_zero(c.force_y, q), s.bonded);
          lines.wall_index.push_back(static_cast<std::int32_t>(w));
        }
    }
  return lines;
}

void write_lines(hid_t group, const ContactLines &lines, const std::filesystem::path &file)
{
  write_doubles(group, "points", lines.points, 3, file);
  write_int64s(group, "connectivity", lines.connectivity, 2, file);
  write_doubles(group, "normal_force", lines.normal_force, 1, file);
  write_doubles(group, "tangential_force", lines.tangential_force, 1, file);
  write_doubles(group, "force_magnitude", lines.force_magnitude, 1, file);
  write_int32s(group, "bonded", lines.bonded, file);
}

// ---- XDMF text ----------------------------------------------------------------------------------

std::string xml_escape(const std::string &s)
{
  std::string out;
  for (char ch : s)
    switch (ch)
      {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += ch;
      }
  return out;
}

struct XdmfGridWriter
{
  std::ostringstream &out;
  std::string file_prefix; // "name.h5:/snapshot_000000/"

  void data_item(const std::string &indent, const std::string &dims, const char *number_type, int precision,
                 const std::string &path)
  {
    out << indent << "<DataItem Dimensions=\"" << dims << "\" NumberType=\"" << number_type
        << "\" Precision=\"" << precision << "\" Format=\"HDF\">" << file_prefix << path << "</DataItem>\n";
  }
  void attribute(const char *name, const char *type, const char *centre, const std::string &dims,
                 const char *number_type, int precision, const std::string &path)
  {
    out << "          <Attribute Name=\"" << name << "\" AttributeType=\"" << type << "\" Center=\"" << centre
        << "\">\n";
    data_item("            ", dims, number_type, precision, path);
    out << "          </Attribute>\n";
  }

  void particles(std::size_t n)
  {
    const std::string ns = std::to_string(n), n3 = ns + " 3";
    out << "        <Grid Name=\"particles\" GridType=\"Uniform\">\n"
        << "          <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
        << "\" NodesPerElement=\"1\">\n";
    data_item("            ", ns, "Int", 8, "particles/connectivity");
    out << "          </Topology>\n"
        << "          <Geometry GeometryType=\"XYZ\">\n";
    data_item("            ", n3, "Float", 8, "particles/position");
    out << "          </Geometry>\n";
    attribute("radius", "Scalar", "Node", ns, "Float", 8, "particles/radius");
    attribute("velocity", "Vector", "Node", n3, "Float", 8, "particles/velocity");
    attribute("cluster_id", "Scalar", "Node", ns, "Int", 8, "particles/cluster_id");
    attribute("rotation", "Scalar", "Node", ns, "Float", 8, "particles/rotation");
    out << "        </Grid>\n";
  }

  void lines(const char *name, std::size_t m, bool with_wall_index)
  {
    const std::string ms = std::to_string(m), group = std::string(name) + "/";
    out << "        <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n"
        << "          <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << m << "\" NodesPerElement=\"2\">\n";
    data_item("            ", ms + " 2", "Int", 8, group + "connectivity");
    out << "          </Topology>\n"
        << "          <Geometry GeometryType=\"XYZ\">\n";
    data_item("            ", std::to_string(2 * m) + " 3", "Float", 8, group + "points");
    out << "          </Geometry>\n";
    attribute("normal_force", "Scalar", "Cell", ms, "Float", 8, group + "normal_force");
    attribute("tangential_force", "Scalar", "Cell", ms, "Float", 8, group + "tangential_force");
    attribute("force_magnitude", "Scalar", "Cell", ms, "Float", 8, group + "force_magnitude");
    attribute("bonded", "Scalar", "Cell", ms, "Int", 4, group + "bonded");
    if (with_wall_index)
      attribute("wall_index", "Scalar", "Cell", ms, "Int", 4, group + "wall_index");
    out << "        </Grid>\n";
  }
};

std::string snapshot_name(std::size_t index)
{
  char name[32];
  std::snprintf(name, sizeof(name), "snapshot_%06zu", index);
  return name;
}
} // namespace

SnapshotWriter::SnapshotWriter(const std::filesystem::path &directory, const std::string &basename)
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

  SilenceHdf5Errors silence;
  Handle fapl = file_access(h5_path_);
  Handle file(H5Fcreate(h5_path_.string().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose,
              h5_path_, "creating the file");
  file.close(h5_path_, "closing the file");
  write_xdmf();
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
  const ContactLines pairs = pair_lines(system);
  const ContactLines walls = wall_lines(system);

  const std::string name = snapshot_name(n_snapshots());
  {
    SilenceHdf5Errors silence;
    Handle fapl = file_access(h5_path_);
    Handle file(H5Fopen(h5_path_.string().c_str(), H5F_ACC_RDWR, fapl.get()), H5Fclose, h5_path_,
                "opening the file");
    // A snapshot that failed half-way earlier may have left its group behind: replace it.
    if (H5Lexists(file.get(), name.c_str(), H5P_DEFAULT) > 0)
      check(H5Ldelete(file.get(), name.c_str(), H5P_DEFAULT), h5_path_, "removing the incomplete group " + name);
    {
      Handle snapshot = create_group(file.get(), name, h5_path_);
      const double time = system.time();
      write_attribute(snapshot.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &time, h5_path_);
      write_count(snapshot.get(), "step", system.step_count(), h5_path_);
      write_count(snapshot.get(), "n_discs", n, h5_path_);
      write_count(snapshot.get(), "n_bodies", p.n_bodies(), h5_path_);
      write_count(snapshot.get(), "n_contacts", pairs.size(), h5_path_);
      write_count(snapshot.get(), "n_wall_contacts", walls.size(), h5_path_);
      {
        Handle g = create_group(snapshot.get(), "particles", h5_path_);
        write_doubles(g.get(), "position", position, 3, h5_path_);
        write_int64s(g.get(), "connectivity", connectivity, 1, h5_path_);
        write_doubles(g.get(), "radius", p.disc_radius, 1, h5_path_);
        write_doubles(g.get(), "velocity", velocity, 3, h5_path_);
        write_int64s(g.get(), "cluster_id", cluster_id, 1, h5_path_);
        write_doubles(g.get(), "rotation", rotation, 1, h5_path_);
      }
      {
        Handle g = create_group(snapshot.get(), "contacts", h5_path_);
        write_lines(g.get(), pairs, h5_path_);
      }
      {
        Handle g = create_group(snapshot.get(), "wall_contacts", h5_path_);
        write_lines(g.get(), walls, h5_path_);
        write_int32s(g.get(), "wall_index", walls.wall_index, h5_path_);
      }
    }
    file.close(h5_path_, "closing the file");
  }

  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(17);
  XdmfGridWriter grid{out, xml_escape(h5_name_) + ":/" + name + "/"};
  out << "      <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      << "        <Time Value=\"" << system.time() << "\"/>\n";
  // ParaView does not read empty grids: leave them out.
  if (n > 0)
    grid.particles(n);
  if (pairs.size() > 0)
    grid.lines("contacts", pairs.size(), false);
  if (walls.size() > 0)
    grid.lines("wall_contacts", walls.size(), true);
  out << "      </Grid>\n";
  xdmf_entries_.push_back(out.str());
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
