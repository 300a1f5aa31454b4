#include "tank_filling.h"

#include "measurements.h"
#include "sample_preparation.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
namespace
{
/// Area of the part of a disc (radius r, centre height yc) below the line y = t.
double disc_area_below(double r, double yc, double t)
{
  const double h = std::clamp(t - yc, -r, r);
  return 0.5 * pi * r * r + h * std::sqrt(std::max(0.0, r * r - h * h)) + r * r * std::asin(h / r);
}

/// Share of body b's solid area that lies in the slab y in [y0, y1]: each disc cut exactly, the
/// discs of a cluster weighted by their areas (which leaves out the lens where they overlap).
double share_in_slab(const ParticleSet &p, std::size_t b, double y0, double y1)
{
  double inside = 0.0, whole = 0.0;
  for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
    {
      const double r = p.disc_radius[d], y = p.disc_y[d], area = pi * r * r;
      whole += area;
      if (y - r >= y0 && y + r <= y1)
        inside += area;
      else if (y + r > y0 && y - r < y1)
        inside += disc_area_below(r, y, y1) - disc_area_below(r, y, y0);
    }
  return inside / whole;
}

/// The REDF settings of one layer (its region is given to each building block separately).
RedfSpec layer_redf_spec(const TankFillingSpec &t, std::size_t layer, std::size_t n_particles, double porosity)
{
  RedfSpec s;
  s.n_particles = n_particles;
  s.shape = t.shape;
  s.size_distribution = t.size_distribution;
  s.cluster_diameter_ratio = t.cluster_diameter_ratio;
  s.cluster_spacing = t.cluster_spacing;
  s.density = t.density;
  s.target_porosity = porosity;
  s.porosity_tolerance = t.porosity_tolerance;
  s.target_stress = t.growth_stress;
  s.particle_contact = t.particle_contact;
  s.initial_growth_friction_deg = t.initial_growth_friction_deg;
  s.wall_contact = t.wall_contact;
  // Each layer its own random stream (SplitMix64 mixes neighbouring seeds well).
  s.seed = t.seed ^ (0x9e3779b97f4a7c15ULL * (layer + 1));
  s.n_threads = t.n_threads;
  s.max_steps = t.max_steps_per_layer;
  return s;
}

/// Grows bodies [first_body, end) only. DemSystem scales every body (and accounts for the growth
/// in its neighbour lists); the bodies below are then given back their sizes exactly. Shrinking
/// them back cannot create a contact, so the neighbour lists stay valid.
class GrowOnlyFrom
{
public:
  GrowOnlyFrom(const ParticleSet &p, std::size_t first_body)
    : n_bodies_(first_body), n_discs_(first_body < p.n_bodies() ? p.first_disc[first_body] : p.n_discs_total()),
      mass_(p.mass.begin(), p.mass.begin() + n_bodies_), inertia_(p.inertia.begin(), p.inertia.begin() + n_bodies_),
      inverse_mass_(p.inverse_mass.begin(), p.inverse_mass.begin() + n_bodies_),
      inverse_inertia_(p.inverse_inertia.begin(), p.inverse_inertia.begin() + n_bodies_),
      radius_(p.disc_radius.begin(), p.disc_radius.begin() + n_discs_),
      offset_x_(p.disc_offset_x.begin(), p.disc_offset_x.begin() + n_discs_),
      offset_y_(p.disc_offset_y.begin(), p.disc_offset_y.begin() + n_discs_)
  {
  }

  void grow(DemSystem &system, double factor) const
  {
    system.scale_particle_sizes(factor);
    ParticleSet &p = system.particles();
    std::copy(mass_.begin(), mass_.end(), p.mass.begin());
    std::copy(inertia_.begin(), inertia_.end(), p.inertia.begin());
    std::copy(inverse_mass_.begin(), inverse_mass_.end(), p.inverse_mass.begin());
    std::copy(inverse_inertia_.begin(), inverse_inertia_.end(), p.inverse_inertia.begin());
    std::copy(radius_.begin(), radius_.end(), p.disc_radius.begin());
    std::copy(offset_x_.begin(), offset_x_.end(), p.disc_offset_x.begin());
    std::copy(offset_y_.begin(), offset_y_.end(), p.disc_offset_y.begin());
    p.update_disc_positions(system.settings().n_threads);
  }

private:
  std::size_t n_bodies_, n_discs_;
  std::vector<double> mass_, inertia_, inverse_mass_, inverse_inertia_, radius_, offset_x_, offset_y_;
};

TankWalls add_tank_walls(DemSystem &system, const TankFillingSpec &t, double lid_level)
{
  const LinearContactLaw law(t.wall_contact);
  const double overhang = 0.1 * std::max(t.width, t.height), w = t.width, h = t.height;
  // Active side on the left of start -> end (wall.h), counter-clockwise as in RectangularBox.
  TankWalls walls;
  walls.base = system.add_wall(Wall("base", Vec2(-overhang, 0.0), Vec2(w + overhang, 0.0), law));
  walls.right = system.add_wall(Wall("right", Vec2(w, -overhang), Vec2(w, h + overhang), law));
  walls.lid = system.add_wall(Wall("lid", Vec2(w + overhang, lid_level), Vec2(-overhang, lid_level), law));
  walls.left = system.add_wall(Wall("left", Vec2(0.0, h + overhang), Vec2(0.0, -overhang), law));
  system.walls()[walls.base].loaded_length = w;
  system.walls()[walls.lid].loaded_length = w;
  system.walls()[walls.left].loaded_length = h;
  system.walls()[walls.right].loaded_length = h;
  return walls;
}

void check_spec(const TankFillingSpec &t)
{
  if (!(t.width > 0.0 && t.height > 0.0))
    throw std::invalid_argument("tank filling: the tank's width and height must be positive");
  if (t.n_layers == 0)
    throw std::invalid_argument("tank filling: the number of layers must be at least 1");
  if (t.n_particles < t.n_layers)
    throw std::invalid_argument("tank filling: " + std::to_string(t.n_particles) + " particles cannot make " +
                                std::to_string(t.n_layers) + " layers");
  if (!t.layer_porosities.empty() && t.layer_porosities.size() != t.n_layers)
    throw std::invalid_argument("tank filling: " + std::to_string(t.layer_porosities.size()) +
                                " layer porosities given for " + std::to_string(t.n_layers) + " layers");
  for (std::size_t k = 0; k < t.n_layers; ++k)
    {
      const double n = t.layer_porosities.empty() ? t.target_porosity : t.layer_porosities[k];
      if (!(n >= 0.05 && n <= 0.8))
        throw std::invalid_argument("tank filling: the target porosity " + std::to_string(n) + " of layer " +
                                    std::to_string(k + 1) + " is outside [0.05, 0.8]");
    }
  if (!(t.gravity > 0.0))
    throw std::invalid_argument("tank filling: gravity must be positive");
  if (!(t.growth_stress > 0.0))
    throw std::invalid_argument("tank filling: the growth stress must be positive");
}
} // namespace

double slab_porosity(const ParticleSet &p, double x_min, double x_max, double y_bottom, double y_top)
{
  double solid = 0.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      const double share = share_in_slab(p, b, y_bottom, y_top);
      if (share > 0.0)
        solid += share * p.body_area(b);
    }
  return 1.0 - solid / ((x_max - x_min) * (y_top - y_bottom));
}

FilledTank fill_tank_in_layers(const TankFillingSpec &t, const std::function<void(double)> &progress)
{
  check_spec(t);
  const std::size_t n_layers = t.n_layers;
  const double thickness = t.height / static_cast<double>(n_layers);
  const auto porosity_of = [&](std::size_t k) { return t.layer_porosities.empty() ? t.target_porosity : t.layer_porosities[k]; };

  // A flat wall loosens a packing along it (hollows between the grains that touch it) over about
  // one particle size. So each layer but the last grows under a lid one band above its level,
  // and its porosity is that of its slab below the level: the loose band above lies in the next
  // layer's slab, whose grains grow into its hollows. The band is the largest particle's size,
  // estimated from the whole fill.
  double band = 0.0;
  if (n_layers > 1)
    {
      const RedfSpec whole = layer_redf_spec(t, 0, t.n_particles, porosity_of(0));
      std::ostringstream region;
      region << "the tank (" << t.width << " m x " << t.height << " m in layers " << thickness << " m thick)";
      band = redf_starting_sizes(whole, t.width * t.height, std::min(t.width, thickness), region.str()).largest_extent;
    }
  // Particles in proportion to the space each layer fills: the first one also fills its band,
  // the last one does not have one but fills the band of the layer below it.
  std::vector<double> cumulative_space(n_layers + 1, 0.0);
  for (std::size_t k = 0; k < n_layers; ++k)
    cumulative_space[k + 1] = static_cast<double>(k + 1) * thickness + (k + 1 < n_layers ? band : 0.0);
  cumulative_space[n_layers] = t.height;
  const auto particles_before = [&](std::size_t k) {
    return static_cast<std::size_t>(std::llround(static_cast<double>(t.n_particles) * cumulative_space[k] / t.height));
  };

  DemSettings growth_settings;
  growth_settings.gravity = Vec2::Zero();
  growth_settings.local_damping = t.local_damping;
  growth_settings.n_threads = t.n_threads;
  growth_settings.track_energy = false;
  DemSettings settling_settings = growth_settings;
  settling_settings.gravity = Vec2(0.0, -t.gravity);

  const LinearContactLaw material(t.particle_contact);
  std::vector<TankLayer> layers;
  std::unique_ptr<DemSystem> settled; // the layers placed so far, settled under gravity
  TankWalls walls{};
  for (std::size_t k = 0; k < n_layers; ++k)
    {
      TankLayer layer;
      layer.bottom = static_cast<double>(k) * thickness;
      layer.top = k + 1 == n_layers ? t.height : static_cast<double>(k + 1) * thickness;
      layer.target_porosity = porosity_of(k);
      const double lid_level = k + 1 == n_layers ? t.height : layer.top + band;
      const double space = cumulative_space[k + 1] - cumulative_space[k];
      const RedfSpec s =
        layer_redf_spec(t, k, particles_before(k + 1) - particles_before(k), layer.target_porosity);
      std::ostringstream region;
      region << "layer " << k + 1 << " of the tank (" << t.width << " m x " << space << " m to fill)";
      const std::string where = "tank filling, layer " + std::to_string(k + 1) + ": ";

      // 1. Random placement between the layer's bottom level and its lid, clear of the grains below.
      ParticleSet particles = settled ? settled->particles() : ParticleSet();
      const std::size_t first_body = particles.n_bodies();
      const std::vector<double> radii =
        redf_starting_sizes(s, t.width * space, std::min(t.width, thickness), region.str()).radii;
      try
        {
          place_at_random(s,
                          {Vec2(0.0, layer.bottom), Vec2(t.width, layer.bottom), Vec2(t.width, lid_level),
                           Vec2(0.0, lid_level)},
                          radii, s.seed, particles);
        }
      catch (const std::invalid_argument &e)
        {
          throw std::invalid_argument(where + e.what());
        }
      layer.first_body = first_body;
      layer.n_bodies = particles.n_bodies() - first_body;
      // While this layer grows, the grains below its slab are fixed (a compacted lift is nearly
      // rigid under the next one): their share of the slab is constant. The grains of the layer
      // below that stand in the slab (its band) stay free, so that they can rearrange with the
      // new grains, as the top of a lift does when the next one is compacted on it.
      double fixed_solid = 0.0;
      std::vector<std::size_t> free_below;
      for (std::size_t b = 0; b < first_body; ++b)
        if (particles.y[b] < layer.bottom)
          {
            particles.fix_body(b);
            fixed_solid += share_in_slab(particles, b, layer.bottom, layer.top) * particles.body_area(b);
          }
        else
          free_below.push_back(b);
      std::vector<double> starting_area(layer.n_bodies);
      for (std::size_t i = 0; i < layer.n_bodies; ++i)
        starting_area[i] = particles.body_area(first_body + i);

      // 2. Growth without gravity under the lid, to the porosity of the layer's slab.
      DemSystem growing(std::move(particles), material, growth_settings);
      walls = add_tank_walls(growing, t, lid_level);
      const GrowOnlyFrom grow_layer(growing.particles(), first_body);
      double area_factor = 1.0; // (size now / starting size)^2 of the growing particles
      RedfGrowth growth;
      growth.jam_stress = [&] { return growing.walls()[walls.lid].normal_stress(); };
      growth.porosity = [&] {
        const ParticleSet &p = growing.particles();
        double solid = fixed_solid, grown_solid = 0.0; // grown_solid at the starting sizes
        for (const std::size_t b : free_below)
          solid += share_in_slab(p, b, layer.bottom, layer.top) * p.body_area(b);
        for (std::size_t i = 0; i < layer.n_bodies; ++i)
          grown_solid += share_in_slab(p, first_body + i, layer.bottom, layer.top) * starting_area[i];
        return 1.0 - (solid + area_factor * grown_solid) / (t.width * (layer.top - layer.bottom));
      };
      growth.grow = [&](double factor) {
        grow_layer.grow(growing, factor);
        area_factor *= factor * factor;
      };
      const double done = static_cast<double>(k) / static_cast<double>(n_layers);
      const double share = 1.0 / static_cast<double>(n_layers);
      RedfGrowthResult grown;
      try
        {
          grown = grow_by_redf(growing, s, growth,
                               progress ? std::function<void(double)>([&](double f) { progress(done + 0.7 * share * f); })
                                        : std::function<void(double)>());
        }
      catch (const std::runtime_error &e)
        {
          throw std::runtime_error(where + e.what());
        }
      layer.porosity_grown = growth.porosity();
      layer.growth_friction_deg = grown.growth_friction_deg;
      layer.n_growth_steps = grown.n_steps;
      growing.set_particle_law(material);

      // 3. Settling under gravity: the same state (contacts and their history) in a system with
      // gravity, the lid parked above the fill, the layers below free again.
      growing.walls()[walls.lid].translate(Vec2(0.0, t.height + thickness - lid_level));
      DemSystemState state = growing.export_state();
      for (std::size_t b = 0; b < first_body; ++b)
        if (state.particles.inverse_mass[b] == 0.0)
          {
            state.particles.inverse_mass[b] = 1.0 / state.particles.mass[b];
            state.particles.inverse_inertia[b] = 1.0 / state.particles.inertia[b];
          }
      settled = std::make_unique<DemSystem>(state.particles, material, settling_settings);
      add_tank_walls(*settled, t, lid_level);
      settled->restore_state(std::move(state));
      settled->request_neighbour_rebuild();
      const std::uint64_t check_every = 200;
      for (;;)
        {
          settled->step();
          if (++layer.n_settling_steps % check_every != 0)
            continue;
          const double unbalanced = unbalanced_force_ratio(*settled);
          if (unbalanced < t.equilibrium_unbalanced_ratio)
            break;
          if (layer.n_growth_steps + layer.n_settling_steps > t.max_steps_per_layer)
            {
              std::ostringstream message;
              message << where << "the fill has not settled under gravity after " << t.max_steps_per_layer
                      << " steps (unbalanced-force ratio " << unbalanced << ", asked below "
                      << t.equilibrium_unbalanced_ratio << ")";
              throw std::runtime_error(message.str());
            }
          if (progress)
            progress(done + share * (0.7 + 0.3 * std::min(1.0, static_cast<double>(layer.n_settling_steps) / 50000.0)));
        }
      layers.push_back(layer);
    }
  for (TankLayer &layer : layers)
    layer.porosity = slab_porosity(settled->particles(), 0.0, t.width, layer.bottom, layer.top);
  if (progress)
    progress(1.0);
  return FilledTank{std::move(*settled), walls, std::move(layers)};
}
} // namespace geohybrid::dem
