#include "tank_filling.h"

#include "lift_cache.h"
#include "lift_growth.h"
#include "lift_placement.h"
#include "lift_settling.h"
#include "sample_preparation.h"
#include "sheet_laying.h"
#include "slab_porosity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
namespace
{
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

void check_spec(const TankFillingSpec &t)
{
  if (!(t.width > 0.0 && t.height > 0.0))
    throw std::invalid_argument("tank filling: the tank's width and height must be positive");
  if (t.n_layers == 0)
    throw std::invalid_argument("tank filling: the number of layers must be at least 1");
  if (t.n_particles < t.n_layers)
    throw std::invalid_argument("tank filling: " + std::to_string(t.n_particles) + " particles cannot make " +
                                std::to_string(t.n_layers) + " layers");
  if (!t.layer_tops.empty())
    {
      if (t.layer_tops.size() != t.n_layers)
        throw std::invalid_argument("tank filling: " + std::to_string(t.layer_tops.size()) + " layer tops given for " +
                                    std::to_string(t.n_layers) + " layers");
      for (std::size_t k = 0; k < t.n_layers; ++k)
        if (!(layer_top(t, k) > layer_bottom(t, k)))
          throw std::invalid_argument("tank filling: the layer tops must rise from the base (layer " +
                                      std::to_string(k + 1) + "'s top at " + std::to_string(layer_top(t, k)) + " m)");
      if (std::abs(t.layer_tops.back() - t.height) > 1e-9 * t.height)
        throw std::invalid_argument("tank filling: the last layer's top " + std::to_string(t.layer_tops.back()) +
                                    " m is not the fill's height " + std::to_string(t.height) + " m");
    }
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
  if (t.sheet)
    {
      if (t.sheet->layers_below < 1 || t.sheet->layers_below >= t.n_layers)
        throw std::invalid_argument("tank filling: the sheet is laid after " + std::to_string(t.sheet->layers_below) +
                                    " layers; it must have between 1 and " + std::to_string(t.n_layers - 1) +
                                    " layers below it");
      if (!t.sheet->lay)
        throw std::invalid_argument("tank filling: the sheet has no function to lay it");
      const std::size_t second = t.sheet->second_part_layers_below;
      if (second != 0 && (second <= t.sheet->layers_below || second >= t.n_layers))
        throw std::invalid_argument("tank filling: the sheet's second part is laid after " + std::to_string(second) +
                                    " layers; it must have between " + std::to_string(t.sheet->layers_below + 1) +
                                    " (above the first part's " + std::to_string(t.sheet->layers_below) + ") and " +
                                    std::to_string(t.n_layers - 1) + " layers below it");
      if (second != 0 && !t.sheet->lay_second_part)
        throw std::invalid_argument("tank filling: the sheet's second part has no function to lay it");
    }
}

/// Where each lift of a fill lies and how many of the fill's grains it gets.
///
/// A flat wall loosens a packing along it (hollows between the grains that touch it) over about
/// one particle size. So each layer but the last grows under a lid one band above its level, and
/// its porosity is that of its slab below the level: the loose band above lies in the next
/// layer's slab, whose grains grow into its hollows. The band is the largest particle's size,
/// estimated from the whole fill.
///
/// The lift a sheet is laid on is levelled, as in the laboratory: it grows under a lid at its
/// level, so that the sheet lies flat on it at the nominal depth. (With the lid a band higher, the
/// sheet rested on the highest grain of a rough surface, up to two grains above its level, and
/// bridged the hollows below it, which the grains above cannot fill: measured on the 400-cluster
/// tank of tests/test_dem_pullout.cc, the sheet 12 mm above its level, the vertical stress on it
/// 0.25 gamma H, and the lift above it grown down to a friction of 0.7 degrees over 238,000 steps
/// to make up for the hollows in its slab.) The sheet separates the two lifts, so the band
/// loosened along the lid is not filled from above: it is the loose band along the sheet, as on
/// its other face. The lift a two-stage sheet's second part is laid on is levelled the same way
/// (tank_filling.h).
class LiftPlan
{
public:
  explicit LiftPlan(const TankFillingSpec &t)
    : t_(t), cumulative_space_(t.n_layers + 1, 0.0)
  {
    const std::size_t n_layers = t.n_layers;
    if (n_layers > 1 || t.soil_continues_above || t.soil_continues_below)
      {
        const RedfSpec whole = layer_redf_spec(t, 0, t.n_particles, porosity(0));
        const double thinnest = thinnest_layer(t);
        std::ostringstream region;
        region << "the tank (" << t.width << " m x " << t.height << " m in layers "
               << (t.layer_tops.empty() ? "" : "at least ") << thinnest << " m thick)";
        band_ = redf_starting_sizes(whole, t.width * t.height, std::min(t.width, thinnest), region.str()).largest_extent;
      }
    // Particles in proportion to the space each layer fills: a layer with a band also fills it;
    // the next one fills from the top of that band.
    for (std::size_t k = 0; k < n_layers; ++k)
      cumulative_space_[k + 1] = top(k) + (has_band(k) ? band_ : 0.0);
    cumulative_space_[n_layers] = t.height;
  }

  double thickness(std::size_t k) const { return layer_thickness(t_, k); }
  double porosity(std::size_t k) const { return t_.layer_porosities.empty() ? t_.target_porosity : t_.layer_porosities[k]; }
  double bottom(std::size_t k) const { return layer_bottom(t_, k); }
  double top(std::size_t k) const { return layer_top(t_, k); }
  double lid(std::size_t k) const { return has_band(k) ? top(k) + band_ : top(k); }
  /// The part of lift k's slab whose porosity its growth aims at: a band below a lid past which
  /// the soil goes on, a band above a base below which it goes on.
  double measured_bottom(std::size_t k) const
  {
    return k == 0 && t_.soil_continues_below ? bottom(k) + band_ : bottom(k);
  }
  double measured_top(std::size_t k) const
  {
    return k + 1 == t_.n_layers && t_.soil_continues_above ? top(k) - band_ : top(k);
  }
  /// The height of the space lift k fills (its slab, with its band, less the band below).
  double space(std::size_t k) const { return cumulative_space_[k + 1] - cumulative_space_[k]; }
  std::size_t n_particles(std::size_t k) const { return particles_before(k + 1) - particles_before(k); }

private:
  bool has_band(std::size_t k) const
  {
    return k + 1 < t_.n_layers &&
           !(t_.sheet && (k + 1 == t_.sheet->layers_below || k + 1 == t_.sheet->second_part_layers_below));
  }
  std::size_t particles_before(std::size_t k) const
  {
    return static_cast<std::size_t>(std::llround(static_cast<double>(t_.n_particles) * cumulative_space_[k] / t_.height));
  }

  const TankFillingSpec &t_;
  double band_ = 0.0;
  std::vector<double> cumulative_space_; ///< height of the space the lifts below k fill
};
} // namespace

double layer_bottom(const TankFillingSpec &t, std::size_t k)
{
  if (t.layer_tops.empty())
    return static_cast<double>(k) * (t.height / static_cast<double>(t.n_layers));
  return k == 0 ? 0.0 : t.layer_tops[k - 1];
}

double layer_top(const TankFillingSpec &t, std::size_t k)
{
  if (k + 1 == t.n_layers)
    return t.height;
  return t.layer_tops.empty() ? static_cast<double>(k + 1) * (t.height / static_cast<double>(t.n_layers)) : t.layer_tops[k];
}

double layer_thickness(const TankFillingSpec &t, std::size_t k)
{
  // Equal layers: height / n_layers as such, the bits every fill made before varied layers.
  return t.layer_tops.empty() ? t.height / static_cast<double>(t.n_layers) : layer_top(t, k) - layer_bottom(t, k);
}

double thinnest_layer(const TankFillingSpec &t)
{
  double thinnest = layer_thickness(t, 0);
  for (std::size_t k = 1; k < t.n_layers; ++k)
    thinnest = std::min(thinnest, layer_thickness(t, k));
  return thinnest;
}

std::optional<std::size_t> layers_below_level(const TankFillingSpec &t, double level, double tolerance)
{
  if (std::abs(level) <= tolerance)
    return 0;
  for (std::size_t k = 0; k < t.n_layers; ++k)
    if (std::abs(layer_top(t, k) - level) <= tolerance)
      return k + 1;
  return std::nullopt;
}

DemSettings tank_settling_settings(const TankFillingSpec &t)
{
  DemSettings s;
  s.gravity = Vec2(0.0, -t.gravity);
  s.local_damping = t.local_damping;
  s.n_threads = t.n_threads;
  s.track_energy = false;
  return s;
}

RedfStartingSizes whole_fill_sizes(const TankFillingSpec &t, double porosity)
{
  check_spec(t);
  // An unbounded width: the sizes only, not the check (fill_tank_in_layers makes that).
  return redf_starting_sizes(layer_redf_spec(t, 0, t.n_particles, porosity), t.width * t.height,
                             std::numeric_limits<double>::max(), "the tank");
}

double largest_particle_extent(const TankFillingSpec &t)
{
  return whole_fill_sizes(t, t.layer_porosities.empty() ? t.target_porosity : t.layer_porosities[0]).largest_extent;
}

FilledTank fill_tank_in_layers(const TankFillingSpec &t, const std::function<void(double)> &progress)
{
  check_spec(t);
  const std::size_t n_layers = t.n_layers;
  const LiftPlan plan(t);
  const DemSettings settling_settings = tank_settling_settings(t);
  DemSettings growth_settings = settling_settings;
  growth_settings.gravity = Vec2::Zero();

  const LinearContactLaw material(t.particle_contact);
  std::vector<TankLayer> layers;
  std::unique_ptr<DemSystem> settled; // the layers placed so far, settled under gravity
  // The sheets laid so far as they stand in the settled layers: carried into the next layer's
  // growth (a second part laid changes a sheet's nodes, which a system's sheets cannot).
  std::vector<SparSheet> laid;
  TankWalls walls{};
  double slot_bottom = 0.0, slot_top = 0.0; // no slot until a sheet is laid
  for (std::size_t k = 0; k < n_layers; ++k)
    {
      TankLayer layer;
      layer.bottom = plan.bottom(k);
      layer.top = plan.top(k);
      layer.measured_bottom = plan.measured_bottom(k);
      layer.measured_top = plan.measured_top(k);
      layer.target_porosity = plan.porosity(k);
      const LiftLevels levels{plan.lid(k), slot_bottom, slot_top};
      RedfSpec s = layer_redf_spec(t, k, plan.n_particles(k), layer.target_porosity);
      if (t.later_lifts_start_near_the_lift_below && !layers.empty() && plan.porosity(k) == plan.porosity(k - 1))
        {
          const double first = s.initial_growth_friction_deg >= 0.0 ? s.initial_growth_friction_deg
                                                                    : s.particle_contact.friction_angle_deg;
          s.initial_growth_friction_deg = std::min(first, layers.back().growth_friction_deg / redf_friction_drop);
        }
      std::ostringstream region;
      region << "layer " << k + 1 << " of the tank (" << t.width << " m x " << plan.space(k) << " m to fill)";
      const std::string where = "tank filling, layer " + std::to_string(k + 1) + ": ";

      // 1. Random placement between the layer's bottom level and its lid, clear of the grains below.
      ParticleSet particles = settled ? settled->particles() : ParticleSet();
      layer.first_body = particles.n_bodies();
      const std::vector<double> radii =
        redf_starting_sizes(s, t.width * plan.space(k), std::min(t.width, plan.thickness(k)), region.str()).radii;
      place_lift_grains(t, s, radii, laid, layer, levels.lid, where, particles);
      layer.n_bodies = particles.n_bodies() - layer.first_body;

      // A lift below the first sheet may have been grown and settled from this very state before.
      const bool cacheable = !t.lift_cache_directory.empty() && t.sheet && k + 1 <= t.sheet->layers_below;
      const std::uint64_t key = cacheable ? lift_cache_key(t, k, s, layer, levels.lid, particles) : 0;
      const std::filesystem::path cached = cacheable ? lift_cache_file(t.lift_cache_directory, key) : "";
      if (std::optional<DemSystemState> saved = cacheable ? load_lift(cached, key, layer) : std::nullopt)
        {
          // As the settling leaves it: the same construction, the saved state restored.
          SettledFill fill = fill_system_from_state(std::move(*saved), t, material, settling_settings, levels);
          settled = std::move(fill.system);
          walls = fill.walls;
          layer.from_cache = true;
          if (progress)
            progress(static_cast<double>(k + 1) / static_cast<double>(n_layers));
        }
      else
        {
          // 2. Growth without gravity under the lid, to the porosity of the layer's slab; 3. settling
          // under gravity, the lid parked above the fill, the layers below free again.
          const double done = static_cast<double>(k) / static_cast<double>(n_layers);
          const double share = 1.0 / static_cast<double>(n_layers);
          using Progress = std::function<void(double)>;
          const Progress growth_progress =
            progress ? Progress([&](double f) { progress(done + 0.7 * share * f); }) : Progress();
          const Progress settling_progress =
            progress ? Progress([&](double f) { progress(done + share * (0.7 + 0.3 * f)); }) : Progress();
          DemSystemState grown =
            grow_lift(std::move(particles), t, s, material, growth_settings, laid, levels, where, growth_progress, layer);
          SettledFill fill =
            settle_lift(std::move(grown), t, material, settling_settings, levels, where, settling_progress, layer);
          settled = std::move(fill.system);
          walls = fill.walls;
          if (cacheable)
            save_lift(*settled, layer, key, cached);
        }
      layers.push_back(layer);
      laid = settled->sheets();
      if (t.sheet && k + 1 == t.sheet->layers_below)
        {
          double slot_height = 0.0;
          laid.push_back(lay_sheet(*t.sheet, *settled, t, slot_height));
          slot_bottom = laid.back().y[0] - 0.5 * slot_height;
          slot_top = laid.back().y[0] + 0.5 * slot_height;
        }
      if (t.sheet && k + 1 == t.sheet->second_part_layers_below)
        laid.back() = lay_second_part(*t.sheet, *settled, laid.back(), t);
    }
  for (TankLayer &layer : layers)
    layer.porosity = slab_porosity_beside_sheets(settled->particles(), settled->sheets(), t.width,
                                                 layer.measured_bottom, layer.measured_top);
  if (progress)
    progress(1.0);
  return FilledTank{std::move(*settled), walls, std::move(layers), slot_bottom, slot_top};
}
} // namespace geohybrid::dem
