#include "tank_filling.h"

#include "lift_cache.h"
#include "measurements.h"
#include "sample_preparation.h"

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

/// Area the sheets take in the slab y in [y0, y1], x in [x_min, x_max] (a tank's: [0, width]):
/// each segment a band of the sheet's thickness, cut at the slab's levels piece by piece. A sheet
/// is not soil: the slab's porosity is that of the space the grains can fill (a 3.2 mm sheet in a
/// 50 mm lift is 6 % of its area, which the grains would otherwise have to make up by packing
/// denser).
double sheet_area_in_slab(const std::vector<SparSheet> &sheets, double x_min, double x_max, double y0, double y1)
{
  constexpr int pieces = 32; // per segment: the band's cut at a level is exact for a flat piece
  double area = 0.0;
  for (const SparSheet &sheet : sheets)
    for (std::size_t k = 0; k < sheet.n_segments(); ++k)
      {
        const Vec2 a = sheet.node(k), b = sheet.node(k + 1);
        const double length = (b - a).norm();
        if (!(length > 0.0))
          continue;
        // Half the band's vertical extent across the thickness: t/2 |cos| of the segment's slope.
        const double half = 0.5 * sheet.thickness() * std::abs(b.x() - a.x()) / length;
        for (int i = 0; i < pieces; ++i)
          {
            const Vec2 c = a + (b - a) * ((i + 0.5) / pieces);
            if (c.x() < x_min || c.x() > x_max)
              continue;
            const double inside = half > 0.0 ? std::max(0.0, std::min(y1, c.y() + half) - std::max(y0, c.y() - half)) / (2.0 * half)
                                             : (c.y() >= y0 && c.y() <= y1 ? 1.0 : 0.0);
            area += inside * sheet.thickness() * length / pieces;
          }
      }
  return area;
}

/// A part of a lift's space that the laid sheets wall off from the rest: x in [x0, x1].
struct Compartment
{
  double x0 = 0.0, x1 = 0.0;
};

/// The parts, left to right, into which the laid sheets divide a lift's space [0, width] x
/// [bottom, lid]: a standing run of a sheet's segments (a wrap-around's held return: each
/// segment steeper than 45 degrees, all within `gap` of one x) whose faces reach from within
/// `gap` of the bottom to within `gap` of the lid is a wall no grain can pass (gap: the smallest
/// grain's width; a held return's foot stands on the lift below it, 0.1 t above its highest
/// grain, and its end 0.1 t below the lid of the lift the upper part is laid on).
/// The compartments end half the sheet's thickness from it; one, [0, width], if no sheet stands
/// across the lift.
std::vector<Compartment> lift_compartments(const std::vector<SparSheet> &sheets, double width, double bottom,
                                           double lid, double gap)
{
  std::vector<std::pair<double, double>> partitions; // [x_min, x_max] of each standing wall
  for (const SparSheet &sheet : sheets)
    {
      std::size_t k = 0;
      while (k < sheet.n_segments())
        {
          const auto steep = [&](std::size_t j) {
            const Vec2 a = sheet.node(j), b = sheet.node(j + 1);
            return std::abs(b.y() - a.y()) > std::abs(b.x() - a.x());
          };
          if (!steep(k))
            {
              ++k;
              continue;
            }
          // Its height over the whole run, its x over the segments in the lift's space (the foot
          // of a return, drawn along by the lower part, may stand a little off it).
          double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
          double y_min = sheet.y[k], y_max = y_min;
          const double half = 0.5 * sheet.thickness();
          for (; k < sheet.n_segments() && steep(k); ++k)
            {
              const Vec2 a = sheet.node(k), b = sheet.node(k + 1);
              y_min = std::min(y_min, b.y());
              y_max = std::max(y_max, b.y());
              if (std::max(a.y(), b.y()) + half > bottom && std::min(a.y(), b.y()) - half < lid)
                {
                  x_min = std::min({x_min, a.x(), b.x()});
                  x_max = std::max({x_max, a.x(), b.x()});
                }
            }
          if (x_max - x_min < gap && y_min - half < bottom + gap && y_max + half > lid - gap)
            partitions.emplace_back(x_min - 0.5 * sheet.thickness(), x_max + 0.5 * sheet.thickness());
        }
    }
  std::sort(partitions.begin(), partitions.end());
  std::vector<Compartment> compartments;
  double x = 0.0;
  for (const auto &[x_min, x_max] : partitions)
    {
      if (x_min - x > gap)
        compartments.push_back({x, x_min});
      x = std::max(x, x_max);
    }
  if (width - x > gap || compartments.empty())
    compartments.push_back({compartments.empty() ? 0.0 : x, width});
  return compartments;
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

/// The tank's walls; with slot_top > slot_bottom, the front wall (x = width) is cut into a part
/// below the slot and one above it.
TankWalls add_tank_walls(DemSystem &system, const TankFillingSpec &t, double lid_level, double slot_bottom = 0.0,
                         double slot_top = 0.0)
{
  const LinearContactLaw law(t.wall_contact);
  const double overhang = 0.1 * std::max(t.width, t.height), w = t.width, h = t.height;
  const bool slot = slot_top > slot_bottom;
  // Active side on the left of start -> end (wall.h), counter-clockwise as in RectangularBox.
  TankWalls walls;
  walls.base = system.add_wall(Wall("base", Vec2(-overhang, 0.0), Vec2(w + overhang, 0.0), law));
  walls.right = system.add_wall(Wall(slot ? "right below the slot" : "right", Vec2(w, -overhang),
                                     Vec2(w, slot ? slot_bottom : h + overhang), law));
  walls.lid = system.add_wall(Wall("lid", Vec2(w + overhang, lid_level), Vec2(-overhang, lid_level), law));
  walls.left = system.add_wall(Wall("left", Vec2(0.0, h + overhang), Vec2(0.0, -overhang), law));
  system.walls()[walls.base].loaded_length = w;
  system.walls()[walls.lid].loaded_length = w;
  system.walls()[walls.left].loaded_length = h;
  system.walls()[walls.right].loaded_length = slot ? slot_bottom : h;
  // The lid is the growth's gauge (a lift is jammed when its grains press the lid beyond the
  // growth stress), not a wall the sheet meets: a held part of a sheet standing through a lift's
  // level (a wrap-around's return) must not load it. One did: in the particle box of
  // examples/pullout_hybrid_wraparound_h040_b025.prm (lifts of 0.1 m, 3,667 clusters) a held
  // node of the return lay 0.1 mm below the second lift's lid, pressed it with kn (t/2 - 0.1 mm)
  // = 15 kN/m, 13.6 kPa over the box's 1.1 m, and the lift "jammed" at porosity 0.53 against 0.25.
  system.walls()[walls.lid].touches_sheets = false;
  if (slot)
    {
      walls.right_upper = system.add_wall(Wall("right above the slot", Vec2(w, slot_top), Vec2(w, h + overhang), law));
      system.walls()[walls.right_upper].loaded_length = std::max(h - slot_top, 0.0);
      system.walls()[walls.right].touches_sheets = false;
      system.walls()[walls.right_upper].touches_sheets = false;
    }
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

/// Moves each new body [first_body, end) that a sheet would cut (a disc closer than r + t/2 to a
/// segment, possibly the two discs of a cluster on both sides of it) off the sheet, along the
/// segment's normal to the side of the body's centre (away from the node, near a free end).
/// Grains are placed at random in the next layer's space, through which a laid sheet runs; a
/// cluster placed astride the sheet would hold it pinched between its two discs forever. The
/// grains are then at a fraction of their final size, so the short moves leave them clear of
/// one another or nearly so (growth sorts out the rest).
void move_new_bodies_off_sheets(ParticleSet &p, std::size_t first_body, const std::vector<SparSheet> &sheets,
                                int n_threads)
{
  for (int pass = 0; pass < 4; ++pass)
    {
      bool moved = false;
      for (std::size_t b = first_body; b < p.n_bodies(); ++b)
        for (const SparSheet &sheet : sheets)
          for (std::size_t k = 0; k < sheet.n_segments(); ++k)
            {
              const Vec2 a = sheet.node(k), e = sheet.node(k + 1), centre(p.x[b], p.y[b]);
              const double length = (e - a).norm();
              const Vec2 u = (e - a) / length, n = perp(u);
              const double side = n.dot(centre - a) >= 0.0 ? 1.0 : -1.0;
              double shift = 0.0;
              Vec2 direction = side * n;
              for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
                {
                  const Vec2 c(p.disc_x[d], p.disc_y[d]);
                  const double clearance = p.disc_radius[d] + 0.5 * sheet.thickness() + 1e-6;
                  const double along = u.dot(c - a);
                  if (along >= 0.0 && along <= length)
                    shift = std::max(shift, clearance - side * n.dot(c - a));
                  else
                    {
                      // Past an end: away from the end node (at a joint, the next segment acts).
                      const Vec2 node = along < 0.0 ? a : e;
                      const double distance = (c - node).norm();
                      if (distance < clearance && ((along < 0.0 && k == 0) || (along > length && k + 1 == sheet.n_segments())))
                        {
                          direction = distance > 0.0 ? Vec2((c - node) / distance) : direction;
                          shift = std::max(shift, clearance - distance);
                        }
                    }
                }
              if (shift > 0.0)
                {
                  p.x[b] += shift * direction.x();
                  p.y[b] += shift * direction.y();
                  for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
                    {
                      p.disc_x[d] += shift * direction.x();
                      p.disc_y[d] += shift * direction.y();
                    }
                  moved = true;
                }
            }
      if (!moved)
        break;
    }
  p.update_disc_positions(n_threads); // the same positions, computed as everywhere else
}

/// Throws unless every node of `sheet` but the first (the clamp, outside) lies in the tank.
void check_nodes_in_tank(const SparSheet &sheet, const TankFillingSpec &t)
{
  const Vec2 clamp = sheet.node(0);
  // Nodes between the clamp and the front wall are outside the tank too, in front of the slot.
  for (std::size_t k = 1; k < sheet.n_nodes(); ++k)
    if (!(sheet.x[k] > 0.0 && sheet.x[k] <= clamp.x() && sheet.y[k] > 0.0 && sheet.y[k] < t.height))
      throw std::invalid_argument("tank filling: node " + std::to_string(k) + " of sheet '" + sheet.name() +
                                  "' lies outside the tank");
}

/// The sheet of `laying`, made on the settled layers below it, checked against the tank, and the
/// height of its slot.
SparSheet lay_sheet(const SheetLaying &laying, const DemSystem &settled, const TankFillingSpec &t, double &slot_height)
{
  SparSheet sheet = laying.lay(settled);
  const Vec2 clamp = sheet.node(0);
  if (!(clamp.x() > t.width))
    throw std::invalid_argument("tank filling: the first node of sheet '" + sheet.name() + "' (x = " +
                                std::to_string(clamp.x()) + " m) must lie outside the front wall (x = " +
                                std::to_string(t.width) + " m), where the clamp holds it");
  check_nodes_in_tank(sheet, t);
  const ParticleSet &p = settled.particles();
  const double smallest = 2.0 * *std::min_element(p.disc_radius.begin(), p.disc_radius.end());
  // The clamp holds the sheet at the slot's mid-height, so the slot leaves a gap of
  // (slot height - thickness) / 2 above and below it; a grain escapes only through a gap wider
  // than itself. The automatic slot leaves a quarter of the smallest grain on each side, so that
  // grains smaller than the sheet is thick (a fine tank: 25,000 clusters in the INSA tank have
  // 2.6 mm grains against GT230's 3.2 mm) stay in too.
  slot_height = laying.slot_height > 0.0 ? laying.slot_height : sheet.thickness() + 0.5 * smallest;
  if (!(slot_height > sheet.thickness()))
    throw std::invalid_argument("tank filling: the slot height " + std::to_string(slot_height) +
                                " m must exceed the thickness of sheet '" + sheet.name() + "' (" +
                                std::to_string(sheet.thickness()) + " m)");
  if (!(slot_height - sheet.thickness() < smallest))
    throw std::invalid_argument("tank filling: the slot height " + std::to_string(slot_height) +
                                " m leaves a gap of " + std::to_string(slot_height - sheet.thickness()) +
                                " m beside sheet '" + sheet.name() + "' (" + std::to_string(sheet.thickness()) +
                                " m thick): it must be below the smallest grain's diameter (" + std::to_string(smallest) +
                                " m), or the soil runs out through it");
  return sheet;
}

/// The whole sheet of a two-stage `laying`, from `laid` (the sheet as it stands in the settled
/// layers), checked: the clamp where it was (the slot was cut at its level), no node dropped,
/// every node in the tank.
SparSheet lay_second_part(const SheetLaying &laying, const DemSystem &settled, const SparSheet &laid,
                          const TankFillingSpec &t)
{
  SparSheet sheet = laying.lay_second_part(settled, laid);
  if (sheet.n_nodes() < laid.n_nodes())
    throw std::invalid_argument("tank filling: laying the second part of sheet '" + laid.name() + "' dropped " +
                                std::to_string(laid.n_nodes() - sheet.n_nodes()) + " of its nodes");
  if (!(sheet.node(0) == laid.node(0)))
    throw std::invalid_argument("tank filling: laying the second part of sheet '" + laid.name() +
                                "' moved its clamp (node 0), which the front wall's slot was cut for");
  check_nodes_in_tank(sheet, t);
  return sheet;
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

DemSettings tank_settling_settings(const TankFillingSpec &t)
{
  DemSettings s;
  s.gravity = Vec2(0.0, -t.gravity);
  s.local_damping = t.local_damping;
  s.n_threads = t.n_threads;
  s.track_energy = false;
  return s;
}

double largest_particle_extent(const TankFillingSpec &t)
{
  check_spec(t);
  const double porosity = t.layer_porosities.empty() ? t.target_porosity : t.layer_porosities[0];
  // An unbounded width: the size only, not the check (fill_tank_in_layers makes that).
  return redf_starting_sizes(layer_redf_spec(t, 0, t.n_particles, porosity), t.width * t.height,
                             std::numeric_limits<double>::max(), "the tank")
    .largest_extent;
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
  // The lift a sheet is laid on is levelled, as in the laboratory: it grows under a lid at its
  // level, so that the sheet lies flat on it at the nominal depth. (With the lid a band higher,
  // the sheet rested on the highest grain of a rough surface, up to two grains above its level,
  // and bridged the hollows below it, which the grains above cannot fill: measured on the
  // 400-cluster tank of tests/test_dem_pullout.cc, the sheet 12 mm above its level, the vertical
  // stress on it 0.25 gamma H, and the lift above it grown down to a friction of 0.7 degrees
  // over 238,000 steps to make up for the hollows in its slab.) The sheet separates the two
  // lifts, so the band loosened along the lid is not filled from above: it is the loose band
  // along the sheet, as on its other face. The lift a two-stage sheet's second part is laid on
  // is levelled the same way (tank_filling.h).
  const auto has_band = [&](std::size_t k) {
    return k + 1 < n_layers &&
           !(t.sheet && (k + 1 == t.sheet->layers_below || k + 1 == t.sheet->second_part_layers_below));
  };
  // Particles in proportion to the space each layer fills: a layer with a band also fills it;
  // the next one fills from the top of that band.
  std::vector<double> cumulative_space(n_layers + 1, 0.0);
  for (std::size_t k = 0; k < n_layers; ++k)
    cumulative_space[k + 1] = static_cast<double>(k + 1) * thickness + (has_band(k) ? band : 0.0);
  cumulative_space[n_layers] = t.height;
  const auto particles_before = [&](std::size_t k) {
    return static_cast<std::size_t>(std::llround(static_cast<double>(t.n_particles) * cumulative_space[k] / t.height));
  };

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
      layer.bottom = static_cast<double>(k) * thickness;
      layer.top = k + 1 == n_layers ? t.height : static_cast<double>(k + 1) * thickness;
      layer.target_porosity = porosity_of(k);
      const double lid_level = has_band(k) ? layer.top + band : layer.top;
      const double space = cumulative_space[k + 1] - cumulative_space[k];
      RedfSpec s = layer_redf_spec(t, k, particles_before(k + 1) - particles_before(k), layer.target_porosity);
      if (t.later_lifts_start_near_the_lift_below && !layers.empty() && porosity_of(k) == porosity_of(k - 1))
        {
          const double first = s.initial_growth_friction_deg >= 0.0 ? s.initial_growth_friction_deg
                                                                    : s.particle_contact.friction_angle_deg;
          s.initial_growth_friction_deg = std::min(first, layers.back().growth_friction_deg / redf_friction_drop);
        }
      std::ostringstream region;
      region << "layer " << k + 1 << " of the tank (" << t.width << " m x " << space << " m to fill)";
      const std::string where = "tank filling, layer " + std::to_string(k + 1) + ": ";

      // 1. Random placement between the layer's bottom level and its lid, clear of the grains below.
      ParticleSet particles = settled ? settled->particles() : ParticleSet();
      const std::size_t first_body = particles.n_bodies();
      const std::vector<double> radii =
        redf_starting_sizes(s, t.width * space, std::min(t.width, thickness), region.str()).radii;
      // A sheet standing across the lift (a wrap-around's held return) walls its space into
      // compartments that no grain passes between while the lift grows: each is a lift of its
      // own, and gets the share of the grains that fills it at the target porosity, the room its
      // space (less the sheets) leaves at that porosity beside the grains already there. Placed
      // at random over the whole lift, a compartment got its share of the area give or take the
      // placement's scatter: in the particle box of the full-size wrap-around (seed 2, lifts of
      // 0.1 m), the third lift's compartment behind the return, 0.098 m of its 1.1 m, got 9.4 %
      // of its grains' area for 9.0 % of its room; it jammed, frictionless, at porosity 0.18
      // under 229 kPa, which is all of the 20.5 kPa the lid read, while the rest of the lift lay
      // loose at 0.21 and the lift could not be grown.
      const std::vector<Compartment> compartments = [&] {
        if (laid.empty())
          return std::vector<Compartment>{{0.0, t.width}};
        // The narrowest a grain is at its starting size: a gap below it passes none.
        const double smallest =
          2.0 * *std::min_element(radii.begin(), radii.end()) * (t.shape == ParticleShape::disc ? 1.0 : t.cluster_diameter_ratio);
        return lift_compartments(laid, t.width, layer.bottom, lid_level, smallest);
      }();
      try
        {
          if (compartments.size() == 1)
            place_at_random(s,
                            {Vec2(compartments[0].x0, layer.bottom), Vec2(compartments[0].x1, layer.bottom),
                             Vec2(compartments[0].x1, lid_level), Vec2(compartments[0].x0, lid_level)},
                            radii, s.seed, particles);
          else
            {
              // Each compartment's room: (1 - n) of its space less the sheets', less the solid of the
              // grains already in it (the band of the lift below, the tops of those under it).
              std::vector<double> room(compartments.size(), 0.0);
              double total_room = 0.0;
              for (std::size_t c = 0; c < compartments.size(); ++c)
                {
                  const Compartment &part = compartments[c];
                  double existing = 0.0;
                  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
                    if (particles.x[b] >= part.x0 && particles.x[b] <= part.x1)
                      existing += share_in_slab(particles, b, layer.bottom, lid_level) * particles.body_area(b);
                  const double space_c = (part.x1 - part.x0) * (lid_level - layer.bottom) -
                                         sheet_area_in_slab(laid, part.x0, part.x1, layer.bottom, lid_level);
                  room[c] = std::max(0.0, (1.0 - layer.target_porosity) * space_c - existing);
                  total_room += room[c];
                }
              if (!(total_room > 0.0)) // no room anywhere: the layer is too dense already; REDF says so
                {
                  for (std::size_t c = 0; c < compartments.size(); ++c)
                    room[c] = compartments[c].x1 - compartments[c].x0;
                  total_room = 0.0;
                  for (const double r : room)
                    total_room += r;
                }
              // The grains, largest first, each to the compartment furthest below its share of
              // the area placed so far (areas as r^2: the grains have one shape): the shares
              // come out exact to within about the last grain's area.
              std::vector<std::vector<double>> radii_of(compartments.size());
              std::vector<double> placed(compartments.size(), 0.0);
              double placed_total = 0.0;
              for (const double r : radii)
                {
                  placed_total += r * r;
                  std::size_t best = 0;
                  double lag_best = -std::numeric_limits<double>::infinity();
                  for (std::size_t c = 0; c < compartments.size(); ++c)
                    {
                      const double lag = room[c] / total_room * placed_total - placed[c];
                      if (lag > lag_best)
                        {
                          lag_best = lag;
                          best = c;
                        }
                    }
                  radii_of[best].push_back(r);
                  placed[best] += r * r;
                }
              for (std::size_t c = 0; c < compartments.size(); ++c)
                if (!radii_of[c].empty())
                  {
                    const Compartment &part = compartments[c];
                    // Each compartment its own random stream.
                    place_at_random(s,
                                    {Vec2(part.x0, layer.bottom), Vec2(part.x1, layer.bottom), Vec2(part.x1, lid_level),
                                     Vec2(part.x0, lid_level)},
                                    radii_of[c], s.seed ^ (0xbf58476d1ce4e5b9ULL * (c + 1)), particles);
                  }
            }
        }
      catch (const std::invalid_argument &e)
        {
          throw std::invalid_argument(where + e.what());
        }
      if (!laid.empty())
        move_new_bodies_off_sheets(particles, first_body, laid, t.n_threads);
      layer.first_body = first_body;
      layer.n_bodies = particles.n_bodies() - first_body;

      // A lift below the first sheet may have been grown and settled from this very state before.
      const bool cacheable = !t.lift_cache_directory.empty() && t.sheet && k + 1 <= t.sheet->layers_below;
      const std::uint64_t key = cacheable ? lift_cache_key(t, k, s, layer, lid_level, particles) : 0;
      const std::filesystem::path cached = cacheable ? lift_cache_file(t.lift_cache_directory, key) : "";
      if (std::optional<DemSystemState> saved = cacheable ? load_lift(cached, key, layer) : std::nullopt)
        {
          // As the settling below leaves it: the same construction, the saved state restored.
          settled = std::make_unique<DemSystem>(saved->particles, material, settling_settings);
          walls = add_tank_walls(*settled, t, lid_level, slot_bottom, slot_top);
          settled->restore_state(std::move(*saved));
          layer.from_cache = true;
          if (progress)
            progress(static_cast<double>(k + 1) / static_cast<double>(n_layers));
        }
      else
        {
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
          const double sheet_area = sheet_area_in_slab(laid, 0.0, t.width, layer.bottom, layer.top);
          std::vector<double> starting_area(layer.n_bodies);
          for (std::size_t i = 0; i < layer.n_bodies; ++i)
            starting_area[i] = particles.body_area(first_body + i);

          // 2. Growth without gravity under the lid, to the porosity of the layer's slab.
          DemSystem growing(std::move(particles), material, growth_settings);
          growing.set_skip_contacts_between_fixed_bodies(true); // the lifts below are fixed: their contacts cannot change
          walls = add_tank_walls(growing, t, lid_level, slot_bottom, slot_top);
          // A sheet laid on the layers below stays where it lies while this layer grows round it.
          for (const SparSheet &sheet : laid)
            growing.add_sheet(sheet);
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
            return 1.0 - (solid + area_factor * grown_solid) / (t.width * (layer.top - layer.bottom) - sheet_area);
          };
          growth.grow = [&](double factor) {
            growing.scale_particle_sizes(factor, first_body); // the lifts below keep their sizes
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
          add_tank_walls(*settled, t, lid_level, slot_bottom, slot_top);
          settled->restore_state(std::move(state));
          // The growth's last forces had no gravity and, with its contacts between fixed bodies
          // skipped, left those out of the lower lifts' resultants: the settling starts from forces
          // evaluated afresh.
          settled->initialise_forces_at_next_step();
          // The growth ran at the step its grains' starting sizes allowed (a fraction of their final
          // ones, so a lighter body and a shorter critical step); grown, they allow a longer one.
          // Without this the settling and the pull-out after the fill ran at 0.61 of the critical
          // step instead of 0.8 (measured on the 6,000-cluster tank: dt 1.006e-5 s, critical
          // 1.655e-5 s), 31 % more steps than needed.
          settled->set_time_step(settling_settings.time_step_safety * settled->critical_time_step());
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
    {
      // Of the space the grains can fill, as while growing: without the sheets' area.
      layer.porosity = slab_porosity(settled->particles(), 0.0, t.width, layer.bottom, layer.top);
      const double sheet_area = sheet_area_in_slab(settled->sheets(), 0.0, t.width, layer.bottom, layer.top);
      if (sheet_area > 0.0)
        {
          const double area = t.width * (layer.top - layer.bottom);
          layer.porosity = 1.0 - (1.0 - layer.porosity) * area / (area - sheet_area);
        }
    }
  if (progress)
    progress(1.0);
  return FilledTank{std::move(*settled), walls, std::move(layers), slot_bottom, slot_top};
}
} // namespace geohybrid::dem
