// SIGTERM and SIGINT stop `geohybrid pullout` and `geohybrid dem` cleanly (apps/interrupt.h). The
// real program runs in a child process and gets a real signal from kill(2), so that the handler,
// the loop's check, the exit status and the files on disk are those a user meets: the status of a
// process the signal killed (143, 130), no summary.json, a checkpoint, every recorded row in the
// curve files, and a --resume that ends where a run that never stopped ends, bit for bit.
#include "geohybrid_child.h"
#include "hybrid_pullout_contract.h"
#include "small_hybrid_pullout_input.h"
#include "temporary_directory.h"
#include "text_file.h"
#include "tiny_pullout_input.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using geohybrid::testing::lines_of;
using geohybrid::testing::read_text;
using geohybrid::testing::run_geohybrid;
using geohybrid::testing::start_geohybrid;
using geohybrid::testing::wait_for;

namespace
{
fs::path interrupt_test_directory()
{
  return geohybrid::testing::fresh_directory("test_app_interrupt_" +
                                             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
}

/// Waits until `ready` holds or the child has ended (false then), polling every millisecond.
template <typename Ready>
bool wait_while_running(pid_t pid, const Ready &ready)
{
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (std::chrono::steady_clock::now() < give_up)
    {
      if (ready())
        return true;
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid)
        return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  return false;
}

std::size_t rows_of(const fs::path &csv)
{
  const std::size_t lines = lines_of(csv).size();
  return lines > 0 ? lines - 1 : 0;
}

/// The text of `"key": value` in a summary.json, as written.
std::string summary_text(const fs::path &file, const std::string &key)
{
  const std::string text = read_text(file), quoted = "\"" + key + "\": ";
  const auto at = text.find(quoted);
  if (at == std::string::npos)
    return "";
  const auto start = at + quoted.size();
  return text.substr(start, text.find_first_of(",\n}", start) - start);
}

/// The tiny pull-out of tiny_pullout_input.h recorded every 0.05 mm over 2 mm (41 points, about
/// 10,000 steps), its output in `out`.
std::string write_pull_input(const fs::path &directory, const std::string &out)
{
  const std::string base = geohybrid::testing::write_tiny_pullout_input(directory);
  const fs::path file = directory / (out + ".prm");
  std::ofstream(file) << read_text(base) << "set output directory = " << (directory / out).string() << "\n"
                      << "subsection Pull\n  set final displacement = 0.002\n  set record interval = 0.00005\n"
                      << "  set tension profiles at = 0.0005, 0.002\nend\n"
                      << "subsection Output\n  set field outputs at = 0.001\nend\n";
  return file.string();
}
} // namespace

// A SIGTERM after a few points of the curve: the pull stops at the end of that step, exits with
// 143, writes its checkpoint and keeps every row recorded (the straight run's rows, as they were),
// and no summary.json; --resume then finishes with the straight run's files, bit for bit, T_max
// the same string. About 12 s of CPU: two fills of 400 clusters and two pulls of 2 mm.
TEST(PullOutInterrupted, SigtermKeepsTheRowsAndResumesBitForBit)
{
  const fs::path d = interrupt_test_directory();
  const std::string straight = write_pull_input(d, "straight"), stopped = write_pull_input(d, "stopped");
  ASSERT_EQ(run_geohybrid({"pullout", straight}, d / "straight.log"), 0) << read_text(d / "straight.log");
  const std::vector<std::string> expected = lines_of(d / "straight" / "pullout_curve.csv");
  ASSERT_EQ(expected.size(), 1u + 41u);

  const pid_t child = start_geohybrid({"pullout", stopped}, d / "stopped.log");
  const fs::path curve = d / "stopped" / "pullout_curve.csv";
  ASSERT_TRUE(wait_while_running(child, [&] { return rows_of(curve) >= 4; })) << read_text(d / "stopped.log");
  const std::size_t rows_at_signal = rows_of(curve);
  ASSERT_EQ(kill(child, SIGTERM), 0);
  EXPECT_EQ(wait_for(child), 143) << read_text(d / "stopped.log");

  const std::string said = read_text(d / "stopped.log");
  EXPECT_NE(said.find("interrupted by SIGTERM at "), std::string::npos) << said;
  EXPECT_NE(said.find("continue with: "), std::string::npos) << said;
  EXPECT_NE(said.find(stopped + " --resume"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(d / "stopped" / "summary.json"));
  EXPECT_TRUE(fs::exists(d / "stopped" / "checkpoint.h5"));
  EXPECT_FALSE(fs::exists(d / "stopped" / "checkpoint.h5.tmp"));
  // Every row recorded before the signal is on disk, and each is the straight run's.
  const std::vector<std::string> kept = lines_of(curve);
  ASSERT_GE(kept.size(), 1u + rows_at_signal);
  ASSERT_LT(kept.size(), expected.size()) << "the pull had finished before the signal";
  for (std::size_t k = 0; k < kept.size(); ++k)
    EXPECT_EQ(kept[k], expected[k]) << "line " << k;
  std::cout << "SIGTERM after " << rows_at_signal << " rows: stopped with " << kept.size() - 1 << " of "
            << expected.size() - 1 << " rows written" << std::endl;

  ASSERT_EQ(run_geohybrid({"pullout", stopped, "--resume"}, d / "resumed.log"), 0) << read_text(d / "resumed.log");
  for (const char *file : {"pullout_curve.csv", "pullout_curve_sheet.csv", "sheet_displacements.csv",
                           "sheet_tension.csv", "grain_displacements_u1mm.csv"})
    EXPECT_TRUE(read_text(d / "stopped" / file) == read_text(d / "straight" / file)) << file;
  const std::string T_max = summary_text(d / "straight" / "summary.json", "T_max_kN_per_m");
  EXPECT_FALSE(T_max.empty());
  EXPECT_EQ(summary_text(d / "stopped" / "summary.json", "T_max_kN_per_m"), T_max);
  fs::remove_all(d);
}

// Hybrid mode shares the pull's loop: a SIGTERM during the coupled pull stops it with 143, a
// checkpoint (the particles' and the continuum's states), the rows so far and no summary.json;
// --resume repeats the set-up from the filled box and ends with the straight run's curve, bit for
// bit; the straight run also meets the hybrid mode's output contract (hybrid_pullout_contract.h).
// About 50 s of CPU: two fills of the small hybrid tank's box, two pulls of 1 mm.
TEST(PullOutInterrupted, HybridSigtermKeepsTheRowsAndResumesBitForBit)
{
  const fs::path d = interrupt_test_directory();
  fs::create_directories(d / "straight");
  fs::create_directories(d / "stopped");
  const std::string straight = geohybrid::testing::write_small_hybrid_pullout_input(d / "straight"),
                    stopped = geohybrid::testing::write_small_hybrid_pullout_input(d / "stopped");
  ASSERT_EQ(run_geohybrid({"pullout", straight}, d / "straight.log"), 0) << read_text(d / "straight.log");
  // The straight run is also the one of the hybrid mode's output contract.
  geohybrid::testing::expect_hybrid_pullout_contract(d / "straight" / "out", straight);
  const std::vector<std::string> expected = lines_of(d / "straight" / "out" / "pullout_curve.csv");
  ASSERT_EQ(expected.size(), 1u + 6u);

  const pid_t child = start_geohybrid({"pullout", stopped}, d / "stopped.log");
  const fs::path curve = d / "stopped" / "out" / "pullout_curve.csv";
  ASSERT_TRUE(wait_while_running(child, [&] { return rows_of(curve) >= 2; })) << read_text(d / "stopped.log");
  ASSERT_EQ(kill(child, SIGTERM), 0);
  EXPECT_EQ(wait_for(child), 143) << read_text(d / "stopped.log");
  EXPECT_NE(read_text(d / "stopped.log").find(stopped + " --resume"), std::string::npos) << read_text(d / "stopped.log");
  EXPECT_FALSE(fs::exists(d / "stopped" / "out" / "summary.json"));
  EXPECT_TRUE(fs::exists(d / "stopped" / "out" / "checkpoint.h5"));
  const std::vector<std::string> kept = lines_of(curve);
  ASSERT_LT(kept.size(), expected.size()) << "the pull had finished before the signal";
  for (std::size_t k = 0; k < kept.size(); ++k)
    EXPECT_EQ(kept[k], expected[k]) << "line " << k;

  ASSERT_EQ(run_geohybrid({"pullout", stopped, "--resume"}, d / "resumed.log"), 0) << read_text(d / "resumed.log");
  for (const char *file :
       {"pullout_curve.csv", "pullout_forces.csv", "sheet_displacements.csv", "sheet_tension.csv", "coupling_diagnostics.csv"})
    EXPECT_TRUE(read_text(d / "stopped" / "out" / file) == read_text(d / "straight" / "out" / file)) << file;
  EXPECT_EQ(summary_text(d / "stopped" / "out" / "summary.json", "T_max_kN_per_m"),
            summary_text(d / "straight" / "out" / "summary.json", "T_max_kN_per_m"));
  fs::remove_all(d);
}

// A SIGTERM while the tank is filling: nothing resumable exists yet; the run stops at once with
// 143, says so, and leaves no checkpoint and no summary.json. About 1 s of CPU.
TEST(PullOutInterrupted, SigtermWhileFillingStopsWithoutACheckpoint)
{
  const fs::path d = interrupt_test_directory();
  const std::string input = write_pull_input(d, "out");
  const pid_t child = start_geohybrid({"pullout", input}, d / "out.log");
  ASSERT_TRUE(wait_while_running(child, [&] { return fs::exists(d / "out" / "parameters.prm"); }));
  ASSERT_EQ(kill(child, SIGTERM), 0);
  EXPECT_EQ(wait_for(child), 143) << read_text(d / "out.log");
  const std::string said = read_text(d / "out.log");
  EXPECT_NE(said.find("interrupted by SIGTERM while filling the tank: nothing to resume yet; run it again: "),
            std::string::npos)
    << said;
  // Its directory holds this run's files: the command that starts it again replaces them.
  EXPECT_NE(said.find(input + " --overwrite"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(d / "out" / "checkpoint.h5"));
  EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
  EXPECT_EQ(rows_of(d / "out" / "pullout_curve.csv"), 0u);
  fs::remove_all(d);
}

// `geohybrid dem` and SIGINT (Ctrl-C): a deposition stopped after a few rows of its time series
// exits with 130, with its checkpoint and those rows and without final_particles.csv or
// summary.json; --resume ends with the straight run's time series and final packing, bit for bit.
TEST(DemInterrupted, SigintKeepsTheRowsAndResumesBitForBit)
{
  const fs::path d = interrupt_test_directory();
  const auto write_input = [&](const std::string &out) {
    const fs::path file = d / (out + ".prm");
    std::ofstream(file) << "set output directory = " << (d / out).string() << "\nset threads = 1\n"
                        << "subsection Particles\n  set number of particles = 300\n  set minimum radius = 0.004\n"
                        << "  set maximum radius = 0.005\nend\n"
                        << "subsection Box\n  set width = 0.3\n  set height = 0.3\nend\n"
                        << "subsection Particle contact\n  set restitution coefficient = 0.5\nend\n"
                        << "subsection Simulation\n  set end time = 0.15\n  set output interval = 0.001\n"
                        << "  set snapshot interval = 0.05\n  set history particles = 0, 7\nend\n";
    return file.string();
  };
  const std::string straight = write_input("straight"), stopped = write_input("stopped");
  ASSERT_EQ(run_geohybrid({"dem", straight}, d / "straight.log"), 0) << read_text(d / "straight.log");
  const std::vector<std::string> expected = lines_of(d / "straight" / "time_series.csv");

  const pid_t child = start_geohybrid({"dem", stopped}, d / "stopped.log");
  const fs::path series = d / "stopped" / "time_series.csv";
  ASSERT_TRUE(wait_while_running(child, [&] { return rows_of(series) >= 5; })) << read_text(d / "stopped.log");
  ASSERT_EQ(kill(child, SIGINT), 0);
  EXPECT_EQ(wait_for(child), 130) << read_text(d / "stopped.log");
  const std::string said = read_text(d / "stopped.log");
  EXPECT_NE(said.find("interrupted by SIGINT at t = "), std::string::npos) << said;
  EXPECT_NE(said.find(stopped + " --resume"), std::string::npos) << said;
  EXPECT_TRUE(fs::exists(d / "stopped" / "checkpoint.h5"));
  EXPECT_FALSE(fs::exists(d / "stopped" / "summary.json"));
  EXPECT_FALSE(fs::exists(d / "stopped" / "final_particles.csv"));
  const std::vector<std::string> kept = lines_of(series);
  ASSERT_LT(kept.size(), expected.size()) << "the run had finished before the signal";
  for (std::size_t k = 0; k < kept.size(); ++k)
    EXPECT_EQ(kept[k], expected[k]) << "line " << k;

  ASSERT_EQ(run_geohybrid({"dem", stopped, "--resume"}, d / "resumed.log"), 0) << read_text(d / "resumed.log");
  for (const char *file : {"time_series.csv", "particle_history.csv", "final_particles.csv"})
    EXPECT_TRUE(read_text(d / "stopped" / file) == read_text(d / "straight" / file)) << file;
  fs::remove_all(d);
}

// `geohybrid pullout` in fem mode and SIGINT (Ctrl-C): the continuum has no checkpoint, so the
// run stops at the next point of its curve with 130, keeps the points so far (flushed at each)
// and says to run it again; no summary.json, no checkpoint. The elastic tank of
// tests/test_app_pullout_fem.cc, pulled 20 mm so that the signal lands well inside the pull.
TEST(FemInterrupted, SigintKeepsTheCurveSoFarAndSaysToRunAgain)
{
  const fs::path d = interrupt_test_directory();
  const fs::path input = d / "fem.prm";
  std::ofstream(input) << "set output directory = " << (d / "out").string() << "\nset mode = fem\n"
                       << "subsection Tank\n  set length = 0.6\n  set fill height = 1.0\nend\n"
                       << "subsection Anchorage\n  set H = 0.775\n  set L = 0.55\nend\n"
                       << "subsection Pull\n  set rate = 0.004\n  set final displacement = 0.02\n"
                       << "  set record interval = 0.0005\n  set ramp displacement = 0\n"
                       << "  set tension profiles at = 0.02\nend\n"
                       << "subsection Continuum\n  set cell size = 0.05\n  set sheet node spacing = 0.025\n"
                       << "  set soil model = linear elastic\n  set Young modulus = 20e6\n  set Poisson ratio = 0.3\nend\n";
  const pid_t child = start_geohybrid({"pullout", input.string()}, d / "out.log");
  const fs::path curve = d / "out" / "pullout_curve.csv";
  ASSERT_TRUE(wait_while_running(child, [&] { return rows_of(curve) >= 3; })) << read_text(d / "out.log");
  ASSERT_EQ(kill(child, SIGINT), 0);
  EXPECT_EQ(wait_for(child), 130) << read_text(d / "out.log");
  const std::string said = read_text(d / "out.log");
  EXPECT_NE(said.find("interrupted by SIGINT at "), std::string::npos) << said;
  EXPECT_NE(said.find("fem mode writes no checkpoints"), std::string::npos) << said;
  EXPECT_NE(said.find("run it again: "), std::string::npos) << said;
  EXPECT_NE(said.find(input.string() + " --overwrite"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
  EXPECT_FALSE(fs::exists(d / "out" / "checkpoint.h5"));
  const std::size_t kept = rows_of(curve);
  EXPECT_GE(kept, 3u);
  EXPECT_LT(kept, 41u) << "the pull had finished before the signal"; // 20 mm every 0.5 mm, and u = 0
  fs::remove_all(d);
}
