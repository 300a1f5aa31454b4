#include "pullout_tank.h"

#include "dem/measurements.h"

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
      // The upper part is laid on the lift whose top is at its level (resolved_filling).
      const double top = (geometry.sheet_level() + geometry.return_height) / thickness;
      require(std::abs(top - std::round(top)) < 1e-6 && std::round(top) < n, where, "Filling/number of layers", n,
              "must put a layer boundary at the level of the sheet's upper part (fill height - H + D1 = " +
                std::to_string(geometry.sheet_level() + geometry.return_height) + " m with layers " +
                std::to_string(thickness) + " m thick) and leave at least one layer above it");
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
  const double thickness = t.height / static_cast<double>(t.n_layers);
  laying.layers_below = static_cast<std::size_t>(std::lround(geometry.sheet_level() / thickness));
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
    laying.second_part_layers_below = static_cast<std::size_t>(std::lround(upper_level / thickness));
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
  // bottom one (dem/measurements.h). sheet_face_stresses divides by the segments' whole length.
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
        // fx is the resultant without local damping (dem/spar_sheet.h): m a = fx + damping_fx.
        parts.inertia += sheet.fx[k] + sheet.damping_fx[k];
        parts.damping -= sheet.damping_fx[k];
      }
  return parts;
}

// Field by field: add() runs at every step of a pull.
void HeadTensionParts::add(const HeadTensionParts &o)
{
  reaction += o.reaction;
  interface_friction += o.interface_friction;
  interface_normal += o.interface_normal;
  node_wall += o.node_wall;
  inertia += o.inertia;
  damping += o.damping;
  normal_force += o.normal_force;
  elastic_normal_force += o.elastic_normal_force;
  tangential_force += o.tangential_force;
}

void HeadTensionParts::scale(double factor)
{
  auto a = as_array();
  for (double &v : a)
    v *= factor;
  *this = from_array(a);
}

std::array<double, HeadTensionParts::n_terms> HeadTensionParts::as_array() const
{
  return {reaction, interface_friction, interface_normal, node_wall, inertia, damping, normal_force,
          elastic_normal_force, tangential_force};
}

HeadTensionParts HeadTensionParts::from_array(const std::array<double, n_terms> &v)
{
  HeadTensionParts p;
  p.reaction = v[0];
  p.interface_friction = v[1];
  p.interface_normal = v[2];
  p.node_wall = v[3];
  p.inertia = v[4];
  p.damping = v[5];
  p.normal_force = v[6];
  p.elastic_normal_force = v[7];
  p.tangential_force = v[8];
  return p;
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

namespace
{
void check_pull_spec(const PullSpec &spec)
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
}
} // namespace

PullOut::PullOut(DemSystem &system, const PullSpec &spec, std::function<void()> advance)
  : system_(system), spec_(spec), advance_(std::move(advance))
{
  if (!advance_)
    throw std::invalid_argument("pull-out: the function that advances the system is empty");
  start();
}

PullOut::PullOut(DemSystem &system, const PullSpec &spec) : system_(system), spec_(spec)
{
  start();
}

void PullOut::start()
{
  check_pull_spec(spec_);
  // Constant acceleration over the ramp: it covers ramp_displacement in 2 ramp_displacement / rate.
  ramp_time_ = 2.0 * spec_.ramp_displacement / spec_.rate;
  SparSheet &sheet = system_.sheets().at(0);
  progress_.clamp_x0 = sheet.x[0];
  progress_.time0 = system_.time();
  progress_.next_record = spec_.record_interval;
  sheet.prescribe_velocity(0, Vec2(clamp_speed(), 0.0));
  system_.set_sheet_local_damping(spec_.sheet_local_damping);
  if (spec_.grain_local_damping)
    system_.set_local_damping(*spec_.grain_local_damping);
  // A system stepped by someone else keeps its forces current (a coupled stepper's include the
  // coupling's, which a new evaluation would apply twice).
  if (!advance_)
    system_.initialise_forces();
  last_point_.head_tension = head_tension(system_);
  last_point_.parts = head_tension_parts(system_);
}

PullOut::PullOut(DemSystem &system, const PullSpec &spec, const PullProgress &progress, std::function<void()> advance)
  : PullOut(system, spec, progress)
{
  if (!advance)
    throw std::invalid_argument("pull-out: the function that advances the system is empty");
  advance_ = std::move(advance);
}

PullOut::PullOut(DemSystem &system, const PullSpec &spec, const PullProgress &progress)
  : system_(system), spec_(spec), progress_(progress)
{
  check_pull_spec(spec);
  ramp_time_ = 2.0 * spec.ramp_displacement / spec.rate;
  // The sheet's damping is a setting of the system, not of its state. The clamp's velocity is
  // in the state, and is what clamp_speed() gives for the same spec (each step prescribes it
  // for the next): prescribed again, it changes nothing when resuming the same pull, and it
  // makes a pull of the same filled tank at another rate start at its own speed.
  system.set_sheet_local_damping(spec.sheet_local_damping);
  if (spec.grain_local_damping)
    system.set_local_damping(*spec.grain_local_damping);
  if (!progress.finished)
    system.sheets().at(0).prescribe_velocity(0, Vec2(clamp_speed(), 0.0));
  last_point_.head_displacement = head_displacement();
  last_point_.head_tension = head_tension(system);
  last_point_.parts = head_tension_parts(system);
}

void PullOut::stop_clamp() { system_.sheets()[0].prescribe_velocity(0, Vec2::Zero()); }

PullPoint PullOut::start_point() const
{
  PullPoint p;
  p.head_tension = head_tension(system_);
  p.parts = head_tension_parts(system_);
  return p;
}

double PullOut::clamp_speed() const
{
  const double t = system_.time() - progress_.time0 + 0.5 * system_.time_step(); // at the middle of the next step
  return ramp_time_ > 0.0 && t < ramp_time_ ? spec_.rate * t / ramp_time_ : spec_.rate;
}

double PullOut::head_displacement() const { return system_.sheets()[0].x[0] - progress_.clamp_x0; }

std::uint64_t PullOut::expected_steps() const
{
  const double distance = spec_.final_displacement + spec_.ramp_displacement; // the ramp takes twice its length in time
  return static_cast<std::uint64_t>(std::ceil(distance / spec_.rate / system_.time_step()));
}

bool PullOut::step()
{
  if (progress_.finished)
    return false;
  if (advance_)
    advance_();
  else
    system_.step();
  SparSheet &sheet = system_.sheets()[0];
  sheet.prescribe_velocity(0, Vec2(clamp_speed(), 0.0));
  progress_.tension_sum += head_tension(system_);
  progress_.parts_sum.add(head_tension_parts(system_));
  ++progress_.n_summed;
  ++progress_.n_steps;
  const double u = sheet.x[0] - progress_.clamp_x0, end = spec_.final_displacement;
  if (!(u >= progress_.next_record - 1e-12 * end || u >= end - 1e-12 * end))
    return false;
  last_point_.head_displacement = u;
  last_point_.head_tension = progress_.tension_sum / static_cast<double>(progress_.n_summed);
  last_point_.parts = progress_.parts_sum;
  last_point_.parts.scale(1.0 / static_cast<double>(progress_.n_summed));
  progress_.parts_sum = HeadTensionParts();
  progress_.tension_sum = 0.0;
  progress_.n_summed = 0;
  progress_.next_record += spec_.record_interval;
  progress_.finished = u >= end - 1e-12 * end;
  return true;
}

namespace
{
constexpr const char *command_name = "pullout";
constexpr std::size_t layer_fields = 10;

void check_command(const CommandState &c)
{
  if (c.name != command_name)
    throw std::runtime_error("the checkpoint is not a pull-out's (" +
                             (c.name.empty() ? std::string("no command state") : "written by '" + c.name + "'") + ")");
}
} // namespace

void store_pullout_tank(const PullOutTank &tank, CommandState &c)
{
  c.name = command_name;
  const FilledTank &f = tank.tank;
  c.counts["tank_walls"] = {f.walls.base, f.walls.right, f.walls.lid, f.walls.left, f.walls.right_upper};
  c.reals["slot"] = {f.slot_bottom, f.slot_top};
  std::vector<double> layers;
  for (const TankLayer &l : f.layers)
    layers.insert(layers.end(), {l.bottom, l.top, static_cast<double>(l.first_body), static_cast<double>(l.n_bodies),
                                 l.target_porosity, l.porosity_grown, l.porosity, l.growth_friction_deg,
                                 static_cast<double>(l.n_growth_steps), static_cast<double>(l.n_settling_steps)});
  c.reals["layers"] = layers;
  std::vector<std::uint64_t> kept;
  for (const TankLayer &l : f.layers)
    kept.push_back(l.from_cache ? 1 : 0);
  c.counts["layers_kept"] = kept; // absent from checkpoints written before the lift cache
  c.reals["sheet_level"] = {tank.sheet_level};
  c.counts["sheet_nodes"] = {tank.lower_part_end, tank.first_node_inside};
  c.counts["final_settling_steps"] = {tank.n_final_settling_steps};
  c.reals["arc_length"] = tank.arc_length;
  std::vector<double> nodes;
  for (const Vec2 &v : tank.initial_nodes)
    nodes.insert(nodes.end(), {v.x(), v.y()});
  c.reals["initial_nodes"] = nodes;
}

PullOutTank restore_pullout_tank(DemSystemState state, const DemSettings &settings, const CommandState &c)
{
  check_command(c);
  DemSystem system(state.particles, LinearContactLaw(state.particle_contact), settings);
  for (const Wall &wall : state.walls)
    system.add_wall(wall); // replaced by the saved walls: restore_state needs as many
  system.restore_state(std::move(state));
  const std::vector<std::uint64_t> &w = c.count("tank_walls", 5);
  const std::vector<double> &slot = c.real("slot", 2);
  TankWalls walls{w[0], w[1], w[2], w[3], w[4]};
  std::vector<TankLayer> layers;
  const std::vector<double> &l = c.real("layers");
  if (l.size() % layer_fields != 0)
    throw std::runtime_error("checkpoint of 'pullout': array 'layers' is not a whole number of layers");
  for (std::size_t k = 0; k < l.size(); k += layer_fields)
    {
      TankLayer layer;
      layer.bottom = l[k];
      layer.top = l[k + 1];
      layer.first_body = static_cast<std::size_t>(l[k + 2]);
      layer.n_bodies = static_cast<std::size_t>(l[k + 3]);
      layer.target_porosity = l[k + 4];
      layer.porosity_grown = l[k + 5];
      layer.porosity = l[k + 6];
      layer.growth_friction_deg = l[k + 7];
      layer.n_growth_steps = static_cast<std::uint64_t>(l[k + 8]);
      layer.n_settling_steps = static_cast<std::uint64_t>(l[k + 9]);
      layers.push_back(layer);
    }
  if (c.counts.count("layers_kept"))
    {
      const std::vector<std::uint64_t> &kept = c.count("layers_kept", layers.size());
      for (std::size_t k = 0; k < layers.size(); ++k)
        layers[k].from_cache = kept[k] != 0;
    }
  const std::size_t n_nodes = system.sheets().empty() ? 0 : system.sheets()[0].n_nodes();
  if (n_nodes == 0)
    throw std::runtime_error("checkpoint of 'pullout': the saved system has no sheet");
  PullOutTank tank{FilledTank{std::move(system), walls, std::move(layers), slot[0], slot[1]}, c.real("sheet_level", 1)[0],
                   0, 0, c.real("arc_length", n_nodes), {}};
  const std::vector<std::uint64_t> &nodes = c.count("sheet_nodes", 2);
  tank.lower_part_end = nodes[0];
  tank.first_node_inside = nodes[1];
  tank.n_final_settling_steps = c.count("final_settling_steps", 1)[0];
  const std::vector<double> &initial = c.real("initial_nodes", 2 * n_nodes);
  for (std::size_t k = 0; k < n_nodes; ++k)
    tank.initial_nodes.emplace_back(initial[2 * k], initial[2 * k + 1]);
  if (tank.lower_part_end >= n_nodes || tank.first_node_inside >= n_nodes)
    throw std::runtime_error("checkpoint of 'pullout': sheet node indices out of range");
  return tank;
}

void store_pull_progress(const PullProgress &p, CommandState &c)
{
  c.reals["pull"] = {p.clamp_x0, p.time0, p.tension_sum, p.next_record};
  c.counts["pull"] = {p.n_summed, p.n_steps, p.finished ? 1u : 0u};
  const auto parts = p.parts_sum.as_array();
  c.reals["pull_parts_sum"] = std::vector<double>(parts.begin(), parts.end());
}

std::optional<PullProgress> restore_pull_progress(const CommandState &c)
{
  check_command(c);
  if (c.reals.count("pull") == 0)
    return std::nullopt;
  const std::vector<double> &r = c.real("pull", 4);
  const std::vector<std::uint64_t> &n = c.count("pull", 3);
  PullProgress p;
  p.clamp_x0 = r[0];
  p.time0 = r[1];
  p.tension_sum = r[2];
  p.next_record = r[3];
  p.n_summed = n[0];
  p.n_steps = n[1];
  p.finished = n[2] != 0;
  // Checkpoints written before the decomposition was recorded have no sums: the interval under
  // way then starts its decomposition from where the run resumes (the curve is unaffected).
  if (c.reals.count("pull_parts_sum") != 0)
    {
      const std::vector<double> &s = c.real("pull_parts_sum", HeadTensionParts::n_terms);
      std::array<double, HeadTensionParts::n_terms> a;
      std::copy(s.begin(), s.end(), a.begin());
      p.parts_sum = HeadTensionParts::from_array(a);
    }
  return p;
}

void store_sheet_level_stress(const SheetLevelStress &s, CommandState &c)
{
  c.reals["sheet_level_stress"] = {s.top_face, s.bottom_face, s.normal_force_both_faces, s.love_weber_above,
                                   s.lower_part_length};
}

SheetLevelStress restore_sheet_level_stress(const CommandState &c)
{
  check_command(c);
  const std::vector<double> &r = c.real("sheet_level_stress", 5);
  return SheetLevelStress{r[0], r[1], r[2], r[3], r[4]};
}

std::vector<PullPoint> pull_out(DemSystem &system, const PullSpec &spec,
                                const std::function<void(const PullPoint &, const DemSystem &)> &record,
                                const std::function<void()> &advance)
{
  PullOut pull = advance ? PullOut(system, spec, advance) : PullOut(system, spec);
  std::vector<PullPoint> points{pull.start_point()};
  if (record)
    record(points.back(), system);
  while (!pull.finished())
    if (pull.step())
      {
        points.push_back(pull.last_point());
        if (record)
          record(points.back(), system);
      }
  pull.stop_clamp();
  return points;
}
} // namespace geohybrid::dem
