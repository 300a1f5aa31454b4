#include "pullout_dem_mode.h"

#include "interrupt.h"
#include "parameters_hash.h"
#include "pull_watch.h"
#include "pullout_field_output.h"
#include "pullout_forces_output.h"
#include "pullout_output.h"
#include "resume_check.h"
#include "run_directory.h"
#include "run_health.h"

#include <deal.II/base/mpi.h>

#include "dem/io/checkpoint.h"
#include "dem/laboratory/pullout_tank.h"
#include "dem/measurements.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

namespace geohybrid::apps
{
using dealii::ParameterHandler;

namespace
{
/// Wall time since the run started (this invocation; a resumed run adds its earlier ones).
class RunClock
{
public:
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// What a pull starts from: the filled tank, filled now or restored from the checkpoint, and
/// what the run knows of it.
struct DemPullStart
{
  /// What a checkpoint keeps beside the system: the tank's description, the stress before the
  /// pull, the wall time spent before, then the pull's progress and rows.
  dem::CommandState saved;
  std::optional<dem::PullOutTank> tank;
  bool resumed = false;
  double earlier_wall_time = 0.0; ///< of the runs before this one, when resuming [s]
  double fill_time = 0.0;         ///< wall time of the fill [s]
  dem::SheetLevelStress before;   ///< the soil's stress on the sheet before the pull
  double actual_cover = 0.0;      ///< H as laid: the fill's height above the sheet [m]
  double gamma_H = 0.0;           ///< [Pa]
  double mu = 0.0;                ///< tan of the interface's friction angle [-]
  double one_face = 0.0;          ///< Coulomb's pull-out force of one face, sigma_top L mu [N/m]
};

/// 1. The tank, filled in layers, the sheet laid at its depth; or the one of the checkpoint.
/// Prepares the output directory and writes parameters.prm on the way.
DemPullStart fill_or_resume_tank(ParameterHandler &prm, const PullOutInput &in, const std::string &where, bool resume,
                                 const std::filesystem::path &out, const RunClock &clock)
{
  const dem::PullOutGeometry &g = in.tank.geometry;
  const std::filesystem::path checkpoint_file = out / "checkpoint.h5";
  DemPullStart start;
  dem::CommandState &saved = start.saved;
  std::optional<dem::PullOutTank> &filled = start.tank;
  if (resume && std::filesystem::exists(checkpoint_file))
    {
      check_pullout_checkpoint(checkpoint_file, prm, where); // before its state is used: it may not even fit
      try
        {
          dem::DemSystemState state = dem::read_checkpoint(checkpoint_file, saved);
          filled.emplace(dem::restore_pullout_tank(std::move(state), dem::tank_settling_settings(in.tank.resolved_filling()),
                                                   saved));
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("cannot resume from '" + checkpoint_file.string() + "' with " + where + ": " + e.what());
        }
      start.earlier_wall_time = saved.real("wall_time_s", 1)[0];
    }
  // A resume with no checkpoint fills the tank again: in its own run's directory only.
  prepare_output_directory(out.string(), resume && (filled || holds_same_pullout_run(out, prm)));
  if (!filled)
    {
      if (resume)
        std::cout << "geohybrid pullout: no checkpoint in " << out.string()
                  << " (the run stopped before its tank was full): filling the tank again from the start" << std::endl;
      std::filesystem::remove(checkpoint_file); // never resume a stale one
    }
  write_resolved_parameters(prm, out);
  start.resumed = filled.has_value();
  if (start.resumed)
    {
      start.fill_time = saved.real("fill_wall_time_s", 1)[0];
      start.before = dem::restore_sheet_level_stress(saved);
      std::cout << "pullout: resuming from " << checkpoint_file.string() << " (tank filled in "
                << number(start.fill_time, 4) << " s)" << std::endl;
    }
  else
    {
      filled.emplace(fill_with_progress(in.tank, "the tank"));
      start.fill_time = clock.seconds();
      start.before = dem::measure_sheet_level_stress(filled->tank.system, *filled, g, in.stress_band);
      saved = dem::CommandState();
      dem::store_pullout_tank(*filled, saved);
      dem::store_sheet_level_stress(start.before, saved);
      saved.reals["fill_wall_time_s"] = {start.fill_time};
    }
  store_pullout_input(prm, saved); // this run's: what a later --resume is checked against
  const dem::PullOutTank &tank = *filled;
  const dem::DemSystem &system = tank.tank.system;
  start.actual_cover = g.fill_height - tank.sheet_level;
  start.gamma_H = in.tank.unit_weight * start.actual_cover;
  start.mu = std::tan(dem::degrees_to_radians(in.tank.sheet.interface.friction_angle_deg));
  start.one_face = start.before.top_face * g.anchorage_length * start.mu;
  std::cout << "pullout: tank filled in " << number(start.fill_time, 4) << " s (" << system.particles().n_bodies()
            << " particles, porosity of the layers";
  for (const dem::TankLayer &layer : tank.tank.layers)
    std::cout << ' ' << number(layer.porosity, 3);
  std::cout << "); sheet at y = " << number(tank.sheet_level, 4) << " m (H = " << number(start.actual_cover, 4)
            << " m as laid); vertical stress at the sheet: top face " << number(start.before.top_face / 1e3, 4)
            << " kPa, Love-Weber above " << number(start.before.love_weber_above / 1e3, 4) << " kPa, gamma H "
            << number(start.gamma_H / 1e3, 4) << " kPa" << std::endl;
  return start;
}

/// 3. summary.json of a finished pull, written last: a directory without it holds an unfinished run.
void write_dem_summary(ParameterHandler &prm, const PullOutInput &in, const DemPullStart &start, PulloutOutput &output,
                       std::uint64_t n_pull_steps, double u_first, double wall_time, std::vector<std::string> warnings,
                       const std::vector<std::string> &found, const std::filesystem::path &out)
{
  const dem::PullOutTank &tank = *start.tank;
  const dem::DemSystem &system = tank.tank.system;
  Summary summary;
  output.fill_summary(summary, "dem", anchorage_name(in.tank.geometry), in.references);
  summary.set("n_particles", static_cast<double>(system.particles().n_bodies()));
  set_dem_sheet_summary(summary, system.sheets()[0], tank.sheet_level, start.actual_cover, start.gamma_H, start.before,
                        start.one_face);
  summary.set("time_step_s", system.time_step());
  summary.set("critical_time_step_s", system.critical_time_step());
  summary.set("n_pull_steps", static_cast<double>(n_pull_steps));
  summary.set("resumed_at_head_displacement_m", start.resumed ? u_first : std::nan("")); // null for a straight run
  summary.set("fill_wall_time_s", start.fill_time);
  // The cost of the run in steps: filling (each layer's growth and settling, then the settling
  // with the sheet freed) and pulling; of the fill, the lifts taken from 'Filling/lift cache
  // directory', whose steps an earlier run made.
  summary.set("n_fill_steps", static_cast<double>(dem::fill_steps(tank)));
  summary.set("n_fill_steps_of_kept_lifts", static_cast<double>(dem::fill_steps_of_kept_lifts(tank)));
  summary.set("wall_time_s", wall_time);
  summary.set("parameters_hash", pullout_parameters_hash(prm));
  warnings.insert(warnings.end(), found.begin(), found.end());
  report_warnings(warnings, "geohybrid pullout", summary, std::cerr);
  summary.write(out / "summary.json");
}
} // namespace

int run_pullout_dem_mode(ParameterHandler &prm, const PullOutInput &in, const std::string &where, bool resume,
                         MPI_Comm communicator, bool check_only)
{
  if (dealii::Utilities::MPI::job_supports_mpi() && dealii::Utilities::MPI::n_mpi_processes(communicator) > 1)
    throw std::invalid_argument(where + ": 'mode' = dem runs in one process (its threads: 'threads'); run it "
                                "without mpirun, or use 'set mode = fem'");
  const dem::PullOutGeometry &g = in.tank.geometry;
  const double checkpoint_interval = prm.get_double("checkpoint interval");
  const auto stop_after = static_cast<std::uint64_t>(prm.get_integer("stop after steps"));
  // A sheet far too stiff is known before the fill (its check after the fill is the exact one).
  refuse_sheet_inertia_before_the_fill(in.tank, in.pull, where);
  if (check_only)
    return 0;

  const std::filesystem::path out = prm.get("output directory");
  if (out.empty())
    throw std::invalid_argument(where + ": parameter 'output directory' is empty");
  const std::filesystem::path checkpoint_file = out / "checkpoint.h5";
  const RunClock clock;
  std::cout << "geohybrid pullout: " << anchorage_description(g) << "; " << in.tank.filling.n_particles
            << " particles, mode dem" << std::endl;

  // 1. The tank, filled or restored.
  DemPullStart start = fill_or_resume_tank(prm, in, where, resume, out, clock);
  const dem::CommandState &saved = start.saved;
  dem::PullOutTank &tank = *start.tank;
  dem::DemSystem &system = tank.tank.system;

  // 2. The pull, from its start or from the checkpoint's progress.
  const std::optional<dem::PullProgress> pulled = start.resumed ? dem::restore_pull_progress(saved) : std::nullopt;
  std::optional<PulloutOutput> output;
  if (pulled)
    output.emplace(out, g.sheet_width, in.profiles_at, saved);
  else
    output.emplace(out, g.sheet_width, in.profiles_at);
  const dem::ParticleSet &grains = system.particles();
  // Surface strips two disc diameters wide: a cluster's centre lies between its discs, so strips
  // one disc wide may hold no centre of a surface grain.
  const double strip = 4.0 * *std::max_element(grains.disc_radius.begin(), grains.disc_radius.end());
  std::optional<PullOutFieldOutput> fields;
  if (pulled)
    fields.emplace(out, in.fields_at, g.tank_length, strip, saved, system);
  else
    fields.emplace(out, in.fields_at, g.tank_length, strip);
  // The pull books its energy terms (the fill does not, for speed): pullout_forces.csv reports
  // the damping and friction work the pull costs. Booking leaves the forces' arithmetic as it is.
  system.set_energy_tracking(true);
  std::optional<PullForcesOutput> forces;
  if (pulled && saved.reals.count("forces_rows") != 0)
    forces.emplace(out, start.mu, saved);
  else // a new pull, or a checkpoint of a version that did not record the decomposition
    forces.emplace(out, start.mu, system.energy());
  std::optional<dem::PullOut> pull;
  if (pulled)
    pull.emplace(system, in.pull, *pulled);
  else
    pull.emplace(system, in.pull);
  const double u_first = pull->head_displacement();
  // The sheet's scaled mass is known exactly now, with the grains' time step: refused if its
  // inertia would set the answer (run_health.h; set-up refused only what was far beyond). The
  // watch looks at every point of the curve.
  std::vector<std::string> warnings = in.warnings;
  if (auto w = check_dem_sheet_inertia(system.sheets()[0], in.pull, system.time_step(), 2.0 * start.one_face, where))
    warnings.push_back(*w);
  const GrainBounds tank_inside{0.0, g.tank_length, 0.0, std::numeric_limits<double>::infinity(), "the tank"};
  const PullWatch::Setup watch_setup{in.pull.record_interval, in.pull.ramp_displacement, tank_inside, true};
  PullWatch watch(watch_setup, system, pulled ? &saved : nullptr);
  std::cout << "pullout: " << fill_steps_per_layer(tank.tank);
  std::cout << ", settling with the sheet freed " << tank.n_final_settling_steps << "; time step "
            << number(system.time_step(), 4) << " s (critical " << number(system.critical_time_step(), 4)
            << " s); the pull takes " << pull->expected_steps() << " steps" << std::endl;
  ProgressReport progress("pulling", in.pull.final_displacement - u_first);
  const auto record = [&](const dem::PullPoint &p, const dem::DemSystem &s) {
    watch.check(p, s); // a point of a pull gone wrong is not written
    add_dem_sheet_point(*output, tank, s.sheets()[0], p);
    forces->add_point(p, s);
    fields->record(p.head_displacement, s);
    progress.update(p.head_displacement - u_first);
  };
  const auto save_checkpoint = [&] {
    dem::CommandState c = saved;
    c.reals["wall_time_s"] = {start.earlier_wall_time + clock.seconds()};
    dem::store_pull_progress(pull->progress(), c);
    output->store(c);
    forces->store(c);
    fields->store(c);
    watch.store(c);
    dem::write_checkpoint(system.export_state(), c, checkpoint_file);
  };
  if (!pulled)
    {
      record(pull->start_point(), system);
      if (checkpoint_interval > 0.0)
        {
          save_checkpoint(); // the filled tank: the longest part of a run not to do again
          // Kept as it is: copied as checkpoint.h5 into the directory of a run of the same input
          // but for its Pull settings, --resume pulls this tank (bench/run_pullout_rate_check).
          std::filesystem::copy_file(checkpoint_file, out / "filled_tank.h5",
                                     std::filesystem::copy_options::overwrite_existing);
        }
    }
  if (!pull_with_checkpoints(
        *pull, [&](const dem::PullPoint &p) { record(p, system); }, save_checkpoint, checkpoint_interval, stop_after,
        checkpoint_file))
    return 0; // stopped as 'stop after steps' asks: continued with --resume
  pull->stop_clamp();
  progress.finish();
  fields->finish();
  forces->finish();

  // 3. The plot, with the experimental T_max as a horizontal line if given, and the summary.
  output->finish("DEM", in.references, in.pull.final_displacement);
  const double T_max = output->max_head_tension(), u_at_T_max = output->head_displacement_at_max();
  if (checkpoint_interval > 0.0)
    save_checkpoint(); // the finished pull: a later --resume has nothing left to do but the files
  const double wall_time = start.earlier_wall_time + clock.seconds();
  write_dem_summary(prm, in, start, *output, pull->progress().n_steps, u_first, wall_time, warnings, watch.warnings(), out);
  std::cout << "geohybrid pullout: T_max = " << number(T_max / 1e3, 4) << " kN/m (" << number(T_max * g.sheet_width / 1e3, 4)
            << " kN for b = " << number(g.sheet_width, 3) << " m) at " << number(1e3 * u_at_T_max, 3) << " mm"
            << experiment_text(in.references) << "; " << number(wall_time, 4) << " s\n"
            << demonstration_lines(in.references) << "results in " << out.string() << '\n';
  return 0;
}
} // namespace geohybrid::apps
