// The `geohybrid dem` command end to end: a tiny scene runs and writes its results; bad input is
// refused before anything is written, with a message naming the file and the parameter.
#include "apps/dem_command.h"
#include "apps/output_guard.h"
#include "dem/io/particle_csv.h"
#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;

namespace
{
class DemCommand : public ::testing::Test
{
protected:
  void SetUp() override
  {
    directory_ = geohybrid::testing::fresh_directory(std::string("test_app_dem_") +
                                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { fs::remove_all(directory_); }

  /// Writes an input file: a small deposition plus `extra` lines, returns its path.
  std::string input(const std::string &extra, const std::string &name = "scene.prm")
  {
    const fs::path file = directory_ / name;
    std::ofstream out(file);
    out << "set output directory = " << (directory_ / "out").string() << "\n"
        << "set threads = 1\n"
        << "subsection Particles\n  set number of particles = 60\n  set minimum radius = 0.004\n"
        << "  set maximum radius = 0.005\nend\n"
        << "subsection Box\n  set width = 0.1\n  set height = 0.2\nend\n"
        << "subsection Simulation\n  set end time = 0.02\n  set output interval = 0.005\n"
        << "  set snapshot interval = 0.01\n  set history particles = 0, 3\nend\n"
        << extra;
    return file.string();
  }

  /// Runs the command and returns the error message (empty if it succeeded).
  static std::string error_of(const std::string &file, bool resume = false)
  {
    try
      {
        geohybrid::apps::run_dem_command(file, resume);
      }
    catch (const std::exception &e)
      {
        return e.what();
      }
    return "";
  }

  static std::string contents(const fs::path &file)
  {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  static std::size_t count_lines(const fs::path &file)
  {
    std::ifstream in(file);
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);)
      ++lines;
    return lines;
  }

  fs::path directory_;
};
} // namespace

TEST_F(DemCommand, SmallDepositionWritesAllOutputs)
{
  ASSERT_EQ(error_of(input("")), "");
  for (const char *name : {"summary.json", "time_series.csv", "particle_history.csv", "particles.h5",
                           "particles.xdmf", "final_particles.csv", "parameters.prm"})
    EXPECT_TRUE(fs::exists(directory_ / "out" / name)) << name;
  // History: one row per chosen particle (2) at each time-series row.
  const auto count_lines = [](const fs::path &file) {
    std::ifstream in(file);
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);)
      ++lines;
    return lines;
  };
  const std::size_t series_rows = count_lines(directory_ / "out" / "time_series.csv") - 1;
  EXPECT_GE(series_rows, 5u); // t = 0 and every 5 ms up to 20 ms
  EXPECT_EQ(count_lines(directory_ / "out" / "particle_history.csv"), 1u + 2u * series_rows);
  // The final packing reads back as the same particles.
  const auto p = geohybrid::dem::read_particle_csv(directory_ / "out" / "final_particles.csv", 2650.0, 0.5);
  EXPECT_EQ(p.n_bodies(), 60u);
}

TEST_F(DemCommand, UnknownParameterNamesFileAndEntry)
{
  const std::string file = input("set stiffnes = 3\n");
  const std::string message = error_of(file);
  EXPECT_NE(message.find("stiffnes"), std::string::npos) << message;
  EXPECT_NE(message.find("scene.prm"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(directory_ / "out"));
}

TEST_F(DemCommand, NegativeStiffnessRefused)
{
  const std::string message = error_of(input("subsection Particle contact\n  set normal stiffness = -7e7\nend\n"));
  EXPECT_NE(message.find("normal stiffness"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(directory_ / "out"));
}

TEST_F(DemCommand, TimeStepAboveStableLimitRefused)
{
  const std::string message = error_of(input("subsection Simulation\n  set time step = 0.01\nend\n"));
  EXPECT_NE(message.find("stable limit"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(directory_ / "out"));
}

TEST_F(DemCommand, MissingInputFileRefused)
{
  const std::string message = error_of((directory_ / "nowhere.prm").string());
  EXPECT_NE(message.find("nowhere.prm"), std::string::npos) << message;
}

TEST_F(DemCommand, OverlappingCsvParticlesRefused)
{
  std::ofstream(directory_ / "particles.csv") << "x,y,radius,vx,vy,omega\n0.05,0.05,0.01,0,0,0\n0.06,0.05,0.01,0,0,0\n";
  const std::string message =
    error_of(input("subsection Particles\n  set source = csv\n  set csv file = particles.csv\nend\n"));
  EXPECT_NE(message.find("particles.csv"), std::string::npos) << message;
  EXPECT_NE(message.find("line 3"), std::string::npos) << message;
  EXPECT_NE(message.find("overlaps"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(directory_ / "out"));
}

TEST_F(DemCommand, MissingCsvFileRefused)
{
  const std::string message =
    error_of(input("subsection Particles\n  set source = csv\n  set csv file = absent.csv\nend\n"));
  EXPECT_NE(message.find("absent.csv"), std::string::npos) << message;
}

TEST_F(DemCommand, ParticlesOutsideTheBoxRefused)
{
  const std::string message = error_of(input("subsection Particles\n  set number of particles = 5000\nend\n"
                                             "subsection Box\n  set top wall = true\nend\n"));
  EXPECT_NE(message.find("outside the box"), std::string::npos) << message;
}

// A CSV scene of two discs colliding head-on: the command reproduces the closed-form rebound.
TEST_F(DemCommand, CsvImpactIsScriptable)
{
  std::ofstream(directory_ / "pair.csv") << "x,y,radius,vx,vy,omega\n0.04,0.1,0.01,0.2,0,0\n0.0601,0.1,0.01,-0.2,0,0\n";
  ASSERT_EQ(error_of(input("subsection Particles\n  set source = csv\n  set csv file = pair.csv\nend\n"
                           "subsection Simulation\n  set gravity = 0\n  set local damping coefficient = 0\n"
                           "  set time step safety factor = 0.02\n"
                           "  set history particles = 0, 1\nend\n")),
            "");
  const auto p = geohybrid::dem::read_particle_csv(directory_ / "out" / "final_particles.csv", 2650.0, 0.5);
  EXPECT_NEAR(p.vx[0], -0.2, 2e-3);
  EXPECT_NEAR(p.vx[1], 0.2, 2e-3);
}

// Without gravity the energy balance is relative to the largest of the budget's terms (here the
// pair's kinetic energy), not to |gravitational| = 0: a head-on impact with dashpots (e = 0.5)
// reports a finite error in summary.json and in every row of the time series (it was 6e291).
// At 0.02 of the critical step the balance closes to 1e-4 (EnergyBalance.* in test_dem_energy.cc);
// 1e-3 is the tolerance.
TEST_F(DemCommand, EnergyBalanceWithoutGravityIsFinite)
{
  std::ofstream(directory_ / "pair.csv") << "x,y,radius,vx,vy,omega\n0.04,0.1,0.01,0.2,0,0\n0.0601,0.1,0.01,-0.2,0,0\n";
  ASSERT_EQ(error_of(input("subsection Particles\n  set source = csv\n  set csv file = pair.csv\nend\n"
                           "subsection Particle contact\n  set restitution coefficient = 0.5\nend\n"
                           "subsection Simulation\n  set gravity = 0\n  set local damping coefficient = 0\n"
                           "  set time step safety factor = 0.02\n  set history particles = 0, 1\nend\n")),
            "");
  const std::string summary = contents(directory_ / "out" / "summary.json");
  const std::string key = "\"energy_balance_error_relative\": ";
  const auto at = summary.find(key);
  ASSERT_NE(at, std::string::npos) << summary;
  ASSERT_NE(summary.compare(at + key.size(), 4, "null"), 0) << summary;
  const double error = std::stod(summary.substr(at + key.size()));
  std::cout << "energy balance without gravity: " << std::scientific << std::setprecision(3) << error << std::defaultfloat << std::endl;
  EXPECT_LT(std::abs(error), 1e-3) << summary;
  EXPECT_NE(summary.find("\"energy_balance_error_relative_definition\""), std::string::npos);
  std::ifstream series(directory_ / "out" / "time_series.csv");
  std::string line;
  std::getline(series, line);
  std::size_t rows = 0;
  for (; std::getline(series, line); ++rows)
    {
      std::istringstream fields(line);
      std::string field;
      for (int column = 0; column < 9; ++column)
        std::getline(fields, field, ',');
      EXPECT_LT(std::abs(std::stod(field)), 1e-3) << line; // column 9: energy_balance_error
    }
  EXPECT_GE(rows, 5u);
  // The pair did collide: the dashpots took energy.
  const auto p = geohybrid::dem::read_particle_csv(directory_ / "out" / "final_particles.csv", 2650.0, 0.5);
  EXPECT_LT(p.vx[1] - p.vx[0], 0.4 * 0.6);
}

// The automatic step is the safety factor times the critical step of the scene with its walls
// (here stiffer than the grains), the one the run prints and the one a refused step is held to.
TEST_F(DemCommand, AutomaticStepIsTheSafetyFactorOfTheCriticalStep)
{
  ASSERT_EQ(error_of(input("subsection Wall contact\n  set normal stiffness = 2e8\n  set shear stiffness = 1e8\nend\n"
                           "subsection Simulation\n  set end time = 0.002\nend\n")),
            "");
  const std::string summary = contents(directory_ / "out" / "summary.json");
  const auto value = [&](const std::string &key) {
    const auto at = summary.find("\"" + key + "\": ");
    return at == std::string::npos ? std::nan("") : std::stod(summary.substr(at + key.size() + 4));
  };
  EXPECT_NEAR(value("time_step_s") / value("critical_time_step_s"), 0.5, 1e-9) << summary;
}

// A run stopped part-way (end time 12.3 ms, off the output and snapshot intervals) and continued
// with --resume to the full end time (20 ms) ends exactly where the straight run ends, and its
// output files are those of the straight run: the rows after the checkpoint that a crashed run may
// leave (simulated by a later row and a half-written one) and the earlier run's off-interval
// end-of-run row and snapshot are dropped.
TEST_F(DemCommand, ResumedRunMatchesStraightRun)
{
  const fs::path straight = directory_ / "straight", split = directory_ / "out";
  ASSERT_EQ(error_of(input("set output directory = " + straight.string() + "\n", "straight.prm")), "");
  ASSERT_EQ(error_of(input("subsection Simulation\n  set end time = 0.0123\nend\n", "part.prm")), "");
  ASSERT_TRUE(fs::exists(split / "checkpoint.h5"));
  EXPECT_FALSE(fs::exists(split / "checkpoint.h5.tmp"));
  EXPECT_NE(contents(split / "summary.json").find("\"resumed_from_time_s\": null"), std::string::npos);
  const std::size_t part_rows = count_lines(split / "time_series.csv");
  {
    std::ofstream later(split / "time_series.csv", std::ios::app);
    later << "0.015" << std::string(12, ',') << std::string(2 * 3, ',') << "\n0.016,1,2";
  }

  ASSERT_EQ(error_of(input("", "full.prm"), true), "");
  for (const char *name : {"final_particles.csv", "time_series.csv", "particle_history.csv", "particles.xdmf"})
    EXPECT_EQ(contents(split / name), contents(straight / name)) << name;
  EXPECT_EQ(count_lines(split / "time_series.csv"), count_lines(straight / "time_series.csv"));
  EXPECT_GT(count_lines(split / "time_series.csv"), part_rows);
  const std::string summary = contents(split / "summary.json");
  EXPECT_NE(summary.find("\"resumed_from_time_s\": 0.0123"), std::string::npos) << summary;
  EXPECT_EQ(contents(split / "summary.json").find("\"end_time_s\""),
            contents(straight / "summary.json").find("\"end_time_s\""));
}

TEST_F(DemCommand, ResumeWithoutCheckpointRefused)
{
  std::string message = error_of(input(""), true);
  EXPECT_NE(message.find((directory_ / "out" / "checkpoint.h5").string()), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(directory_ / "out"));
  // 'checkpoint interval = 0' writes none, and removes a stale one from an earlier run.
  ASSERT_EQ(error_of(input("subsection Simulation\n  set end time = 0.002\nend\n")), "");
  ASSERT_TRUE(fs::exists(directory_ / "out" / "checkpoint.h5"));
  geohybrid::apps::set_overwrite_output(true); // a new run where the last one was
  ASSERT_EQ(error_of(input("subsection Simulation\n  set end time = 0.002\n  set checkpoint interval = 0\nend\n")),
            "");
  geohybrid::apps::set_overwrite_output(false);
  EXPECT_FALSE(fs::exists(directory_ / "out" / "checkpoint.h5"));
  message = error_of(input(""), true);
  EXPECT_NE(message.find("checkpoint.h5"), std::string::npos) << message;
}

TEST_F(DemCommand, ResumeBeforeCheckpointTimeRefused)
{
  ASSERT_EQ(error_of(input("subsection Simulation\n  set end time = 0.004\nend\n")), "");
  const std::string message = error_of(input("subsection Simulation\n  set end time = 0.002\nend\n"), true);
  EXPECT_NE(message.find("end time"), std::string::npos) << message;
  EXPECT_NE(message.find("checkpoint"), std::string::npos) << message;
}

// A resume with other physics (more particles, another stiffness) is refused before anything is
// written, naming the entries, both values and the checkpoint; the run-control entries (threads,
// the end time, the output intervals) may change. Its checkpoint keeps the input for that.
TEST_F(DemCommand, ResumeWithOtherPhysicsRefused)
{
  ASSERT_EQ(error_of(input("subsection Simulation\n  set end time = 0.004\nend\n")), "");
  const std::string parameters = contents(directory_ / "out" / "parameters.prm");
  const std::string message =
    error_of(input("subsection Particles\n  set number of particles = 70\nend\n"
                   "subsection Wall contact\n  set normal stiffness = 2e8\nend\n", "changed.prm"),
             true);
  EXPECT_NE(message.find("cannot resume from '" + (directory_ / "out" / "checkpoint.h5").string() + "'"),
            std::string::npos)
    << message;
  EXPECT_NE(message.find("changed.prm"), std::string::npos) << message;
  EXPECT_NE(message.find("'Particles/number of particles' = '70' (checkpoint: '60')"), std::string::npos) << message;
  EXPECT_NE(message.find("'Wall contact/normal stiffness' = '2e8' (checkpoint: "), std::string::npos) << message;
  EXPECT_EQ(contents(directory_ / "out" / "parameters.prm"), parameters); // still the run's own
  ASSERT_EQ(error_of(input("set threads = 2\nsubsection Simulation\n  set end time = 0.006\n"
                           "  set output interval = 0.002\n  set checkpoint interval = 100\nend\n",
                           "further.prm"),
                     true),
            "");
  EXPECT_NE(contents(directory_ / "out" / "summary.json").find("\"resumed_from_time_s\": 0.004"), std::string::npos);
}

// A second run into the directory of a first is refused, naming it; with --overwrite it removes
// the first run's files first (its particle_history.csv, which the second does not write, is
// gone) and leaves the user's own.
TEST_F(DemCommand, AnotherRunsDirectoryRefusedUnlessOverwrite)
{
  ASSERT_EQ(error_of(input("subsection Simulation\n  set end time = 0.002\nend\n")), "");
  ASSERT_TRUE(fs::exists(directory_ / "out" / "particle_history.csv"));
  std::ofstream(directory_ / "out" / "notes.txt") << "the first run\n";
  const std::string second = input("subsection Simulation\n  set end time = 0.002\n  set history particles =\nend\n",
                                   "second.prm");
  const std::string message = error_of(second);
  EXPECT_NE(message.find("output directory '" + (directory_ / "out").string() + "' holds the files of another run"),
            std::string::npos)
    << message;
  EXPECT_NE(message.find("--overwrite"), std::string::npos) << message;
  geohybrid::apps::set_overwrite_output(true);
  const std::string overwritten = error_of(second);
  geohybrid::apps::set_overwrite_output(false);
  ASSERT_EQ(overwritten, "");
  EXPECT_TRUE(fs::exists(directory_ / "out" / "summary.json"));
  EXPECT_FALSE(fs::exists(directory_ / "out" / "particle_history.csv"));
  EXPECT_EQ(contents(directory_ / "out" / "notes.txt"), "the first run\n");
}

// A particle CSV row with fewer fields than its header (a cluster id missing) is refused, naming
// the file and the line, instead of making the particle a lone disc.
TEST_F(DemCommand, CsvRowShorterThanItsHeaderRefused)
{
  std::ofstream(directory_ / "short.csv") << "x,y,radius,vx,vy,omega,cluster_id\n0.04,0.1,0.01,0,0,0,0\n"
                                             "0.0601,0.1,0.01,0,0,0\n";
  const std::string message = error_of(input("subsection Particles\n  set source = csv\n  set csv file = short.csv\nend\n"));
  EXPECT_NE(message.find("particle CSV '" + (directory_ / "short.csv").string() + "', line 3: has 6 fields, fewer than "
                         "the 7 of the header"),
            std::string::npos)
    << message;
}
