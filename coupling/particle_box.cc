#include "particle_box.h"

#include "coupling/hybrid_pullout.h"
#include "dem/laboratory/tank_filling.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace geohybrid::coupling
{
namespace
{
/// How the box is cut below the sheet: `n_below` lifts of `thickness`, reaching `below` down
/// from the sheet (their sum, kept as the given rule computes it so that its box is as before).
struct Lifts
{
  double thickness = 0.0; ///< the thinnest, with `tops`
  std::size_t n_below = 0;
  double below = 0.0;
  /// Lifts of their own thickness in each part of the box (lifts_by_part): their tops above the
  /// box's bottom, bottom first. Empty: lifts of `thickness` all the way up.
  std::vector<double> tops;
};

/// The given rule: the margin below the sheet (or the whole soil below it) divided evenly into
/// lifts at most `at_most` thick.
Lifts lifts_at_most(const HybridPullOutSpec &spec, double at_most)
{
  const double below = std::min(spec.region.margin, spec.tank.geometry.sheet_level());
  const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(below / at_most - 1e-9)));
  return {below / static_cast<double>(n), n, below, {}};
}

/// The box cut into `lifts` below the sheet and as many of the same above as reach the margin
/// above its highest part; its grains not checked yet.
ParticleBox box_in_lifts(const HybridPullOutSpec &spec, const Lifts &lifts, const std::string &where)
{
  const dem::PullOutGeometry &g = spec.tank.geometry;
  const double margin = spec.region.margin;
  const double sheet_level = g.sheet_level();
  // A sheet that crosses into the continuum has only (part of) its lower part in the box: the box
  // is a run-out's.
  const bool crossing = spec.region.dem_region_length > 0.0;
  const bool wrap = g.anchorage == dem::Anchorage::wrap_around && !crossing;
  const double rise = wrap ? g.return_height : 0.0; // from the lower part to the upper part
  ParticleBox box;
  const double lift = lifts.thickness;
  box.y0 = sheet_level - lifts.below;
  box.bottom_shared = box.y0 > 1e-9;
  // Above: lifts by part as lifts_by_part cut them; or lifts of the same thickness up to `margin`
  // above the sheet's highest part, or to the surface if it falls on a lift boundary (else the
  // last whole lift below it).
  std::size_t lifts_above = 0;
  if (!lifts.tops.empty())
    {
      lifts_above = lifts.tops.size() - lifts.n_below;
      box.y1 = std::min(box.y0 + lifts.tops.back(), g.fill_height);
    }
  else
    {
      lifts_above = static_cast<std::size_t>(std::ceil((rise + margin) / lift - 1e-9));
      const double room = (g.fill_height - sheet_level) / lift;
      if (static_cast<double>(lifts_above) >= room - 1e-6)
        lifts_above = static_cast<std::size_t>(std::floor(room + 1e-6));
      box.y1 = sheet_level + static_cast<double>(lifts_above) * lift;
    }
  box.top_shared = box.y1 < g.fill_height - 1e-9;
  if (box.y1 - (sheet_level + rise) < 0.5 * margin && box.top_shared)
    throw std::invalid_argument(where + ": parameter 'Hybrid/DEM region margin' = " + std::to_string(margin) +
                                " m leaves the particle box's top " + std::to_string(box.y1 - sheet_level - rise) +
                                " m above the sheet, less than half the margin (lifts of " + std::to_string(lift) +
                                " m): change the margin or 'Hybrid/lift thickness'");
  box.x1 = g.tank_length;
  box.x0 = crossing ? g.tank_length - spec.region.dem_region_length
                    : std::max(0.0, g.tank_length - g.anchorage_length - margin);
  box.left_shared = box.x0 > 1e-9;
  box.n_lifts = lifts.n_below + lifts_above;
  box.lift_thickness = lift;
  if (!box.left_shared && !box.bottom_shared && !box.top_shared)
    throw std::invalid_argument(where + ": parameter 'Hybrid/DEM region margin' = " + std::to_string(margin) +
                                " m puts the whole tank in the particle box: use 'mode' = dem");
  const double tank_area = g.tank_length * g.fill_height, box_area = (box.x1 - box.x0) * (box.y1 - box.y0);
  box.n_particles = static_cast<std::size_t>(
    std::lround(static_cast<double>(spec.tank.filling.n_particles) * box_area / tank_area));

  // The box as a tank of its own, in its frame (origin at (x0, y0)).
  dem::PullOutTankSpec &t = box.box_tank;
  t = spec.tank;
  t.geometry.tank_length = box.x1 - box.x0;
  t.geometry.fill_height = box.y1 - box.y0;
  t.geometry.cover = box.y1 - sheet_level;
  if (wrap)
    t.geometry.upper_cover = box.y1 - (sheet_level + rise);
  if (crossing)
    {
      // The box's sheet: a run-out reaching two thicknesses from the box's back (its temporary
      // wall, which a node touches within half a thickness), through the pad and the band that
      // will be cut off to the continuum.
      t.geometry.anchorage = dem::Anchorage::simple_run_out;
      t.geometry.anchorage_length = t.geometry.tank_length - 2.0 * spec.tank.sheet.thickness;
    }
  t.filling.n_layers = box.n_lifts;
  t.filling.layer_tops = lifts.tops;
  t.filling.n_particles = box.n_particles;
  // A shared top is not the soil's surface: the top lift's porosity is measured a band below it.
  // A floor inside the tank's first lift stands for the tank's base, whose loose band that lift
  // counts; above it the tank's soil has no floor band, so the first lift is measured a band
  // above the floor (docs/coupling.md, "Layout"; VALIDATION.md 6.4, "The box's floor").
  t.filling.soil_continues_above = box.top_shared;
  t.filling.soil_continues_below = box.bottom_shared && box.y0 >= dem::layer_top(spec.tank.resolved_filling(), 0) - 1e-9;
  if (!t.filling.layer_porosities.empty())
    {
      double mean = 0.0;
      for (const double n : t.filling.layer_porosities)
        mean += n / static_cast<double>(t.filling.layer_porosities.size());
      t.filling.target_porosity = mean;
      t.filling.layer_porosities.clear();
    }
  t.validate(where + " (the particle box)");
  box.largest_grain = dem::largest_particle_extent(t.resolved_filling());
  return box;
}

/// Whether the fill takes the box's grains (`room` 1: its check, dem::fill_tank_in_layers), or
/// takes them with `room` to spare: the largest at most a fifth of the narrowest of a lift's
/// thickness and the box's width.
bool takes_its_grains(const ParticleBox &box, double room)
{
  const dem::TankFillingSpec &f = box.box_tank.filling;
  dem::TankFillingSpec resolved = f;
  resolved.height = box.box_tank.geometry.fill_height;
  const double thickness = dem::thinnest_layer(resolved);
  return room * box.largest_grain <= 0.2 * std::min(box.box_tank.geometry.tank_length, thickness);
}

/// The box with `lifts`, or none if that cut is refused (a misaligned upper part, too little
/// margin above).
std::optional<ParticleBox> try_box(const HybridPullOutSpec &spec, const Lifts &lifts, const std::string &where)
{
  try
    {
      return box_in_lifts(spec, lifts, where);
    }
  catch (const std::invalid_argument &)
    {
      return std::nullopt;
    }
}

/// How lifts_by_part divides each part of the box.
enum class PartLifts
{
  tank_lifts, ///< at the whole tank's own lift boundaries ('Filling/number of layers') inside it
  even        ///< evenly, into as many lifts at least `least` thick as it holds
};

/// Each part of the box in lifts of its own: the margin below the sheet (or the soil below it),
/// a wrap-around's rise to its upper part, and the margin above its highest part (or the soil
/// above it, where the continuum left above would be thinner than `least`), divided as `how`
/// says. None if a lift would be thinner than `least`.
std::optional<Lifts> lifts_by_part(const HybridPullOutSpec &spec, double least, PartLifts how)
{
  const dem::PullOutGeometry &g = spec.tank.geometry;
  const double sheet_level = g.sheet_level();
  const bool wrap = g.anchorage == dem::Anchorage::wrap_around && spec.region.dem_region_length == 0.0;
  const double rise = wrap ? g.return_height : 0.0;
  const double below = std::min(spec.region.margin, sheet_level);
  const double soil_above = g.fill_height - sheet_level - rise;
  const double above = soil_above - spec.region.margin < least ? soil_above : spec.region.margin;
  dem::TankFillingSpec tank = spec.tank.filling;
  tank.height = g.fill_height;
  Lifts lifts;
  lifts.below = below;
  lifts.thickness = g.fill_height;
  const double y0 = sheet_level - below; // the box's bottom in the tank's frame
  double level = 0.0;                    // the part's bottom in the box's frame
  for (const double part : {below, rise, above})
    {
      if (part <= 0.0)
        continue;
      std::vector<double> tops;
      if (how == PartLifts::tank_lifts)
        {
          for (std::size_t k = 0; k + 1 < tank.n_layers; ++k)
            if (const double top = dem::layer_top(tank, k) - y0; top > level + 1e-9 && top < level + part - 1e-9)
              tops.push_back(top);
          tops.push_back(level + part);
        }
      else
        {
          const auto n = static_cast<std::size_t>(std::floor(part / least + 1e-9));
          for (std::size_t i = 1; i <= n; ++i)
            tops.push_back(i == n ? level + part : level + part * static_cast<double>(i) / static_cast<double>(n));
        }
      double bottom = level;
      for (const double top : tops)
        {
          if (top - bottom < least)
            return std::nullopt;
          lifts.thickness = std::min(lifts.thickness, top - bottom);
          bottom = top;
        }
      lifts.tops.insert(lifts.tops.end(), tops.begin(), tops.end());
      if (lifts.n_below == 0)
        lifts.n_below = tops.size();
      level += part;
    }
  return lifts;
}

/// The automatic choice's cuts after the former default's, best first: the margin below the
/// sheet divided into fewer lifts; each part of the box in lifts of its own (lifts_by_part), the
/// whole tank's lifts first (the box's grains then grow in lifts of the thickness pure DEM's do,
/// which sets the friction they grow at), then the thinnest the grains allow; then whole lifts
/// reaching past the margin (the box further down), aligned with a wrap-around's upper part, from
/// the thinnest the grains allow.
std::vector<Lifts> thicker_cuts(const HybridPullOutSpec &spec, const Lifts &former)
{
  std::vector<Lifts> cuts;
  for (std::size_t n = former.n_below - 1; n >= 1; --n)
    cuts.push_back({former.below / static_cast<double>(n), n, former.below, {}});
  const dem::PullOutGeometry &g = spec.tank.geometry;
  const double sheet_level = g.sheet_level();
  // The grains' size from the whole tank: the box's draw is the same size give or take its scatter.
  const double least = 5.0 * automatic_lift_room * dem::largest_particle_extent(spec.tank.resolved_filling());
  // In steps of 1 % for the box's draw, which scatters round the tank's by about that.
  for (const PartLifts how : {PartLifts::tank_lifts, PartLifts::even})
    for (const double step : {1.0, 1.01, 1.02, 1.03, 1.05})
      if (std::optional<Lifts> by_part = lifts_by_part(spec, least * step, how))
        if (cuts.empty() || by_part->tops != cuts.back().tops)
          cuts.push_back(*by_part);
  const bool wrap = g.anchorage == dem::Anchorage::wrap_around && spec.region.dem_region_length == 0.0;
  std::vector<double> thicknesses;
  if (wrap)
    for (auto k = static_cast<std::size_t>(std::max(1.0, std::floor(g.return_height / least))); k >= 1; --k)
      thicknesses.push_back(g.return_height / static_cast<double>(k));
  else
    // To the millimetre above, to read well; in steps of 1 % for the box's draw, which scatters
    // round the tank's by about that.
    for (const double step : {1.0, 1.01, 1.02, 1.03, 1.05})
      if (const double t = std::ceil(least * step * 1e3) / 1e3; thicknesses.empty() || t > thicknesses.back())
        thicknesses.push_back(t);
  thicknesses.push_back(sheet_level); // one lift down to the base
  for (const double t : thicknesses)
    {
      const auto n = static_cast<std::size_t>(std::ceil(former.below / t - 1e-9));
      if (static_cast<double>(n) * t <= sheet_level * (1.0 + 1e-9))
        cuts.push_back({t, n, std::min(static_cast<double>(n) * t, sheet_level), {}});
    }
  return cuts;
}

/// The automatic lifts, or none if no cut takes the grains.
std::optional<ParticleBox> automatic_box(const HybridPullOutSpec &spec, const std::string &where)
{
  // The former default where the fill takes its grains: an input that ran keeps its numbers.
  const Lifts former = lifts_at_most(spec, automatic_lift_cap);
  if (const auto box = try_box(spec, former, where); box && takes_its_grains(*box, 1.0))
    return box;
  for (const Lifts &cut : thicker_cuts(spec, former))
    if (const auto box = try_box(spec, cut, where); box && takes_its_grains(*box, automatic_lift_room))
      return box;
  return std::nullopt;
}

/// The whole tank's particles that give the box cut into `lifts` grains at most a fifth of a
/// lift with the automatic room, rounded up to a hundred.
std::size_t particles_for(HybridPullOutSpec spec, const Lifts &lifts, const std::string &where)
{
  // The grains' size goes as 1 / sqrt(particles per area); the box's draw moves a little with
  // the count, so the count is checked and raised until it fits.
  const ParticleBox box = box_in_lifts(spec, lifts, where);
  const double ratio = 5.0 * automatic_lift_room * box.largest_grain / lifts.thickness;
  const double n = static_cast<double>(spec.tank.filling.n_particles);
  auto needed = static_cast<std::size_t>(std::ceil(n * ratio * ratio / 100.0) * 100.0);
  for (int attempt = 0; attempt < 20; ++attempt)
    {
      spec.tank.filling.n_particles = needed;
      if (const auto more = try_box(spec, lifts, where); more && takes_its_grains(*more, automatic_lift_room))
        break;
      needed += 100;
    }
  return needed;
}

std::string lifts_description(const ParticleBox &box)
{
  std::ostringstream text;
  text << box.n_lifts << " lifts of " << (box.box_tank.filling.layer_tops.empty() ? "" : "at least ") << box.lift_thickness
       << " m, the box [" << box.x0 << ", " << box.x1 << "] x ["
       << box.y0 << ", " << box.y1 << "] m";
  return text.str();
}
} // namespace

ParticleBox particle_box(const HybridPullOutSpec &spec, const std::string &where)
{
  spec.validate(where);
  const std::size_t n = spec.tank.filling.n_particles;
  if (spec.region.lift_thickness > 0.0)
    {
      const Lifts given = lifts_at_most(spec, spec.region.lift_thickness);
      ParticleBox box;
      try
        {
          box = box_in_lifts(spec, given, where);
        }
      catch (const std::invalid_argument &e)
        {
          // Lifts of one thickness that miss a wrap-around's upper part, or leave too little above.
          throw std::invalid_argument(std::string(e.what()) + " (with 'Hybrid/lift thickness' = " +
                                      std::to_string(spec.region.lift_thickness) +
                                      "; 'Hybrid/lift thickness' = auto gives each part of the box lifts of its own)");
        }
      if (takes_its_grains(box, 1.0) || spec.region.box_cut_from_a_filled_tank)
        return box;
      std::ostringstream message;
      message << where << ": parameter 'Hybrid/lift thickness' = " << spec.region.lift_thickness << " cuts the particle box into "
              << lifts_description(box) << ", and its grains ('Filling/number of particles' = " << n
              << " in the whole tank) would be up to " << box.largest_grain
              << " m across, more than a fifth of a lift: set 'Filling/number of particles' to "
              << particles_for(spec, given, where) << " (grains 5 % under a fifth of a lift)";
      HybridPullOutSpec automatic = spec;
      automatic.region.lift_thickness = 0.0;
      if (const auto chosen = automatic_box(automatic, where))
        message << ", or 'Hybrid/lift thickness' = auto (here " << lifts_description(*chosen) << ")";
      throw std::invalid_argument(message.str());
    }
  if (auto box = automatic_box(spec, where))
    return *box;
  // No cut takes the grains: the particles that would fill the box with the margin below the
  // sheet in one lift.
  const Lifts one = lifts_at_most(spec, spec.tank.geometry.fill_height);
  const ParticleBox thick = box_in_lifts(spec, one, where);
  std::ostringstream message;
  message << where << ": parameter 'Filling/number of particles' = " << n << " makes grains up to " << thick.largest_grain
          << " m across, and the particle box ('Hybrid/DEM region margin' = " << spec.region.margin
          << " m, 'Hybrid/lift thickness' = auto) has no lifts five of them thick that put the sheet on a lift "
          << "boundary: set 'Filling/number of particles' to " << particles_for(spec, one, where)
          << " (then " << lifts_description(thick) << ")";
  throw std::invalid_argument(message.str());
}
} // namespace geohybrid::coupling
