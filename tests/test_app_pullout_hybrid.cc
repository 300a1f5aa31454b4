// `geohybrid pullout` with 'mode = hybrid' end to end on the small tank of
// test_coupling_hybrid_pullout.cc (0.4 m x 0.2 m, 4,000 grains for the whole tank, about 1,500 in
// the box, an elastic continuum elsewhere), pulled 1 mm: the output contract (dem mode's curve
// files, summary.json with the hybrid's keys), and bad input refused by name before summary.json.
#include "apps/pullout_command.h"
#include "dem/io/checkpoint.h"
#include "small_hybrid_pullout_input.h"
#include "temporary_directory.h"
#include "text_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using geohybrid::testing::lines_of;
using geohybrid::testing::read_text;

namespace
{
fs::path test_directory()
{
  return geohybrid::testing::fresh_directory("test_app_pullout_hybrid_" +
                                             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
}

std::string error_of(const std::string &file, bool resume = false)
{
  try
    {
      geohybrid::apps::run_pullout_command(file, resume);
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}

/// The number a flat summary.json gives `key` (NaN if it has none).
double summary_number(const std::string &json, const std::string &key)
{
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos)
    return std::nan("");
  return std::stod(json.substr(at + key.size() + 4));
}
} // namespace

// About 40 s of CPU: the fill of the box, the coupled settling, 1 mm of pull.
TEST(PullOutHybridMode, WritesTheContractWithTheHybridKeys)
{
  const fs::path d = test_directory();
  const std::string input = geohybrid::testing::write_small_hybrid_pullout_input(d, "");
  ASSERT_EQ(error_of(input), "");
  const fs::path out = d / "out";
  const std::vector<std::string> curve = lines_of(out / "pullout_curve.csv");
  ASSERT_EQ(curve.size(), 1u + 6u); // header, the start and five intervals of 0.2 mm
  EXPECT_EQ(curve[0], "head_displacement_m,head_tension_kN_per_m");
  EXPECT_EQ(lines_of(out / "pullout_curve_sheet.csv").size(), curve.size());
  const std::vector<std::string> moves = lines_of(out / "sheet_displacements.csv");
  ASSERT_EQ(moves.size(), curve.size());
  EXPECT_EQ(moves[0], "head_displacement_m,beginning_displacement_m,middle_displacement_m,end_displacement_m");
  const std::vector<std::string> profiles = lines_of(out / "sheet_tension.csv");
  EXPECT_GT(profiles.size(), 2u * 25u); // two profiles of a row per segment (0.25 m of 1 cm segments)
  EXPECT_TRUE(fs::exists(out / "pullout_curve.png"));
  EXPECT_TRUE(fs::exists(out / "parameters.prm"));
  // The coupling's diagnostics at each point of the curve.
  const std::vector<std::string> diagnostics = lines_of(out / "coupling_diagnostics.csv");
  ASSERT_EQ(diagnostics.size(), curve.size());
  EXPECT_EQ(diagnostics[0].rfind("time_s,head_displacement_m,head_tension_N_per_m,particles_unbalanced_ratio,", 0), 0u)
    << diagnostics[0];

  std::stringstream text;
  text << std::ifstream(out / "summary.json").rdbuf();
  const std::string summary = text.str();
  EXPECT_NE(summary.find("\"mode\": \"hybrid\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"parameters_hash\": \"" + geohybrid::apps::check_pullout_input(input) + "\""),
            std::string::npos)
    << summary;
  EXPECT_NE(summary.find("\"coupling_method\": \"multipliers\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"DEM_region\": ["), std::string::npos) << summary;
  // The box [0.1, 0.4] x [0.05, 0.15] m of the 0.4 m x 0.2 m tank: 3/8 of 4,000 grains.
  EXPECT_NEAR(summary_number(summary, "n_particles"), 1500.0, 100.0) << summary;
  EXPECT_EQ(summary_number(summary, "n_particles_full_tank"), 4000.0);
  EXPECT_GT(summary_number(summary, "n_cells"), 0.0);
  EXPECT_GT(summary_number(summary, "band_width_m"), 0.0);
  EXPECT_LT(summary_number(summary, "band_width_m"), 0.05);
  EXPECT_GT(summary_number(summary, "T_max_kN_per_m"), 0.0);
  const double dt = summary_number(summary, "time_step_s"), dt_particles = summary_number(summary, "particle_time_step_s");
  EXPECT_GT(dt, 0.0);
  EXPECT_LE(dt, dt_particles * (1.0 + 1e-12));
  EXPECT_GT(summary_number(summary, "n_settling_steps"), 0.0);
  // The box's top was loaded by the 0.05 m of soil above it before the coupling (gamma 15.2
  // kN/m^3: 760 Pa), the lid released within 1 % of it.
  EXPECT_NEAR(summary_number(summary, "overburden_Pa"), 15.2e3 * 0.05, 1e-6) << summary;
  EXPECT_NEAR(summary_number(summary, "overburden_reached_Pa"), 15.2e3 * 0.05, 0.01 * 15.2e3 * 0.05);
  // The coupling forces on the two sides cancel to round-off at every point of the pull (the
  // multipliers act as -lambda on a particle and N_I lambda on the nodes, sum_I N_I = 1).
  const double largest = summary_number(summary, "coupling_force_max_N_per_m");
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(summary_number(summary, "coupling_force_imbalance_max_N_per_m"), 1e-10 * largest) << summary;
  // The coupled system's energy balance over the pull (the particles' budget booked from the
  // coupling on, the continuum's work ledger, the coupling's stored energy): measured 1.0e-4 at the
  // end, 1.9e-4 at most, of the clamp's work (0.13 J/m); 1.34 when the particles' dissipation was
  // not booked. The csv has its terms.
  std::cout << "energy balance over the pull: " << summary_number(summary, "energy_balance_error_relative")
            << " at the end, largest " << summary_number(summary, "energy_balance_error_max_relative") << std::endl;
  EXPECT_LT(summary_number(summary, "energy_balance_error_max_relative"), 1e-3) << summary;
  EXPECT_NE(diagnostics[0].find(",continuum_internal_work_J_per_m,continuum_damping_work_J_per_m,"
                                "continuum_gravity_work_J_per_m,coupling_work_on_continuum_J_per_m,continuum_sheet_truss_work_J_per_m,"
                                "continuum_sheet_interface_work_J_per_m,energy_balance_error"),
            std::string::npos)
    << diagnostics[0];
  // 1 mm at 5 mm/s: at least 0.2 s of coupled steps, and not much more (the start's ramp).
  const double pulled_for = summary_number(summary, "n_pull_steps") * dt;
  EXPECT_GE(pulled_for, 0.2 * (1.0 - 1e-9));
  EXPECT_LT(pulled_for, 0.3);
  // At 5 mm/s the pull is quasi-static: the watch, which keeps the grains in the box and weighs
  // their kinetic energy against the clamp's work, has nothing to say.
  EXPECT_NE(summary.find("\"warnings\": []"), std::string::npos) << summary;
  EXPECT_GT(summary_number(summary, "fill_wall_time_s"), 0.0);
  EXPECT_GE(summary_number(summary, "wall_time_s"), summary_number(summary, "fill_wall_time_s"));
  // Where the time went (issue 26): the set-up's settlings within it, the coupled steps' parts
  // each taken and within the pull's wall time, the pull after the set-up.
  const double set_up = summary_number(summary, "set_up_wall_time_s"), pull = summary_number(summary, "pull_wall_time_s");
  EXPECT_GT(summary_number(summary, "coupled_settling_wall_time_s"), 0.0);
  EXPECT_LE(summary_number(summary, "box_settling_wall_time_s") + summary_number(summary, "coupled_settling_wall_time_s"),
            set_up - summary_number(summary, "fill_wall_time_s"));
  double parts = 0.0;
  for (const char *part : {"pull_continuum_wall_time_s", "pull_coupling_wall_time_s", "pull_particles_wall_time_s"})
    {
      EXPECT_GT(summary_number(summary, part), 0.0) << part;
      parts += summary_number(summary, part);
    }
  EXPECT_GE(summary_number(summary, "pull_band_drive_wall_time_s"), 0.0);
  parts += summary_number(summary, "pull_band_drive_wall_time_s");
  EXPECT_LE(parts, pull);
  EXPECT_LE(set_up + pull, summary_number(summary, "wall_time_s") * (1.0 + 1e-9));
  for (const char *key : {"experimental_T_max_kN_per_m", "T_max_difference_percent", "gamma_H_Pa",
                          "sigma_v_top_face_Pa", "n_sheet_nodes"})
    EXPECT_NE(summary.find(std::string("\"") + key + "\""), std::string::npos) << key;
  fs::remove_all(d);
}

// The sheet crossing into the continuum from the input: 0.15 m of the 0.25 m sheet in the
// particles, the rest in the continuum (about 25 s of CPU).
TEST(PullOutHybridMode, SheetCrossesIntoTheContinuumFromTheInput)
{
  const fs::path d = test_directory();
  ASSERT_EQ(error_of(geohybrid::testing::write_small_hybrid_pullout_input(d, "subsection Hybrid\n  set DEM region length = 0.15\n"
                                    "  set continuum interface friction angle = 20\nend\n")),
            "");
  std::stringstream text;
  text << std::ifstream(d / "out" / "summary.json").rdbuf();
  const std::string summary = text.str();
  EXPECT_EQ(summary_number(summary, "DEM_region_length_m"), 0.15);
  EXPECT_GT(summary_number(summary, "sheet_nodes_in_particles"), 2.0);
  EXPECT_GT(summary_number(summary, "sheet_nodes_in_continuum"), 5.0);
  // The box starts at x = 0.25 m; the crossing lies a pad and a band (about 2 cm) inside it.
  EXPECT_GT(summary_number(summary, "sheet_crossing_x_m"), 0.25);
  EXPECT_LT(summary_number(summary, "sheet_crossing_x_m"), 0.3);
  EXPECT_GT(summary_number(summary, "T_max_kN_per_m"), 0.0);
  // The energy balance closes with the continuum's sheet booked (the library's test measures
  // 8.8e-5 with it, 0.37 without).
  std::cout << "energy balance over the pull, the sheet crossing: "
            << summary_number(summary, "energy_balance_error_max_relative") << " at most" << std::endl;
  EXPECT_LT(summary_number(summary, "energy_balance_error_max_relative"), 1e-3) << summary;
  fs::remove_all(d);
}

// Refused before the fill, naming the entry and the file, with no summary.json.
TEST(PullOutHybridMode, BadInputNamesTheEntryAndTheFile)
{
  const fs::path d = test_directory();
  struct Case
  {
    std::string extra, expected;
  };
  for (const Case &c : {Case{"subsection Hybrid\n  set coupling method = interface\n  set DEM region length = 0.15\nend\n",
                             "coupling method"},
                        Case{"subsection Hybrid\n  set coupling method = magic\nend\n", "coupling method"},
                        Case{"subsection Hybrid\n  set DEM region margin = -0.05\nend\n", "Hybrid/DEM region margin"},
                        Case{"subsection Hybrid\n  set DEM region margin = 1\nend\n", "Hybrid/DEM region margin"},
                        Case{"subsection Hybrid\n  set coupling method = penalty\n  set penalty factor = 0\nend\n",
                             "Hybrid/penalty factor"},
                        Case{"subsection Hybrid\n  set driven below weight = 1\nend\n", "Hybrid/driven below weight"},
                        Case{"subsection Hybrid\n  set DEM region length = 0.25\nend\n", "Hybrid/DEM region length"},
                        Case{"subsection Hybrid\n  set DEM region length = -0.1\nend\n", "Hybrid/DEM region length"},
                        Case{"subsection Hybrid\n  set continuum interface friction angle = 95\nend\n",
                             "Hybrid/continuum interface friction angle"},
                        Case{"subsection Hybrid\n  set lift thickness = thin\nend\n", "'Hybrid/lift thickness' = 'thin'"},
                        // The sheet's scaled inertia would set the answer, known before the fill.
                        Case{"subsection Sheet\n  set axial stiffness = 1e10\nend\n", "'Sheet/axial stiffness' = 1e+10 N/m"},
                        Case{"subsection Hybrid\n  set lift thickness = 0\nend\n", "'Hybrid/lift thickness' = '0'"},
                        // 0.05 m lifts (the input's) with 1,000 grains in the tank, up to 0.02 m
                        // across: the entries to change, with values that work.
                        Case{"subsection Filling\n  set number of particles = 1000\nend\n",
                             "set 'Filling/number of particles' to "},
                        Case{"subsection Filling\n  set number of particles = 1000\nend\n", "'Hybrid/lift thickness' = 0.05"}})
    {
      const std::string file = geohybrid::testing::write_small_hybrid_pullout_input(d, c.extra);
      const std::string error = error_of(file);
      EXPECT_NE(error.find(c.expected), std::string::npos) << c.extra << " -> " << error;
      EXPECT_NE(error.find(file), std::string::npos) << c.extra << " -> " << error;
      EXPECT_FALSE(fs::exists(d / "out" / "summary.json")) << c.extra;
    }
  fs::remove_all(d);
}

// The same pull 20 times faster (0.1 m/s) still runs to its end, and the watch says that the
// particles' kinetic energy (the continuum's left out) is a large share of the clamp's work
// (measured 13.1 % at 0.8 mm, where the warning starts at 5 %; none at 5 mm/s, above). About 20 s.
TEST(PullOutHybridMode, AFastPullFinishesWithTheWatchsWarning)
{
  const fs::path d = test_directory();
  const std::string input = geohybrid::testing::write_small_hybrid_pullout_input(d, "subsection Pull\n  set rate = 0.1\nend\n");
  ASSERT_EQ(error_of(input), "");
  const std::string summary = read_text(d / "out" / "summary.json");
  EXPECT_NE(summary.find("the pull's kinetic energy reached 13.1 % of the clamp's work"), std::string::npos) << summary;
  fs::remove_all(d);
}

// A coupled pull stopped twice ('stop after steps') and resumed from its checkpoints writes the
// same files, bit for bit, as the pull that never stopped, and ends in the same state: the
// particles and the continuum. The case with the most state: the sheet crossing into a
// Mohr-Coulomb continuum (its plastic strains, its sheet's slip and interface). A resumed run
// takes the filled box from filled_box.h5 and repeats the coupled set-up from it; one resumed
// before its box was full fills it again and says so.
TEST(PullOutHybridMode, ResumesAStoppedPullBitForBit)
{
  using geohybrid::apps::run_pullout_command;
  const fs::path d = test_directory();
  const std::string extra = "subsection Hybrid\n  set DEM region length = 0.15\n"
                            "  set continuum interface friction angle = 20\nend\n"
                            "subsection Continuum\n  set soil model = Mohr-Coulomb\n  set friction angle = 25\n"
                            "  set dilatancy angle = 0\nend\n";
  const std::string input = geohybrid::testing::write_small_hybrid_pullout_input(d, extra);
  const auto run_file = [&](const std::string &name) {
    const fs::path file = d / (name + ".prm");
    std::ofstream(file) << read_text(input) << "set output directory = " << (d / name).string() << "\n";
    return file.string();
  };
  const std::string straight = run_file("straight"), stopped = run_file("stopped"), refilled = run_file("refilled");
  ASSERT_EQ(run_pullout_command(straight, false), 0);
  ASSERT_EQ(run_pullout_command(stopped, false, {{"stop after steps", "2000"}}), 0);
  EXPECT_FALSE(fs::exists(d / "stopped" / "summary.json")); // not a finished run
  ASSERT_TRUE(fs::exists(d / "stopped" / "filled_box.h5"));
  ASSERT_TRUE(fs::exists(d / "stopped" / "checkpoint.h5"));
  // Resumed with another continuum: refused before the set-up, naming the entry and the file.
  std::string refused;
  try
    {
      run_pullout_command(stopped, true, {{"Hybrid/continuum interface friction angle", "22"}});
    }
  catch (const std::exception &e)
    {
      refused = e.what();
    }
  EXPECT_NE(refused.find("cannot resume from '" + (d / "stopped" / "filled_box.h5").string() + "'"), std::string::npos)
    << refused;
  EXPECT_NE(refused.find("'Hybrid/continuum interface friction angle' = '22' (checkpoint: '20')"), std::string::npos)
    << refused;
  ASSERT_EQ(run_pullout_command(stopped, true, {{"stop after steps", "5000"}}), 0);
  EXPECT_FALSE(fs::exists(d / "stopped" / "summary.json"));
  ASSERT_EQ(run_pullout_command(stopped, true), 0);

  testing::internal::CaptureStdout();
  const int status = run_pullout_command(refilled, true);
  const std::string said = testing::internal::GetCapturedStdout();
  ASSERT_EQ(status, 0);
  EXPECT_NE(said.find("filling the box again from the start"), std::string::npos) << said;

  for (const char *file : {"pullout_curve.csv", "pullout_curve_sheet.csv", "sheet_displacements.csv", "sheet_tension.csv",
                           "coupling_diagnostics.csv"})
    for (const char *other : {"stopped", "refilled"})
      {
        const std::string expected = read_text(d / "straight" / file);
        EXPECT_GT(expected.size(), 50u) << file;
        EXPECT_TRUE(read_text(d / other / file) == expected) << other << '/' << file;
      }
  EXPECT_EQ(lines_of(d / "straight" / "pullout_curve.csv").size(), 1u + 6u);
  const std::string summary = read_text(d / "stopped" / "summary.json");
  EXPECT_GT(summary_number(summary, "resumed_at_head_displacement_m"), 0.0) << summary;
  EXPECT_EQ(summary_number(summary, "T_max_kN_per_m"), summary_number(read_text(d / "straight" / "summary.json"), "T_max_kN_per_m"));
  const auto hash_in = [](const std::string &text) {
    const auto at = text.find("\"parameters_hash\": \"");
    return at == std::string::npos ? std::string("none") : text.substr(at + 20, 16);
  };
  EXPECT_NE(hash_in(summary), "none");
  EXPECT_EQ(hash_in(summary), hash_in(read_text(d / "straight" / "summary.json"))); // stop after steps: run control
  // The final states (each run writes a checkpoint at its end): every body, the continuum.
  geohybrid::dem::CommandState ca, cb;
  const geohybrid::dem::DemSystemState a = geohybrid::dem::read_checkpoint(d / "straight" / "checkpoint.h5", ca),
                                       b = geohybrid::dem::read_checkpoint(d / "stopped" / "checkpoint.h5", cb);
  EXPECT_EQ(a.step_count, b.step_count);
  EXPECT_EQ(a.time, b.time);
  ASSERT_EQ(a.particles.n_bodies(), b.particles.n_bodies());
  for (std::size_t k = 0; k < a.particles.n_bodies(); ++k)
    {
      ASSERT_EQ(a.particles.x[k], b.particles.x[k]) << "body " << k;
      ASSERT_EQ(a.particles.vy[k], b.particles.vy[k]) << "body " << k;
    }
  for (const char *key : {"continuum_displacement", "continuum_velocity", "continuum_material_points",
                          "continuum_sheet_displacement", "continuum_sheet_arc_length", "continuum_ledger"})
    EXPECT_TRUE(ca.real(key) == cb.real(key)) << key;
  // The Mohr-Coulomb continuum yielded somewhere (a plastic strain in the state), so the test
  // carries its plastic state across the stops.
  const std::vector<double> &points = ca.real("continuum_material_points");
  double largest_plastic = 0.0;
  for (std::size_t p = 0; p + 26 <= points.size(); p += 26)
    for (std::size_t k = 6; k < 12; ++k)
      largest_plastic = std::max(largest_plastic, std::abs(points[p + k]));
  std::cout << "largest plastic strain component in the continuum " << largest_plastic << std::endl;
  EXPECT_GT(largest_plastic, 0.0);
  fs::remove_all(d);
}
