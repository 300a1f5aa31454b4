#include "hybrid_pullout.h"

#include "coupling/hybrid_box_settling.h"
#include "coupling/hybrid_continuum.h"
#include "dem/measurements.h"
#include "fem/constitutive/parameter_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace geohybrid::coupling
{
void HybridRegionSpec::validate(const std::string &where) const
{
  fem::require_parameter(margin > 0.0 && std::isfinite(margin), where, "Hybrid/DEM region margin", margin, "must be positive [m]");
  fem::require_parameter(lift_thickness >= 0.0 && std::isfinite(lift_thickness), where, "Hybrid/lift thickness", lift_thickness,
          "must be zero (automatic) or positive [m]");
  fem::require_parameter(band_width >= 0.0 && std::isfinite(band_width), where, "Hybrid/band width", band_width,
          "must be zero (automatic) or positive [m]");
  fem::require_parameter(cell_size >= 0.0 && std::isfinite(cell_size), where, "Hybrid/cell size", cell_size,
          "must be zero (automatic) or positive [m]");
  fem::require_parameter(far_cell_size >= 0.0 && std::isfinite(far_cell_size), where, "Hybrid/far cell size", far_cell_size,
          "must be zero (automatic) or positive [m]");
  fem::require_parameter(dem_region_length >= 0.0 && std::isfinite(dem_region_length), where, "Hybrid/DEM region length",
                         dem_region_length, "must be zero (the whole sheet in the particles) or positive [m]");
  fem::require_parameter(driven_below_weight >= 0.0 && driven_below_weight < 1.0, where, "Hybrid/driven below weight",
          driven_below_weight, "must lie in [0, 1) [-]");
  if (const auto *penalty = std::get_if<PenaltyCoupling>(&method))
    penalty->validate(where, "Hybrid/penalty factor");
  if (continuum_step_ratio != 1 && !std::holds_alternative<LagrangeMultiplierCoupling>(method))
    throw std::invalid_argument(where + ": parameter 'Hybrid/continuum step ratio' = " +
                                std::to_string(continuum_step_ratio) + " needs 'Hybrid/coupling method' = " +
                                std::string(LagrangeMultiplierCoupling::name) + " (multi-rate stepping ties the band "
                                "by the multipliers); give 1 with " + std::string(name_of(method)));
  if (continuum_step_ratio != 1 && dem_region_length > 0.0)
    throw std::invalid_argument(where + ": parameter 'Hybrid/continuum step ratio' = " +
                                std::to_string(continuum_step_ratio) + " cannot be combined with 'Hybrid/DEM region "
                                "length' > 0 (the sheet crossing steps with both models together): give 1");
  if (!has_band(method) && dem_region_length > 0.0)
    throw std::invalid_argument(where + ": parameter 'Hybrid/coupling method' = " + std::string(name_of(method)) +
                                " cannot be combined with 'Hybrid/DEM region length' > 0 (the sheet crossing needs a "
                                "band): use " + std::string(LagrangeMultiplierCoupling::name) + " or " +
                                std::string(PenaltyCoupling::name) + ", or a DEM region length of 0");
}

void HybridPullOutSpec::validate(const std::string &where) const
{
  tank.validate(where);
  region.validate(where);
  fem::require_parameter(region.dem_region_length < tank.geometry.anchorage_length, where, "Hybrid/DEM region length",
                         region.dem_region_length,
                         "must be shorter than the lower part 'Anchorage/L' (the sheet then crosses into the "
                         "continuum), or 0 (the whole sheet in the particles) [m]");
  fem::require_parameter(continuum.k0 >= 0.0 && std::isfinite(continuum.k0), where, "Continuum/K0", continuum.k0,
          "must be zero (the soil's 1 - sin phi) or positive [-]");
  const double delta = continuum.sheet_interface.friction_angle_deg;
  fem::require_parameter(delta > 0.0 && delta < 90.0, where, "Hybrid/continuum interface friction angle", delta,
                         "must lie in [0, 90): 0 takes 'Sheet/Interface/friction angle' [deg]");
  fem::require_parameter(continuum.local_damping >= 0.0 && continuum.local_damping < 1.0, where, "Continuum/local damping",
          continuum.local_damping, "must lie in [0, 1) [-]");
}

HybridPullOut::HybridPullOut(const HybridPullOutSpec &spec, const std::string &where,
                             const std::function<void(double)> &progress)
  : box_(particle_box(spec, where))
{
  tank_ = std::make_unique<dem::PullOutTank>(dem::fill_pull_out_tank(box_.box_tank, progress));
  set_up_coupled_model(spec, where);
}

HybridPullOut::HybridPullOut(const HybridPullOutSpec &spec, const std::string &where, dem::PullOutTank filled_box)
  : box_(particle_box(spec, where))
{
  if (filled_box.tank.system.particles().n_bodies() == 0)
    throw std::invalid_argument(where + ": the filled particle box holds no particles");
  tank_ = std::make_unique<dem::PullOutTank>(std::move(filled_box));
  set_up_coupled_model(spec, where);
}

void HybridPullOut::set_up_coupled_model(const HybridPullOutSpec &spec, const std::string &where)
{
  dem::DemSystem &particles = tank_->tank.system;
  const dem::ParticleSet &p = particles.particles();
  set_up_.n_particles = p.n_bodies();
  set_up_.particle_time_step = particles.time_step();
  set_up_.fill_steps = dem::fill_steps(*tank_); // every lift's, not the last system's count
  const dem::PullOutGeometry &g = spec.tank.geometry;

  // The band and the pad from the grains as filled: w four mean disc diameters unless given, the
  // pad one branch (twice the largest reach of a body's discs from its centre).
  double reach = 0.0, diameters = 0.0;
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    {
      reach = std::max(reach, std::hypot(p.disc_offset_x[d], p.disc_offset_y[d]) + p.disc_radius[d]);
      diameters += 2.0 * p.disc_radius[d];
    }
  const double w = spec.region.band_width > 0.0 ? spec.region.band_width
                                                 : 4.0 * diameters / static_cast<double>(p.n_discs_total());
  const double cell = spec.region.cell_size > 0.0 ? spec.region.cell_size : 0.5 * w;
  const double pad = 2.0 * reach;
  set_up_.band_width = w;
  set_up_.cell_size = cell;
  set_up_.pad = pad;

  // The DEM core, in the box's frame: the box less pad and band on its shared sides; the other
  // sides lie past the tank's walls (they idle).
  const double width = box_.x1 - box_.x0, height = box_.y1 - box_.y0;
  const double beyond = 1.0 + g.tank_length + g.fill_height;
  // Method 3 (the non-overlapping interface) has neither band nor pad: the core is the box, whose
  // shared sides become the continuum's boundary edges that the grains touch.
  const bool interface = !has_band(spec.region.method);
  const double inset = interface ? 0.0 : pad + w;
  const double cx0 = box_.left_shared ? inset : -beyond, cx1 = width + beyond;
  const double cy0 = box_.bottom_shared ? inset : -beyond;
  double cy1 = box_.top_shared ? height - inset : height + beyond;
  if (!(cx1 > cx0 && cy1 > cy0))
    throw std::invalid_argument(where + ": parameter 'Hybrid/DEM region margin' = " + std::to_string(spec.region.margin) +
                                " m leaves no DEM core inside the pad and the band");
  band_ = std::make_unique<OverlapBand>(
    OverlapBand::around_convex_region({Vec2(cx0, cy0), Vec2(cx1, cy0), Vec2(cx1, cy1), Vec2(cx0, cy1)}, w));
  // Without a DEM region length the sheet stays in the core, one branch clear of the band (its
  // contacts are not weighted and the tied particles' ties must not touch it). With one, it is
  // cut at the core's edge and its rest goes to the continuum (below).
  const dem::SparSheet &sheet = particles.sheets().at(0);
  const bool crossing = spec.region.dem_region_length > 0.0;
  std::vector<dealii::Point<fem::dim>> continuum_sheet_nodes;
  std::size_t n_kept = sheet.n_nodes();
  double crossing_rest_length = 0.0;
  if (crossing)
    {
      n_kept = 0;
      while (n_kept < sheet.n_nodes() && band_->coordinate(sheet.node(n_kept)) <= 0.0)
        ++n_kept;
      if (n_kept < 2 || n_kept == sheet.n_nodes())
        {
          std::ostringstream message;
          message << where << ": parameter 'Hybrid/DEM region length' = " << spec.region.dem_region_length
                  << " m leaves " << n_kept << " of the sheet's " << sheet.n_nodes()
                  << " nodes in the particles' core (its edge " << pad + w << " m from the box's back; the sheet "
                  << "ends " << sheet.x[sheet.n_nodes() - 1] << " m from it): it must leave at least 2 in and 1 out";
          throw std::invalid_argument(message.str());
        }
      // The particles' part is cut now, before the box settles under its overburden (below), so
      // that the grains close the gap the cut-off nodes leave in the pad and the band while the
      // box's walls still hold them: tied to the continuum, the band's grains falling into it
      // strained the band's cells (measured: sigma_nn 18.6 kPa at the continuum sheet's first node
      // against gamma H = 2.3 kPa).
      crossing_rest_length = sheet.rest_length[n_kept - 1];
      particles.cut_sheet(0, n_kept);
      // The tank's description follows the cut: the particles' part ends at its last node (the
      // curve's "end of the lower part" displacement is then that node's; it read past the cut
      // sheet's arrays before).
      tank_->lower_part_end = std::min(tank_->lower_part_end, n_kept - 1);
      tank_->first_node_inside = std::min(tank_->first_node_inside, n_kept - 1);
      tank_->arc_length.resize(n_kept);
      tank_->initial_nodes.resize(n_kept);
    }
  const double fill_ratio = spec.tank.filling.equilibrium_unbalanced_ratio;
  // The box's top surface (box frame): where the lid settled under the overburden, else the
  // highest grain's top. Method 3's continuum starts there, on the grains, not at the lift's top
  // above them (a gap the continuum would fall through: 1.8 mm measured on the test tank).
  double top_surface = highest_grain_top(p);
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const Clock::time_point box_settling_start = Clock::now();
  // A box cut out of a filled tank already stands under the whole overburden, as the tank's soil.
  if (spec.region.fill_under_overburden && box_.top_shared && !spec.region.box_cut_from_a_filled_tank)
    {
      set_up_.overburden = spec.tank.unit_weight * (g.fill_height - box_.y1);
      const OverburdenSettling settled = settle_under_overburden(
        particles, tank_->tank.walls.lid, set_up_.overburden, fill_ratio, spec.max_settling_steps, where);
      set_up_.box_settling_steps = settled.steps;
      set_up_.overburden_reached = settled.stress_reached;
      top_surface = settled.top_surface;
    }
  else if (crossing)
    set_up_.box_settling_steps = step_particles_until(
      particles, [&] { return dem::unbalanced_force_ratio(particles) < fill_ratio; }, spec.max_settling_steps,
      [&] { return where + ": the particle box did not settle after its sheet was cut"; });
  set_up_.box_settling_wall_time = seconds_since(box_settling_start);
  if (interface && box_.top_shared)
    {
      cy1 = top_surface;
      band_ = std::make_unique<OverlapBand>(
        OverlapBand::around_convex_region({Vec2(cx0, cy0), Vec2(cx1, cy0), Vec2(cx1, cy1), Vec2(cx0, cy1)}, w));
    }
  if (crossing)
    {
      // The continuum's part starts one segment (the DEM sheet's) past the last node in the core,
      // straight towards the sheet's end as drawn, and follows the drawing from there (a wrap-
      // around's return and upper part), at the level the sheet was laid at (the clamp's, which
      // has not moved), in the box's frame. The laid nodes past the core are not used: the fill
      // may have crumpled the end of the box's sheet against the box's back (tension-only spars).
      const Vec2 last_in_core = sheet.node(n_kept - 1);
      std::vector<Vec2> drawn;
      for (const Vec2 &corner : g.sheet_corners(sheet.y[0] + box_.y0))
        drawn.push_back(corner - Vec2(box_.x0, box_.y0));
      const Vec2 towards_end = (drawn[1] - last_in_core).normalized();
      std::vector<Vec2> path{last_in_core + crossing_rest_length * towards_end};
      path.insert(path.end(), drawn.begin() + 1, drawn.end());
      for (const Vec2 &node : dem::subdivide_polyline(path, spec.tank.max_segment_length))
        continuum_sheet_nodes.emplace_back(node.x(), node.y());
      for (std::size_t k = 0; k < continuum_sheet_nodes.size(); ++k)
        if (!(band_->coordinate(Vec2(continuum_sheet_nodes[k][0], continuum_sheet_nodes[k][1])) > 0.0))
          {
            std::ostringstream message;
            message << where << ": parameter 'Hybrid/DEM region length' = " << spec.region.dem_region_length
                    << " m: the sheet's part past the particles' core re-enters it (node at x = "
                    << continuum_sheet_nodes[k][0] + box_.x0 << " m, y = " << continuum_sheet_nodes[k][1] + box_.y0
                    << " m in the tank): a wrap-around's upper part must lie outside the particle box";
            throw std::invalid_argument(message.str());
          }
      set_up_.crossing_x = sheet.x[n_kept - 1] + box_.x0;
    }
  for (std::size_t k = 0; !crossing && k < sheet.n_nodes(); ++k)
    {
      const double s = band_->coordinate(Vec2(sheet.x[k], sheet.y[k]));
      if (s > -pad)
        {
          std::ostringstream message;
          message << where << ": parameter 'Hybrid/DEM region margin' = " << spec.region.margin
                  << " m is too small: sheet node " << k << " lies " << -s << " m inside the DEM core's edge, "
                  << "less than a branch (" << pad << " m); the margin must exceed the pad and the band ("
                  << pad + w << " m) by a branch";
          throw std::invalid_argument(message.str());
        }
    }

  // The continuum: the tank's mesh with lines on the core's and the band's edges, the core's cells
  // removed, its soil at the geostatic stress (hybrid_continuum.h).
  const double far = spec.region.far_cell_size > 0.0 ? spec.region.far_cell_size : 4.0 * cell;
  mesh_ = hybrid_continuum_mesh(box_, g, {cx0, cy0, cx1, cy1}, *band_, w, cell, far);
  set_up_.n_cells = mesh_->n_global_active_cells();
  continuum_ = hybrid_continuum_solver(*mesh_, spec, box_);
  if (crossing)
    {
      // The sheet's part in the continuum, its mass scaled as the particles' part is, or more if
      // it is unstable at the particles' step, which the coupled step does not exceed (the
      // continuum is set to that step: a heavier sheet, scaled for the continuum's own step,
      // lagged behind the pull by its inertia); then the particles' part cut.
      fem::TrussSheetParameters truss;
      truss.axial_stiffness = spec.tank.sheet.axial_stiffness;
      truss.areal_mass = spec.tank.sheet.areal_mass;
      truss.interface = spec.continuum.sheet_interface;
      const fem::EmbeddedSheet unscaled(continuum_->space(), fem::TrussSheet(continuum_sheet_nodes, truss, where), {},
                                        where);
      const double step = std::min(particles.time_step(), continuum_->time_step());
      continuum_->set_time_step(step);
      truss.mass_scaling =
        std::max(sheet.parameters().mass_scaling, 1.25 * std::pow(step / unscaled.stable_time_step(), 2));
      continuum_->attach_sheet(fem::TrussSheet(continuum_sheet_nodes, truss, where), {});
      set_up_.n_sheet_nodes_particles = n_kept;
      set_up_.n_sheet_nodes_continuum = continuum_sheet_nodes.size();
    }

  // The temporary walls on the shared sides are parked away (the lid already is, above the
  // box); the driven particles that stood against them now hold the grains, moved by the continuum.
  const double park = 10.0 * pad + 0.05;
  std::vector<dem::Wall> &walls = particles.walls();
  if (box_.left_shared)
    walls[tank_->tank.walls.left].translate(Vec2(-park, 0.0));
  if (box_.bottom_shared)
    walls[tank_->tank.walls.base].translate(Vec2(0.0, -park));
  particles.request_neighbour_rebuild();
  // The fill ran without the energy budget's booking (for speed); the coupled run books it, so
  // that the coupled system's balance (coupled_stepper.h, ledger_total) can be checked.
  particles.set_energy_tracking(true);
  if (interface)
    {
      // The grains touch the continuum's edges through their own contact law (the continuum is
      // the same soil), frictional, never bonded.
      InterfaceCoupling coupling = std::get<InterfaceCoupling>(spec.region.method);
      coupling.boundary_id = dem_core_boundary_id;
      coupling.contact = box_.box_tank.filling.particle_contact;
      coupling.contact.tensile_strength = coupling.contact.shear_strength = 0.0;
      coupling.contact.bond_new_contacts = false;
      stepper_ = std::make_unique<CoupledStepper>(particles, *continuum_, coupling);
    }
  else
    {
      stepper_ = std::make_unique<CoupledStepper>(
        particles, *continuum_, *band_, spec.region.method,
        BandTreatment{spec.region.driven_below_weight, spec.region.scale_band_inertia},
        MultiRate{spec.region.continuum_step_ratio});
      set_up_.n_tied = stepper_->band_particles().size();
      set_up_.n_driven = stepper_->band_particles().driven_body.size();
    }
  if (crossing)
    stepper_->cross_sheet(0, crossing_rest_length);
  set_up_.time_step = stepper_->time_step();

  // The overburden now comes through the band: settle together, both models below the fill's
  // unbalanced-force ratio, and for at least the time a P-wave takes to cross the tank ten times
  // (the particles were at rest under their own weight alone: their ratio starts low).
  const double target = spec.tank.filling.equilibrium_unbalanced_ratio;
  const fem::IsotropicElasticity &elasticity = continuum_->soil().elasticity();
  const double p_wave_modulus = elasticity.lame_lambda() + 2.0 * elasticity.shear_modulus();
  const double wave_crossing =
    std::max(g.fill_height, g.tank_length) / std::sqrt(p_wave_modulus / continuum_->settings().density);
  const auto min_steps = static_cast<std::uint64_t>(10.0 * wave_crossing / stepper_->time_step());
  const Clock::time_point coupled_settling_start = Clock::now();
  for (;;)
    {
      stepper_->run_steps(500);
      set_up_.settling_steps += 500;
      set_up_.settled_unbalanced_ratio =
        std::max(dem::unbalanced_force_ratio(particles), continuum_->out_of_balance_ratio());
      if (set_up_.settled_unbalanced_ratio < target && set_up_.settling_steps >= min_steps)
        {
          set_up_.coupled_settling_wall_time = seconds_since(coupled_settling_start);
          break;
        }
      if (set_up_.settling_steps >= spec.max_settling_steps)
        {
          std::ostringstream message;
          message << where << ": the coupled model did not settle in " << set_up_.settling_steps
                  << " steps (unbalanced-force ratio " << set_up_.settled_unbalanced_ratio << ", target " << target
                  << ")";
          throw std::runtime_error(message.str());
        }
    }
}

HybridPullOut::~HybridPullOut() = default;

std::vector<dem::PullPoint> HybridPullOut::pull(const dem::PullSpec &spec,
                                                const std::function<void(const dem::PullPoint &)> &record)
{
  return dem::pull_out(
    tank_->tank.system, spec,
    [&record](const dem::PullPoint &point, const dem::DemSystem &) {
      if (record)
        record(point);
    },
    pull_step());
}

std::function<void()> HybridPullOut::pull_step()
{
  return [this] {
    stepper_->step();
    ++pull_steps_;
  };
}

void HybridPullOut::restore_state(dem::DemSystemState particles, const fem::ExplicitSolverState &continuum,
                                  std::uint64_t pull_steps)
{
  if (std::abs(particles.time_step - stepper_->time_step()) > 1e-15 * stepper_->time_step())
    throw std::invalid_argument("hybrid pull-out: the saved particles' time step does not fit this set-up's "
                                "coupled step");
  tank_->tank.system.restore_state(std::move(particles));
  continuum_->restore_state(continuum);
  pull_steps_ = pull_steps;
}
} // namespace geohybrid::coupling
