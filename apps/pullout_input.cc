// The input of `geohybrid pullout`: its entries declared (declare_pullout_parameters, with their
// defaults, bounds and units) and read into a PullOutInput that every mode shares
// (parse_pullout), with the checks that need more than one entry.
#include "pullout_input.h"

#include "contact_parameters.h"
#include "parameters_hash.h"
#include "pullout_command.h"
#include "pullout_fem_mode.h"
#include "pullout_hybrid_mode.h"
#include "run_directory.h"
#include "run_health.h"

#include <deal.II/base/utilities.h>

#include "dem/measurements.h"

#include <algorithm>
#include <locale>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

namespace
{
/// A default that is a number, written as the input file reads it.
std::string default_text(double v) { return number(v); }

/// Subsections Tank, Anchorage and Sheet: the tank, the anchorage's geometry and the geosynthetic.
void declare_tank_and_sheet_entries(ParameterHandler &prm)
{
  const dem::PullOutGeometry g;
  const dem::SheetParameters sheet;
  prm.enter_subsection("Tank");
  prm.declare_entry("length", default_text(g.tank_length), Patterns::Double(1e-6),
                    "Inner length from the back wall to the front wall; the INSA tank's length is not given in the "
                    "paper's text, 1.5 m is this model's choice [m]");
  prm.declare_entry("fill height", default_text(g.fill_height), Patterns::Double(1e-6),
                    "Height of the soil surface above the base (H plus the soil below the sheet) [m]");
  prm.declare_entry("wall friction angle", default_text(g.wall_friction_deg), Patterns::Double(0.0, 89.99),
                    "Soil-wall friction angle (measured: 28 degrees, section 4.3); dem and hybrid modes (the continuum's "
                    "walls are smooth) [deg]");
  prm.declare_entry("clamp offset", default_text(g.clamp_offset), Patterns::Double(1e-6),
                    "Distance of the clamp (the sheet's first node) outside the front wall; dem and hybrid modes (the "
                    "continuum's clamp is the sheet's node at the front wall) [m]");
  prm.leave_subsection();

  prm.enter_subsection("Anchorage");
  prm.declare_entry("type", "simple run-out", Patterns::Selection("simple run-out|wrap-around"),
                    "Simple run-out (L, H) or wrap-around (L, D1, D2, B, H = D1 + D2), section 2.2; fem mode lays the "
                    "wrap-around's corners as arcs of twice 'Continuum/sheet node spacing' [-]");
  prm.declare_entry("H", default_text(g.cover), Patterns::Double(1e-6), "Soil above the lower part of the sheet [m]");
  prm.declare_entry("L", default_text(g.anchorage_length), Patterns::Double(1e-6),
                    "Length of the lower part of the sheet in the soil, from the front wall [m]");
  prm.declare_entry("D1", default_text(g.return_height), Patterns::Double(0.0),
                    "Wrap-around: height of the vertical return [m]");
  prm.declare_entry("D2", default_text(g.upper_cover), Patterns::Double(0.0),
                    "Wrap-around: soil above the upper part [m]");
  prm.declare_entry("B", default_text(g.upper_length), Patterns::Double(0.0),
                    "Wrap-around: length of the upper part, from the return towards the front wall [m]");
  prm.leave_subsection();

  prm.enter_subsection("Sheet");
  prm.declare_entry("width", default_text(g.sheet_width), Patterns::Double(1e-6),
                    "b, width of the sheet in the bench, for the per-sheet outputs (INSA: 0.5 m) [m]");
  prm.declare_entry("axial stiffness", default_text(sheet.axial_stiffness), Patterns::Double(1e-6),
                    "J per metre of width (GT230: 2104 kN/m, GT75: 687 kN/m, Table 2) [N/m]");
  prm.declare_entry("thickness", default_text(sheet.thickness), Patterns::Double(1e-9), "For contact (GT230: 3.2 mm); dem and hybrid modes (the continuum's sheet has no thickness) [m]");
  prm.declare_entry("areal mass", default_text(sheet.areal_mass), Patterns::Double(1e-9),
                    "Mass per unit area (GT230: 620 g/m2) [kg/m^2]");
  prm.declare_entry("segment length", "0.01", Patterns::Double(1e-6),
                    "Longest spar element; dem and hybrid modes (fem: 'Continuum/sheet node spacing') [m]");
  prm.enter_subsection("Interface");
  declare_contact_parameters(prm, dem::default_interface_parameters());
  prm.leave_subsection();
  prm.leave_subsection();
}

/// Subsections Soil and Filling: the grains and how the tank is filled with them.
void declare_soil_and_filling_entries(ParameterHandler &prm)
{
  const dem::TankFillingSpec fill;
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
  prm.declare_entry("target porosity", default_text(fill.target_porosity), Patterns::Double(0.05, 0.8),
                    "2D porosity of every layer (Table 5: 0.2) [-]");
  prm.declare_entry("porosity tolerance", default_text(fill.porosity_tolerance), Patterns::Double(1e-6, 0.1),
                    "Accepted porosity error [-]");
  prm.declare_entry("growth stress", default_text(fill.growth_stress), Patterns::Double(1e-6),
                    "Lid stress at which a growing layer counts as jammed (compaction of a lift) [Pa]");
  prm.declare_entry("local damping", default_text(fill.local_damping), Patterns::Double(0.0, 0.99),
                    "PFC local damping while filling and pulling [-]");
  prm.declare_entry("equilibrium unbalanced ratio", default_text(fill.equilibrium_unbalanced_ratio),
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
}

/// Subsections Pull and Output: the clamp's programme, the curve's points and what is written.
void declare_pull_and_output_entries(ParameterHandler &prm)
{
  const dem::PullSpec pull;
  prm.enter_subsection("Pull");
  prm.declare_entry("rate", default_text(pull.rate), Patterns::Double(1e-9), "Clamp speed [m/s]");
  prm.declare_entry("final displacement", default_text(pull.final_displacement), Patterns::Double(1e-9),
                    "Head displacement at the end [m]");
  prm.declare_entry("record interval", default_text(pull.record_interval), Patterns::Double(1e-9),
                    "Head displacement between two points of the curve (each the mean over its interval) [m]");
  prm.declare_entry("ramp displacement", default_text(pull.ramp_displacement), Patterns::Double(0.0),
                    "The clamp's speed rises linearly from 0 to the rate over this head displacement, so that "
                    "the start does not jerk the sheet [m]");
  prm.declare_entry("sheet local damping", default_text(pull.sheet_local_damping), Patterns::Double(0.0, 0.99),
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
}
} // namespace

void declare_pullout_parameters(ParameterHandler &prm)
{
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

  declare_tank_and_sheet_entries(prm);
  declare_soil_and_filling_entries(prm);
  declare_pull_and_output_entries(prm);

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
} // namespace geohybrid::apps
