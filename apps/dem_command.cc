// `geohybrid dem`: a scene of discs or two-disc clusters in a box, generated on a loose lattice
// and deposited under gravity, or read from CSV; any number of extra walls. It writes
//   time_series.csv      energies, coordination, unbalanced force, wall forces, per output step
//   particle_history.csv time, id, x, y, rotation, vx, vy, omega of the chosen particles
//   particles.h5/.xdmf   snapshots for ParaView (positions, radii, velocities, contact forces)
//   final_particles.csv  the end state in the input CSV format (to reuse a deposited packing)
//   parameters.prm       the resolved input;  summary.json  written last
//   checkpoint.h5        the complete state, every 'checkpoint interval' s of wall-clock time and at
//                        the end; `geohybrid dem FILE --resume` continues from it (see run_dem_command)
#include "dem_command.h"

#include "contact_parameters.h"
#include "interrupt.h"
#include "plot.h"
#include "resume_check.h"
#include "run_directory.h"
#include "run_health.h"

#include "dem/dem_system.h"
#include "dem/io/checked_output.h"
#include "dem/io/checkpoint.h"
#include "dem/io/particle_csv.h"
#include "dem/io/snapshot_writer.h"
#include "dem/laboratory/packing.h"
#include "dem/measurements.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace geohybrid::apps
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_dem_parameters(ParameterHandler &prm)
{
  prm.declare_entry("output directory", "output/dem", Patterns::Anything(),
                    "Directory for all results, created if needed, relative to the working directory");
  prm.declare_entry("threads", "2", Patterns::Integer(1, 256),
                    "Number of threads; results are identical for any number [-]");

  prm.enter_subsection("Particles");
  prm.declare_entry("source", "generate", Patterns::Selection("generate|csv"),
                    "generate: a loose lattice deposited under gravity; csv: read from 'csv file'");
  prm.declare_entry("csv file", "", Patterns::Anything(),
                    "Particle CSV (x,y,radius,vx,vy,omega[,cluster_id]), relative to the input file's directory");
  prm.declare_entry("csv overlap tolerance", "0.01", Patterns::Double(0.0, 1.0),
                    "Largest overlap allowed between CSV particles, as a fraction of the smaller radius [-]");
  prm.declare_entry("density", "2650", Patterns::Double(1e-9),
                    "Solid density of the particles [kg/m^3]");
  prm.declare_entry("shape", "disc", Patterns::Selection("disc|two-disc cluster"),
                    "Generated particle shape: a disc, or a rigid cluster of discs of diameters d and ratio*d");
  prm.declare_entry("number of particles", "10000", Patterns::Integer(1), "Generated particles [-]");
  prm.declare_entry("minimum radius", "1.5e-3", Patterns::Double(1e-9),
                    "Smallest radius of a generated (large) disc [m]");
  prm.declare_entry("maximum radius", "2.5e-3", Patterns::Double(1e-9),
                    "Largest radius of a generated (large) disc [m]");
  prm.declare_entry("cluster diameter ratio", "0.9", Patterns::Double(0.1, 1.0),
                    "Small over large disc diameter in a cluster (0.9 in the reference paper) [-]");
  prm.declare_entry("cluster centre spacing", "0.95", Patterns::Double(0.01, 0.95),
                    "Distance between a cluster's disc centres over the large diameter; 0.95 = the two "
                    "discs (d and 0.9 d) touch [-]");
  prm.declare_entry("seed", "1", Patterns::Integer(0), "Seed of the random sizes and orientations [-]");
  prm.leave_subsection();

  prm.enter_subsection("Box");
  prm.declare_entry("width", "1.0", Patterns::Double(1e-9), "Inner width between the side walls [m]");
  prm.declare_entry("height", "1.0", Patterns::Double(1e-9), "Height of the side walls above the floor [m]");
  prm.declare_entry("top wall", "false", Patterns::Bool(), "Close the box with a fixed top wall [-]");
  prm.declare_entry("extra walls", "", Patterns::Anything(),
                    "More walls, separated by ';', each 'x0 y0 x1 y1 vx vy' (active side on the left of "
                    "start->end, velocity prescribed) [m, m/s]");
  prm.leave_subsection();

  prm.enter_subsection("Particle contact");
  declare_contact_parameters(prm, dem::ContactParameters{});
  prm.leave_subsection();
  prm.enter_subsection("Wall contact");
  dem::ContactParameters wall_defaults;
  wall_defaults.friction_angle_deg = 28.0; // soil/wall friction of the reference paper
  declare_contact_parameters(prm, wall_defaults);
  prm.leave_subsection();

  prm.enter_subsection("Simulation");
  prm.declare_entry("gravity", "9.81", Patterns::Double(0.0), "Gravitational acceleration, along -y [m/s^2]");
  prm.declare_entry("local damping coefficient", "0.7", Patterns::Double(0.0, 0.99),
                    "PFC local non-viscous damping alpha; 0 for true dynamics [-]");
  prm.declare_entry("time step", "0", Patterns::Double(0.0),
                    "Time step; 0 = safety factor x critical step; a value above the critical step is refused [s]");
  prm.declare_entry("time step safety factor", "0.5", Patterns::Double(0.01, 1.0),
                    "Fraction of the critical time step used when 'time step' is 0 [-]");
  prm.declare_entry("end time", "0.5", Patterns::Double(0.0), "Simulated duration [s]");
  prm.declare_entry("output interval", "0.005", Patterns::Double(0.0),
                    "Interval of time_series.csv and particle_history.csv rows [s]");
  prm.declare_entry("snapshot interval", "0.05", Patterns::Double(0.0),
                    "Interval of HDF5/XDMF snapshots; 0 = first and last only [s]");
  prm.declare_entry("history particles", "", Patterns::Anything(),
                    "Particle ids (comma separated) written to particle_history.csv, 'all', or empty for none");
  prm.declare_entry("checkpoint interval", "300", Patterns::Double(0.0),
                    "Wall-clock time between checkpoints (OUTPUT/checkpoint.h5, also written at the end; "
                    "continue with 'geohybrid dem FILE --resume'); 0 = never [s]");
  prm.leave_subsection();
}

namespace
{
std::vector<std::vector<double>> parse_walls(const std::string &text)
{
  std::vector<std::vector<double>> walls;
  std::stringstream all(text);
  std::string one;
  while (std::getline(all, one, ';'))
    {
      if (one.find_first_not_of(" \t") == std::string::npos)
        continue;
      std::istringstream fields(one);
      std::vector<double> v(6);
      for (double &x : v)
        if (!(fields >> x))
          throw std::invalid_argument("parameter 'Box/extra walls': '" + one +
                                      "' is not 'x0 y0 x1 y1 vx vy'");
      walls.push_back(v);
    }
  return walls;
}

std::vector<std::size_t> parse_history_ids(const std::string &text, std::size_t n_bodies)
{
  std::vector<std::size_t> ids;
  if (text == "all")
    {
      for (std::size_t b = 0; b < n_bodies; ++b)
        ids.push_back(b);
      return ids;
    }
  for (const std::string &item : dealii::Utilities::split_string_list(text, ','))
    {
      if (item.empty())
        continue;
      const int id = dealii::Utilities::string_to_int(item);
      if (id < 0 || static_cast<std::size_t>(id) >= n_bodies)
        throw std::invalid_argument("parameter 'Simulation/history particles': id " + item +
                                    " does not exist (there are " + std::to_string(n_bodies) + " particles)");
      ids.push_back(static_cast<std::size_t>(id));
    }
  return ids;
}
} // namespace

int run_dem_command(const std::string &input_file, bool resume)
{
  ParameterHandler prm;
  declare_dem_parameters(prm);
  parse_input_file(prm, input_file);
  const std::filesystem::path input_directory = std::filesystem::path(input_file).parent_path();
  const std::string where = "input file '" + input_file + "'";

  // ---- everything is read and checked before anything is written ----
  const int n_threads = prm.get_integer("threads");
  prm.enter_subsection("Box");
  const double width = prm.get_double("width");
  const double height = prm.get_double("height");
  const bool top_wall = prm.get_bool("top wall");
  const auto extra_walls = parse_walls(prm.get("extra walls"));
  prm.leave_subsection();

  prm.enter_subsection("Particles");
  const double density = prm.get_double("density");
  dem::ParticleSet particles;
  if (prm.get("source") == "csv")
    {
      std::filesystem::path csv = prm.get("csv file");
      if (csv.empty())
        throw std::invalid_argument(where + ": 'Particles/source' is csv but 'csv file' is empty");
      if (csv.is_relative())
        csv = input_directory / csv;
      particles = dem::read_particle_csv(csv, density, prm.get_double("csv overlap tolerance"));
    }
  else
    {
      dem::LooseLatticeSpec spec;
      spec.n_particles = static_cast<std::size_t>(prm.get_integer("number of particles"));
      spec.x_min = 0.0;
      spec.x_max = width;
      spec.y_min = 0.0;
      spec.radius_min = prm.get_double("minimum radius");
      spec.radius_max = prm.get_double("maximum radius");
      if (spec.radius_max < spec.radius_min)
        throw std::invalid_argument(where + ": 'Particles/maximum radius' is below 'minimum radius'");
      spec.density = density;
      spec.shape = prm.get("shape") == "disc" ? dem::ParticleShape::disc : dem::ParticleShape::two_disc_cluster;
      spec.cluster_diameter_ratio = prm.get_double("cluster diameter ratio");
      spec.cluster_spacing = prm.get_double("cluster centre spacing");
      spec.seed = static_cast<std::uint64_t>(prm.get_integer("seed"));
      particles = dem::make_loose_lattice(spec);
    }
  prm.leave_subsection();

  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    if (particles.x[b] < 0.0 || particles.x[b] > width || particles.y[b] < 0.0 ||
        (top_wall && particles.y[b] > height))
      throw std::invalid_argument(where + ": particle " + std::to_string(particles.body_id[b]) +
                                  " lies outside the box ('Box/width', 'Box/height'); enlarge the box or "
                                  "use fewer particles");

  prm.enter_subsection("Particle contact");
  const dem::LinearContactLaw particle_law(parse_contact_parameters(prm, where + ", subsection 'Particle contact'"));
  prm.leave_subsection();
  prm.enter_subsection("Wall contact");
  const dem::LinearContactLaw wall_law(parse_contact_parameters(prm, where + ", subsection 'Wall contact'"));
  prm.leave_subsection();

  prm.enter_subsection("Simulation");
  dem::DemSettings settings;
  settings.gravity = dem::Vec2(0.0, -prm.get_double("gravity"));
  settings.local_damping = prm.get_double("local damping coefficient");
  settings.time_step = prm.get_double("time step");
  settings.time_step_safety = prm.get_double("time step safety factor");
  settings.n_threads = n_threads;
  const double end_time = prm.get_double("end time");
  const double output_interval = prm.get_double("output interval");
  const double snapshot_interval = prm.get_double("snapshot interval");
  const std::string history_text = prm.get("history particles");
  const double checkpoint_interval = prm.get_double("checkpoint interval");
  prm.leave_subsection();

  dem::DemSystem system = [&] {
    try
      {
        dem::DemSystem s(std::move(particles), particle_law, settings);
        // Active side on the left of start -> end (dem/wall.h): the box is walked clockwise.
        s.add_wall(dem::Wall("floor", dem::Vec2(0.0, 0.0), dem::Vec2(width, 0.0), wall_law));
        s.add_wall(dem::Wall("left", dem::Vec2(0.0, height), dem::Vec2(0.0, 0.0), wall_law));
        s.add_wall(dem::Wall("right", dem::Vec2(width, 0.0), dem::Vec2(width, height), wall_law));
        if (top_wall)
          s.add_wall(dem::Wall("top", dem::Vec2(width, height), dem::Vec2(0.0, height), wall_law));
        for (std::size_t k = 0; k < extra_walls.size(); ++k)
          {
            const auto &w = extra_walls[k];
            dem::Wall wall("extra_" + std::to_string(k), dem::Vec2(w[0], w[1]), dem::Vec2(w[2], w[3]), wall_law);
            wall.velocity = dem::Vec2(w[4], w[5]);
            s.add_wall(wall);
          }
        return s;
      }
    catch (const std::invalid_argument &e)
      {
        throw std::invalid_argument(where + ": " + e.what());
      }
  }();
  const std::vector<std::size_t> history = parse_history_ids(history_text, system.particles().n_bodies());
  if (!resume)
    check_particle_speeds(system, where); // grains the time step cannot follow (run_health.h)

  // The energy at t = 0 (the reference of the energy balance), also when resuming: the system
  // is built from the same input as the run that wrote the checkpoint.
  const dem::EnergyBudget energy_start = system.energy();
  const std::filesystem::path out = prm.get("output directory");
  if (out.empty())
    throw std::invalid_argument(where + ": parameter 'output directory' is empty");
  const std::filesystem::path checkpoint_file = out / "checkpoint.h5";
  ParameterHandler defaults;
  declare_dem_parameters(defaults);
  if (resume)
    {
      if (!std::filesystem::exists(checkpoint_file))
        throw std::runtime_error("cannot resume: there is no checkpoint '" + checkpoint_file.string() +
                                 "' (runs write one every 'Simulation/checkpoint interval' seconds and at their end)");
      dem::CommandState saved;
      dem::DemSystemState state = dem::read_checkpoint(checkpoint_file, saved);
      check_resumed_input(saved, prm, defaults, dem_resume_entries(), checkpoint_file, where, "geohybrid dem");
      try
        {
          system.restore_state(std::move(state));
        }
      catch (const std::invalid_argument &e)
        {
          throw std::invalid_argument("checkpoint '" + checkpoint_file.string() + "' does not fit " + where + ": " +
                                      e.what());
        }
    }
  else if (particle_law.parameters().shear_strength > 0.0 || particle_law.parameters().tensile_strength > 0.0)
    system.bond_touching_contacts(); // PFC-style contact bonds on the initial contacts
  const std::uint64_t first_step = system.step_count(); // 0, or the checkpoint's step
  const double resumed_from_time = system.time();
  const std::uint64_t n_steps = static_cast<std::uint64_t>(std::ceil(end_time / system.time_step() - 1e-9));
  if (first_step > n_steps)
    throw std::invalid_argument(where + ": 'Simulation/end time' (" + std::to_string(end_time) +
                                " s) is before the time of the checkpoint (" + std::to_string(resumed_from_time) +
                                " s)");
  const std::uint64_t output_every =
    output_interval > 0.0 ? std::max<std::uint64_t>(1, std::llround(output_interval / system.time_step())) : n_steps + 1;
  const std::uint64_t snapshot_every =
    snapshot_interval > 0.0 ? std::max<std::uint64_t>(1, std::llround(snapshot_interval / system.time_step())) : n_steps + 1;
  // Output happens at these steps (the last one always); a resumed run continues the files with
  // the rows and snapshots a straight run would have written up to the checkpoint, dropping an
  // end-of-run row of the earlier run that is not on this run's grid, and those after the checkpoint.
  const auto output_at = [&](std::uint64_t k, std::uint64_t every) { return k % every == 0 || k == n_steps; };
  const auto keep_until = [&](std::uint64_t every) -> std::optional<double> {
    if (!resume)
      return std::nullopt;
    const double half_step = 0.5 * system.time_step(); // rows are written rounded: compare with slack
    return output_at(first_step, every) ? resumed_from_time + half_step : resumed_from_time - half_step;
  };

  // ---- run ----
  prepare_output_directory(out.string(), resume);
  write_resolved_parameters(prm, out);
  if (!resume)
    std::filesystem::remove(checkpoint_file); // a stale one from an earlier run must not be resumed
  std::string series_header =
    "time,kinetic_energy,gravitational_energy,elastic_energy,friction_dissipated,viscous_dissipated,"
    "local_damping_dissipated,boundary_work,energy_balance_error,coordination_number,"
    "unbalanced_force_ratio,n_contacts,broken_bonds";
  for (const dem::Wall &w : system.walls())
    series_header += ",wall_" + w.name + "_fx,wall_" + w.name + "_fy";
  std::ofstream series = open_csv_rows(out / "time_series.csv", series_header, keep_until(output_every));
  series << std::setprecision(10);
  std::ofstream history_out;
  if (!history.empty())
    {
      history_out = open_csv_rows(out / "particle_history.csv", "time,id,x,y,rotation,vx,vy,omega",
                                  keep_until(output_every));
      history_out << std::setprecision(12);
    }
  dem::SnapshotWriter snapshots = resume ? dem::SnapshotWriter::resume(out, "particles", *keep_until(snapshot_every))
                                         : dem::SnapshotWriter(out, "particles");

  // The run's watch (run_health.h), at each row before it is written: a row of a run gone wrong
  // is not written, the run stops without summary.json.
  DemRunWatch watch(width, height, top_wall);
  const auto write_rows = [&] {
    const dem::EnergyBudget e = system.energy();
    const double balance_error = dem::energy_balance_error(energy_start, e);
    watch.check(system, e, balance_error);
    series << system.time() << ',' << e.kinetic << ',' << e.gravitational << ',' << e.elastic << ','
           << e.friction_dissipated << ',' << e.viscous_dissipated << ',' << e.local_damping_dissipated << ','
           << e.boundary_work << ',' << balance_error << ','
           << dem::coordination_number(system) << ',' << dem::unbalanced_force_ratio(system) << ','
           << system.n_touching_pairs() << ',' << system.n_broken_bonds();
    for (const dem::Wall &w : system.walls())
      series << ',' << w.force_from_particles.x() << ',' << w.force_from_particles.y();
    series << '\n';
    const dem::ParticleSet &p = system.particles();
    for (std::size_t b : history)
      history_out << system.time() << ',' << p.body_id[b] << ',' << p.x[b] << ',' << p.y[b] << ','
                  << p.rotation[b] << ',' << p.vx[b] << ',' << p.vy[b] << ',' << p.omega[b] << '\n';
    // Flushed at every row: a run killed later keeps them, and a full disk stops the run here,
    // naming the file.
    dem::flush_checked(series, out / "time_series.csv");
    if (history_out.is_open())
      dem::flush_checked(history_out, out / "particle_history.csv");
  };
  // The rows up to the checkpoint are in the files already (write_rows flushes them), so that
  // a resumed run finds them.
  // The input beside the state: a --resume with other physics is refused (resume_check.h).
  dem::CommandState input;
  input.name = "dem";
  store_input(prm, defaults, input);
  const auto save_checkpoint = [&] { dem::write_checkpoint(system.export_state(), input, checkpoint_file); };

  const auto wall_start = std::chrono::steady_clock::now();
  std::cout << "geohybrid dem: " << system.particles().n_bodies() << " particles ("
            << system.particles().n_discs_total() << " discs), time step " << system.time_step()
            << " s (critical " << system.critical_time_step() << " s), " << n_steps << " steps, "
            << n_threads << " thread(s)\n";
  if (resume)
    std::cout << "geohybrid dem: resuming from t = " << resumed_from_time << " s (step " << first_step << ") of "
              << checkpoint_file.string() << '\n';

  if (!resume)
    {
      write_rows();
      snapshots.write(system);
    }
  WallClockInterval checkpoint_due(checkpoint_interval);
  ProgressReport progress("dem", static_cast<double>(n_steps - first_step));
  for (std::uint64_t k = first_step + 1; k <= n_steps; ++k)
    {
      system.step();
      if (output_at(k, output_every))
        write_rows();
      if (output_at(k, snapshot_every))
        snapshots.write(system);
      if (checkpoint_due.due())
        save_checkpoint();
      if (k % 256 == 0)
        progress.update(static_cast<double>(k - first_step));
      // A signal (interrupt.h): this step done, a checkpoint whatever the interval, so that
      // --resume goes on bit for bit; no final_particles.csv, no summary.json.
      if (const int signal = interrupt_signal(); signal != 0 && k < n_steps)
        {
          save_checkpoint();
          std::cerr << '\n';
          throw Interrupted(signal,
                            "at t = " + number(system.time(), 6) + " s (step " + std::to_string(k) + " of " +
                              std::to_string(n_steps) + "): the checkpoint " + checkpoint_file.string() +
                              " and the time series so far are written, no summary.json",
                            true);
        }
    }
  progress.finish();
  if (checkpoint_interval > 0.0)
    save_checkpoint();
  const double wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  dem::write_particle_csv(system.particles(), out / "final_particles.csv");
  dem::close_checked(series, out / "time_series.csv");
  if (history_out.is_open())
    dem::close_checked(history_out, out / "particle_history.csv");

  const dem::EnergyBudget e = system.energy();
  const double height_of_packing = [&] {
    double top = 0.0;
    for (std::size_t d = 0; d < system.particles().n_discs_total(); ++d)
      top = std::max(top, system.particles().disc_y[d] + system.particles().disc_radius[d]);
    return top;
  }();
  const dem::Region bulk{0.1 * width, 0.1 * height_of_packing, 0.9 * width, 0.8 * height_of_packing};
  const auto stress = dem::love_weber_stress(system, bulk);
  Summary summary;
  summary.set("command", "dem");
  summary.set("n_particles", static_cast<double>(system.particles().n_bodies()));
  summary.set("n_discs", static_cast<double>(system.particles().n_discs_total()));
  summary.set("time_step_s", system.time_step());
  summary.set("critical_time_step_s", system.critical_time_step());
  summary.set("n_steps", static_cast<double>(n_steps));
  summary.set("end_time_s", system.time());
  summary.set("wall_time_s", wall_time);
  summary.set("threads", n_threads);
  summary.set("particle_steps_per_second",
              static_cast<double>(n_steps - first_step) * system.particles().n_bodies() / wall_time);
  summary.set("resumed_from_time_s", resume ? resumed_from_time : std::nan("")); // null for a fresh run
  summary.set("kinetic_energy_J_per_m", e.kinetic);
  summary.set("energy_balance_error_relative", dem::energy_balance_error(energy_start, e));
  summary.set("energy_balance_error_relative_definition",
              "the change of the energy budget's total since t = 0 (kinetic + gravitational + elastic + dissipated "
              "- boundary work) over the largest magnitude of its terms at t = 0 or at the end "
              "(dem::energy_balance_error); the time series' column is the same at each row");
  summary.set("coordination_number", dem::coordination_number(system));
  summary.set("unbalanced_force_ratio", dem::unbalanced_force_ratio(system));
  summary.set("packing_height_m", height_of_packing);
  summary.set("porosity_bulk", dem::porosity(system, bulk));
  summary.set("stress_xx_bulk_Pa", stress[0]);
  summary.set("stress_yy_bulk_Pa", stress[1]);
  summary.set("stress_xy_bulk_Pa", stress[2]);
  summary.set("floor_normal_stress_Pa", system.walls()[0].normal_stress());
  report_warnings(watch.warnings(), "geohybrid dem", summary, std::cerr);
  const std::filesystem::path series_csv = out / "time_series.csv";
  plot_png(out / "time_series.png", "DEM run: energy and contacts",
           {PlotPanel{"time [s]", "kinetic energy [J/m]", {PlotSeries{series_csv, 1, 2, "kinetic"}}},
            PlotPanel{"time [s]", "coordination number [-]", {PlotSeries{series_csv, 1, 10, "coordination"}}},
            PlotPanel{"time [s]", "energy balance error [-]", {PlotSeries{series_csv, 1, 9, "relative error"}}}});
  summary.write(out / "summary.json");
  std::cout << "geohybrid dem: done in " << std::fixed << std::setprecision(1) << wall_time
            << " s; results in " << out.string() << " (summary.json, time_series.csv, particles.xdmf)\n";
  return 0;
}
} // namespace geohybrid::apps
