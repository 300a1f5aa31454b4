// `geohybrid pullout`: the pull-out test of the reference paper (sections 4.3-4.5). In dem mode the tank is
// filled in layers with the calibrated soil, the sheet laid at its depth on the lift below it;
// then the clamp, outside the front wall, pulls the sheet horizontally at a set rate and the run
// records the head tension (the clamp's reaction) against the head displacement.
//
// Before pulling, the run measures the normal stress the soil applies to the sheet (on its top
// and bottom faces, and Love-Weber in a band of soil above it) and reports it against gamma H:
// side-wall friction carries part of the weight, and the sheet lies a little above its nominal
// level (on the grains of the lift below), so sigma_v < gamma H is expected.
//
// mode = dem is this file (below); mode = fem, the same test with a deal.II continuum for the
// soil, is pullout_fem_mode.cc; mode = hybrid, particles round the sheet and the continuum
// elsewhere, is pullout_hybrid_mode.cc. All read this input (declare_pullout_parameters, parse_pullout)
// and write the same files through apps/pullout_output.h, plus parameters.prm and summary.json
// (written last). In dem mode, also the soil's fields at 'Output/field outputs at'
// (pullout_field_output.h): pullout_fields.h5/.xdmf, grain_displacements_u*mm.csv/.png,
// force_network_u*mm.csv/.png, surface_uplift.csv/.png.
//
// Long runs (dem mode): checkpoint.h5 holds the whole run (the system, the tank's description, the
// pull's progress, every row recorded, the field outputs' schedule and reference); it is written
// when the tank is full (and copied to filled_tank.h5), every 'checkpoint interval' s of wall
// time and at the end. `geohybrid pullout FILE --resume` continues from it, bit for bit; without
// one (the run stopped while filling) it fills the tank again and says so.
//
// Every mode's summary.json holds `parameters_hash`, the hash of the resolved input without its
// run-control entries (apps/parameters_hash.h); `--print-parameters-hash` (check_pullout_input)
// reads and checks an input as a run does, each mode stopping before its first file.
#include "pullout_command.h"

#include "contact_parameters.h"
#include "parameters_hash.h"
#include "interrupt.h"
#include "pullout_fem_mode.h"
#include "pullout_hybrid_mode.h"
#include "pullout_field_output.h"
#include "pullout_input.h"
#include "pullout_forces_output.h"
#include "pullout_output.h"
#include "pull_watch.h"
#include "resume_check.h"
#include "run_health.h"
#include "run_directory.h"

#include <deal.II/base/mpi.h>

#include "dem/measurements.h"
#include "dem/pullout_tank.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <locale>
#include <optional>
#include <sstream>
#include <unistd.h>

namespace geohybrid::apps
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_pullout_parameters(ParameterHandler &prm)
{
  const dem::PullOutGeometry g;
  const dem::SheetParameters sheet;
  const dem::TankFillingSpec fill;
  const dem::PullSpec pull;
  const auto text = [](double v) { return number(v); };
  prm.declare_entry("output directory", "output/pullout", Patterns::Anything(),
                    "Directory for all results, created if needed, relative to the working directory");
  prm.declare_entry("threads", "2", Patterns::Integer(1, 256),
                    "Number of OpenMP threads of the particles; dem and hybrid modes (fem mode runs on the MPI ranks "
                    "of mpirun) [-]");
  prm.declare_entry("checkpoint interval", "300", Patterns::Double(0.0),
                    "dem and hybrid modes: wall-clock time between checkpoints (OUTPUT/checkpoint.h5: the filled tank, the pull, "
                    "the rows recorded; one is also written when the tank is full; hybrid mode: OUTPUT/filled_box.h5 "
                    "when the box is full, then checkpoint.h5 with the continuum's state, the set-up repeated from the "
                    "box on resuming); continue an interrupted run with 'geohybrid pullout FILE --resume'; 0 = never [s]");
  prm.declare_entry("stop after steps", "0", Patterns::Integer(0),
                    "dem and hybrid modes: stop the pull after this many time steps of this invocation, writing a checkpoint "
                    "(to split a long run into jobs, each continued with --resume); 0 = run to the end [-]");
  prm.declare_entry("mode", "dem", Patterns::Selection("dem|fem|hybrid"),
                    "Soil model: dem (discrete elements everywhere, subsections Filling and Soil/Particle contact); "
                    "fem (a deal.II continuum, subsection Continuum); hybrid (particles in a box round the sheet, "
                    "the continuum elsewhere: the input of dem mode plus subsection Hybrid and the soil of "
                    "subsection Continuum; no field outputs). All modes write the same curve "
                    "files [-]");

  prm.enter_subsection("Tank");
  prm.declare_entry("length", text(g.tank_length), Patterns::Double(1e-6),
                    "Inner length from the back wall to the front wall; the INSA tank's length is not given in the "
                    "paper's text, 1.5 m is this model's choice [m]");
  prm.declare_entry("fill height", text(g.fill_height), Patterns::Double(1e-6),
                    "Height of the soil surface above the base (H plus the soil below the sheet) [m]");
  prm.declare_entry("wall friction angle", text(g.wall_friction_deg), Patterns::Double(0.0, 89.99),
                    "Soil-wall friction angle (measured: 28 degrees, section 4.3); dem and hybrid modes (the continuum's "
                    "walls are smooth) [deg]");
  prm.declare_entry("clamp offset", text(g.clamp_offset), Patterns::Double(1e-6),
                    "Distance of the clamp (the sheet's first node) outside the front wall; dem and hybrid modes (the "
                    "continuum's clamp is the sheet's node at the front wall) [m]");
  prm.leave_subsection();

  prm.enter_subsection("Anchorage");
  prm.declare_entry("type", "simple run-out", Patterns::Selection("simple run-out|wrap-around"),
                    "Simple run-out (L, H) or wrap-around (L, D1, D2, B, H = D1 + D2), section 2.2; fem mode lays the "
                    "wrap-around's corners as arcs of twice 'Continuum/sheet node spacing' [-]");
  prm.declare_entry("H", text(g.cover), Patterns::Double(1e-6), "Soil above the lower part of the sheet [m]");
  prm.declare_entry("L", text(g.anchorage_length), Patterns::Double(1e-6),
                    "Length of the lower part of the sheet in the soil, from the front wall [m]");
  prm.declare_entry("D1", text(g.return_height), Patterns::Double(0.0),
                    "Wrap-around: height of the vertical return [m]");
  prm.declare_entry("D2", text(g.upper_cover), Patterns::Double(0.0),
                    "Wrap-around: soil above the upper part [m]");
  prm.declare_entry("B", text(g.upper_length), Patterns::Double(0.0),
                    "Wrap-around: length of the upper part, from the return towards the front wall [m]");
  prm.leave_subsection();

  prm.enter_subsection("Sheet");
  prm.declare_entry("width", text(g.sheet_width), Patterns::Double(1e-6),
                    "b, width of the sheet in the bench, for the per-sheet outputs (INSA: 0.5 m) [m]");
  prm.declare_entry("axial stiffness", text(sheet.axial_stiffness), Patterns::Double(1e-6),
                    "J per metre of width (GT230: 2104 kN/m, GT75: 687 kN/m, Table 2) [N/m]");
  prm.declare_entry("thickness", text(sheet.thickness), Patterns::Double(1e-9), "For contact (GT230: 3.2 mm); dem and hybrid modes (the continuum's sheet has no thickness) [m]");
  prm.declare_entry("areal mass", text(sheet.areal_mass), Patterns::Double(1e-9),
                    "Mass per unit area (GT230: 620 g/m2) [kg/m^2]");
  prm.declare_entry("segment length", "0.01", Patterns::Double(1e-6),
                    "Longest spar element; dem and hybrid modes (fem: 'Continuum/sheet node spacing') [m]");
  prm.enter_subsection("Interface");
  declare_contact_parameters(prm, dem::default_interface_parameters());
  prm.leave_subsection();
  prm.leave_subsection();

  prm.enter_subsection("Soil");
  prm.declare_entry("unit weight", "15.2e3", Patterns::Double(1e-6),
                    "gamma of the soil at the fill's porosity (sand 1: 15.2 kN/m3, Table 1); sets the grains' "
                    "density gamma / (g (1 - n)) in dem mode, the continuum's density gamma / g in fem mode, both in "
                    "hybrid mode [N/m^3]");
  prm.enter_subsection("Particle contact");
  declare_contact_parameters(prm, dem::ContactParameters());
  prm.leave_subsection();
  prm.leave_subsection();

  prm.enter_subsection("Filling");
  prm.declare_entry("number of particles", "20000", Patterns::Integer(2), "Particles in the whole fill [-]");
  prm.declare_entry("number of layers", "6", Patterns::Integer(2),
                    "Lifts of equal thickness; one boundary must lie at the sheet level (fill height - H) [-]");
  prm.declare_entry("shape", "two-disc cluster", Patterns::Selection("disc|two-disc cluster"),
                    "Particle shape; the paper uses clusters of two discs of diameters d and 0.9 d");
  prm.declare_entry("size ratio", "0.5", Patterns::Double(0.05, 1.0),
                    "Smallest over largest particle size (uniform distribution) [-]");
  prm.declare_entry("target porosity", text(fill.target_porosity), Patterns::Double(0.05, 0.8),
                    "2D porosity of every layer (Table 5: 0.2) [-]");
  prm.declare_entry("porosity tolerance", text(fill.porosity_tolerance), Patterns::Double(1e-6, 0.1),
                    "Accepted porosity error [-]");
  prm.declare_entry("growth stress", text(fill.growth_stress), Patterns::Double(1e-6),
                    "Lid stress at which a growing layer counts as jammed (compaction of a lift) [Pa]");
  prm.declare_entry("local damping", text(fill.local_damping), Patterns::Double(0.0, 0.99),
                    "PFC local damping while filling and pulling [-]");
  prm.declare_entry("equilibrium unbalanced ratio", text(fill.equilibrium_unbalanced_ratio),
                    Patterns::Double(1e-9, 0.1), "Settling stops below this unbalanced-force ratio [-]");
  prm.declare_entry("growth friction of later lifts", fill.later_lifts_start_near_the_lift_below ? "near the lift below" : "as the first",
                    Patterns::Selection("near the lift below|as the first"),
                    "REDF's growth friction at the start of each lift after the first (of the same porosity): one step "
                    "above the friction the lift below ended its growth at (a 6,000-cluster wrap-around tank: its later "
                    "lifts in a tenth of the growth steps), or the material's, as the first lift starts");
  prm.declare_entry("seed", "1", Patterns::Integer(0), "Seed of the random fill [-]");
  prm.declare_entry("lift cache directory", "", Patterns::Anything(),
                    "dem and hybrid modes: the lifts below the sheet, once grown and settled, are kept in this directory "
                    "(relative to the working directory) and taken from it by any run that starts them from the same "
                    "state: the cases of one tank and seed that differ above them (B, D1, the geosynthetic, the "
                    "interface) share them, with the same numbers bit for bit; empty = none. It steers the run only "
                    "(not in parameters_hash) [-]");
  prm.leave_subsection();

  prm.enter_subsection("Pull");
  prm.declare_entry("rate", text(pull.rate), Patterns::Double(1e-9), "Clamp speed [m/s]");
  prm.declare_entry("final displacement", text(pull.final_displacement), Patterns::Double(1e-9),
                    "Head displacement at the end [m]");
  prm.declare_entry("record interval", text(pull.record_interval), Patterns::Double(1e-9),
                    "Head displacement between two points of the curve (each the mean over its interval) [m]");
  prm.declare_entry("ramp displacement", text(pull.ramp_displacement), Patterns::Double(0.0),
                    "The clamp's speed rises linearly from 0 to the rate over this head displacement, so that "
                    "the start does not jerk the sheet [m]");
  prm.declare_entry("sheet local damping", text(pull.sheet_local_damping), Patterns::Double(0.0, 0.99),
                    "Local damping of the sheet's nodes while pulling (the grains keep 'Filling/local damping'): "
                    "damping a sheet that slides one way through fluctuating contacts drags it whatever the rate, "
                    "so 0 by default; dem and hybrid modes (fem: 'Continuum/local damping' acts on soil and sheet) [-]");
  prm.declare_entry("grain local damping", "", Patterns::Anything(),
                    "Local damping of the grains while pulling; empty: 'Filling/local damping'. The damping's drag "
                    "on grains that keep moving one way grows with the pull rate (bench/RESULTS.md) [-]");
  prm.declare_entry("tension profiles at", "0.006, 0.06", Patterns::List(Patterns::Double(0.0)),
                    "Head displacements at which the tension along the sheet is written [m]");
  prm.leave_subsection();

  prm.enter_subsection("Output");
  prm.declare_entry("experimental T_max", "", Patterns::Anything(),
                    "Measured maximum head tension to mark on the plot; empty = none [kN/m]");
  prm.declare_entry("field outputs at", "0.006, 0.06", Patterns::List(Patterns::Double(0.0), 0, 100),
                    "Head displacements at which the grains' displacements since the start of the pull, the "
                    "contact-force network, an HDF5/XDMF snapshot and the surface uplift are written (the "
                    "paper's Figures 10-12); empty = none; dem mode only (hybrid mode writes none yet) [m]");
  prm.declare_entry("demonstration", "", Patterns::Anything(),
                    "Empty: the run is a result. Otherwise it is only a demonstration of the workflow (made small or "
                    "soft to run in minutes), and this says why: it heads the plot and is written to summary.json, "
                    "so that its T_max is not taken for the model's answer [-]");
  prm.declare_entry("full-size runs", "", Patterns::Anything(),
                    "Directory of finished runs of the same case at full size, one per seed (seed1, seed2, ... as "
                    "validation/runs/CASE, or seed_1, ... of 'pullout --seeds'), relative to the working directory: "
                    "their mean curve is drawn beside this run's and their T_max written to summary.json; empty = none");
  prm.declare_entry("stress band", "0.05", Patterns::Double(1e-6),
                    "Height of the soil band above the sheet where the Love-Weber vertical stress is measured; dem "
                    "and hybrid modes [m]");
  prm.leave_subsection();

  declare_continuum_parameters(prm);
  declare_hybrid_parameters(prm);
}

std::string anchorage_description(const dem::PullOutGeometry &g)
{
  std::string text = anchorage_name(g) + ", H = " + number(g.cover, 4) + " m, L = " + number(g.anchorage_length, 4) + " m";
  if (g.anchorage == dem::Anchorage::wrap_around)
    text += ", D1 = " + number(g.return_height, 4) + " m, B = " + number(g.upper_length, 4) + " m";
  return text;
}

PullOutInput parse_pullout(ParameterHandler &prm, const std::string &where, bool dem_mode)
{
  PullOutInput in;
  dem::PullOutGeometry &g = in.tank.geometry;
  prm.enter_subsection("Tank");
  g.tank_length = prm.get_double("length");
  g.fill_height = prm.get_double("fill height");
  g.wall_friction_deg = prm.get_double("wall friction angle");
  g.clamp_offset = prm.get_double("clamp offset");
  prm.leave_subsection();

  prm.enter_subsection("Anchorage");
  g.anchorage = prm.get("type") == "wrap-around" ? dem::Anchorage::wrap_around : dem::Anchorage::simple_run_out;
  g.cover = prm.get_double("H");
  g.anchorage_length = prm.get_double("L");
  g.return_height = prm.get_double("D1");
  g.upper_cover = prm.get_double("D2");
  g.upper_length = prm.get_double("B");
  prm.leave_subsection();

  prm.enter_subsection("Sheet");
  g.sheet_width = prm.get_double("width");
  dem::SheetParameters &s = in.tank.sheet;
  s.axial_stiffness = prm.get_double("axial stiffness");
  s.thickness = prm.get_double("thickness");
  s.areal_mass = prm.get_double("areal mass");
  in.tank.max_segment_length = prm.get_double("segment length");
  prm.enter_subsection("Interface");
  s.interface = parse_contact_parameters(prm, where + ", subsection Sheet/Interface");
  prm.leave_subsection();
  prm.leave_subsection();

  prm.enter_subsection("Soil");
  in.tank.unit_weight = prm.get_double("unit weight");
  prm.enter_subsection("Particle contact");
  dem::TankFillingSpec &f = in.tank.filling;
  f.particle_contact = parse_contact_parameters(prm, where + ", subsection Soil/Particle contact");
  prm.leave_subsection();
  prm.leave_subsection();

  f.n_threads = prm.get_integer("threads");
  prm.enter_subsection("Filling");
  f.n_particles = static_cast<std::size_t>(prm.get_integer("number of particles"));
  f.n_layers = static_cast<std::size_t>(prm.get_integer("number of layers"));
  f.shape = prm.get("shape") == "disc" ? dem::ParticleShape::disc : dem::ParticleShape::two_disc_cluster;
  f.size_distribution = dem::SizeDistribution::uniform(prm.get_double("size ratio"));
  f.target_porosity = prm.get_double("target porosity");
  f.porosity_tolerance = prm.get_double("porosity tolerance");
  f.growth_stress = prm.get_double("growth stress");
  f.local_damping = prm.get_double("local damping");
  f.equilibrium_unbalanced_ratio = prm.get_double("equilibrium unbalanced ratio");
  f.later_lifts_start_near_the_lift_below = prm.get("growth friction of later lifts") == "near the lift below";
  f.seed = static_cast<std::uint64_t>(prm.get_integer("seed"));
  f.lift_cache_directory = prm.get("lift cache directory");
  f.lift_cache_version = numbers_version;
  prm.leave_subsection();

  prm.enter_subsection("Pull");
  in.pull.rate = prm.get_double("rate");
  in.pull.final_displacement = prm.get_double("final displacement");
  in.pull.record_interval = prm.get_double("record interval");
  in.pull.ramp_displacement = prm.get_double("ramp displacement");
  in.pull.sheet_local_damping = prm.get_double("sheet local damping");
  if (const std::string alpha = prm.get("grain local damping"); !alpha.empty())
    {
      double value = -1.0;
      std::istringstream text(alpha);
      text.imbue(std::locale::classic());
      if (!(text >> value) || !(text >> std::ws).eof() || !(value >= 0.0 && value < 1.0))
        throw std::invalid_argument(where + ": 'Pull/grain local damping' = '" + alpha +
                                    "' must be empty or a number in [0, 1)");
      in.pull.grain_local_damping = value;
    }
  if (!(in.pull.ramp_displacement < in.pull.final_displacement))
    throw std::invalid_argument(where + ": 'Pull/ramp displacement' = " + number(in.pull.ramp_displacement) +
                                " m must be shorter than 'Pull/final displacement'");
  for (const std::string &item : dealii::Utilities::split_string_list(prm.get("tension profiles at"), ','))
    in.profiles_at.push_back(std::stod(item));
  std::sort(in.profiles_at.begin(), in.profiles_at.end());
  prm.leave_subsection();

  prm.enter_subsection("Output");
  const std::string measured = prm.get("experimental T_max");
  if (measured.find_first_not_of(" \t") != std::string::npos)
    {
      std::istringstream value(measured);
      value.imbue(std::locale::classic());
      double T;
      if (!(value >> T) || !(value >> std::ws).eof() || !(T > 0.0))
        throw std::invalid_argument(where + ": 'Output/experimental T_max' = '" + measured +
                                    "' must be a positive number [kN/m] or empty");
      in.references.experimental_T_max = 1e3 * T;
    }
  in.references.demonstration = prm.get("demonstration");
  if (const std::string full = prm.get("full-size runs"); full.find_first_not_of(" \t") != std::string::npos)
    in.references.full_size = read_reference_runs(full, where + ": parameter 'Output/full-size runs' = '" + full + "'");
  in.stress_band = prm.get_double("stress band");
  for (const std::string &item : dealii::Utilities::split_string_list(prm.get("field outputs at"), ','))
    in.fields_at.push_back(std::stod(item));
  prm.leave_subsection();

  if (dem_mode)
    in.tank.validate(where);
  else
    in.tank.geometry.validate(where);
  if (in.pull.record_interval > in.pull.final_displacement)
    throw std::invalid_argument(where + ": 'Pull/record interval' = " + number(in.pull.record_interval) +
                                " m is longer than 'Pull/final displacement' = " + number(in.pull.final_displacement) +
                                " m");
  // The pull's inertial number with the grains' density (the continuum's in fem mode) at gamma H.
  const double gravity = 9.81, density = dem_mode ? dem::solid_density_for_unit_weight(in.tank.unit_weight, f.target_porosity, gravity)
                                                  : in.tank.unit_weight / gravity;
  if (auto warning = check_pull_rate(in.pull.rate, density, in.tank.unit_weight * g.cover, where))
    in.warnings.push_back(*warning);
  return in;
}

namespace
{
/// mode = dem: the tank filled with particles, then pulled. With `resume`, the tank and the
/// pull continue from OUTPUT/checkpoint.h5 (one is written when the tank is full, then every
/// 'checkpoint interval' s of wall time): the result files are those of a run that never
/// stopped, bit for bit. With `check_only`, returns before the first file is written.
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
  const auto start_time = std::chrono::steady_clock::now();
  const auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  };
  std::cout << "geohybrid pullout: " << anchorage_description(g) << "; " << in.tank.filling.n_particles
            << " particles, mode dem" << std::endl;

  // 1. The tank, filled in layers, the sheet laid at its depth; or the one of the checkpoint.
  // `saved` holds what a checkpoint keeps beside the system: the tank's description, the
  // stress before the pull, the wall time spent before, then the pull's progress and rows.
  dem::CommandState saved;
  std::optional<dem::PullOutTank> filled;
  double earlier_wall_time = 0.0; // of the runs before this one, when resuming
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
      earlier_wall_time = saved.real("wall_time_s", 1)[0];
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
  const bool resumed = filled.has_value();
  double fill_time = 0.0;
  dem::SheetLevelStress before;
  if (resumed)
    {
      fill_time = saved.real("fill_wall_time_s", 1)[0];
      before = dem::restore_sheet_level_stress(saved);
      std::cout << "pullout: resuming from " << checkpoint_file.string() << " (tank filled in " << number(fill_time, 4)
                << " s)" << std::endl;
    }
  else
    {
      ProgressReport fill_progress("filling the tank", 1.0);
      filled.emplace(dem::fill_pull_out_tank(in.tank, [&](double f) {
        fill_progress.update(f);
        throw_if_interrupted("filling the tank"); // a partial fill cannot be resumed
      }));
      fill_progress.finish();
      fill_time = seconds();
      before = dem::measure_sheet_level_stress(filled->tank.system, *filled, g, in.stress_band);
      saved = dem::CommandState();
      dem::store_pullout_tank(*filled, saved);
      dem::store_sheet_level_stress(before, saved);
      saved.reals["fill_wall_time_s"] = {fill_time};
    }
  store_pullout_input(prm, saved); // this run's: what a later --resume is checked against
  dem::PullOutTank &tank = *filled;
  dem::DemSystem &system = tank.tank.system;
  const double actual_cover = g.fill_height - tank.sheet_level;
  const double gamma_H = in.tank.unit_weight * actual_cover;
  const double mu = std::tan(dem::degrees_to_radians(in.tank.sheet.interface.friction_angle_deg));
  const double one_face = before.top_face * g.anchorage_length * mu;
  std::cout << "pullout: tank filled in " << number(fill_time, 4) << " s (" << system.particles().n_bodies()
            << " particles, porosity of the layers";
  for (const dem::TankLayer &layer : tank.tank.layers)
    std::cout << ' ' << number(layer.porosity, 3);
  std::cout << "); sheet at y = " << number(tank.sheet_level, 4) << " m (H = " << number(actual_cover, 4)
            << " m as laid); vertical stress at the sheet: top face " << number(before.top_face / 1e3, 4)
            << " kPa, Love-Weber above " << number(before.love_weber_above / 1e3, 4) << " kPa, gamma H "
            << number(gamma_H / 1e3, 4) << " kPa" << std::endl;

  // 2. The pull, from its start or from the checkpoint's progress.
  const std::optional<dem::PullProgress> pulled = resumed ? dem::restore_pull_progress(saved) : std::nullopt;
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
    forces.emplace(out, mu, saved);
  else // a new pull, or a checkpoint of a version that did not record the decomposition
    forces.emplace(out, mu, system.energy());
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
  if (auto w = check_dem_sheet_inertia(system.sheets()[0], in.pull, system.time_step(), 2.0 * one_face, where))
    warnings.push_back(*w);
  const PullWatch::Setup watch_setup{in.pull.record_interval, in.pull.ramp_displacement, g.tank_length, true};
  PullWatch watch(watch_setup, system, pulled ? &saved : nullptr);
  std::cout << "pullout: fill steps per layer (growth + settling)";
  for (const dem::TankLayer &layer : tank.tank.layers)
    std::cout << ' ' << layer.n_growth_steps << '+' << layer.n_settling_steps << (layer.from_cache ? " (kept lift)" : "");
  std::cout << ", lowest growth friction per layer";
  for (const dem::TankLayer &layer : tank.tank.layers)
    std::cout << ' ' << number(layer.growth_friction_deg, 3);
  std::cout << " deg, settling with the sheet freed " << tank.n_final_settling_steps << "; time step "
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
    c.reals["wall_time_s"] = {earlier_wall_time + seconds()};
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

  // 3. The plot, with the experimental T_max as a horizontal line if given.
  output->finish("DEM", in.references, in.pull.final_displacement);
  const double T_max = output->max_head_tension(), u_at_T_max = output->head_displacement_at_max();
  if (checkpoint_interval > 0.0)
    save_checkpoint(); // the finished pull: a later --resume has nothing left to do but the files

  const double wall_time = earlier_wall_time + seconds();
  Summary summary;
  output->fill_summary(summary, "dem", anchorage_name(g), in.references);
  summary.set("n_particles", static_cast<double>(system.particles().n_bodies()));
  set_dem_sheet_summary(summary, system.sheets()[0], tank.sheet_level, actual_cover, gamma_H, before, one_face);
  summary.set("time_step_s", system.time_step());
  summary.set("critical_time_step_s", system.critical_time_step());
  summary.set("n_pull_steps", static_cast<double>(pull->progress().n_steps));
  summary.set("resumed_at_head_displacement_m", resumed ? u_first : std::nan("")); // null for a straight run
  summary.set("fill_wall_time_s", fill_time);
  // The cost of the run in steps: filling (each layer's growth and settling, then the settling
  // with the sheet freed) and pulling.
  double fill_steps = static_cast<double>(tank.n_final_settling_steps);
  for (const dem::TankLayer &layer : tank.tank.layers)
    fill_steps += static_cast<double>(layer.n_growth_steps + layer.n_settling_steps);
  summary.set("n_fill_steps", fill_steps);
  // Lifts taken from 'Filling/lift cache directory': their steps were made by an earlier run.
  double kept_steps = 0.0;
  for (const dem::TankLayer &layer : tank.tank.layers)
    if (layer.from_cache)
      kept_steps += static_cast<double>(layer.n_growth_steps + layer.n_settling_steps);
  summary.set("n_fill_steps_of_kept_lifts", kept_steps);
  summary.set("wall_time_s", wall_time);
  summary.set("parameters_hash", pullout_parameters_hash(prm));
  const std::vector<std::string> found = watch.warnings();
  warnings.insert(warnings.end(), found.begin(), found.end());
  report_warnings(warnings, "geohybrid pullout", summary, std::cerr);
  summary.write(out / "summary.json");
  std::cout << "geohybrid pullout: T_max = " << number(T_max / 1e3, 4) << " kN/m (" << number(T_max * g.sheet_width / 1e3, 4)
            << " kN for b = " << number(g.sheet_width, 3) << " m) at " << number(1e3 * u_at_T_max, 3) << " mm"
            << experiment_text(in.references) << "; " << number(wall_time, 4) << " s\n"
            << demonstration_lines(in.references) << "results in " << out.string() << '\n';
  return 0;
}
/// The input of FILE with `overrides`, read and checked as every run reads it, then run; with
/// `hash`, each mode stops before its first file is written, and *hash gets the input's hash.
int read_and_run(const std::string &input_file, bool resume, MPI_Comm communicator, const ParameterOverrides &overrides,
                 std::string *hash)
{
  ParameterHandler prm;
  declare_pullout_parameters(prm);
  parse_input_file(prm, input_file);
  for (const auto &[path, value] : overrides)
    set_parameter(prm, path, value);
  const std::string where = "input file '" + input_file + "'";
  const std::string mode = prm.get("mode");
  if (resume && mode == "fem")
    throw std::invalid_argument(where + ": --resume continues a run of 'mode' = dem or hybrid only (fem mode writes "
                                "no checkpoints): run it again without --resume");
  // Hybrid mode fills its particle box from the whole tank's Filling: checked as in dem mode.
  const PullOutInput in = parse_pullout(prm, where, mode != "fem");
  const bool check_only = hash != nullptr;
  const int status = mode == "hybrid" ? run_pullout_hybrid_mode(prm, in, where, resume, communicator, check_only)
                     : mode == "dem"  ? run_pullout_dem_mode(prm, in, where, resume, communicator, check_only)
                                      : run_pullout_fem_mode(prm, in, where, communicator, check_only);
  if (hash)
    *hash = pullout_parameters_hash(prm);
  return status;
}
} // namespace

int run_pullout_command(const std::string &input_file, bool resume, const ParameterOverrides &overrides)
{
  return run_pullout_command(input_file, resume, MPI_COMM_WORLD, overrides);
}

int run_pullout_command(const std::string &input_file, bool resume, MPI_Comm communicator,
                        const ParameterOverrides &overrides)
{
  return read_and_run(input_file, resume, communicator, overrides, nullptr);
}

std::string check_pullout_input(const std::string &input_file, MPI_Comm communicator, const ParameterOverrides &overrides)
{
  std::string hash;
  read_and_run(input_file, false, communicator, overrides, &hash);
  return hash;
}
} // namespace geohybrid::apps
