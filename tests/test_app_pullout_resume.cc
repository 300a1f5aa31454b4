// `geohybrid pullout` stopped and resumed: a pull stopped twice and resumed from its checkpoints is
// the straight pull, bit for bit, and a resume with other physics is refused naming each entry.
// The command's output contract: test_app_pullout.cc.
#include "apps/pullout_command.h"
#include "apps/resume_check.h"
#include "dem/io/checkpoint.h"
#include "temporary_directory.h"
#include "text_file.h"
#include "tiny_pullout_input.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using geohybrid::testing::lines_of;

namespace
{
fs::path test_directory()
{
  return geohybrid::testing::fresh_directory("test_app_pullout_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
}

std::string write_tiny_input(const fs::path &directory) { return geohybrid::testing::write_tiny_pullout_input(directory); }

std::string contents_of(const fs::path &file) { return geohybrid::testing::read_text(file); }

/// The tiny tank with its output in `out`, field outputs at 0.25 and 0.75 mm.
std::string write_resume_input(const fs::path &directory, const std::string &out)
{
  const std::string input = write_tiny_input(directory);
  const fs::path file = directory / (out + ".prm");
  std::ofstream(file) << contents_of(input) << "set output directory = " << (directory / out).string() << "\n"
                      << "subsection Output\n  set field outputs at = 0.00025, 0.00075\nend\n";
  return file.string();
}
} // namespace

// A pull stopped twice ('stop after steps', an exact step, not a signal's race) and resumed
// from its checkpoints writes the same files, bit for bit, as the pull that never stopped, and
// ends in the same state; a run resumed before its tank was full fills it again and says so.
TEST(PullOutCommand, ResumesAStoppedPullBitForBit)
{
  using geohybrid::apps::run_pullout_command;
  const fs::path d = test_directory();
  const std::string straight = write_resume_input(d, "straight"), stopped = write_resume_input(d, "stopped"),
                    refilled = write_resume_input(d, "refilled");
  ASSERT_EQ(run_pullout_command(straight, false), 0);
  // The pull takes 0.125 s of simulated time (1 mm at 10 mm/s, the ramp of 0.25 mm taking
  // 0.05 s), 5,093 steps of 2.45e-5 s: the first stop is early in the ramp (step 700), the
  // second (step 3,000) after the field output at 0.25 mm (step 2,037) and before the one at
  // 0.75 mm (step 4,075).
  ASSERT_EQ(run_pullout_command(stopped, false, {{"stop after steps", "700"}}), 0);
  EXPECT_FALSE(fs::exists(d / "stopped" / "summary.json")); // not a finished run
  ASSERT_TRUE(fs::exists(d / "stopped" / "checkpoint.h5"));
  ASSERT_EQ(run_pullout_command(stopped, true, {{"stop after steps", "2300"}}), 0);
  EXPECT_FALSE(fs::exists(d / "stopped" / "summary.json"));
  ASSERT_EQ(run_pullout_command(stopped, true), 0);

  testing::internal::CaptureStdout();
  const int status = run_pullout_command(refilled, true);
  const std::string said = testing::internal::GetCapturedStdout();
  ASSERT_EQ(status, 0);
  EXPECT_NE(said.find("filling the tank again from the start"), std::string::npos) << said;

  // The same tank pulled at another rate: a run at 20 mm/s keeps its filled tank, and a run at
  // the straight run's 10 mm/s resumed from it is the straight run (the rate-halving check
  // pulls one tank at every rate so).
  const std::string fast = write_resume_input(d, "fast"), from_fast = write_resume_input(d, "from_fast");
  ASSERT_EQ(run_pullout_command(fast, false, {{"Pull/rate", "0.02"}}), 0);
  fs::create_directories(d / "from_fast");
  fs::copy_file(d / "fast" / "filled_tank.h5", d / "from_fast" / "checkpoint.h5");
  ASSERT_EQ(run_pullout_command(from_fast, true), 0);
  EXPECT_TRUE(contents_of(d / "from_fast" / "pullout_curve.csv") == contents_of(d / "straight" / "pullout_curve.csv"));
  EXPECT_FALSE(contents_of(d / "fast" / "pullout_curve.csv") == contents_of(d / "straight" / "pullout_curve.csv"));
  // The grains' damping while pulling: the fill's value given explicitly is the straight run, bit
  // for bit; another value pulls the same tank another way.
  const std::string same_damping = write_resume_input(d, "same_damping"), less_damping = write_resume_input(d, "less_damping");
  for (const char *run : {"same_damping", "less_damping"})
    {
      fs::create_directories(d / run);
      fs::copy_file(d / "fast" / "filled_tank.h5", d / run / "checkpoint.h5");
    }
  ASSERT_EQ(run_pullout_command(same_damping, true, {{"Pull/grain local damping", "0.7"}}), 0);
  ASSERT_EQ(run_pullout_command(less_damping, true, {{"Pull/grain local damping", "0.1"}}), 0);
  EXPECT_TRUE(contents_of(d / "same_damping" / "pullout_curve.csv") == contents_of(d / "straight" / "pullout_curve.csv"));
  EXPECT_FALSE(contents_of(d / "less_damping" / "pullout_curve.csv") == contents_of(d / "straight" / "pullout_curve.csv"));

  for (const char *file : {"pullout_curve.csv", "pullout_curve_sheet.csv", "pullout_forces.csv", "sheet_displacements.csv", "sheet_tension.csv",
                           "surface_uplift.csv", "grain_displacements_u0.25mm.csv", "grain_displacements_u0.75mm.csv",
                           "force_network_u0.75mm.csv"})
    for (const char *other : {"stopped", "refilled", "from_fast"})
      {
        const std::string expected = contents_of(d / "straight" / file);
        EXPECT_GT(expected.size(), 50u) << file;
        EXPECT_TRUE(contents_of(d / other / file) == expected) << other << '/' << file;
      }
  EXPECT_EQ(lines_of(d / "straight" / "pullout_curve.csv").size(), 1u + 5u);
  // Stopped or not, in another directory: the same physics, the same hash; another rate, another.
  const auto hash_of = [&](const char *run) {
    const std::string text = contents_of(d / run / "summary.json");
    const auto at = text.find("\"parameters_hash\": \"");
    return at == std::string::npos ? std::string("none") : text.substr(at + 20, 16);
  };
  EXPECT_EQ(hash_of("stopped"), hash_of("straight"));
  EXPECT_EQ(hash_of("from_fast"), hash_of("straight"));
  EXPECT_NE(hash_of("fast"), hash_of("straight"));
  EXPECT_NE(hash_of("straight"), "none");
  // The final states (each run writes a checkpoint at its end): every body, every sheet node.
  const geohybrid::dem::DemSystemState a = geohybrid::dem::read_checkpoint(d / "straight" / "checkpoint.h5"),
                                       b = geohybrid::dem::read_checkpoint(d / "stopped" / "checkpoint.h5");
  EXPECT_EQ(a.step_count, b.step_count);
  EXPECT_EQ(a.time, b.time);
  ASSERT_EQ(a.particles.n_bodies(), b.particles.n_bodies());
  for (std::size_t k = 0; k < a.particles.n_bodies(); ++k)
    {
      ASSERT_EQ(a.particles.x[k], b.particles.x[k]) << "body " << k;
      ASSERT_EQ(a.particles.y[k], b.particles.y[k]) << "body " << k;
      ASSERT_EQ(a.particles.vx[k], b.particles.vx[k]) << "body " << k;
      ASSERT_EQ(a.particles.omega[k], b.particles.omega[k]) << "body " << k;
    }
  ASSERT_EQ(a.sheets.size(), 1u);
  ASSERT_EQ(b.sheets.size(), 1u);
  for (std::size_t k = 0; k < a.sheets[0].n_nodes(); ++k)
    {
      ASSERT_EQ(a.sheets[0].x[k], b.sheets[0].x[k]) << "node " << k;
      ASSERT_EQ(a.sheets[0].vy[k], b.sheets[0].vy[k]) << "node " << k;
      ASSERT_EQ(a.sheets[0].tension[std::min(k, a.sheets[0].n_segments() - 1)],
                b.sheets[0].tension[std::min(k, b.sheets[0].n_segments() - 1)]);
    }
  ASSERT_EQ(a.pairs.size(), b.pairs.size());
  for (std::size_t q = 0; q < a.pairs.size(); ++q)
    ASSERT_EQ(a.pairs.state[q].tangential_force, b.pairs.state[q].tangential_force) << "pair " << q;
  fs::remove_all(d);
}

// A pull-out resumed with other physics (another stiffness, more particles) is refused before a
// file is written, naming each entry with both values; its run-control entries may change. A
// checkpoint written before checkpoints kept their input (the validation campaign's) still
// resumes, and the terminal says its input was not checked. Without a checkpoint, --resume fills
// again only in a directory of the same run. About 6 s (the tiny tank filled twice).
TEST(PullOutCommand, ResumeWithOtherPhysicsRefused)
{
  using geohybrid::apps::run_pullout_command;
  const fs::path d = test_directory();
  const std::string input = write_resume_input(d, "stopped");
  ASSERT_EQ(run_pullout_command(input, false, {{"stop after steps", "10"}}), 0);
  const fs::path checkpoint = d / "stopped" / "checkpoint.h5";
  const std::string parameters = contents_of(d / "stopped" / "parameters.prm");
  std::string message;
  try
    {
      run_pullout_command(input, true,
                          {{"Soil/Particle contact/normal stiffness", "2e7"}, {"Filling/number of particles", "500"},
                           {"Pull/rate", "0.02"}});
    }
  catch (const std::exception &e)
    {
      message = e.what();
    }
  EXPECT_NE(message.find("cannot resume from '" + checkpoint.string() + "': input file '" + input + "' differs"),
            std::string::npos)
    << message;
  EXPECT_NE(message.find("'Soil/Particle contact/normal stiffness' = '2e7' (checkpoint: '1e7')"), std::string::npos)
    << message;
  EXPECT_NE(message.find("'Filling/number of particles' = '500' (checkpoint: '400')"), std::string::npos) << message;
  // The pull has started: its rate is part of the run now.
  EXPECT_NE(message.find("'Pull/rate' = '0.02' (checkpoint: '0.01')"), std::string::npos) << message;
  EXPECT_EQ(contents_of(d / "stopped" / "parameters.prm"), parameters);

  // As a checkpoint of an earlier version: no input kept. It resumes (threads and the stop changed).
  geohybrid::dem::CommandState command;
  const geohybrid::dem::DemSystemState state = geohybrid::dem::read_checkpoint(checkpoint, command);
  ASSERT_EQ(command.texts.count(geohybrid::apps::checkpoint_input_key), 1u);
  command.texts.clear();
  geohybrid::dem::write_checkpoint(state, command, checkpoint);
  testing::internal::CaptureStdout();
  const int status = run_pullout_command(input, true, {{"threads", "2"}, {"stop after steps", "20"}});
  const std::string said = testing::internal::GetCapturedStdout();
  ASSERT_EQ(status, 0);
  EXPECT_NE(said.find(checkpoint.string() + " was written before checkpoints kept their input"), std::string::npos)
    << said;
  // Its next checkpoint keeps this run's input.
  EXPECT_EQ(geohybrid::dem::read_checkpoint_command(checkpoint).texts.count(geohybrid::apps::checkpoint_input_key), 1u);

  // No checkpoint left: a --resume fills the tank again, in its own run's directory only.
  fs::remove(checkpoint);
  fs::remove(d / "stopped" / "filled_tank.h5");
  message.clear();
  try
    {
      run_pullout_command(input, true, {{"Filling/seed", "4"}});
    }
  catch (const std::exception &e)
    {
      message = e.what();
    }
  EXPECT_NE(message.find("output directory '" + (d / "stopped").string() + "' holds the files of another run"),
            std::string::npos)
    << message;
  testing::internal::CaptureStdout();
  const int refilled = run_pullout_command(input, true, {{"stop after steps", "1"}});
  const std::string refill_said = testing::internal::GetCapturedStdout();
  ASSERT_EQ(refilled, 0);
  EXPECT_NE(refill_said.find("filling the tank again from the start"), std::string::npos) << refill_said;
  fs::remove_all(d);
}
