#include "pullout_tank.h"

#include "measurements.h"

#include <algorithm>
#include <cmath>
#include <limits>
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
  const double n = static_cast<double>(filling.n_layers);
  const double thickness = geometry.fill_height / n;
  const double below = geometry.sheet_level() / thickness;
  require(filling.n_layers >= 2 && std::abs(below - std::round(below)) < 1e-6 && std::round(below) >= 1.0, where,
          "Filling/number of layers", n,
          "must put a layer boundary at the sheet level (fill height - H = " + std::to_string(geometry.sheet_level()) +
            " m with layers " + std::to_string(thickness) + " m thick)");
  if (geometry.anchorage == Anchorage::wrap_around)
    {
      const double top = (geometry.sheet_level() + geometry.return_height) / thickness;
      require(std::ceil(top - 1e-6) < n, where, "Filling/number of layers", n,
              "must leave at least one layer above the upper part of the sheet");
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
  laying.layers_below = static_cast<std::size_t>(std::lround(geometry.sheet_level() / (t.height / t.n_layers)));
  const PullOutGeometry g = geometry;
  const SheetParameters sheet_parameters = sheet;
  const double segment = max_segment_length;
  laying.slot_height = 0.0; // automatic: between the sheet's thickness and the smallest grain
  laying.lay = [g, sheet_parameters, segment](const DemSystem &settled) {
    // The sheet rests on the highest grain under its lower part (it is laid on the lift).
    const ParticleSet &p = settled.particles();
    const double x_end = g.tank_length - g.anchorage_length;
    double surface = 0.0;
    for (std::size_t d = 0; d < p.n_discs_total(); ++d)
      if (p.disc_x[d] + p.disc_radius[d] >= x_end)
        surface = std::max(surface, p.disc_y[d] + p.disc_radius[d]);
    const double t = sheet_parameters.thickness;
    const double level = surface + 0.6 * t;
    SparSheet chain("geosynthetic", subdivide_polyline(g.sheet_corners(level), segment), sheet_parameters);
    chain.set_mass_scaling(settled.required_sheet_mass_scaling(chain));
    chain.prescribe_velocity(0, Vec2::Zero()); // the clamp holds the sheet
    // The return and the upper part of a wrap-around stand in the layers still to come: they
    // are held in place until the tank is full, as the sheet is held while the lifts are placed.
    for (std::size_t k = 1; k < chain.n_nodes(); ++k)
      if (chain.y[k] > level + 0.5 * t)
        chain.prescribe_velocity(k, Vec2::Zero());
    return chain;
  };
  t.sheet = laying;
  return t;
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

SheetLevelStress measure_sheet_level_stress(const DemSystem &system, const PullOutTank &tank,
                                            const PullOutGeometry &geometry, double band)
{
  SheetLevelStress s;
  const SparSheet &sheet = system.sheets().at(0);
  // The segments of the lower part inside the tank now: from the one through the slot (the
  // lower part runs along -x from the clamp) to its end; their length inside the front wall.
  std::size_t first = 0;
  while (first < tank.lower_part_end && std::min(sheet.x[first], sheet.x[first + 1]) >= geometry.tank_length)
    ++first;
  double full_length = 0.0;
  for (std::size_t k = first; k < tank.lower_part_end; ++k)
    {
      const double length = sheet.segment_length(k);
      const double x_in = std::min(sheet.x[k], sheet.x[k + 1]), x_out = std::max(sheet.x[k], sheet.x[k + 1]);
      const double inside = x_out > geometry.tank_length ? (geometry.tank_length - x_in) / (x_out - x_in) : 1.0;
      full_length += length;
      s.lower_part_length += inside * length;
    }
  if (!(s.lower_part_length > 0.0))
    return s;
  // The lower part runs along -x from the clamp: perp(u) points down, so its "left" face is the
  // bottom one (measurements.h). sheet_face_stresses divides by the segments' whole length.
  const SheetFaceStresses faces = sheet_face_stresses(system, 0, first, tank.lower_part_end);
  const double to_inside = full_length / s.lower_part_length;
  s.top_face = faces.normal_right * to_inside;
  s.bottom_face = faces.normal_left * to_inside;
  s.normal_force_both_faces = (faces.normal_left + faces.normal_right) * full_length;
  const Region above{geometry.tank_length - geometry.anchorage_length, tank.sheet_level, geometry.tank_length,
                     tank.sheet_level + band};
  s.love_weber_above = -love_weber_stress(system, above)[1];
  return s;
}

double head_tension(const DemSystem &system) { return system.sheets().at(0).reaction(0).x(); }

HeadTensionParts head_tension_parts(const DemSystem &system)
{
  const SparSheet &sheet = system.sheets().at(0);
  const SheetContacts &c = system.sheet_contacts().at(0);
  const ParticleSet &p = system.particles();
  HeadTensionParts parts;
  parts.reaction = head_tension(system);
  for (std::size_t q = 0; q < c.size(); ++q)
    {
      if (c.force_x[q] == 0.0 && c.force_y[q] == 0.0)
        continue;
      const Vec2 centre(p.disc_x[c.disc[q]], p.disc_y[c.disc[q]]);
      const Vec2 to_sheet = point_on_segment(sheet, c.segment[q], c.position[q]) - centre;
      const double distance = to_sheet.norm();
      const Vec2 on_sheet(-c.force_x[q], -c.force_y[q]);
      // The normal force pushes the sheet away from the disc, along to_sheet.
      const Vec2 n = distance > 0.0 ? Vec2(to_sheet / distance) : Vec2(on_sheet.normalized());
      const double normal = on_sheet.dot(n);
      const Vec2 tangential = on_sheet - normal * n;
      parts.interface_normal -= normal * n.x();
      parts.interface_friction -= tangential.x();
      parts.normal_force += normal;
      parts.elastic_normal_force += c.elastic_normal_force[q];
      parts.tangential_force += tangential.norm();
    }
  for (const SheetWallContacts &w : c.walls)
    for (std::size_t q = 0; q < w.size(); ++q)
      parts.node_wall -= w.force_x[q];
  for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
    if (!sheet.is_kinematic(k))
      {
        // fx is the resultant without local damping (spar_sheet.h): m a = fx + damping_fx.
        parts.inertia += sheet.fx[k] + sheet.damping_fx[k];
        parts.damping -= sheet.damping_fx[k];
      }
  return parts;
}

DemSystem with_threads(const DemSystem &system, int n_threads)
{
  DemSystemState state = system.export_state();
  DemSettings settings = system.settings();
  settings.n_threads = n_threads;
  DemSystem copy(state.particles, system.particle_law(), settings);
  for (const Wall &wall : system.walls())
    copy.add_wall(wall);
  copy.set_sheet_local_damping(system.sheet_local_damping() >= 0.0 ? system.sheet_local_damping()
                                                                   : settings.local_damping);
  copy.restore_state(std::move(state));
  return copy;
}

std::vector<PullPoint> pull_out(DemSystem &system, const PullSpec &spec,
                                const std::function<void(const PullPoint &, const DemSystem &)> &record)
{
  if (!positive(spec.rate))
    throw std::invalid_argument("pull-out: 'Pull/rate' = " + std::to_string(spec.rate) + " must be positive [m/s]");
  if (!positive(spec.final_displacement))
    throw std::invalid_argument("pull-out: 'Pull/final displacement' = " + std::to_string(spec.final_displacement) +
                                " must be positive [m]");
  if (!positive(spec.record_interval))
    throw std::invalid_argument("pull-out: 'Pull/record interval' = " + std::to_string(spec.record_interval) +
                                " must be positive [m]");
  if (!(spec.ramp_displacement >= 0.0 && spec.ramp_displacement < spec.final_displacement))
    throw std::invalid_argument("pull-out: 'Pull/ramp displacement' = " + std::to_string(spec.ramp_displacement) +
                                " must lie in [0, final displacement) [m]");
  SparSheet &sheet = system.sheets().at(0);
  const double x0 = sheet.x[0], t0 = system.time();
  // Constant acceleration over the ramp: it covers ramp_displacement in 2 ramp_displacement / rate.
  const double ramp_time = 2.0 * spec.ramp_displacement / spec.rate;
  const auto clamp_speed = [&] {
    const double t = system.time() - t0 + 0.5 * system.time_step(); // at the middle of the next step
    return ramp_time > 0.0 && t < ramp_time ? spec.rate * t / ramp_time : spec.rate;
  };
  sheet.prescribe_velocity(0, Vec2(clamp_speed(), 0.0));
  system.set_sheet_local_damping(spec.sheet_local_damping);
  std::vector<PullPoint> points;
  PullPoint start;
  system.initialise_forces();
  start.head_tension = head_tension(system);
  points.push_back(start);
  if (record)
    record(start, system);
  double sum = 0.0;
  std::uint64_t n_summed = 0;
  double next_record = spec.record_interval;
  const double end = spec.final_displacement;
  for (;;)
    {
      system.step();
      system.sheets()[0].prescribe_velocity(0, Vec2(clamp_speed(), 0.0));
      sum += head_tension(system);
      ++n_summed;
      const double u = system.sheets()[0].x[0] - x0;
      if (u >= next_record - 1e-12 * end || u >= end - 1e-12 * end)
        {
          PullPoint p;
          p.head_displacement = u;
          p.head_tension = sum / static_cast<double>(n_summed);
          points.push_back(p);
          if (record)
            record(p, system);
          sum = 0.0;
          n_summed = 0;
          next_record += spec.record_interval;
          if (u >= end - 1e-12 * end)
            break;
        }
    }
  system.sheets()[0].prescribe_velocity(0, Vec2::Zero());
  return points;
}
} // namespace geohybrid::dem
