#include "sample_file.h"

#include "dem/io/checkpoint.h"
#include "dem/io/hdf5_handles.h"
#include "dem/io/hdf5_writable_file.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <tuple>

namespace geohybrid::dem
{
namespace
{
using hdf5::fail;
using hdf5::Handle;

constexpr const char *format_name = "geohybrid REDF sample";
constexpr const char *group_name = "redf_sample";

// A field added to one of these structures must be stored too, or two different samples would
// pass for the same one (sample_spec_differences) and a reloaded one would differ from the one
// made. These sizes (x86-64, libstdc++) make such a change fail to compile here: add the field to
// the tables below (raising sample_file_format_version if files of the old layout exist), then
// update the size.
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(RedfSpec) == 272, "RedfSpec changed: update the sample file");
static_assert(sizeof(RedfResult) == 40, "RedfResult changed: update the sample file");
static_assert(sizeof(DemSettings) == 64, "DemSettings changed: update the sample file");
static_assert(sizeof(ContactParameters) == 56, "ContactParameters changed: update the sample file");
static_assert(sizeof(RectangularBox) == 4 * sizeof(std::size_t), "RectangularBox changed: update the sample file");
#endif

std::string describe(const std::filesystem::path &file) { return "REDF sample file '" + file.string() + "'"; }

// ---- the stored fields, one table per structure: written, read and compared from the same list ----

template <typename Owner>
struct DoubleField
{
  const char *name;
  double Owner::*member;
};

constexpr DoubleField<RedfSpec> spec_doubles[] = {
  {"width", &RedfSpec::width},
  {"height", &RedfSpec::height},
  {"cluster_diameter_ratio", &RedfSpec::cluster_diameter_ratio},
  {"cluster_spacing", &RedfSpec::cluster_spacing},
  {"density", &RedfSpec::density},
  {"target_porosity", &RedfSpec::target_porosity},
  {"porosity_tolerance", &RedfSpec::porosity_tolerance},
  {"target_stress", &RedfSpec::target_stress},
  {"stress_tolerance", &RedfSpec::stress_tolerance},
  {"equilibrium_unbalanced_ratio", &RedfSpec::equilibrium_unbalanced_ratio},
  {"initial_growth_friction_deg", &RedfSpec::initial_growth_friction_deg},
};

constexpr DoubleField<ContactParameters> contact_doubles[] = {
  {"normal_stiffness", &ContactParameters::normal_stiffness},
  {"shear_stiffness", &ContactParameters::shear_stiffness},
  {"friction_angle_deg", &ContactParameters::friction_angle_deg},
  {"shear_strength", &ContactParameters::shear_strength},
  {"tensile_strength", &ContactParameters::tensile_strength},
  {"restitution", &ContactParameters::restitution},
};

constexpr DoubleField<RedfResult> result_doubles[] = {
  {"result_porosity", &RedfResult::porosity},
  {"result_mean_stress", &RedfResult::mean_stress},
  {"result_growth_friction_deg", &RedfResult::growth_friction_deg},
  {"result_size_scale", &RedfResult::size_scale},
};

constexpr DoubleField<DemSettings> settings_doubles[] = {
  {"settings_local_damping", &DemSettings::local_damping},
  {"settings_time_step", &DemSettings::time_step},
  {"settings_time_step_safety", &DemSettings::time_step_safety},
  {"settings_skin", &DemSettings::skin},
};

const char *shape_name(ParticleShape shape) { return shape == ParticleShape::disc ? "disc" : "two-disc cluster"; }

// ---- the size distribution: uniform (its smallest ratio) or classes (size, area fraction) ----

void put_size_distribution(hid_t g, const SizeDistribution &sizes, const std::string &where);
SizeDistribution get_size_distribution(hid_t g, const std::string &where);

// ---- attributes ----

void put_double(hid_t parent, const char *name, double value, const std::string &where)
{
  hdf5::write_attribute(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, where);
}

void put_count(hid_t parent, const char *name, std::uint64_t value, const std::string &where)
{
  hdf5::write_attribute(parent, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value, where);
}

void put_flag(hid_t parent, const char *name, bool value, const std::string &where)
{
  const std::uint8_t byte = value ? 1 : 0;
  hdf5::write_attribute(parent, name, H5T_STD_U8LE, H5T_NATIVE_UINT8, &byte, where);
}

double get_double(hid_t parent, const char *name, const std::string &where)
{
  double value = 0.0;
  hdf5::read_attribute(parent, name, H5T_NATIVE_DOUBLE, &value, where);
  return value;
}

std::uint64_t get_count(hid_t parent, const char *name, const std::string &where)
{
  std::uint64_t value = 0;
  hdf5::read_attribute(parent, name, H5T_NATIVE_UINT64, &value, where);
  return value;
}

bool get_flag(hid_t parent, const char *name, const std::string &where)
{
  std::uint8_t byte = 0;
  hdf5::read_attribute(parent, name, H5T_NATIVE_UINT8, &byte, where);
  if (byte > 1)
    fail(where, std::string("attribute '") + name + "' is not 0 or 1");
  return byte == 1;
}

void put_contact(hid_t parent, const char *name, const ContactParameters &c, const std::string &where)
{
  Handle group = hdf5::create_group(parent, name, where);
  for (const auto &field : contact_doubles)
    put_double(group.get(), field.name, c.*field.member, where);
  put_flag(group.get(), "bond_new_contacts", c.bond_new_contacts, where);
}

ContactParameters get_contact(hid_t parent, const char *name, const std::string &where)
{
  Handle group = hdf5::open_group(parent, name, where);
  ContactParameters c;
  for (const auto &field : contact_doubles)
    c.*field.member = get_double(group.get(), field.name, where);
  c.bond_new_contacts = get_flag(group.get(), "bond_new_contacts", where);
  return c;
}

void put_size_distribution(hid_t g, const SizeDistribution &sizes, const std::string &where)
{
  put_double(g, "size_distribution_min_ratio", sizes.is_uniform() ? sizes.min_ratio() : 0.0, where);
  put_count(g, "size_distribution_n_classes", sizes.classes().size(), where);
  for (std::size_t k = 0; k < sizes.classes().size(); ++k)
    {
      const std::string prefix = "size_class_" + std::to_string(k);
      put_double(g, (prefix + "_relative_size").c_str(), sizes.classes()[k].relative_size, where);
      put_double(g, (prefix + "_area_fraction").c_str(), sizes.classes()[k].area_fraction, where);
    }
}

SizeDistribution get_size_distribution(hid_t g, const std::string &where)
{
  const std::uint64_t n_classes = get_count(g, "size_distribution_n_classes", where);
  if (n_classes == 0)
    return SizeDistribution::uniform(get_double(g, "size_distribution_min_ratio", where));
  std::vector<SizeDistribution::SizeClass> classes;
  for (std::uint64_t k = 0; k < n_classes; ++k)
    {
      const std::string prefix = "size_class_" + std::to_string(k);
      classes.push_back({get_double(g, (prefix + "_relative_size").c_str(), where),
                         get_double(g, (prefix + "_area_fraction").c_str(), where)});
    }
  return SizeDistribution::fractions(classes);
}

/// Equal to rounding: class fractions read back are normalised again, which may move them by an ulp.
bool same_size_distribution(const SizeDistribution &a, const SizeDistribution &b)
{
  const auto same = [](double x, double y) { return std::abs(x - y) <= 1e-14 * std::max(std::abs(x), std::abs(y)); };
  if (a.is_uniform() != b.is_uniform() || a.classes().size() != b.classes().size())
    return false;
  if (a.is_uniform())
    return a.min_ratio() == b.min_ratio();
  for (std::size_t k = 0; k < a.classes().size(); ++k)
    if (!same(a.classes()[k].relative_size, b.classes()[k].relative_size) ||
        !same(a.classes()[k].area_fraction, b.classes()[k].area_fraction))
      return false;
  return true;
}

void put_metadata(hid_t file, const StoredSample &s, const std::string &where)
{
  Handle group = hdf5::create_group(file, group_name, where);
  const hid_t g = group.get();
  hdf5::write_string_attribute(g, "format", format_name, where);
  hdf5::write_attribute(g, "format_version", H5T_STD_U32LE, H5T_NATIVE_UINT32, &sample_file_format_version, where);
  for (const auto &field : spec_doubles)
    put_double(g, field.name, s.spec.*field.member, where);
  put_count(g, "n_particles", s.spec.n_particles, where);
  put_count(g, "seed", s.spec.seed, where);
  put_count(g, "max_steps", s.spec.max_steps, where);
  hdf5::write_string_attribute(g, "shape", shape_name(s.spec.shape), where);
  put_size_distribution(g, s.spec.size_distribution, where);
  put_contact(g, "particle_contact", s.spec.particle_contact, where);
  put_contact(g, "wall_contact", s.spec.wall_contact, where);
  for (const auto &field : result_doubles)
    put_double(g, field.name, s.result.*field.member, where);
  put_count(g, "result_n_steps", s.result.n_steps, where);
  for (const auto &field : settings_doubles)
    put_double(g, field.name, s.settings.*field.member, where);
  put_double(g, "settings_gravity_x", s.settings.gravity.x(), where);
  put_double(g, "settings_gravity_y", s.settings.gravity.y(), where);
  put_flag(g, "settings_track_energy", s.settings.track_energy, where);
  put_count(g, "box_left", s.box.left, where);
  put_count(g, "box_right", s.box.right, where);
  put_count(g, "box_bottom", s.box.bottom, where);
  put_count(g, "box_top", s.box.top, where);
}

/// Everything but the state.
StoredSample get_metadata(hid_t file, const std::string &where)
{
  if (H5Lexists(file, group_name, H5P_DEFAULT) <= 0)
    fail(where, std::string("is not a REDF sample file: it has no '") + group_name +
                  "' group (a DEM checkpoint or another HDF5 file?)");
  Handle group = hdf5::open_group(file, group_name, where);
  const hid_t g = group.get();
  if (H5Aexists(g, "format") <= 0 || hdf5::read_string_attribute(g, "format", where) != format_name)
    fail(where, "is not a geohybrid REDF sample file");
  std::uint32_t version = 0;
  hdf5::read_attribute(g, "format_version", H5T_NATIVE_UINT32, &version, where);
  if (version != sample_file_format_version)
    fail(where, "has sample format version " + std::to_string(version) + "; this program reads version " +
                  std::to_string(sample_file_format_version));
  StoredSample s;
  for (const auto &field : spec_doubles)
    s.spec.*field.member = get_double(g, field.name, where);
  s.spec.n_particles = static_cast<std::size_t>(get_count(g, "n_particles", where));
  s.spec.seed = get_count(g, "seed", where);
  s.spec.max_steps = get_count(g, "max_steps", where);
  const std::string shape = hdf5::read_string_attribute(g, "shape", where);
  if (shape == shape_name(ParticleShape::disc))
    s.spec.shape = ParticleShape::disc;
  else if (shape == shape_name(ParticleShape::two_disc_cluster))
    s.spec.shape = ParticleShape::two_disc_cluster;
  else
    fail(where, "unknown particle shape '" + shape + "'");
  s.spec.size_distribution = get_size_distribution(g, where);
  s.spec.particle_contact = get_contact(g, "particle_contact", where);
  s.spec.wall_contact = get_contact(g, "wall_contact", where);
  for (const auto &field : result_doubles)
    s.result.*field.member = get_double(g, field.name, where);
  s.result.n_steps = get_count(g, "result_n_steps", where);
  for (const auto &field : settings_doubles)
    s.settings.*field.member = get_double(g, field.name, where);
  s.settings.gravity = Vec2(get_double(g, "settings_gravity_x", where), get_double(g, "settings_gravity_y", where));
  s.settings.track_energy = get_flag(g, "settings_track_energy", where);
  s.box.left = static_cast<std::size_t>(get_count(g, "box_left", where));
  s.box.right = static_cast<std::size_t>(get_count(g, "box_right", where));
  s.box.bottom = static_cast<std::size_t>(get_count(g, "box_bottom", where));
  s.box.top = static_cast<std::size_t>(get_count(g, "box_top", where));
  return s;
}

std::string number(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.15g", value);
  return text;
}
} // namespace

StoredSample store_sample(const RedfSample &sample, const RedfSpec &spec)
{
  return StoredSample{spec, sample.result, sample.system.settings(), sample.box, sample.system.export_state()};
}

RedfSample restore_sample(const StoredSample &stored, int n_threads)
{
  DemSettings settings = stored.settings;
  settings.n_threads = n_threads;
  // The system is built with the stored particles and walls, then takes the whole state (contact
  // histories, servo integrals, Verlet list, time step), as a resumed run does.
  DemSystem system(stored.state.particles, LinearContactLaw(stored.state.particle_contact), settings);
  for (const Wall &wall : stored.state.walls)
    system.add_wall(wall);
  system.restore_state(stored.state);
  return RedfSample{std::move(system), stored.box, stored.result};
}

void write_sample_file(const StoredSample &sample, const std::filesystem::path &file)
{
  const std::string where = describe(file);
  std::error_code error;
  if (file.has_parent_path())
    {
      std::filesystem::create_directories(file.parent_path(), error);
      if (error)
        fail(where, "cannot create its directory: " + error.message());
    }
  // The checkpoint first (it creates the file), then the sample's group, then the name.
  std::filesystem::path partial = file;
  partial += ".partial";
  try
    {
      write_checkpoint(sample.state, partial);
      hdf5::SilenceErrors silence;
      hdf5::WritableFile h5 = hdf5::WritableFile::open(partial, where);
      put_metadata(h5.get(), sample, where);
      h5.close();
    }
  catch (...)
    {
      std::filesystem::remove(partial, error);
      throw;
    }
  std::filesystem::rename(partial, file, error);
  if (error)
    fail(where, "cannot replace it with '" + partial.string() + "': " + error.message());
}

StoredSample read_sample_file(const std::filesystem::path &file)
{
  const std::string where = describe(file);
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    fail(where, "does not exist or is not a file");
  StoredSample sample;
  {
    hdf5::SilenceErrors silence;
    Handle fapl = hdf5::file_access(where);
#if H5_VERSION_GE(1, 12, 0)
    const htri_t is_hdf5 = H5Fis_accessible(file.c_str(), fapl.get());
#else
    const htri_t is_hdf5 = H5Fis_hdf5(file.c_str());
#endif
    if (is_hdf5 <= 0)
      fail(where, "is not a readable HDF5 file (damaged or not a sample file)");
    Handle h5(H5Fopen(file.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose, where, "opening the file");
    sample = get_metadata(h5.get(), where);
    h5.close(where, "closing the file");
  }
  try
    {
      sample.state = read_checkpoint(file);
    }
  catch (const std::runtime_error &e)
    {
      fail(where, std::string("its DEM state cannot be read: ") + e.what());
    }
  const std::size_t n_walls = sample.state.walls.size();
  const RectangularBox &b = sample.box;
  if (b.left >= n_walls || b.right >= n_walls || b.bottom >= n_walls || b.top >= n_walls || b.left == b.right ||
      b.bottom == b.top || b.left == b.bottom || b.left == b.top || b.right == b.bottom || b.right == b.top)
    fail(where, "inconsistent content: the box's wall indices do not name four of its " + std::to_string(n_walls) +
                  " walls");
  if (sample.state.particles.n_bodies() != sample.spec.n_particles)
    fail(where, "inconsistent content: " + std::to_string(sample.state.particles.n_bodies()) +
                  " particles stored for a sample of " + std::to_string(sample.spec.n_particles));
  return sample;
}

std::vector<std::string> sample_spec_differences(const RedfSpec &stored, const RedfSpec &wanted)
{
  std::vector<std::string> differences;
  const auto compare = [&](const std::string &name, const std::string &a, const std::string &b) {
    if (a != b)
      differences.push_back(name + ": " + a + " stored, " + b + " wanted");
  };
  const auto compare_number = [&](const std::string &name, double a, double b) {
    if (a != b)
      differences.push_back(name + ": " + number(a) + " stored, " + number(b) + " wanted");
  };
  for (const auto &field : spec_doubles)
    compare_number(field.name, stored.*field.member, wanted.*field.member);
  compare("n_particles", std::to_string(stored.n_particles), std::to_string(wanted.n_particles));
  compare("seed", std::to_string(stored.seed), std::to_string(wanted.seed));
  compare("shape", shape_name(stored.shape), shape_name(wanted.shape));
  if (!same_size_distribution(stored.size_distribution, wanted.size_distribution))
    differences.push_back("size_distribution: " + stored.size_distribution.to_string() + " stored, " +
                          wanted.size_distribution.to_string() + " wanted");
  for (const auto &[label, a, b] : {std::tuple{"particle_contact.", &stored.particle_contact, &wanted.particle_contact},
                                    std::tuple{"wall_contact.", &stored.wall_contact, &wanted.wall_contact}})
    {
      for (const auto &field : contact_doubles)
        compare_number(std::string(label) + field.name, a->*field.member, b->*field.member);
      compare(std::string(label) + "bond_new_contacts", a->bond_new_contacts ? "true" : "false",
              b->bond_new_contacts ? "true" : "false");
    }
  return differences;
}
} // namespace geohybrid::dem
