// `geohybrid coupling-test`: the DEM-FEM coupling's benchmarks for the method the input chooses.
//
// What it shows, and why these three figures (coupling/README.md discusses each):
//   - max_ghost_force_relative: a bonded hexagonal lattice and the continuum strained uniformly by
//     the same strain must stay in equilibrium across the band. The largest force left on an
//     interior disc of the particle-only region or at an interior node of the continuum (the
//     constrained system's residual), relative to |sigma| times the length the disc (d) or the
//     node (the cell) carries. The issue asks for 1e-10. Methods 1 and 2 meet it with the band
//     along the lattice's rows, cells commensurate with the lattice and the continuum carrying the
//     lattice's own stress (about 3e-11; coupling_benchmarks.h gives the conditions); across the
//     rows with the closed-form moduli a quadrature error of about 2e-2 remains (reported too).
//   - reflected_energy_fraction: a long pulse crosses the band in a strip; the energy of the
//     difference from a run of the particles alone (no band: no reflection), in the particle-only
//     region once the pulse is well into the continuum, over the incident energy.
//   - energy_drift_relative: an undamped coupled run of a pulse crossing the band; the mean
//     relative energy change over the last quarter of the run minus that over the first quarter.
// Methods 1 and 2 run them on a lattice and a continuum overlapping in a band, method 3 (the
// non-overlapping interface) on a lattice standing on the continuum; each summary states its
// definitions (coupling_test_benchmarks.cc).
// Everything is read and checked, and the three benchmarks run, before the output directory is
// made: a failed run leaves nothing, and a directory with summary.json is a finished run.
#include "coupling_test_command.h"

#include "coupling_test_benchmarks.h"
#include "run_directory.h"

#include "dem/io/checked_output.h"

#include <deal.II/base/utilities.h>

#include <nlohmann/json.hpp>

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
/// Rethrows what `check` throws as std::invalid_argument naming the input and the subsection.
template <typename Check>
void checked(const std::string &where, const char *subsection, Check check)
{
  try
    {
      check();
    }
  catch (const std::invalid_argument &e)
    {
      throw std::invalid_argument(where + ", subsection " + subsection + ": " + e.what());
    }
}

template <typename... Reader>
struct Readers : Reader...
{
  using Reader::operator()...;
};
template <typename... Reader>
Readers(Reader...) -> Readers<Reader...>;

/// The method 'method' names (coupling/coupling_method.h: its names, and the old spellings as
/// aliases), with its own parameters read from its subsection (`lattice`: the particles',
/// already read). A method without its reader here does not compile.
CouplingMethod read_method(ParameterHandler &prm, const std::string &where, const bench::PatchGeometry &lattice)
{
  CouplingMethod method = coupling::parse_coupling_method_name(prm.get("method"), where, "method");
  std::visit(Readers{[](coupling::LagrangeMultiplierCoupling &) {},
                     [&](coupling::PenaltyCoupling &penalty) {
                       prm.enter_subsection("Penalty");
                       penalty.penalty_factor = prm.get_double("factor");
                       prm.leave_subsection();
                       checked(where, "Penalty", [&] { penalty.validate(); });
                     },
                     // The interface springs relative to the matched ones
                     // (apps/coupling_benchmarks/standing_lattice.h), which depend on the
                     // lattice: kn = (lambda + 2 mu) d / r, ks = mu d / r.
                     [&](coupling::InterfaceCoupling &interface) {
                       prm.enter_subsection("Interface");
                       const double normal_factor = prm.get_double("normal stiffness factor");
                       const double shear_factor = prm.get_double("shear stiffness factor");
                       const double friction_angle = prm.get_double("friction angle");
                       prm.leave_subsection();
                       checked(where, "Interface", [&] {
                         interface = bench::matched_interface(lattice, normal_factor, shear_factor, friction_angle);
                         interface.validate();
                       });
                     }},
             method);
  return method;
}

/// `method = name` in the input's words, for the entries' documentation.
std::string method_is(std::string_view name)
{
  return "method = " + std::string(name);
}
} // namespace

void declare_coupling_test_parameters(ParameterHandler &prm)
{
  const bench::PatchGeometry g;
  const bench::StripSpec strip;
  const auto text = [](double v) { return number(v); };
  prm.declare_entry("output directory", "output/coupling_test", Patterns::Anything(),
                    "Directory for all results, created if needed, relative to the working directory [-]");
  using coupling::InterfaceCoupling, coupling::LagrangeMultiplierCoupling, coupling::PenaltyCoupling;
  prm.declare_entry("method", std::string(LagrangeMultiplierCoupling::name),
                    Patterns::Selection(coupling::coupling_method_selection(true)),
                    "How the particles are coupled to the continuum: " + std::string(LagrangeMultiplierCoupling::name) +
                      " (Lagrange multipliers: the bridging domain of Xiao & Belytschko 2004 in an overlap band: "
                      "velocities equal, exactly), " + std::string(PenaltyCoupling::name) +
                      " (springs between the displacements in the band, subsection Penalty) or " +
                      std::string(InterfaceCoupling::name) +
                      " (the non-overlapping interface, no band: the continuum's boundary edges are deformable walls "
                      "the discs touch, subsection Interface; its benchmarks are a lattice standing on the continuum, "
                      "docs/coupling.md); the names of 'Hybrid/coupling method' of geohybrid pullout. 'Lagrange "
                      "multipliers' and 'non-overlapping interface' are still accepted [-]");

  prm.enter_subsection("Particles");
  prm.declare_entry("normal stiffness", text(g.kn), Patterns::Double(1.0, 1e14),
                    "Normal contact stiffness kn of the bonded hexagonal lattice, per metre of thickness [N/m/m]");
  prm.declare_entry("shear stiffness", text(g.ks), Patterns::Double(1.0, 1e14),
                    "Tangential contact stiffness ks of the lattice, per metre of thickness; the continuum's E and "
                    "nu follow from kn and ks in closed form (apps/coupling_benchmarks/hexagonal_lattice.h) [N/m/m]");
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
                    "(the wave has its own, subsection Wave; method 3 has no band, its cells are one spacing) [-]");
  prm.leave_subsection();

  prm.enter_subsection("Penalty");
  prm.declare_entry("factor", "1", Patterns::Double(1e-3, 1e3),
                    method_is(PenaltyCoupling::name) + ": spring stiffness k_p per particle over E d / w (E the continuum's Young "
                    "modulus, d the spacing, w the band width); stiffer lowers the time step [-]");
  prm.leave_subsection();

  prm.enter_subsection("Interface");
  prm.declare_entry("normal stiffness factor", "1", Patterns::Double(1e-3, 1e3),
                    method_is(InterfaceCoupling::name) + ": the disc-edge normal stiffness over the matched (lambda + "
                    "2 mu) d / r (lambda, mu the lattice's moduli, d the spacing, r the radius), which carries sigma_yy "
                    "d exactly under a uniaxial strain; the particles' own kn is 1/3 of it for kn = 2 ks [-]");
  prm.declare_entry("shear stiffness factor", "1", Patterns::Double(1e-3, 1e3),
                    method_is(InterfaceCoupling::name) + ": the disc-edge tangential stiffness over the matched mu d / r [-]");
  prm.declare_entry("friction angle", "30", Patterns::Double(0.0, 89.0),
                    method_is(InterfaceCoupling::name) + ": the disc-edge Coulomb friction angle (the interface is "
                    "frictional and carries no tension) [deg]");
  prm.leave_subsection();

  prm.enter_subsection("Patch test");
  prm.declare_entry("strain xx", "1e-7", Patterns::Double(-1e-3, 1e-3),
                    "Uniform strain eps_xx applied to both sides (small: the lattice is geometrically exact, the "
                    "continuum linear) [-]");
  prm.declare_entry("strain yy", "-0.4e-7", Patterns::Double(-1e-3, 1e-3), "Uniform strain eps_yy [-]");
  prm.declare_entry("strain xy", "0.3e-7", Patterns::Double(-1e-3, 1e-3),
                    "Uniform (tensorial) shear strain eps_xy; left out by " + method_is(InterfaceCoupling::name) + " (a "
                    "disc-edge contact formed at the strained state starts with an unloaded tangential spring), "
                    "whose applied strain the summary states [-]");
  prm.declare_entry("strain size along the rows", "1e-3", Patterns::Double(1e-6, 1e-2),
                    "Methods 1 and 2: the patch test along the lattice's rows (the band's normal +y, where the "
                    "weights are exact; its figure is max_ghost_force_relative) applies the strain above scaled so "
                    "that its largest component is this. Large enough for the discs' position round-off (1e-17 m "
                    "against contact displacements strain x d) to stay below 1e-10 of the forces; the continuum "
                    "carries the strained lattice's own stress, so the lattice's non-linearity does not enter [-]");
  prm.leave_subsection();

  prm.enter_subsection("Wave");
  prm.declare_entry("pulse width", text(strip.pulse_width), Patterns::Double(0.5, 20.0),
                    "Width s of the Gaussian velocity pulse exp(-(x/s)^2), in particle spacings (s = 4 puts its "
                    "spectrum at wavelengths above about 12 spacings: long waves) [-]");
  prm.declare_entry("strip length", text(strip.length), Patterns::Double(8.0, 400.0),
                    "Length of the strip's particle-only region and of its continuum-only region, each, in particle "
                    "spacings; the strip is 6 rows high (method 3: 6 columns wide, the lattice standing on the "
                    "continuum); at least 8 pulse widths and 2 (band width + 2 pulse widths) [-]");
  prm.declare_entry("cell size", text(strip.cell_size), Patterns::Double(0.5, 8.0),
                    "Length of the strip's Q1 cells along it, in particle spacings (methods 1 and 2: 3 cells over its "
                    "height; method 3: cells one spacing across, about this long down) [-]");
  prm.leave_subsection();

  prm.enter_subsection("Energy");
  prm.declare_entry("number of undamped steps", "10000", Patterns::Integer(40, 100000000),
                    "Steps of the undamped coupled run whose energy drift is measured (issue 6: 10,000) [-]");
  prm.leave_subsection();

  prm.enter_subsection("Multi-rate");
  prm.declare_entry("continuum step ratios", "", Patterns::List(Patterns::Integer(2, 10)),
                    "method " + std::string(LagrangeMultiplierCoupling::name) + ": the wave and the energy run again "
                    "with the continuum stepping once per this many particle steps, each (the particles at the "
                    "lockstep's step over it, the continuum at the lockstep's); for the energy run's samples, every "
                    "10 steps, a divisor of 10 (2 or 5); empty: none [-]");
  prm.leave_subsection();
}

CouplingTestInput parse_coupling_test(ParameterHandler &prm, const std::string &where)
{
  CouplingTestInput in;
  in.output_directory = prm.get("output directory");
  if (in.output_directory.empty())
    throw std::invalid_argument(where + ": 'output directory' is empty");
  bench::PatchGeometry &g = in.patch;
  prm.enter_subsection("Particles");
  g.kn = prm.get_double("normal stiffness");
  g.ks = prm.get_double("shear stiffness");
  g.radius = prm.get_double("disc radius");
  g.density = prm.get_double("density");
  prm.leave_subsection();

  in.method = read_method(prm, where, g);
  in.method_name = coupling::name_of(in.method);

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
  const double row_strain_size = prm.get_double("strain size along the rows");
  prm.leave_subsection();
  if (in.strain.xx == 0.0 && in.strain.yy == 0.0 && in.strain.xy == 0.0)
    throw std::invalid_argument(where + ": 'Patch test/strain xx', 'strain yy' and 'strain xy' are all 0: the ghost "
                                "forces are measured relative to the stress of a non-zero strain");
  const double scale =
    row_strain_size / std::max({std::abs(in.strain.xx), std::abs(in.strain.yy), std::abs(in.strain.xy)});
  in.row_patch_strain = {scale * in.strain.xx, scale * in.strain.yy, scale * in.strain.xy};
  in.row_patch_layout = bench::commensurate_row_patch(g.band_width, cell_size);
  // Method 3's set-up cannot strain the interface in shear (standing_lattice.h): it applies the
  // input's eps_xx and eps_yy, and says so in the summary; it does not trade eps_xx (whose
  // Poisson coupling the interface lacks: the ghost force lambda eps_xx / |sigma|) for a strain
  // that hides it.
  in.patch_strain = in.strain;
  if (!coupling::has_band(in.method))
    {
      in.patch_strain.xy = 0.0;
      if (in.strain.xx == 0.0 && in.strain.yy == 0.0)
        throw std::invalid_argument(where + ": 'Patch test/strain xx' and 'strain yy' are both 0: " +
                                    method_is(in.method_name) + " leaves out 'strain xy', so its patch test has no strain");
    }

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
  prm.enter_subsection("Multi-rate");
  for (const std::string &ratio : dealii::Utilities::split_string_list(prm.get("continuum step ratios")))
    {
      const int r = dealii::Utilities::string_to_int(ratio);
      if (10 % r != 0)
        throw std::invalid_argument(where + ": parameter 'Multi-rate/continuum step ratios' holds " + ratio +
                                    ": the energy run samples every 10 steps, between windows: give 2 or 5");
      in.continuum_step_ratios.push_back(static_cast<unsigned int>(r));
    }
  prm.leave_subsection();
  if (!in.continuum_step_ratios.empty() && !std::holds_alternative<coupling::LagrangeMultiplierCoupling>(in.method))
    throw std::invalid_argument(where + ": parameter 'Multi-rate/continuum step ratios' needs 'method' = " +
                                std::string(coupling::LagrangeMultiplierCoupling::name));
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
  dem::close_checked(out, file);
}

void write_wave_history(const std::filesystem::path &file, const std::vector<bench::WaveSample> &history)
{
  std::ofstream out = open_csv_rows(file, "time_s,reflected_energy_fraction,continuum_energy_fraction", std::nullopt);
  for (const bench::WaveSample &s : history)
    out << number(s.time) << ',' << number(s.reflected) << ',' << number(s.in_continuum) << '\n';
  dem::close_checked(out, file);
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
  // Claimed before the benchmarks run, so that a directory holding another run's files is refused
  // at once, not after minutes of work.
  const std::filesystem::path out = prepare_output_directory(in.output_directory, false);

  // ---- the three benchmarks, in memory: no file is written if one of them fails ----
  const auto start = std::chrono::steady_clock::now();
  const BenchmarkRunning running = [&](const char *what, const std::function<void()> &run) {
    try
      {
        run();
      }
    catch (const std::exception &e)
      {
        throw std::runtime_error(where + ", method '" + in.method_name + "', " + what + ": " + e.what());
      }
  };
  const BenchmarkFigures f = run_benchmarks(in, running);
  const double ghost = f.max_ghost();
  if (f.row_patch)
    std::cout << "coupling-test (" << in.method_name << "): patch test along the rows (strain " << in.row_patch_strain.xx
              << ", " << in.row_patch_strain.yy << ", " << in.row_patch_strain.xy << "), largest ghost force " << ghost
              << " (discs " << f.row_patch->ghost.particles_outside_band << ", continuum nodes "
              << f.row_patch->ghost.continuum_nodes << "), largest disc moment " << f.row_patch->disc_moments
              << std::endl;
  std::cout << "coupling-test (" << in.method_name << "): patch test" << (f.row_patch ? " across the rows" : "")
            << " (strain " << in.patch_strain.xx << ", " << in.patch_strain.yy << ", " << in.patch_strain.xy
            << "), largest ghost force " << std::max(f.ghost_discs, f.ghost_nodes) << " (discs " << f.ghost_discs
            << ", continuum nodes " << f.ghost_nodes << ")" << std::endl;
  std::cout << "coupling-test (" << in.method_name << "): wave, reflected energy fraction " << f.wave.reflected
            << " (" << f.wave.transmitted << " in the continuum, " << f.wave.n_steps << " steps)" << std::endl;
  std::cout << "coupling-test (" << in.method_name << "): energy drift " << f.energy.drift << " over "
            << in.n_energy_steps << " undamped steps (largest deviation " << f.energy.largest_deviation << ")"
            << std::endl;
  for (const BenchmarkFigures::MultiRateFigures &m : f.multi_rate)
    std::cout << "coupling-test (" << in.method_name << "): continuum at " << m.ratio
              << " particle steps: reflected energy fraction " << m.wave.reflected << ", energy drift "
              << m.energy.drift << std::endl;
  const double wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // ---- the results; summary.json last ----
  write_resolved_parameters(prm, out);
  write_energy_history(out / "energy_history.csv", f.energy.history);
  write_wave_history(out / "wave_reflection.csv", f.wave.history);

  Summary summary;
  summary.set("method", in.method_name);
  if (const auto *interface = std::get_if<coupling::InterfaceCoupling>(&in.method))
    {
      summary.set("interface_normal_stiffness_N_per_m_per_m", interface->contact.normal_stiffness);
      summary.set("interface_shear_stiffness_N_per_m_per_m", interface->contact.shear_stiffness);
    }
  summary.set("max_ghost_force_relative", ghost);
  summary.set("max_ghost_force_relative_definition", f.ghost_definition);
  summary.set("patch_strain_xx", in.patch_strain.xx);
  summary.set("patch_strain_yy", in.patch_strain.yy);
  summary.set("patch_strain_xy", in.patch_strain.xy);
  summary.set("ghost_force_untied_discs_relative", f.ghost_discs);
  summary.set("ghost_force_continuum_nodes_relative", f.ghost_nodes);
  if (f.row_patch)
    {
      summary.set("ghost_force_across_rows_relative", std::max(f.ghost_discs, f.ghost_nodes));
      summary.set("row_patch_strain_xx", in.row_patch_strain.xx);
      summary.set("row_patch_strain_yy", in.row_patch_strain.yy);
      summary.set("row_patch_strain_xy", in.row_patch_strain.xy);
      summary.set("ghost_force_row_patch_untied_discs_relative", f.row_patch->ghost.particles_outside_band);
      summary.set("ghost_force_row_patch_continuum_nodes_relative", f.row_patch->ghost.continuum_nodes);
      summary.set("row_patch_disc_moment_relative", f.row_patch->disc_moments);
      summary.set("row_patch_band_width_spacings", in.row_patch_layout.band_width);
      summary.set("row_patch_cell_width_spacings",
                  (in.row_patch_layout.mesh_right - in.row_patch_layout.mesh_left) / in.row_patch_layout.cells_x);
      summary.set("row_patch_n_measured_discs", static_cast<double>(f.row_patch->n_discs));
      summary.set("row_patch_n_measured_node_dofs", static_cast<double>(f.row_patch->n_nodes));
    }
  summary.set("reflected_energy_fraction", f.wave.reflected);
  summary.set("reflected_energy_fraction_definition", f.wave_definition);
  summary.set("wave_energy_in_continuum_fraction", f.wave.transmitted);
  summary.set("energy_drift_relative", f.energy.drift);
  summary.set("energy_drift_relative_definition", f.energy_definition);
  summary.set("energy_largest_deviation_relative", f.energy.largest_deviation);
  summary.set("energy_continuum_share_max", f.energy.continuum_share);
  summary.set("coupling_force_imbalance_max_N_per_m", f.energy.largest_force_imbalance);
  summary.set("coupling_force_max_N_per_m", f.energy.largest_coupling_force);
  if (!f.multi_rate.empty())
    {
      nlohmann::json rows = nlohmann::json::array();
      for (const BenchmarkFigures::MultiRateFigures &m : f.multi_rate)
        rows.push_back({{"continuum_step_ratio", m.ratio},
                        {"particle_time_step_s", m.energy.time_step},
                        {"reflected_energy_fraction", m.wave.reflected},
                        {"wave_energy_in_continuum_fraction", m.wave.transmitted},
                        {"energy_drift_relative", m.energy.drift},
                        {"energy_largest_deviation_relative", m.energy.largest_deviation}});
      summary.set_json("multi_rate", rows);
      summary.set("multi_rate_definition", "method 1 with the continuum stepping once per continuum_step_ratio "
                                           "particle steps, the particles at the lockstep's step over it: the wave "
                                           "and the energy run as above (coupling/coupled_stepper.h)");
    }
  summary.set("n_energy_steps", static_cast<double>(in.n_energy_steps));
  summary.set("n_particles", static_cast<double>(f.n_particles));
  summary.set("n_cells", static_cast<double>(f.n_cells));
  summary.set("n_particles_cells_definition", "of the patch test; the wave's are wave_n_*");
  summary.set("wave_n_particles", static_cast<double>(f.wave.n_particles));
  summary.set("wave_n_cells", static_cast<double>(f.wave.n_cells));
  summary.set("wave_n_steps", static_cast<double>(f.wave.n_steps));
  summary.set("time_step_energy_run_s", f.energy.time_step);
  summary.set("time_step_wave_s", f.wave.time_step);
  summary.set("wall_time_s", wall_time);
  summary.write(out / "summary.json");
  std::cout << "coupling-test (" << in.method_name << "): results in " << out.string() << " (" << number(wall_time, 3)
            << " s)" << std::endl;
  return 0;
}
} // namespace geohybrid::apps
