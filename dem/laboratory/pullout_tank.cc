// The tank and its fill: the geometry's and the spec's checks, the filling spec as used (the sheet
// laid in one or two stages), the fill with the sheet freed but for its clamp and settled again.
#include "pullout_tank.h"

#include "dem/measurements.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
namespace
{
/// Throws naming the parameter as the input file spells it.
void require(bool condition, const std::string &where, const std::string &name, double value, const std::string &what)
{
  if (!condition)
    {
      std::ostringstream message;
      message << where << ": '" << name << "' = " << value << " " << what;
      throw std::invalid_argument(message.str());
    }
}

bool positive(double v) { return v > 0.0 && std::isfinite(v); }
} // namespace

void PullOutGeometry::validate(const std::string &where) const
{
  require(positive(tank_length), where, "Tank/length", tank_length, "must be positive [m]");
  require(positive(fill_height), where, "Tank/fill height", fill_height, "must be positive [m]");
  require(wall_friction_deg >= 0.0 && wall_friction_deg < 90.0, where, "Tank/wall friction angle", wall_friction_deg,
          "must lie in [0, 90) [deg]");
  require(positive(clamp_offset), where, "Tank/clamp offset", clamp_offset,
          "must be positive: the clamp is outside the front wall [m]");
  require(positive(sheet_width), where, "Sheet/width", sheet_width, "must be positive [m]");
  require(positive(cover), where, "Anchorage/H", cover, "must be positive [m]");
  require(cover < fill_height, where, "Anchorage/H", cover,
          "must be below 'Tank/fill height' = " + std::to_string(fill_height) + " m: the sheet would be outside the tank");
  require(positive(anchorage_length), where, "Anchorage/L", anchorage_length, "must be positive [m]");
  require(anchorage_length < tank_length, where, "Anchorage/L", anchorage_length,
          "must be shorter than 'Tank/length' = " + std::to_string(tank_length) +
            " m: the sheet would reach through the back wall");
  if (anchorage == Anchorage::wrap_around)
    {
      require(positive(return_height), where, "Anchorage/D1", return_height, "must be positive [m]");
      require(positive(upper_cover), where, "Anchorage/D2", upper_cover, "must be positive [m]");
      require(std::abs(return_height + upper_cover - cover) <= 1e-9 * cover, where, "Anchorage/H", cover,
              "must equal D1 + D2 = " + std::to_string(return_height + upper_cover) + " m for a wrap-around");
      require(positive(upper_length), where, "Anchorage/B", upper_length, "must be positive [m]");
      require(upper_length < tank_length, where, "Anchorage/B", upper_length,
              "must be shorter than the tank ('Tank/length' = " + std::to_string(tank_length) + " m)");
      require(upper_length < anchorage_length, where, "Anchorage/B", upper_length,
              "must be shorter than L = " + std::to_string(anchorage_length) +
                " m: the upper part runs back from the return towards the front wall and would leave the tank");
    }
}

std::vector<Vec2> PullOutGeometry::sheet_corners(double level) const
{
  const double front = tank_length, end = tank_length - anchorage_length;
  std::vector<Vec2> corners{Vec2(front + clamp_offset, level), Vec2(end, level)};
  if (anchorage == Anchorage::wrap_around)
    {
      corners.emplace_back(end, level + return_height);
      corners.emplace_back(end + upper_length, level + return_height);
    }
  return corners;
}

double solid_density_for_unit_weight(double unit_weight, double porosity, double gravity)
{
  return unit_weight / (gravity * (1.0 - porosity));
}

void PullOutTankSpec::validate(const std::string &where) const
{
  geometry.validate(where);
  sheet.validate(where + ", subsection Sheet");
  require(positive(max_segment_length), where, "Sheet/segment length", max_segment_length, "must be positive [m]");
  require(positive(unit_weight), where, "Soil/unit weight", unit_weight, "must be positive [N/m^3]");
  TankFillingSpec f = filling;
  f.height = geometry.fill_height;
  const double n = static_cast<double>(filling.n_layers);
  std::string layers;
  if (f.layer_tops.empty())
    layers = "layers " + std::to_string(geometry.fill_height / n) + " m thick";
  else
    for (const double top : f.layer_tops)
      layers += (layers.empty() ? "layer tops at " : ", ") + std::to_string(top);
  const double tolerance = 1e-6 * thinnest_layer(f);
  const std::optional<std::size_t> below = layers_below_level(f, geometry.sheet_level(), tolerance);
  require(filling.n_layers >= 2 && below && *below >= 1 && *below < filling.n_layers, where, "Filling/number of layers", n,
          "must put a layer boundary at the sheet level (fill height - H = " + std::to_string(geometry.sheet_level()) +
            " m with " + layers + ")");
  if (geometry.anchorage == Anchorage::wrap_around)
    {
      // The upper part is laid on the lift whose top is at its level (resolved_filling).
      const std::optional<std::size_t> top =
        layers_below_level(f, geometry.sheet_level() + geometry.return_height, tolerance);
      require(top && *top < filling.n_layers, where, "Filling/number of layers", n,
              "must put a layer boundary at the level of the sheet's upper part (fill height - H + D1 = " +
                std::to_string(geometry.sheet_level() + geometry.return_height) + " m with " + layers +
                ") and leave at least one layer above it");
    }
}

TankFillingSpec PullOutTankSpec::resolved_filling() const
{
  TankFillingSpec t = filling;
  t.width = geometry.tank_length;
  t.height = geometry.fill_height;
  // The fill's porosity: the layers' mean if they have their own, weighted equally (equal thickness).
  double porosity = t.target_porosity;
  if (!t.layer_porosities.empty())
    {
      porosity = 0.0;
      for (const double n : t.layer_porosities)
        porosity += n / static_cast<double>(t.layer_porosities.size());
    }
  t.density = solid_density_for_unit_weight(unit_weight, porosity, t.gravity);
  t.wall_contact = t.particle_contact;
  t.wall_contact.friction_angle_deg = geometry.wall_friction_deg;
  t.wall_contact.shear_strength = 0.0;
  t.wall_contact.tensile_strength = 0.0;
  t.wall_contact.bond_new_contacts = false;

  SheetLaying laying;
  const double tolerance = 1e-6 * thinnest_layer(t); // validate() found the boundaries
  const auto boundary = [&](double level) {
    if (const std::optional<std::size_t> below = layers_below_level(t, level, tolerance))
      return *below;
    if (t.layer_tops.empty()) // the nearest boundary, as before varied layers (validate() refuses it)
      return static_cast<std::size_t>(std::lround(level / (t.height / static_cast<double>(t.n_layers))));
    throw std::invalid_argument("pull-out tank: no layer boundary at the sheet's level " + std::to_string(level) +
                                " m ('Filling/number of layers')");
  };
  laying.layers_below = boundary(geometry.sheet_level());
  const PullOutGeometry g = geometry;
  const SheetParameters sheet_parameters = sheet;
  const double segment = max_segment_length;
  const bool wrap = g.anchorage == Anchorage::wrap_around;
  // A wrap-around is laid as in the laboratory, in two stages (tank_filling.h): the lower part on
  // its lift with the return standing up from its end, held, through the lifts placed next; once
  // the fill reaches the upper part's level (a layer boundary, validate()), the upper part is
  // folded over that lift, levelled as the one under the lower part.
  const double upper_level = g.sheet_level() + g.return_height; // nominal
  if (wrap)
    laying.second_part_layers_below = boundary(upper_level);
  laying.slot_height = 0.0; // automatic: the sheet's thickness plus half the smallest grain
  laying.lay = [g, sheet_parameters, segment, wrap, upper_level](const DemSystem &settled) {
    // The sheet rests on the highest grain under its lower part (it is laid on the lift).
    const ParticleSet &p = settled.particles();
    const double x_end = g.tank_length - g.anchorage_length;
    double surface = 0.0;
    for (std::size_t d = 0; d < p.n_discs_total(); ++d)
      if (p.disc_x[d] + p.disc_radius[d] >= x_end)
        surface = std::max(surface, p.disc_y[d] + p.disc_radius[d]);
    const double t = sheet_parameters.thickness;
    const double level = surface + 0.6 * t;
    std::vector<Vec2> corners = g.sheet_corners(level);
    if (wrap)
      {
        // The return ends 0.6 t below the level of the lift its upper part will be laid on, where
        // that lift's lid will be: clear of the lid (a node touches a wall within t / 2), so that
        // the held end does not load the lid the lift's growth reads its jamming from. A disc of
        // radius above 0.6 t under the lid cannot reach over the return's end, so the return can
        // later be lengthened up to the upper part without cutting into it.
        corners.pop_back();
        corners.back().y() = upper_level - 0.6 * t;
        if (!(corners.back().y() - level > t))
          throw std::invalid_argument("pull-out tank: the return ('Anchorage/D1' = " + std::to_string(g.return_height) +
                                      " m) is too short for the sheet laid at " + std::to_string(level) +
                                      " m: its end would be " + std::to_string(corners.back().y() - level) +
                                      " m above the lower part");
      }
    SparSheet chain("geosynthetic", subdivide_polyline(corners, segment), sheet_parameters);
    chain.set_mass_scaling(settled.required_sheet_mass_scaling(chain));
    chain.prescribe_velocity(0, Vec2::Zero()); // the clamp holds the sheet
    // The return of a wrap-around stands in the layers still to come: it is held in place until
    // the tank is full, as the sheet is held up while the lifts are placed round it.
    for (std::size_t k = 1; k < chain.n_nodes(); ++k)
      if (chain.y[k] > level + 0.5 * t)
        chain.prescribe_velocity(k, Vec2::Zero());
    return chain;
  };
  if (wrap)
    laying.lay_second_part = [g, segment](const DemSystem &settled, const SparSheet &laid) {
      // The upper part rests on the highest grain under it, the lift being levelled as the
      // lower part's; the return's end (held) is moved up to it along the return, and that
      // segment is re-laid at its new length (the others keep theirs).
      const ParticleSet &p = settled.particles();
      const std::size_t end = laid.n_nodes() - 1;
      const double x_end = laid.x[end], x_far = x_end + g.upper_length;
      double surface = 0.0;
      for (std::size_t d = 0; d < p.n_discs_total(); ++d)
        if (p.disc_x[d] + p.disc_radius[d] >= x_end && p.disc_x[d] - p.disc_radius[d] <= x_far)
          surface = std::max(surface, p.disc_y[d] + p.disc_radius[d]);
      const double level = std::max(surface + 0.6 * laid.thickness(), laid.y[end]);
      std::vector<Vec2> nodes;
      for (std::size_t k = 0; k <= end; ++k)
        nodes.push_back(laid.node(k));
      nodes.back().y() = level;
      const std::vector<Vec2> upper = subdivide_polyline({Vec2(x_end, level), Vec2(x_far, level)}, segment);
      nodes.insert(nodes.end(), upper.begin() + 1, upper.end());
      SparSheet chain(laid.name(), nodes, laid.parameters());
      for (std::size_t k = 0; k + 1 < end; ++k)
        chain.rest_length[k] = laid.rest_length[k];
      chain.set_mass_scaling(settled.required_sheet_mass_scaling(chain));
      // The laid nodes keep their motion and their holds (the clamp, the return). The upper part
      // is held where it lies until the tank is full, as the return: free, its free end was
      // pushed back along the lift by the grains of the next one growing round it, and the
      // part crumpled (measured on the tank of tests/test_dem_wraparound_fill.cc: its last
      // segment 3.4 mm long instead of 10 mm, the end 14 mm short of where it was laid). The
      // lower part needs no hold: the clamp and the return keep it taut.
      for (std::size_t k = 0; k <= end; ++k)
        {
          chain.vx[k] = laid.vx[k];
          chain.vy[k] = laid.vy[k];
          if (laid.is_kinematic(k))
            chain.prescribe_velocity(k, Vec2(laid.vx[k], laid.vy[k]));
        }
      for (std::size_t k = end + 1; k < chain.n_nodes(); ++k)
        chain.prescribe_velocity(k, Vec2::Zero());
      return chain;
    };
  t.sheet = laying;
  return t;
}

std::uint64_t fill_steps(const PullOutTank &tank)
{
  std::uint64_t steps = tank.n_final_settling_steps;
  for (const TankLayer &layer : tank.tank.layers)
    steps += layer.n_growth_steps + layer.n_settling_steps;
  return steps;
}

std::uint64_t fill_steps_of_kept_lifts(const PullOutTank &tank)
{
  std::uint64_t steps = 0;
  for (const TankLayer &layer : tank.tank.layers)
    if (layer.from_cache)
      steps += layer.n_growth_steps + layer.n_settling_steps;
  return steps;
}

PullOutTank fill_pull_out_tank(const PullOutTankSpec &spec, const std::function<void(double)> &progress)
{
  spec.validate("pull-out tank");
  const TankFillingSpec filling = spec.resolved_filling();
  const PullOutGeometry &g = spec.geometry;
  PullOutTank out{fill_tank_in_layers(filling, progress ? std::function<void(double)>([&](double f) { progress(0.95 * f); })
                                                        : std::function<void(double)>()),
                  0.0, 0, 0, {}, {}};
  DemSystem &system = out.tank.system;
  SparSheet &sheet = system.sheets().at(0);
  // The tank is full: the sheet is free but for its clamp, and everything settles again.
  for (std::size_t k = 1; k < sheet.n_nodes(); ++k)
    if (sheet.is_kinematic(k))
      sheet.release(k);
  const std::uint64_t check_every = 200;
  for (std::uint64_t n = 1;; ++n)
    {
      system.step();
      out.n_final_settling_steps = n;
      if (n % check_every != 0)
        continue;
      const double unbalanced = unbalanced_force_ratio(system);
      if (unbalanced < filling.equilibrium_unbalanced_ratio)
        break;
      if (n > filling.max_steps_per_layer)
        {
          std::ostringstream message;
          message << "pull-out tank: the fill with its sheet has not settled after " << filling.max_steps_per_layer
                  << " steps (unbalanced-force ratio " << unbalanced << ", asked below "
                  << filling.equilibrium_unbalanced_ratio << ")";
          throw std::runtime_error(message.str());
        }
      if (progress)
        progress(0.95 + 0.05 * std::min(1.0, static_cast<double>(n) / 50000.0));
    }
  out.sheet_level = sheet.y[0];
  out.first_node_inside = sheet.n_nodes();
  out.lower_part_end = sheet.n_nodes() - 1;
  out.arc_length.assign(sheet.n_nodes(), 0.0);
  double arc = 0.0;
  bool end_found = false;
  for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
    {
      if (k > 0)
        arc += sheet.rest_length[k - 1];
      out.arc_length[k] = arc;
      out.initial_nodes.push_back(sheet.node(k));
      if (out.first_node_inside == sheet.n_nodes() && sheet.x[k] < g.tank_length)
        out.first_node_inside = k;
      // The lower part ends at the corner laid at x_end (subdivide_polyline keeps corners), found
      // by its rest length along the chain: arc L + clamp offset.
      if (!end_found && arc >= g.anchorage_length + g.clamp_offset - 1e-9)
        {
          out.lower_part_end = k;
          end_found = true;
        }
    }
  if (progress)
    progress(1.0);
  return out;
}
} // namespace geohybrid::dem
