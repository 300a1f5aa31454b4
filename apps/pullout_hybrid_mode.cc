#include "pullout_hybrid_mode.h"

#include "apps/coupling_diagnostics_file.h"
#include "apps/hybrid_box_source.h"
#include "apps/interrupt.h"
#include "apps/pullout_fem_mode.h"
#include "apps/parameters_hash.h"
#include "apps/pullout_forces_output.h"
#include "apps/pullout_output.h"
#include "apps/pull_watch.h"
#include "apps/resume_check.h"
#include "apps/run_health.h"
#include "apps/run_directory.h"

#include "coupling/hybrid_checkpoint.h"
#include "coupling/hybrid_pullout.h"
#include "dem/conventions.h"
#include "dem/laboratory/tank_filling.h"
#include "dem/measurements.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace geohybrid::apps
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_hybrid_parameters(ParameterHandler &prm)
{
  const coupling::HybridRegionSpec region;
  const coupling::PenaltyCoupling penalty;
  const std::string multipliers(coupling::LagrangeMultiplierCoupling::name), penalty_name(coupling::PenaltyCoupling::name),
    interface(coupling::InterfaceCoupling::name);
  prm.enter_subsection("Hybrid");
  // Any number passes the patterns: the library refuses the bad ones naming the entry and the
  // input file (a pattern error would name only deal.II's pattern).
  prm.declare_entry("DEM region margin", number(region.margin), Patterns::Double(),
                    "hybrid mode: the particle box reaches this far beyond the sheet below it, above it (above a "
                    "wrap-around's upper part) and behind its far end, clipped to the tank; it must exceed the band "
                    "and a pad of one branch length by a branch, and leave some continuum; the default, 0.15 m, is the least "
                    "whose sheet normal force is within 3 % of pure DEM's on the GT230 wrap-around in sand 1 "
                    "(VALIDATION.md 6.4): check another case with bench/run_hybrid_paired [m]");
  prm.declare_entry("DEM region length", number(region.dem_region_length), Patterns::Double(),
                    "hybrid mode: 0 puts the whole sheet in the particles; a length shorter than the lower part "
                    "'Anchorage/L' makes the particle box only that long behind the front wall: the sheet crosses into "
                    "the continuum at the particles' core edge, and its rest (a wrap-around's return and upper part "
                    "too) is held by the continuum's interface ('Continuum/interface ...', friction angle "
                    "'Sheet/Interface/friction angle') [m]");
  prm.declare_entry("continuum interface friction angle", "0", Patterns::Double(),
                    "hybrid mode, DEM region length > 0: delta of the sheet's interface in the continuum; 0 takes "
                    "'Sheet/Interface/friction angle', the grains' contact angle, which is above the angle the DEM's "
                    "sheet mobilises (calibrate it on a DEM pull-out: tan delta = T_max / (2 sigma_v L)) [deg]");
  prm.declare_entry("lift thickness", "auto", Patterns::Anything(),
                    "hybrid mode: the particle box is filled in its own lifts ('Filling/number of layers' is only "
                    "checked for the whole tank, as in dem mode), with the sheet and a wrap-around's upper part on lift "
                    "boundaries; the fill refuses grains larger than a fifth of a lift. auto: 0.05 m lifts if the "
                    "grains allow, else the thinnest lifts at least 5.25 of the largest grains thick (the box may "
                    "then reach further below the sheet than the margin). A number: lifts at most this thick, the "
                    "margin below the sheet divided evenly [m]");
  prm.declare_entry("band width", number(region.band_width), Patterns::Double(),
                    "hybrid mode: width of the overlap band where the particles are tied to the continuum; 0 = "
                    "four mean grain diameters [m]");
  prm.declare_entry("cell size", number(region.cell_size), Patterns::Double(),
                    "hybrid mode: the continuum's cells are at most this size (Q1, a generated mesh of the tank "
                    "less the DEM core; 'Continuum/cell size' is fem mode's); 0 = half the band width [m]");
  prm.declare_entry("coupling method", multipliers, Patterns::Selection(coupling::coupling_method_selection()),
                    "hybrid mode: how the particles meet the continuum: " + multipliers +
                      " (bridging domain, Lagrange multipliers: the band's velocities equal the continuum's, "
                      "exactly), " + penalty_name + " (springs of 'penalty factor' x E x d / w), or " + interface +
                      " (no band: the continuum's edges round the box are deformable walls the grains touch with "
                      "their own contact law; not with 'DEM region length') [-]");
  prm.declare_entry("penalty factor", number(penalty.penalty_factor), Patterns::Double(),
                    "hybrid mode, coupling method = " + penalty_name + ": k_p / (E d / w), E 'Continuum/Young modulus', d the "
                    "particle's diameter, w the band width; stiffer ties better and lowers the stable step [-]");
  prm.declare_entry("driven below weight", number(region.driven_below_weight), Patterns::Double(),
                    "hybrid mode: the band's particles whose energy weight (1 at the core's edge, 0 at the "
                    "continuum's) is below this are moved by the continuum instead of tied to it, which keeps the "
                    "coupled step near the particles' own; in [0, 1) [-]");
  prm.declare_entry("scale band inertia", region.scale_band_inertia ? "true" : "false", Patterns::Bool(),
                    "hybrid mode: raise the inertial mass (not the weight) of each band particle to the weight of "
                    "its stiffest contact, so that the band does not lower the stable step (a density scaling of "
                    "the band: its statics are unchanged, its dynamics are not the weighted ones; a quasi-static "
                    "pull needs only the statics)");
  prm.declare_entry("continuum step ratio", std::to_string(region.continuum_step_ratio), Patterns::Integer(0),
                    "hybrid mode, coupling method = " + multipliers + ": the continuum steps once per this many "
                    "particle steps (multi-rate: its stable step is many of the particles'; docs/coupling.md); 1 "
                    "steps both together, 0 takes the largest ratio the continuum is stable at, up to " +
                      std::to_string(coupling::MultiRate::largest_automatic_ratio) +
                      " (larger ratios raise the tied grains' inertia by the ratio squared, which moved the mean "
                      "tension; VALIDATION.md 6.4) [-]");
  prm.declare_entry("particles from", "", Patterns::Anything(),
                    "hybrid mode: empty fills the particle box in its own lifts; a dem-mode run's filled_tank.h5 "
                    "(the same input but for the mode and subsections Hybrid, Continuum, Pull, Output) cuts the box "
                    "out of that tank instead, the grains whose centres lie in the box: the hybrid then pulls the grains "
                    "pure DEM pulled round the sheet, and the two differ only by the continuum and the coupling "
                    "(a given 'lift thickness' then shapes the box whatever the grains' size)");
  prm.declare_entry("fill under overburden", region.fill_under_overburden ? "true" : "false", Patterns::Bool(),
                    "hybrid mode: before the coupling, load the particle box's top with the weight of the soil "
                    "above it, gamma (fill height - box top), through a frictionless servo-controlled lid, and "
                    "settle it (the continuum starts at its geostatic stress: so do the particles then); false "
                    "lets the box take that load only once tied, when it settles more than the continuum beside it "
                    "and the load arches onto the continuum");
  prm.leave_subsection();
}

namespace
{
/// 'Hybrid/lift thickness': auto (0, the library's automatic lifts) or a positive number.
double lift_thickness(const std::string &value, const std::string &where)
{
  if (value == "auto")
    return 0.0;
  std::size_t read = 0;
  double thickness = 0.0;
  try
    {
      thickness = std::stod(value, &read);
    }
  catch (const std::exception &)
    {
      read = 0;
    }
  if (read == 0 || value.find_first_not_of(" \t", read) != std::string::npos || !(thickness > 0.0) ||
      !std::isfinite(thickness))
    throw std::invalid_argument(where + ": parameter 'Hybrid/lift thickness' = '" + value +
                                "' must be auto or a positive thickness [m]");
  return thickness;
}

/// subsection Hybrid and the soil of subsection Continuum, with the shared input, as the
/// library's spec; checked (std::invalid_argument naming `where` and the entry).
coupling::HybridPullOutSpec parse_hybrid(ParameterHandler &prm, const PullOutInput &in, const std::string &where)
{
  coupling::HybridPullOutSpec spec;
  spec.tank = in.tank;
  coupling::HybridRegionSpec &r = spec.region;
  prm.enter_subsection("Hybrid");
  r.margin = prm.get_double("DEM region margin");
  r.dem_region_length = prm.get_double("DEM region length");
  // 0 takes the grains' angle on the sheet (Sheet/Interface/friction angle).
  const double delta = prm.get_double("continuum interface friction angle");
  spec.continuum.sheet_interface.friction_angle_deg = delta != 0.0 ? delta : in.tank.sheet.interface.friction_angle_deg;
  r.lift_thickness = lift_thickness(prm.get("lift thickness"), where);
  r.band_width = prm.get_double("band width");
  r.cell_size = prm.get_double("cell size");
  r.method = coupling::parse_coupling_method_name(prm.get("coupling method"), where, "Hybrid/coupling method");
  if (auto *penalty = std::get_if<coupling::PenaltyCoupling>(&r.method))
    penalty->penalty_factor = prm.get_double("penalty factor");
  r.driven_below_weight = prm.get_double("driven below weight");
  r.scale_band_inertia = prm.get_bool("scale band inertia");
  r.continuum_step_ratio = static_cast<unsigned int>(prm.get_integer("continuum step ratio"));
  r.fill_under_overburden = prm.get_bool("fill under overburden");
  r.box_cut_from_a_filled_tank = !prm.get("particles from").empty();
  prm.leave_subsection();

  const ContinuumSoilInput soil = parse_continuum_soil(prm);
  spec.continuum.soil = soil.soil;
  spec.continuum.k0 = soil.k0;
  spec.continuum.local_damping = soil.local_damping;
  prm.enter_subsection("Continuum");
  spec.continuum.sheet_interface.cohesion = prm.get_double("interface cohesion");
  spec.continuum.sheet_interface.normal_stiffness = prm.get_double("interface normal stiffness");
  spec.continuum.sheet_interface.shear_stiffness = prm.get_double("interface shear stiffness");
  prm.leave_subsection();
  spec.validate(where);
  return spec;
}

} // namespace

int run_pullout_hybrid_mode(ParameterHandler &prm, const PullOutInput &in, const std::string &where, bool resume,
                            MPI_Comm communicator, bool check_only)
{
  if (dealii::Utilities::MPI::job_supports_mpi() && dealii::Utilities::MPI::n_mpi_processes(communicator) > 1)
    throw std::invalid_argument(where + ": 'mode' = hybrid runs in one process; run it without mpirun");
  const auto start_time = std::chrono::steady_clock::now();
  const auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  };
  const dem::PullOutGeometry &g = in.tank.geometry;
  const coupling::HybridPullOutSpec spec = parse_hybrid(prm, in, where);
  const double checkpoint_interval = prm.get_double("checkpoint interval");
  const auto stop_after = static_cast<std::uint64_t>(prm.get_integer("stop after steps"));
  // The box is computed (and the margin checked) before a file is written; the refusals that need
  // the filled grains (the band against the sheet) come after the fill, with no summary.json.
  const coupling::ParticleBox box = coupling::particle_box(spec, where);
  // The sheet and the grains are dem mode's, and so is its estimate of the sheet's inertia.
  refuse_sheet_inertia_before_the_fill(in.tank, in.pull, where);
  const std::string out_name = prm.get("output directory");
  if (out_name.empty())
    throw std::invalid_argument(where + ": parameter 'output directory' is empty");
  if (check_only)
    return 0;

  const std::filesystem::path out = out_name;
  // Checkpoints: the filled box (the particles only, written once: the set-up after it is
  // repeated on resuming, deterministic and short), then, during the pull, the particles' and the
  // continuum's states with the pull's progress and the rows recorded. Each keeps the input, and
  // a resume with another is refused before a file is written (resume_check.h).
  const std::filesystem::path box_file = out / "filled_box.h5", checkpoint_file = out / "checkpoint.h5";
  prm.enter_subsection("Hybrid");
  const std::string particles_from = prm.get("particles from");
  prm.leave_subsection();
  // Cut before a file is written: a tank that does not fit is refused with nothing begun.
  std::optional<dem::PullOutTank> cut;
  if (!particles_from.empty() && !(resume && std::filesystem::exists(box_file)))
    cut.emplace(box_cut_from_filled_tank(particles_from, prm, in.tank, box, where));
  if (resume)
    for (const auto &file : {box_file, checkpoint_file})
      if (std::filesystem::exists(file))
        check_pullout_checkpoint(file, prm, where);
  prepare_output_directory(out_name, resume && (std::filesystem::exists(box_file) || holds_same_pullout_run(out, prm)));
  dem::CommandState input;
  store_pullout_input(prm, input);
  if (!resume)
    for (const auto &stale : {box_file, checkpoint_file})
      std::filesystem::remove(stale); // never resume a stale one
  write_resolved_parameters(prm, out);
  std::cout << "geohybrid pullout: " << anchorage_description(g) << "; mode hybrid: " << box.n_particles << " particles in the box [" << number(box.x0, 4) << ", "
            << number(box.x1, 4) << "] x [" << number(box.y0, 4) << ", " << number(box.y1, 4) << "] m in "
            << box.n_lifts << " lifts of " << (box.box_tank.filling.layer_tops.empty() ? "" : "at least ")
            << number(box.lift_thickness, 4) << " m ("
            << in.tank.filling.n_particles << " for the whole tank), " << fem::to_string(spec.continuum.soil.kind)
            << " continuum, coupling " << coupling::name_of(spec.region.method) << std::endl;

  // 1. The box filled (or taken from its checkpoint), the continuum built and tied, both settled.
  double fill_time = 0.0;
  std::optional<dem::PullOutTank> filled;
  // With 'checkpoint interval' = 0 the filled box is kept here instead, and written with the
  // first checkpoint a signal or 'stop after steps' asks for: --resume needs both files.
  std::optional<std::pair<dem::DemSystemState, dem::CommandState>> unwritten_box;
  if (resume && std::filesystem::exists(box_file))
    {
      dem::CommandState saved_box;
      try
        {
          dem::DemSystemState state = dem::read_checkpoint(box_file, saved_box);
          filled.emplace(dem::restore_pullout_tank(
            std::move(state), dem::tank_settling_settings(box.box_tank.resolved_filling()), saved_box));
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("cannot resume from '" + box_file.string() + "' with " + where + ": " + e.what());
        }
      fill_time = saved_box.real("fill_wall_time_s", 1)[0];
      std::cout << "pullout: resuming: the particle box of " << box_file.string() << " (filled in "
                << number(fill_time, 4) << " s); the coupled set-up again" << std::endl;
    }
  else
    {
      if (resume)
        std::cout << "geohybrid pullout: no checkpoint in " << out.string()
                  << " (the run stopped before its box was full): filling the box again from the start" << std::endl;
      std::filesystem::remove(checkpoint_file);
      if (cut)
        {
          filled.emplace(std::move(*cut));
          cut.reset();
          std::cout << "pullout: the particle box cut from " << particles_from << ": "
                    << filled->tank.system.particles().n_bodies() << " grains, their centres inside it, in the tank's stress (no settling under a lid)" << std::endl;
        }
      else
        {
          filled.emplace(fill_with_progress(box.box_tank, "the particle box"));
          std::cout << "pullout: the box's " << fill_steps_per_layer(filled->tank) << ", settling with the sheet freed "
                    << filled->n_final_settling_steps << std::endl;
        }
      fill_time = seconds();
      dem::CommandState c;
      dem::store_pullout_tank(*filled, c);
      c.reals["fill_wall_time_s"] = {fill_time};
      c.texts = input.texts;
      if (checkpoint_interval > 0.0)
        dem::write_checkpoint(filled->tank.system.export_state(), c, box_file);
      else
        unwritten_box.emplace(filled->tank.system.export_state(), std::move(c));
    }
  std::optional<coupling::HybridPullOut> hybrid;
  hybrid.emplace(spec, where, std::move(*filled));
  filled.reset();
  const double set_up_time = seconds();
  const coupling::HybridSetUp &s = hybrid->set_up();
  const dem::PullOutTank &tank = hybrid->particles();
  const double sheet_level = box.y0 + tank.sheet_level; // in the tank's frame
  const double actual_cover = g.fill_height - sheet_level;
  const double gamma_H = in.tank.unit_weight * actual_cover;
  const dem::SheetLevelStress before =
    dem::measure_sheet_level_stress(hybrid->particle_system(), tank, box.box_tank.geometry, in.stress_band);
  const double mu = std::tan(dem::degrees_to_radians(in.tank.sheet.interface.friction_angle_deg));
  std::cout << "pullout: box filled in " << number(fill_time, 4) << " s (" << s.n_particles << " particles, "
            << s.fill_steps << " steps); " << s.n_cells << " continuum cells of " << number(s.cell_size, 3)
            << " m, band " << number(s.band_width, 3) << " m (" << s.n_tied << " particles tied, " << s.n_driven
            << " driven); "
            << (s.n_sheet_nodes_continuum > 0
                  ? "the sheet crosses into the continuum at x = " + number(s.crossing_x, 4) + " m (" +
                      std::to_string(s.n_sheet_nodes_particles) + " nodes in the particles, " +
                      std::to_string(s.n_sheet_nodes_continuum) + " in the continuum); "
                  : std::string())
            << (s.overburden > 0.0 ? "the box settled under its overburden " + number(s.overburden / 1e3, 4) +
                                         " kPa (the lid at " + number(s.overburden_reached / 1e3, 4) + " kPa) in " +
                                         std::to_string(s.box_settling_steps) + " steps; "
                                   : std::string())
            << "settled together in " << s.settling_steps << " steps (unbalanced ratio "
            << number(s.settled_unbalanced_ratio, 3) << "), set-up " << number(set_up_time, 4)
            << " s; time step " << number(s.time_step, 4) << " s (the particles' own " << number(s.particle_time_step, 4)
            << " s), the continuum's " << hybrid->stepper().continuum_step_ratio() << " of them"
            << (hybrid->stepper().tied_inertia_factor() > 1.0
                  ? " (the tied grains' inertia x " + number(hybrid->stepper().tied_inertia_factor(), 3) + ")"
                  : std::string())
            << "; sheet at y = " << number(sheet_level, 4) << " m (H = " << number(actual_cover, 4)
            << " m as laid); vertical stress at the sheet: top face " << number(before.top_face / 1e3, 4)
            << " kPa, Love-Weber above " << number(before.love_weber_above / 1e3, 4) << " kPa, gamma H "
            << number(gamma_H / 1e3, 4) << " kPa" << std::endl;

  // 2. The pull: each point of the curve with the sheet as it is then (positions in the tank's
  // frame; the box's frame is shifted by (x0, y0)); from its start or from the checkpoint's
  // progress. The energy balance is measured from the pull's first point: the set-up's state,
  // with the clamp started (a resumed run has just repeated the set-up: the same state).
  dem::DemSystem &system = hybrid->particle_system();
  DiagnosticsFile diagnostics(out);
  std::optional<dem::PullOut> pull;
  pull.emplace(system, in.pull, hybrid->pull_step());
  diagnostics.set_start(hybrid->stepper().diagnostics());
  dem::CommandState saved;
  const bool resumed = resume && std::filesystem::exists(checkpoint_file);
  double earlier_wall_time = 0.0; // of the runs before this one, when resuming
  std::optional<PulloutOutput> output;
  if (resumed)
    {
      try
        {
          dem::DemSystemState state = dem::read_checkpoint(checkpoint_file, saved);
          const std::optional<dem::PullProgress> progress = dem::restore_pull_progress(saved);
          if (!progress)
            throw std::runtime_error("it holds no pull");
          hybrid->restore_state(std::move(state), coupling::restore_continuum_state(saved),
                                saved.count("hybrid_pull_steps", 1)[0]);
          coupling::restore_window_phase(saved, hybrid->stepper());
          pull.emplace(system, in.pull, *progress, hybrid->pull_step());
          output.emplace(out, g.sheet_width, in.profiles_at, saved);
          diagnostics.restore(saved);
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("cannot resume from '" + checkpoint_file.string() + "' with " + where + ": " + e.what());
        }
      earlier_wall_time = saved.real("wall_time_s", 1)[0];
      std::cout << "pullout: resuming the pull at " << number(1e3 * pull->head_displacement(), 4) << " mm from "
                << checkpoint_file.string() << std::endl;
    }
  else
    output.emplace(out, g.sheet_width, in.profiles_at);
  // pullout_forces.csv as in dem mode: the sheet's normal force and mobilised friction along the
  // pull, the figures that tell where the hybrid's tension differs from pure DEM's.
  std::optional<PullForcesOutput> forces;
  if (resumed && saved.reals.count("forces_rows") != 0)
    forces.emplace(out, mu, saved);
  else // a new pull, or a checkpoint of a version that did not record the decomposition
    forces.emplace(out, mu, system.energy());
  const double u_first = pull->head_displacement();
  // Where the pull's time goes (issue 26, part 1): the coupled steps' parts, and the pull's wall
  // time, carried through checkpoints so that a resumed run reports the whole pull's.
  const auto earlier = [&](const char *key, std::size_t n) {
    const auto found = saved.reals.find(key);
    return resumed && found != saved.reals.end() && found->second.size() == n ? found->second
                                                                             : std::vector<double>(n, 0.0);
  };
  const std::vector<double> earlier_parts = earlier("pull_step_wall_times_s", 4);
  hybrid->stepper().reset_step_times({earlier_parts[0], earlier_parts[1], earlier_parts[2], earlier_parts[3]});
  const double earlier_pull_time = earlier("pull_wall_time_s", 1)[0], pull_start = seconds();
  const auto pull_time = [&] { return earlier_pull_time + seconds() - pull_start; };
  // The sheet's inertia checked as in dem mode, then the watch of the pull (apps/pull_watch.h):
  // the grains kept in the box, their kinetic energy (not the continuum's) against the work.
  std::vector<std::string> warnings = in.warnings;
  if (auto w = check_dem_sheet_inertia(system.sheets()[0], in.pull, system.time_step(),
                                       2.0 * before.top_face * g.anchorage_length * mu, where))
    warnings.push_back(*w);
  const PullWatch::Setup watch_setup{in.pull.record_interval, in.pull.ramp_displacement, particle_box_bounds(box), true};
  PullWatch watch(watch_setup, system, resumed ? &saved : nullptr);
  ProgressReport progress("pulling", in.pull.final_displacement - u_first);
  const auto record = [&](const dem::PullPoint &p) {
    watch.check(p, system);
    add_dem_sheet_point(*output, tank, system.sheets()[0], p, dem::Vec2(box.x0, box.y0));
    forces->add_point(p, system);
    diagnostics.add(p, *hybrid);
    progress.update(p.head_displacement - u_first);
  };
  const auto save_checkpoint = [&] {
    if (unwritten_box)
      {
        dem::write_checkpoint(unwritten_box->first, unwritten_box->second, box_file);
        unwritten_box.reset();
      }
    dem::CommandState c;
    c.name = "pullout";
    c.reals["wall_time_s"] = {earlier_wall_time + seconds()};
    const coupling::CoupledStepTimes &t = hybrid->stepper().step_times();
    c.reals["pull_step_wall_times_s"] = {t.continuum, t.band_drive, t.particles, t.coupling};
    c.reals["pull_wall_time_s"] = {pull_time()};
    dem::store_pull_progress(pull->progress(), c);
    output->store(c);
    forces->store(c);
    diagnostics.store(c);
    watch.store(c);
    coupling::store_continuum_state(hybrid->continuum_state(), c);
    coupling::store_window_phase(hybrid->stepper(), c);
    c.counts["hybrid_pull_steps"] = {hybrid->pull_steps()};
    c.texts = input.texts;
    dem::write_checkpoint(system.export_state(), c, checkpoint_file);
  };
  if (!resumed)
    record(pull->start_point());
  if (!pull_with_checkpoints(*pull, record, save_checkpoint, checkpoint_interval, stop_after, checkpoint_file))
    return 0; // stopped as 'stop after steps' asks: continued with --resume
  pull->stop_clamp();
  progress.finish();
  const std::size_t n_points = diagnostics.n_rows();

  // 3. The plot, then summary.json last.
  output->finish("hybrid DEM-FEM", in.references, in.pull.final_displacement);
  forces->finish();
  if (checkpoint_interval > 0.0)
    save_checkpoint(); // the finished pull: a later --resume has nothing left to do but the files
  const double T_max = output->max_head_tension(), wall_time = earlier_wall_time + seconds();
  Summary summary;
  output->fill_summary(summary, "hybrid", anchorage_name(g), in.references);
  summary.set("n_particles", static_cast<double>(s.n_particles));
  summary.set("n_particles_full_tank", static_cast<double>(in.tank.filling.n_particles));
  summary.set("coupling_method", std::string(coupling::name_of(spec.region.method)));
  summary.set("continuum_step_ratio", static_cast<double>(hybrid->stepper().continuum_step_ratio()));
  summary.set("tied_inertia_factor", hybrid->stepper().tied_inertia_factor());
  summary.set("n_cells", static_cast<double>(s.n_cells));
  summary.set("cell_size_m", s.cell_size);
  summary.set("band_width_m", s.band_width);
  summary.set("pad_m", s.pad);
  summary.set("DEM_region", std::vector<double>{box.x0, box.y0, box.x1, box.y1});
  summary.set("n_tied_particles", static_cast<double>(s.n_tied));
  summary.set("n_driven_particles", static_cast<double>(s.n_driven));
  summary.set("DEM_region_length_m", spec.region.dem_region_length);
  summary.set("sheet_nodes_in_particles", static_cast<double>(s.n_sheet_nodes_particles));
  summary.set("sheet_nodes_in_continuum", static_cast<double>(s.n_sheet_nodes_continuum));
  if (s.n_sheet_nodes_continuum > 0)
    summary.set("sheet_crossing_x_m", s.crossing_x);
  summary.set("soil_model", fem::to_string(spec.continuum.soil.kind));
  set_dem_sheet_summary(summary, hybrid->particle_system().sheets()[0], sheet_level, actual_cover, gamma_H, before,
                        before.top_face * g.anchorage_length * mu);
  summary.set("time_step_s", s.time_step);
  summary.set("particle_time_step_s", s.particle_time_step);
  summary.set("n_fill_steps", static_cast<double>(s.fill_steps));
  summary.set("n_settling_steps", static_cast<double>(s.settling_steps));
  summary.set("n_pull_steps", static_cast<double>(hybrid->pull_steps()));
  summary.set("settled_unbalanced_ratio", s.settled_unbalanced_ratio);
  summary.set("overburden_Pa", s.overburden);
  summary.set("overburden_reached_Pa", s.overburden_reached);
  summary.set("n_box_settling_steps", static_cast<double>(s.box_settling_steps));
  diagnostics.finish(summary);
  summary.set("n_curve_points", static_cast<double>(n_points));
  summary.set("resumed_at_head_displacement_m", resumed ? u_first : std::nan("")); // null for a straight run
  summary.set("fill_wall_time_s", fill_time);
  summary.set("set_up_wall_time_s", set_up_time);
  summary.set("box_settling_wall_time_s", s.box_settling_wall_time);
  summary.set("coupled_settling_wall_time_s", s.coupled_settling_wall_time);
  const coupling::CoupledStepTimes &parts = hybrid->stepper().step_times();
  summary.set("pull_wall_time_s", pull_time());
  summary.set("pull_continuum_wall_time_s", parts.continuum);
  summary.set("pull_coupling_wall_time_s", parts.coupling);
  summary.set("pull_band_drive_wall_time_s", parts.band_drive);
  summary.set("pull_particles_wall_time_s", parts.particles);
  summary.set("pull_wall_time_parts_definition",
              "the pull's coupled steps: the continuum's step, the coupling forces (ties or multipliers, "
              "interface contacts, the sheet crossing), the driven particles' velocities from the continuum, "
              "and the particles' step without the coupling; the rest of pull_wall_time_s is the curve's "
              "points (output, watch, diagnostics) and checkpoints. Summed over a resumed run's parts");
  summary.set("wall_time_s", wall_time);
  summary.set("parameters_hash", pullout_parameters_hash(prm));
  const std::vector<std::string> found = watch.warnings();
  warnings.insert(warnings.end(), found.begin(), found.end());
  report_warnings(warnings, "geohybrid pullout", summary, std::cerr);
  summary.write(out / "summary.json");
  std::cout << "geohybrid pullout: T_max = " << number(T_max / 1e3, 4) << " kN/m ("
            << number(T_max * g.sheet_width / 1e3, 4) << " kN for b = " << number(g.sheet_width, 3) << " m) at "
            << number(1e3 * output->head_displacement_at_max(), 3) << " mm"
            << experiment_text(in.references) << "; " << number(wall_time, 4) << " s\n"
            << demonstration_lines(in.references) << "results in " << out.string() << '\n';
  return 0;
}
} // namespace geohybrid::apps
