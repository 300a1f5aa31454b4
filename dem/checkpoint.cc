#include "checkpoint.h"

#include "checkpoint_writer.h"
#include "hdf5_handles.h"
#include "hdf5_types.h"
#include "hdf5_writable_file.h"

#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <cerrno>
#include <fcntl.h>
#include <unistd.h>

namespace geohybrid::dem
{
namespace
{
using hdf5::check;
using hdf5::fail;
using hdf5::Handle;
using hdf5::Type;

constexpr const char *format_name = "geohybrid DEM checkpoint";

std::string describe(const std::filesystem::path &file) { return "DEM checkpoint '" + file.string() + "'"; }

std::string numbered(const char *prefix, std::size_t index)
{
  char name[48];
  std::snprintf(name, sizeof(name), "%s_%06zu", prefix, index);
  return name;
}

const char *control_name(WallControl control)
{
  return control == WallControl::servo_stress ? "servo_stress" : "prescribed_velocity";
}

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

// ---- reading ----------------------------------------------------------------------------------------

template <typename T>
T get_attr(hid_t parent, const char *name, const std::string &where)
{
  T value{};
  hdf5::read_attribute(parent, name, Type<T>::memory(), &value, where);
  return value;
}

/// Reads a dataset of any number of rows and `columns` columns (one dimension if columns == 1)
/// whose stored type is of the class and size of T.
template <typename T>
SoaVector<T> get(hid_t parent, const char *name, const std::string &where, std::size_t columns = 1)
{
  const std::string what = std::string("dataset '") + name + "'";
  Handle set(H5Dopen2(parent, name, H5P_DEFAULT), H5Dclose, where, "opening " + what);
  Handle type(H5Dget_type(set.get()), H5Tclose, where, "reading the type of " + what);
  if (H5Tget_class(type.get()) != Type<T>::type_class || H5Tget_size(type.get()) != sizeof(T))
    fail(where, what + " has an unexpected type");
  const std::vector<hsize_t> dims = hdf5::dataset_shape(set.get(), where, what);
  if (dims.size() != (columns > 1 ? 2u : 1u) || (columns > 1 && dims[1] != columns))
    fail(where, what + " has an unexpected shape");
  SoaVector<T> values(static_cast<std::size_t>(dims[0]) * columns);
  if (!values.empty())
    check(H5Dread(set.get(), Type<T>::memory(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), where,
          "reading " + what);
  return values;
}

std::vector<Vec2> get_vec2s(hid_t parent, const char *name, const std::string &where)
{
  const auto flat = get<double>(parent, name, where, 2);
  std::vector<Vec2> values(flat.size() / 2);
  for (std::size_t k = 0; k < values.size(); ++k)
    values[k] = Vec2(flat[2 * k], flat[2 * k + 1]);
  return values;
}

Vec2 get_vec2(hid_t parent, const char *name, const std::string &where)
{
  const auto v = get<double>(parent, name, where);
  if (v.size() != 2)
    fail(where, std::string("dataset '") + name + "' does not hold 2 values");
  return Vec2(v[0], v[1]);
}

bool get_bool(hid_t parent, const char *name, const std::string &where)
{
  const std::uint8_t b = get_attr<std::uint8_t>(parent, name, where);
  if (b > 1)
    fail(where, std::string("attribute '") + name + "' is not 0 or 1");
  return b == 1;
}

SoaVector<ContactState> get_states(hid_t parent, const std::string &where)
{
  const auto tangential_force = get<double>(parent, "tangential_force", where);
  const auto bonded = get<std::uint8_t>(parent, "bonded", where);
  const auto touching = get<std::uint8_t>(parent, "touching", where);
  const auto dashpot_force = get<double>(parent, "dashpot_force", where);
  if (bonded.size() != tangential_force.size() || touching.size() != tangential_force.size() ||
      dashpot_force.size() != tangential_force.size())
    fail(where, "contact states of different lengths");
  SoaVector<ContactState> states(tangential_force.size());
  for (std::size_t q = 0; q < states.size(); ++q)
    {
      if (bonded[q] > 1 || touching[q] > 1)
        fail(where, "a contact state flag is not 0 or 1");
      states[q].tangential_force = tangential_force[q];
      states[q].bonded = bonded[q] == 1;
      states[q].touching = touching[q] == 1;
      states[q].dashpot_force = dashpot_force[q];
    }
  return states;
}

ContactParameters get_law(hid_t parent, const char *name, const std::string &where)
{
  ContactParameters c;
  Handle law = hdf5::open_group(parent, name, where);
  c.normal_stiffness = get_attr<double>(law.get(), "normal_stiffness", where);
  c.shear_stiffness = get_attr<double>(law.get(), "shear_stiffness", where);
  c.friction_angle_deg = get_attr<double>(law.get(), "friction_angle_deg", where);
  c.shear_strength = get_attr<double>(law.get(), "shear_strength", where);
  c.tensile_strength = get_attr<double>(law.get(), "tensile_strength", where);
  c.restitution = get_attr<double>(law.get(), "restitution", where);
  c.bond_new_contacts = get_bool(law.get(), "bond_new_contacts", where);
  return c;
}

Wall get_wall(hid_t group, const std::string &where)
{
  const ContactParameters c = get_law(group, "law", where);
  const std::string name = hdf5::read_string_attribute(group, "name", where);
  LinearContactLaw law;
  try
    {
      law = LinearContactLaw(c);
    }
  catch (const std::invalid_argument &e)
    {
      fail(where, "wall '" + name + "': " + e.what());
    }
  Wall wall(name, get_vec2(group, "start", where), get_vec2(group, "end", where), law);
  const std::string control = hdf5::read_string_attribute(group, "control", where);
  if (control == control_name(WallControl::servo_stress))
    wall.control = WallControl::servo_stress;
  else if (control == control_name(WallControl::prescribed_velocity))
    wall.control = WallControl::prescribed_velocity;
  else
    fail(where, "wall '" + name + "' has an unknown control '" + control + "'");
  wall.velocity = get_vec2(group, "velocity", where);
  wall.servo.target_stress = get_attr<double>(group, "servo_target_stress", where);
  wall.servo.relaxation = get_attr<double>(group, "servo_relaxation", where);
  wall.servo.max_speed = get_attr<double>(group, "servo_max_speed", where);
  wall.servo.integral_gain = get_attr<double>(group, "servo_integral_gain", where);
  wall.servo.integral = get_attr<double>(group, "servo_integral", where);
  wall.force_from_particles = get_vec2(group, "force_from_particles", where);
  wall.n_contacts = static_cast<std::size_t>(get_attr<std::uint64_t>(group, "n_contacts", where));
  wall.loaded_length = get_attr<double>(group, "loaded_length", where);
  // Checkpoints written before the attribute existed: every wall touched sheets.
  wall.touches_sheets =
    H5Aexists(group, "touches_sheets") <= 0 || get_attr<std::uint64_t>(group, "touches_sheets", where) != 0;
  return wall;
}

std::size_t get_count(hid_t group, const std::string &where)
{
  const std::uint64_t count = get_attr<std::uint64_t>(group, "count", where);
  if (count > 1000000)
    fail(where, "implausible count " + std::to_string(count));
  return static_cast<std::size_t>(count);
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

SparSheet get_sheet(hid_t group, SheetContacts &c, const std::string &where)
{
  const std::string name = hdf5::read_string_attribute(group, "name", where);
  SheetParameters parameters;
  parameters.axial_stiffness = get_attr<double>(group, "axial_stiffness", where);
  parameters.thickness = get_attr<double>(group, "thickness", where);
  parameters.areal_mass = get_attr<double>(group, "areal_mass", where);
  parameters.mass_scaling = get_attr<double>(group, "mass_scaling", where);
  parameters.interface = get_law(group, "interface", where);
  const SoaVector<double> rest_length = get<double>(group, "rest_length", where);
  // A chain of the right size, built to validate the parameters; every array is then replaced
  // by the stored one.
  std::vector<Vec2> nodes(rest_length.size() + 1);
  for (std::size_t k = 0; k < nodes.size(); ++k)
    nodes[k] = Vec2(static_cast<double>(k), 0.0);
  std::optional<SparSheet> sheet;
  try
    {
      sheet.emplace(name, nodes, parameters);
    }
  catch (const std::invalid_argument &e)
    {
      fail(where, e.what());
    }
  SparSheet &out = *sheet;
  out.rest_length = rest_length;
  out.x = get<double>(group, "x", where);
  out.y = get<double>(group, "y", where);
  out.vx = get<double>(group, "vx", where);
  out.vy = get<double>(group, "vy", where);
  out.fx = get<double>(group, "fx", where);
  out.fy = get<double>(group, "fy", where);
  out.mass = get<double>(group, "mass", where);
  out.inverse_mass = get<double>(group, "inverse_mass", where);
  out.gravitational_mass = get<double>(group, "gravitational_mass", where);
  out.damping_fx = get<double>(group, "damping_fx", where);
  out.damping_fy = get<double>(group, "damping_fy", where);
  out.reaction_x = get<double>(group, "reaction_x", where);
  out.reaction_y = get<double>(group, "reaction_y", where);
  out.load_x = get<double>(group, "load_x", where);
  out.load_y = get<double>(group, "load_y", where);
  out.tension = get<double>(group, "tension", where);
  {
    Handle g = hdf5::open_group(group, "contacts", where);
    c.disc = get<std::uint32_t>(g.get(), "disc", where);
    c.segment = get<std::uint32_t>(g.get(), "segment", where);
    c.state = get_states(g.get(), where);
    c.position = get<double>(g.get(), "position", where);
    c.overlap = get<double>(g.get(), "overlap", where);
    c.counted = get<std::uint8_t>(g.get(), "counted", where);
    c.force_x = get<double>(g.get(), "force_x", where);
    c.force_y = get<double>(g.get(), "force_y", where);
    c.elastic_normal_force = get<double>(g.get(), "elastic_normal_force", where);
    c.friction_work = get<double>(g.get(), "friction_work", where);
    c.viscous_work = get<double>(g.get(), "viscous_work", where);
    c.node_x_at_rebuild = get<double>(g.get(), "node_x_at_rebuild", where);
    c.node_y_at_rebuild = get<double>(g.get(), "node_y_at_rebuild", where);
  }
  {
    Handle g = hdf5::open_group(group, "wall_contacts", where);
    const std::size_t count = get_count(g.get(), where);
    c.walls.resize(count);
    for (std::size_t w = 0; w < count; ++w)
      {
        SheetWallContacts &wc = c.walls[w];
        Handle one = hdf5::open_group(g.get(), numbered("wall", w), where);
        wc.node = get<std::uint32_t>(one.get(), "node", where);
        wc.state = get_states(one.get(), where);
        wc.force_x = get<double>(one.get(), "force_x", where);
        wc.force_y = get<double>(one.get(), "force_y", where);
        wc.elastic_normal_force = get<double>(one.get(), "elastic_normal_force", where);
        wc.friction_work = get<double>(one.get(), "friction_work", where);
        wc.viscous_work = get<double>(one.get(), "viscous_work", where);
      }
  }
  return out;
}

DemSystemState get_everything(hid_t file, std::uint32_t version, const std::string &where)
{
  DemSystemState s;
  s.time = get_attr<double>(file, "time", where);
  s.time_step = get_attr<double>(file, "time_step", where);
  s.skin = get_attr<double>(file, "skin", where);
  s.radius_growth_since_rebuild = get_attr<double>(file, "radius_growth_since_rebuild", where);
  s.particle_contact = get_law(file, "particle_law", where);
  s.step_count = get_attr<std::uint64_t>(file, "step_count", where);
  s.n_rebuilds = get_attr<std::uint64_t>(file, "n_rebuilds", where);
  s.n_broken_bonds = get_attr<std::uint64_t>(file, "n_broken_bonds", where);
  s.rebuild_needed = get_bool(file, "rebuild_needed", where);
  {
    Handle g = hdf5::open_group(file, "energy", where);
    EnergyBudget &e = s.accumulated;
    e.kinetic = get_attr<double>(g.get(), "kinetic", where);
    e.gravitational = get_attr<double>(g.get(), "gravitational", where);
    e.elastic = get_attr<double>(g.get(), "elastic", where);
    e.friction_dissipated = get_attr<double>(g.get(), "friction_dissipated", where);
    e.viscous_dissipated = get_attr<double>(g.get(), "viscous_dissipated", where);
    e.local_damping_dissipated = get_attr<double>(g.get(), "local_damping_dissipated", where);
    e.boundary_work = get_attr<double>(g.get(), "boundary_work", where);
    if (version >= 2)
      {
        e.sheet_kinetic = get_attr<double>(g.get(), "sheet_kinetic", where);
        e.sheet_elastic = get_attr<double>(g.get(), "sheet_elastic", where);
        e.interface_friction_dissipated = get_attr<double>(g.get(), "interface_friction_dissipated", where);
      }
  }
  {
    Handle g = hdf5::open_group(file, "particles", where);
    ParticleSet &p = s.particles;
    p.body_id = get<std::int64_t>(g.get(), "body_id", where);
    p.x = get<double>(g.get(), "x", where);
    p.y = get<double>(g.get(), "y", where);
    p.rotation = get<double>(g.get(), "rotation", where);
    p.vx = get<double>(g.get(), "vx", where);
    p.vy = get<double>(g.get(), "vy", where);
    p.omega = get<double>(g.get(), "omega", where);
    p.fx = get<double>(g.get(), "fx", where);
    p.fy = get<double>(g.get(), "fy", where);
    p.torque = get<double>(g.get(), "torque", where);
    p.mass = get<double>(g.get(), "mass", where);
    p.inertia = get<double>(g.get(), "inertia", where);
    p.inverse_mass = get<double>(g.get(), "inverse_mass", where);
    p.inverse_inertia = get<double>(g.get(), "inverse_inertia", where);
    p.first_disc = get<std::uint32_t>(g.get(), "first_disc", where);
    p.n_discs = get<std::uint32_t>(g.get(), "n_discs", where);
    p.disc_body = get<std::uint32_t>(g.get(), "disc_body", where);
    p.disc_radius = get<double>(g.get(), "disc_radius", where);
    p.disc_offset_x = get<double>(g.get(), "disc_offset_x", where);
    p.disc_offset_y = get<double>(g.get(), "disc_offset_y", where);
    p.disc_x = get<double>(g.get(), "disc_x", where);
    p.disc_y = get<double>(g.get(), "disc_y", where);
  }
  {
    Handle g = hdf5::open_group(file, "pairs", where);
    PairContacts &c = s.pairs;
    c.disc_i = get<std::uint32_t>(g.get(), "disc_i", where);
    c.disc_j = get<std::uint32_t>(g.get(), "disc_j", where);
    c.state = get_states(g.get(), where);
    c.force_x = get<double>(g.get(), "force_x", where);
    c.force_y = get<double>(g.get(), "force_y", where);
    c.torque_i = get<double>(g.get(), "torque_i", where);
    c.torque_j = get<double>(g.get(), "torque_j", where);
    c.elastic_normal_force = get<double>(g.get(), "elastic_normal_force", where);
    c.friction_work = get<double>(g.get(), "friction_work", where);
    c.viscous_work = get<double>(g.get(), "viscous_work", where);
  }
  {
    Handle g = hdf5::open_group(file, "walls", where);
    const std::size_t count = get_count(g.get(), where);
    for (std::size_t w = 0; w < count; ++w)
      {
        Handle one = hdf5::open_group(g.get(), numbered("wall", w), where);
        s.walls.push_back(get_wall(one.get(), where));
      }
  }
  {
    Handle g = hdf5::open_group(file, "wall_contacts", where);
    const std::size_t count = get_count(g.get(), where);
    s.wall_contacts.resize(count);
    for (std::size_t w = 0; w < count; ++w)
      {
        WallContacts &c = s.wall_contacts[w];
        Handle one = hdf5::open_group(g.get(), numbered("wall", w), where);
        c.disc = get<std::uint32_t>(one.get(), "disc", where);
        c.state = get_states(one.get(), where);
        c.force_x = get<double>(one.get(), "force_x", where);
        c.force_y = get<double>(one.get(), "force_y", where);
        c.elastic_normal_force = get<double>(one.get(), "elastic_normal_force", where);
        c.friction_work = get<double>(one.get(), "friction_work", where);
        c.viscous_work = get<double>(one.get(), "viscous_work", where);
      }
  }
  {
    Handle g = hdf5::open_group(file, "verlet", where);
    s.disc_x_at_rebuild = get<double>(g.get(), "disc_x_at_rebuild", where);
    s.disc_y_at_rebuild = get<double>(g.get(), "disc_y_at_rebuild", where);
    s.wall_start_at_rebuild = get_vec2s(g.get(), "wall_start_at_rebuild", where);
  }
  s.wall_force_previous = get_vec2s(file, "wall_force_previous", where);
  {
    Handle g = hdf5::open_group(file, "damping", where);
    s.damping_fx = get<double>(g.get(), "fx", where);
    s.damping_fy = get<double>(g.get(), "fy", where);
    s.damping_torque = get<double>(g.get(), "torque", where);
  }
  if (version >= 2) // version 1 had no sheets
    {
      Handle g = hdf5::open_group(file, "sheets", where);
      const std::size_t count = get_count(g.get(), where);
      s.sheet_contacts.resize(count);
      for (std::size_t k = 0; k < count; ++k)
        {
          Handle one = hdf5::open_group(g.get(), numbered("sheet", k), where);
          s.sheets.push_back(get_sheet(one.get(), s.sheet_contacts[k], where));
        }
    }
  check_consistency(s, where);
  return s;
}

std::vector<std::string> split_keys(const std::string &text)
{
  std::vector<std::string> keys;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    keys.push_back(text.substr(start, end - start));
  return keys;
}

CommandState get_command(hid_t file, const std::string &where)
{
  CommandState c;
  if (H5Lexists(file, "command", H5P_DEFAULT) <= 0)
    return c;
  Handle g = hdf5::open_group(file, "command", where);
  c.name = hdf5::read_string_attribute(g.get(), "name", where);
  {
    Handle reals = hdf5::open_group(g.get(), "reals", where);
    for (const std::string &key : split_keys(hdf5::read_string_attribute(g.get(), "real_keys", where)))
      {
        const SoaVector<double> v = get<double>(reals.get(), key.c_str(), where);
        c.reals[key].assign(v.begin(), v.end());
      }
  }
  {
    Handle counts = hdf5::open_group(g.get(), "counts", where);
    for (const std::string &key : split_keys(hdf5::read_string_attribute(g.get(), "count_keys", where)))
      {
        const SoaVector<std::uint64_t> v = get<std::uint64_t>(counts.get(), key.c_str(), where);
        c.counts[key].assign(v.begin(), v.end());
      }
  }
  if (H5Aexists(g.get(), "text_keys") > 0)
    {
      Handle texts = hdf5::open_group(g.get(), "texts", where);
      for (const std::string &key : split_keys(hdf5::read_string_attribute(g.get(), "text_keys", where)))
        c.texts[key] = hdf5::read_string_attribute(texts.get(), key.c_str(), where);
    }
  return c;
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
        checkpoint_fields::Writer root(h5.get(), where);
        root.text("format", format_name);
        root.attribute("format_version", checkpoint_format_version);
        checkpoint_fields::visit_fields(state, root);
        if (command)
          root.group("command", [&](checkpoint_fields::Writer &in) { checkpoint_fields::visit_fields(*command, in); });
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
  const std::uint32_t version = get_attr<std::uint32_t>(h5.get(), "format_version", where);
  if (version < 1 || version > checkpoint_format_version)
    fail(where, "has checkpoint format version " + std::to_string(version) + "; this program reads versions 1 to " +
                  std::to_string(checkpoint_format_version));
  if (state)
    *state = get_everything(h5.get(), version, where);
  if (command)
    *command = get_command(h5.get(), where);
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
