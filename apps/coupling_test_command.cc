// `geohybrid coupling-test`: the DEM-FEM coupling's benchmarks for the method the input chooses.
//
// What it shows, and why these three figures (coupling/README.md discusses each):
//   - max_ghost_force_relative: a bonded hexagonal lattice and the matching plane-strain continuum
//     strained uniformly by the same strain must stay in equilibrium across the band. The largest
//     force left on an interior disc of the particle-only region or at an interior node of the
//     continuum (the constrained system's residual), relative to |sigma| times the length the disc
//     (d) or the node (the cell width) carries. The issue asks for 1e-10; the bridging domain with
//     Q1 elements on a hexagonal lattice gives about 2e-2 (a quadrature error that falls as d / w).
//   - reflected_energy_fraction: a long pulse crosses the band in a strip; the energy of the
//     difference from a run of the particles alone (no band: no reflection), in the particle-only
//     region once the pulse is well into the continuum, over the incident energy.
//   - energy_drift_relative: an undamped coupled run of a pulse crossing the band; the mean
//     relative energy change over the last quarter of the run minus that over the first quarter.
// Everything is read and checked, and the three benchmarks run, before the output directory is
// made: a failed run leaves nothing, and a directory with summary.json is a finished run.
#include "coupling_test_command.h"

#include "run_directory.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <variant>

namespace geohybrid::apps
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;
using coupling::CouplingMethod;
namespace bench = coupling::benchmarks;

namespace
{
/// The methods the input may choose, by name: a new method is one more row here (and one more
/// alternative of coupling::CouplingMethod), its own parameters read by `make` from the file.
struct MethodChoice
{
  const char *name;
  std::function<CouplingMethod(ParameterHandler &, const std::string &where)> make;
};

constexpr std::size_t n_methods = 2;
// Method 3 (coupling::InterfaceCoupling, the non-overlapping interface) has no row yet: its
// scenarios (a lattice standing on the continuum, tests/test_coupling_interface*.cc) are not yet
// benchmark functions of coupling_benchmarks.h, so the command cannot run it.
constexpr std::size_t n_methods_without_row = 1;
static_assert(std::variant_size_v<CouplingMethod> == n_methods + n_methods_without_row,
              "every alternative of coupling::CouplingMethod needs its row in method_choices()");

const std::array<MethodChoice, n_methods> &method_choices()
{
  static const std::array<MethodChoice, n_methods> choices{{
    {"Lagrange multipliers", [](ParameterHandler &, const std::string &) { return CouplingMethod(coupling::LagrangeMultiplierCoupling{}); }},
    {"penalty",
     [](ParameterHandler &prm, const std::string &where) {
       prm.enter_subsection("Penalty");
       coupling::PenaltyCoupling penalty{prm.get_double("factor")};
       prm.leave_subsection();
       try
         {
           penalty.validate();
         }
       catch (const std::invalid_argument &e)
         {
           throw std::invalid_argument(where + ", subsection Penalty: " + e.what());
         }
       return CouplingMethod(penalty);
     }},
  }};
  return choices;
}

std::string method_selection()
{
  std::string names;
  for (const MethodChoice &choice : method_choices())
    names += (names.empty() ? "" : "|") + std::string(choice.name);
  return names;
}
} // namespace

void declare_coupling_test_parameters(ParameterHandler &prm)
{
  const bench::PatchGeometry g;
  const bench::StripSpec strip;
  const auto text = [](double v) { return number(v); };
  prm.declare_entry("output directory", "output/coupling_test", Patterns::Anything(),
                    "Directory for all results, created if needed, relative to the working directory [-]");
  prm.declare_entry("method", "Lagrange multipliers", Patterns::Selection(method_selection()),
                    "How the particles are tied to the continuum in the overlap band: Lagrange multipliers (the "
                    "bridging domain of Xiao & Belytschko 2004: velocities equal, exactly) or penalty (springs "
                    "between the displacements, subsection Penalty) [-]");

  prm.enter_subsection("Particles");
  prm.declare_entry("normal stiffness", text(g.kn), Patterns::Double(1.0, 1e14),
                    "Normal contact stiffness kn of the bonded hexagonal lattice, per metre of thickness [N/m/m]");
  prm.declare_entry("shear stiffness", text(g.ks), Patterns::Double(1.0, 1e14),
                    "Tangential contact stiffness ks of the lattice, per metre of thickness; the continuum's E and "
                    "nu follow from kn and ks in closed form (coupling/hexagonal_lattice.h) [N/m/m]");
  prm.declare_entry("disc radius", text(g.radius), Patterns::Double(1e-5, 1.0),
                    "Radius of the lattice's equal discs; the particle spacing d is twice it [m]");
  prm.declare_entry("density", text(g.density), Patterns::Double(1.0, 1e5),
                    "Density of the discs' material; the continuum's is this times the solid fraction pi / (2 "
                    "sqrt(3)) [kg/m^3]");
  prm.leave_subsection();

  prm.enter_subsection("Band");
  prm.declare_entry("width", text(g.band_width), Patterns::Double(2.0, 20.0),
                    "Width w of the overlap band, in particle spacings: at least 2 (ghost forces grow as d / w: "
                    "7.1e-2 at 2 spacings, coupling/README.md) [-]");
  prm.declare_entry("cell size", "2", Patterns::Double(0.5, 8.0),
                    "Width of the continuum's Q1 cells in the patch test and the energy run, in particle spacings "
                    "(the wave has its own, subsection Wave) [-]");
  prm.leave_subsection();

  prm.enter_subsection("Penalty");
  prm.declare_entry("factor", "1", Patterns::Double(1e-3, 1e3),
                    "method = penalty: spring stiffness k_p per particle over E d / w (E the continuum's Young "
                    "modulus, d the spacing, w the band width); stiffer lowers the time step [-]");
  prm.leave_subsection();

  prm.enter_subsection("Patch test");
  prm.declare_entry("strain xx", "1e-7", Patterns::Double(-1e-3, 1e-3),
                    "Uniform strain eps_xx applied to both sides (small: the lattice is geometrically exact, the "
                    "continuum linear) [-]");
  prm.declare_entry("strain yy", "-0.4e-7", Patterns::Double(-1e-3, 1e-3), "Uniform strain eps_yy [-]");
  prm.declare_entry("strain xy", "0.3e-7", Patterns::Double(-1e-3, 1e-3),
                    "Uniform (tensorial) shear strain eps_xy [-]");
  prm.leave_subsection();

  prm.enter_subsection("Wave");
  prm.declare_entry("pulse width", text(strip.pulse_width), Patterns::Double(0.5, 20.0),
                    "Width s of the Gaussian velocity pulse exp(-(x/s)^2), in particle spacings (s = 4 puts its "
                    "spectrum at wavelengths above about 12 spacings: long waves) [-]");
  prm.declare_entry("strip length", text(strip.length), Patterns::Double(8.0, 400.0),
                    "Length of the strip's particle-only region and of its continuum-only region, each, in particle "
                    "spacings; the strip is 6 rows high; at least 8 pulse widths and 2 (band width + 2 pulse "
                    "widths) [-]");
  prm.declare_entry("cell size", text(strip.cell_size), Patterns::Double(0.5, 8.0),
                    "Length of the strip's Q1 cells along it, in particle spacings (3 cells over its height) [-]");
  prm.leave_subsection();

  prm.enter_subsection("Energy");
  prm.declare_entry("number of undamped steps", "10000", Patterns::Integer(40, 100000000),
                    "Steps of the undamped coupled run whose energy drift is measured (issue 6: 10,000) [-]");
  prm.leave_subsection();
}

CouplingTestInput parse_coupling_test(ParameterHandler &prm, const std::string &where)
{
  CouplingTestInput in;
  in.output_directory = prm.get("output directory");
  if (in.output_directory.empty())
    throw std::invalid_argument(where + ": 'output directory' is empty");
  in.method_name = prm.get("method");
  const auto &choices = method_choices();
  const auto choice = std::find_if(choices.begin(), choices.end(),
                                   [&](const MethodChoice &c) { return in.method_name == c.name; });
  if (choice == choices.end()) // the Selection pattern lists exactly the table's names
    throw std::logic_error(where + ": 'method' = '" + in.method_name + "' passed the pattern but has no row");
  in.method = choice->make(prm, where);

  bench::PatchGeometry &g = in.patch;
  prm.enter_subsection("Particles");
  g.kn = prm.get_double("normal stiffness");
  g.ks = prm.get_double("shear stiffness");
  g.radius = prm.get_double("disc radius");
  g.density = prm.get_double("density");
  prm.leave_subsection();

  // The patch: 12 rows, the band 5.3 spacings in (an untied particle region of five columns), the
  // continuum four spacings past the band, cells of about `cell size` both ways.
  prm.enter_subsection("Band");
  g.band_width = prm.get_double("width");
  const double cell_size = prm.get_double("cell size");
  prm.leave_subsection();
  g.continuum_end = g.band_start + g.band_width + 4.0;
  const auto cells = [&](double length) {
    return static_cast<unsigned int>(std::max(1L, std::lround(length / cell_size)));
  };
  g.cells_x = cells(g.continuum_end - g.band_start);
  g.cells_y = cells(g.rows * std::sqrt(3.0) / 2.0);

  prm.enter_subsection("Patch test");
  in.strain = {prm.get_double("strain xx"), prm.get_double("strain yy"), prm.get_double("strain xy")};
  prm.leave_subsection();
  if (in.strain.xx == 0.0 && in.strain.yy == 0.0 && in.strain.xy == 0.0)
    throw std::invalid_argument(where + ": 'Patch test/strain xx', 'strain yy' and 'strain xy' are all 0: the ghost "
                                "forces are measured relative to the stress of a non-zero strain");

  prm.enter_subsection("Wave");
  in.strip.band_width = g.band_width;
  in.strip.pulse_width = prm.get_double("pulse width");
  in.strip.length = prm.get_double("strip length");
  in.strip.cell_size = prm.get_double("cell size");
  prm.leave_subsection();
  if (in.strip.length < 8.0 * in.strip.pulse_width)
    throw std::invalid_argument(where + ": 'Wave/strip length' = " + number(in.strip.length) +
                                " spacings is below 8 times 'Wave/pulse width' (" + number(in.strip.pulse_width) +
                                "): the pulse would not fit in the particle region");
  // The pulse's left-going half, reflected at the strip's free end, must still be one pulse width
  // short of the band's free edge when the measurement is made (after the right-going half has run
  // length / 2 + band width into the continuum).
  if (in.strip.length < 2.0 * (in.strip.band_width + 2.0 * in.strip.pulse_width))
    throw std::invalid_argument(where + ": 'Wave/strip length' = " + number(in.strip.length) +
                                " spacings is below 2 ('Band/width' + 2 'Wave/pulse width') = " +
                                number(2.0 * (in.strip.band_width + 2.0 * in.strip.pulse_width)) +
                                ": the pulse's half reflected at the strip's free end would reach the band");

  prm.enter_subsection("Energy");
  in.n_energy_steps = static_cast<unsigned int>(prm.get_integer("number of undamped steps"));
  prm.leave_subsection();
  return in;
}

namespace
{
void write_energy_history(const std::filesystem::path &file, const std::vector<bench::EnergySample> &history)
{
  std::ofstream out = open_csv_rows(file,
                                    "time_s,relative_energy_change,particle_energy_J_per_m,continuum_kinetic_J_per_m,"
                                    "continuum_elastic_J_per_m,coupling_energy_J_per_m",
                                    std::nullopt);
  for (const bench::EnergySample &s : history)
    out << number(s.time) << ',' << number(s.relative_change) << ',' << number(s.particle_energy) << ','
        << number(s.continuum_kinetic) << ',' << number(s.continuum_elastic) << ',' << number(s.coupling_energy) << '\n';
  if (!out)
    throw std::runtime_error("cannot write " + file.string());
}

void write_wave_history(const std::filesystem::path &file, const std::vector<bench::WaveSample> &history)
{
  std::ofstream out = open_csv_rows(file, "time_s,reflected_energy_fraction,continuum_energy_fraction", std::nullopt);
  for (const bench::WaveSample &s : history)
    out << number(s.time) << ',' << number(s.reflected) << ',' << number(s.in_continuum) << '\n';
  if (!out)
    throw std::runtime_error("cannot write " + file.string());
}
} // namespace

int run_coupling_test_command(const std::string &input_file, bool resume)
{
  ParameterHandler prm;
  declare_coupling_test_parameters(prm);
  parse_input_file(prm, input_file);
  const std::string where = "input file '" + input_file + "'";
  if (resume)
    throw std::invalid_argument(where + ": coupling-test has no checkpoint to resume from (run it again)");
  const CouplingTestInput in = parse_coupling_test(prm, where);

  // ---- the three benchmarks, in memory: nothing is written if one of them fails ----
  const auto start = std::chrono::steady_clock::now();
  const auto running = [&](const char *what, auto &&run) {
    try
      {
        return run();
      }
    catch (const std::exception &e)
      {
        throw std::runtime_error(where + ", method '" + in.method_name + "', " + what + ": " + e.what());
      }
  };
  const bench::PatchTestResult patch =
    running("patch test", [&] { return bench::patch_test(in.method, in.strain, in.patch); });
  std::cout << "coupling-test (" << in.method_name << "): patch test, largest ghost force " << patch.ghost.largest()
            << " (untied discs " << patch.ghost.particles_outside_band << ", continuum nodes "
            << patch.ghost.continuum_nodes << ")" << std::endl;
  const bench::WaveRecord wave = running("wave", [&] { return bench::strip_crossing(in.method, in.strip, in.patch); });
  std::cout << "coupling-test (" << in.method_name << "): wave, reflected energy fraction " << wave.reflected
            << " (" << wave.transmitted << " in the continuum, " << wave.n_steps << " steps)" << std::endl;
  const bench::EnergyRecord energy =
    running("energy run", [&] { return bench::energy_record(in.method, in.n_energy_steps, 0.0, in.patch); });
  std::cout << "coupling-test (" << in.method_name << "): energy drift " << energy.drift << " over "
            << in.n_energy_steps << " undamped steps (largest deviation " << energy.largest_deviation << ")"
            << std::endl;
  const double wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // ---- the results; summary.json last ----
  const std::filesystem::path out = prepare_output_directory(in.output_directory);
  write_resolved_parameters(prm, out);
  write_energy_history(out / "energy_history.csv", energy.history);
  write_wave_history(out / "wave_reflection.csv", wave.history);

  Summary summary;
  summary.set("method", in.method_name);
  summary.set("max_ghost_force_relative", patch.ghost.largest());
  summary.set("max_ghost_force_relative_definition",
              "patch test under a uniform strain: the largest force on an interior untied disc (relative to |sigma| d) "
              "or residual at an interior continuum node, f_ext - f_int + sum_p N_I(X_p) F_p (relative to |sigma| "
              "times the cell width)");
  summary.set("ghost_force_untied_discs_relative", patch.ghost.particles_outside_band);
  summary.set("ghost_force_continuum_nodes_relative", patch.ghost.continuum_nodes);
  summary.set("reflected_energy_fraction", wave.reflected);
  summary.set("reflected_energy_fraction_definition",
              "a Gaussian velocity pulse crossing the band of a 6-row strip: the energy of the difference from a run of "
              "the particles alone (no band), over the particle-only region's discs once the pulse is half the strip "
              "length into the continuum, over the incident (right-going, half the initial) energy");
  summary.set("wave_energy_in_continuum_fraction", wave.transmitted);
  summary.set("energy_drift_relative", energy.drift);
  summary.set("energy_drift_relative_definition",
              "undamped coupled run of a pulse crossing the band: mean of (E(t) - E(0)) / E(0) over the last quarter of "
              "the steps minus its mean over the first quarter, sampled every 10 steps");
  summary.set("energy_largest_deviation_relative", energy.largest_deviation);
  summary.set("energy_continuum_share_max", energy.continuum_share);
  summary.set("n_energy_steps", static_cast<double>(in.n_energy_steps));
  summary.set("n_particles", static_cast<double>(patch.n_particles));
  summary.set("n_cells", static_cast<double>(patch.n_cells));
  summary.set("n_particles_cells_definition", "of the patch (patch test and energy run); the strip's are wave_n_*");
  summary.set("wave_n_particles", static_cast<double>(wave.n_particles));
  summary.set("wave_n_cells", static_cast<double>(wave.n_cells));
  summary.set("wave_n_steps", static_cast<double>(wave.n_steps));
  summary.set("time_step_patch_s", energy.time_step);
  summary.set("time_step_wave_s", wave.time_step);
  summary.set("wall_time_s", wall_time);
  summary.write(out / "summary.json");
  std::cout << "coupling-test (" << in.method_name << "): results in " << out.string() << " (" << number(wall_time, 3)
            << " s)" << std::endl;
  return 0;
}
} // namespace geohybrid::apps
