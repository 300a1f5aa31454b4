#include "lift_cache.h"

#include "dem/io/checkpoint.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace geohybrid::dem
{
namespace
{
/// FNV-1a, 64 bits, over the bytes of what is added (doubles by their bit patterns: a value that
/// differs in its last bit is another key, which only costs a lift made again).
class KeyHash
{
public:
  void bytes(const void *data, std::size_t n)
  {
    const auto *c = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < n; ++i)
      {
        hash_ ^= c[i];
        hash_ *= 0x100000001b3ULL;
      }
  }
  void real(double v) { bytes(&v, sizeof v); }
  void count(std::uint64_t v) { bytes(&v, sizeof v); }
  void text(const std::string &s)
  {
    count(s.size());
    bytes(s.data(), s.size());
  }
  template <typename T>
  void array(const SoaVector<T> &v)
  {
    count(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  void contact(const ContactParameters &c)
  {
    for (const double v : {c.normal_stiffness, c.shear_stiffness, c.friction_angle_deg, c.shear_strength,
                           c.tensile_strength, c.restitution})
      real(v);
    count(c.bond_new_contacts ? 1 : 0);
  }
  void sizes(const SizeDistribution &d)
  {
    count(d.is_uniform() ? 1 : 0);
    if (d.is_uniform())
      real(d.min_ratio());
    for (const SizeDistribution::SizeClass &c : d.classes())
      {
        real(c.relative_size);
        real(c.area_fraction);
      }
  }
  std::uint64_t value() const { return hash_; }

private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

// A field added to one of these must be added to the key below: a lift taken from the cache with
// a setting the key does not see would be a lift made with another setting. (Sizes on x86-64.)
static_assert(sizeof(ContactParameters) == 56, "ContactParameters changed: add the field to lift_cache_key");
static_assert(sizeof(RedfSpec) == 272, "RedfSpec changed: add the field to lift_cache_key");
static_assert(sizeof(TankFillingSpec) == 512, "TankFillingSpec changed: add the field to lift_cache_key");
} // namespace

std::uint64_t lift_cache_key(const TankFillingSpec &t, std::size_t layer_index, const RedfSpec &s,
                             const TankLayer &layer, double lid_level, const ParticleSet &p)
{
  KeyHash h;
  h.text("geohybrid tank lift 1");
  h.text(t.lift_cache_version);
  // The fill's spec, but its sheet (laid above these lifts), its threads and the cache itself.
  for (const double v : {t.width, t.height, t.cluster_diameter_ratio, t.cluster_spacing, t.density, t.target_porosity,
                         t.porosity_tolerance, t.growth_stress, t.initial_growth_friction_deg, t.gravity,
                         t.local_damping, t.equilibrium_unbalanced_ratio})
    h.real(v);
  for (const std::uint64_t v : {std::uint64_t(t.n_layers), std::uint64_t(t.n_particles), std::uint64_t(t.shape),
                                std::uint64_t(t.later_lifts_start_near_the_lift_below), t.seed, t.max_steps_per_layer})
    h.count(v);
  if (!t.layer_tops.empty()) // keys made before varied layers kept
    {
      h.count(t.layer_tops.size());
      for (const double v : t.layer_tops)
        h.real(v);
    }
  h.count(t.layer_porosities.size());
  for (const double v : t.layer_porosities)
    h.real(v);
  h.sizes(t.size_distribution);
  h.contact(t.particle_contact);
  h.contact(t.wall_contact);
  // The lift: its index, levels, lid and REDF spec (its threads aside).
  h.count(layer_index);
  for (const double v : {layer.bottom, layer.top, layer.target_porosity, lid_level})
    h.real(v);
  if (layer.measured_bottom != layer.bottom || layer.measured_top != layer.top) // keys made before kept
    for (const double v : {layer.measured_bottom, layer.measured_top})
      h.real(v);
  h.count(layer.first_body);
  h.count(layer.n_bodies);
  for (const double v : {s.width, s.height, s.cluster_diameter_ratio, s.cluster_spacing, s.density, s.target_porosity,
                         s.porosity_tolerance, s.target_stress, s.stress_tolerance, s.equilibrium_unbalanced_ratio,
                         s.initial_growth_friction_deg})
    h.real(v);
  for (const std::uint64_t v : {std::uint64_t(s.n_particles), std::uint64_t(s.shape), s.seed, s.max_steps})
    h.count(v);
  h.sizes(s.size_distribution);
  h.contact(s.particle_contact);
  h.contact(s.wall_contact);
  // The particles as placed, with the lifts below as they were left.
  h.array(p.body_id);
  for (const SoaVector<double> *v : {&p.x, &p.y, &p.rotation, &p.vx, &p.vy, &p.omega, &p.fx, &p.fy, &p.torque, &p.mass,
                                     &p.inertia, &p.inverse_mass, &p.inverse_inertia, &p.disc_radius, &p.disc_offset_x,
                                     &p.disc_offset_y, &p.disc_x, &p.disc_y})
    h.array(*v);
  h.array(p.first_disc);
  h.array(p.n_discs);
  h.array(p.disc_body);
  return h.value();
}

std::filesystem::path lift_cache_file(const std::filesystem::path &directory, std::uint64_t key)
{
  char name[32];
  std::snprintf(name, sizeof name, "lift_%016llx.h5", static_cast<unsigned long long>(key));
  return directory / name;
}

namespace
{
const char *const record_key = "lift";

std::string hex(std::uint64_t key)
{
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(key));
  return text;
}
} // namespace

void save_lift(const DemSystem &settled, const TankLayer &layer, std::uint64_t key, const std::filesystem::path &file)
{
  CommandState record;
  record.name = "tank lift";
  record.texts["key"] = hex(key);
  record.reals[record_key] = {layer.bottom, layer.top, layer.target_porosity, layer.porosity_grown,
                              layer.growth_friction_deg};
  record.counts[record_key] = {layer.first_body, layer.n_bodies, layer.n_growth_steps, layer.n_settling_steps};
  std::error_code error;
  std::filesystem::create_directories(file.parent_path(), error);
  if (error)
    throw std::runtime_error("lift cache: cannot create the directory '" + file.parent_path().string() +
                             "': " + error.message());
  // Written under a name of this process's, then renamed: another fill may write the same lift.
  std::filesystem::path mine = file;
  mine += "." + std::to_string(::getpid());
  write_checkpoint(settled.export_state(), record, mine);
  std::filesystem::rename(mine, file, error);
  if (error)
    {
      std::filesystem::remove(mine, error);
      throw std::runtime_error("lift cache: cannot rename '" + mine.string() + "' to '" + file.string() + "'");
    }
}

std::optional<DemSystemState> load_lift(const std::filesystem::path &file, std::uint64_t key, TankLayer &layer)
{
  std::error_code error;
  if (!std::filesystem::exists(file, error))
    return std::nullopt;
  CommandState record;
  DemSystemState state;
  try
    {
      state = read_checkpoint(file, record);
      if (record.name != "tank lift" || record.texts.count("key") == 0 || record.texts.at("key") != hex(key))
        throw std::runtime_error("it holds another lift");
      const std::vector<double> &r = record.real(record_key, 5);
      const std::vector<std::uint64_t> &c = record.count(record_key, 4);
      layer.bottom = r[0];
      layer.top = r[1];
      layer.target_porosity = r[2];
      layer.porosity_grown = r[3];
      layer.growth_friction_deg = r[4];
      layer.first_body = c[0];
      layer.n_bodies = c[1];
      layer.n_growth_steps = c[2];
      layer.n_settling_steps = c[3];
    }
  catch (const std::exception &e)
    {
      throw std::runtime_error("lift cache: '" + file.string() + "' cannot be used (" + e.what() +
                               "): delete it, and the fill makes the lift anew");
    }
  return state;
}
} // namespace geohybrid::dem
