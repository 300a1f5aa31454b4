// `geohybrid pullout` with 'mode = hybrid' end to end on the small tank of
// test_coupling_hybrid_pullout.cc (0.4 m x 0.2 m, 4,000 grains for the whole tank, about 1,500 in
// the box, an elastic continuum elsewhere), pulled 1 mm: the sheet crossing, a fast pull, resumes,
// and bad input refused by name before summary.json (the output contract: hybrid_pullout_contract.h).
#include "apps/pullout_command.h"
#include "dem/io/checkpoint.h"
#include "hybrid_pullout_contract.h"
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
using geohybrid::testing::summary_number;

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
} // namespace

// The output contract (hybrid_pullout_contract.h) is checked on the straight run of
// PullOutInterrupted.HybridSigtermKeepsTheRowsAndResumesBitForBit (test_app_interrupt.cc), the same input.

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
                        Case{"subsection Filling\n  set number of particles = 1000\nend\n", "'Hybrid/lift thickness' = 0.05"},
                        // The box cut from a tank that is not there, or from a hybrid run's box.
                        Case{"subsection Hybrid\n  set particles from = no_such_tank.h5\nend\n",
                             "parameter 'Hybrid/particles from' = 'no_such_tank.h5': cannot read a filled tank there"},
                        Case{"subsection Hybrid\n  set particles from = " GEOHYBRID_SOURCE_DIR "/tests/main_job/filled_box.h5\nend\n",
                             "/tests/main_job/filled_box.h5': not a dem-mode run's tank"}})
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
// (measured 9.91 % at 0.8 mm, where the warning starts at 5 %; none at 5 mm/s, above). About 20 s.
TEST(PullOutHybridMode, AFastPullFinishesWithTheWatchsWarning)
{
  const fs::path d = test_directory();
  const std::string input = geohybrid::testing::write_small_hybrid_pullout_input(d, "subsection Pull\n  set rate = 0.1\nend\n");
  ASSERT_EQ(error_of(input), "");
  const std::string summary = read_text(d / "out" / "summary.json");
  EXPECT_NE(summary.find("the pull's kinetic energy reached 9.91 % of the clamp's work"), std::string::npos) << summary;
  fs::remove_all(d);
}

// A coupled pull stopped twice ('stop after steps') and resumed from its checkpoints writes the
// same files, bit for bit, as the pull that never stopped, and ends in the same state: the
// particles and the continuum. The case with the most state: the sheet crossing into a
// Mohr-Coulomb continuum (its plastic strains, its sheet's slip and interface). A resumed run
// takes the filled box from filled_box.h5 and repeats the coupled set-up from it; one resumed
// before its box was full fills it again and says so: the stopped run's first part is such a
// resume (of a run never started), so that the whole chain, refill included, ends bit for bit as
// the straight run without a third run of its own.
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
  const std::string straight = run_file("straight"), stopped = run_file("stopped");
  ASSERT_EQ(run_pullout_command(straight, false), 0);
  testing::internal::CaptureStdout();
  const int status = run_pullout_command(stopped, true, {{"stop after steps", "2000"}});
  const std::string said = testing::internal::GetCapturedStdout();
  ASSERT_EQ(status, 0);
  EXPECT_NE(said.find("filling the box again from the start"), std::string::npos) << said;
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

  for (const char *file : {"pullout_curve.csv", "pullout_curve_sheet.csv", "pullout_forces.csv", "sheet_displacements.csv",
                           "sheet_tension.csv", "coupling_diagnostics.csv"})
    {
      const std::string expected = read_text(d / "straight" / file);
      EXPECT_GT(expected.size(), 50u) << file;
      EXPECT_TRUE(read_text(d / "stopped" / file) == expected) << file;
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
