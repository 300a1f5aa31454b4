// Issue 24, section 2: one run per output directory (apps/output_guard.h), a resume only with the
// checkpointed run's physics (apps/resume_check.h), and inputs that are not parameter files
// refused (apps/run_directory.h). The commands' own use of them is in test_app_dem.cc and
// test_app_pullout*.cc.
#include "apps/dem_command.h"
#include "apps/output_guard.h"
#include "apps/pullout_command.h"
#include "apps/resume_check.h"
#include "apps/run_directory.h"
#include "temporary_directory.h"
#include "tiny_pullout_input.h"

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace
{
/// The message of what `f` throws ("" if nothing).
template <typename F>
std::string guard_error_of(F &&f)
{
  try
    {
      f();
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}

/// Sets --overwrite for one scope.
struct OverwriteOutput
{
  OverwriteOutput() { geohybrid::apps::set_overwrite_output(true); }
  ~OverwriteOutput() { geohybrid::apps::set_overwrite_output(false); }
};

/// A dem input holding `lines`, parsed.
void parse_dem_lines(dealii::ParameterHandler &prm, const fs::path &file, const std::string &lines)
{
  geohybrid::apps::declare_dem_parameters(prm);
  std::ofstream(file) << lines;
  geohybrid::apps::parse_input_file(prm, file.string());
}
} // namespace

// The files a first run left (those of the issue: experimental_T_max.csv, the field outputs,
// surface_uplift.png) refuse a second run there; --resume keeps them; --overwrite removes them
// and only them: the user's notes and input, and a seed directory's own file, stay.
TEST(OutputGuard, AnotherRunsFilesRefusedAndOverwriteRemovesOnlyThem)
{
  geohybrid::testing::TemporaryDirectory d("run_guard");
  const fs::path out = d.path / "out";
  fs::create_directories(out / "seed_3");
  for (const char *name : {"summary.json", "parameters.prm", "experimental_T_max.csv", "force_network_u6mm.csv",
                           "grain_displacements_u6mm.png", "surface_uplift.png", "pullout_curve.png.gp",
                           "checkpoint.h5.tmp", "notes.txt", "input.prm", "seed_3/pullout_curve.csv", "seed_3/mine.txt"})
    std::ofstream(out / name) << "x\n";
  EXPECT_TRUE(geohybrid::apps::is_run_file("biaxial_100kPa.csv"));
  EXPECT_FALSE(geohybrid::apps::is_run_file("input.prm"));
  EXPECT_EQ(geohybrid::apps::run_files(out).size(), 9u);

  const std::string refused = guard_error_of([&] { geohybrid::apps::prepare_output_directory(out.string(), false); });
  EXPECT_NE(refused.find("output directory '" + out.string() + "' holds the files of another run"), std::string::npos)
    << refused;
  EXPECT_NE(refused.find("checkpoint.h5.tmp, experimental_T_max.csv, force_network_u6mm.csv, grain_displacements_u6mm.png "
                         "and 5 more"),
            std::string::npos)
    << refused;
  EXPECT_NE(refused.find("--overwrite"), std::string::npos) << refused;
  EXPECT_TRUE(fs::exists(out / "summary.json")); // nothing touched

  EXPECT_EQ(guard_error_of([&] { geohybrid::apps::prepare_output_directory(out.string(), true); }), "");
  EXPECT_TRUE(fs::exists(out / "experimental_T_max.csv")); // a resume keeps its run's files
  EXPECT_FALSE(fs::exists(out / "summary.json"));          // but it is not finished any more

  {
    OverwriteOutput overwrite;
    EXPECT_EQ(guard_error_of([&] { geohybrid::apps::prepare_output_directory(out.string(), false); }), "");
  }
  EXPECT_TRUE(geohybrid::apps::run_files(out).empty());
  for (const char *kept : {"notes.txt", "input.prm", "seed_3/mine.txt"})
    EXPECT_TRUE(fs::exists(out / kept)) << kept;
  EXPECT_FALSE(fs::exists(out / "surface_uplift.png"));
  // A directory of the user's files only is no run's: a run goes in without --overwrite.
  EXPECT_EQ(guard_error_of([&] { geohybrid::apps::prepare_output_directory(out.string(), false); }), "");
}

// The record a checkpoint keeps, compared with the input of a resume: each differing entry named
// with both values (an entry at its default shown as such), the run-control ones let through, a
// record-less (older) checkpoint accepted with a note on the terminal.
TEST(ResumeCheck, NamesEveryDifferingEntryWithBothValues)
{
  geohybrid::testing::TemporaryDirectory d("resume_check");
  dealii::ParameterHandler then, now, defaults;
  geohybrid::apps::declare_dem_parameters(defaults);
  parse_dem_lines(then, d.path / "then.prm",
                  "set threads = 1\nsubsection Particles\n  set number of particles = 60\nend\n"
                  "subsection Simulation\n  set end time = 0.01\nend\n");
  parse_dem_lines(now, d.path / "now.prm",
                  "set threads = 2\nsubsection Particles\n  set number of particles = 80\nend\n"
                  "subsection Particle contact\n  set normal stiffness = 2e8\nend\n"
                  "subsection Simulation\n  set end time = 0.02\nend\n");
  geohybrid::dem::CommandState saved;
  geohybrid::apps::store_input(then, defaults, saved);
  const fs::path checkpoint = d.path / "out" / "checkpoint.h5";
  const auto check = [&](const dealii::ParameterHandler &prm) {
    return guard_error_of([&] {
      geohybrid::apps::check_resumed_input(saved, prm, defaults, geohybrid::apps::dem_resume_entries(), checkpoint,
                                           "input file 'now.prm'", "geohybrid dem");
    });
  };
  const std::string message = check(now);
  EXPECT_NE(message.find("cannot resume from '" + checkpoint.string() + "': input file 'now.prm' differs"),
            std::string::npos)
    << message;
  EXPECT_NE(message.find("'Particle contact/normal stiffness' = '2e8' (checkpoint: '70000000' (default))"), std::string::npos)
    << message;
  EXPECT_NE(message.find("'Particles/number of particles' = '80' (checkpoint: '60')"), std::string::npos) << message;
  EXPECT_EQ(message.find("threads' ="), std::string::npos) << message; // run control: may change
  EXPECT_EQ(message.find("end time' ="), std::string::npos) << message;
  EXPECT_NE(message.find("Only 'output directory', 'threads', 'Simulation/checkpoint interval', 'Simulation/end time'"),
            std::string::npos)
    << message;
  EXPECT_EQ(check(then), "");

  geohybrid::dem::CommandState older; // written before checkpoints kept their input
  testing::internal::CaptureStdout();
  EXPECT_EQ(guard_error_of([&] {
              geohybrid::apps::check_resumed_input(older, now, defaults, geohybrid::apps::dem_resume_entries(),
                                                   checkpoint, "input file 'now.prm'", "geohybrid dem");
            }),
            "");
  const std::string said = testing::internal::GetCapturedStdout();
  EXPECT_NE(said.find("was written before checkpoints kept their input: resuming it without checking"),
            std::string::npos)
    << said;
}

// An empty input (or one of comments only) is refused instead of running every default; a binary
// file is refused without its bytes in the message.
TEST(InputFile, EmptyAndBinaryFilesRefused)
{
  geohybrid::testing::TemporaryDirectory d("input_text");
  const auto message_of = [&](const std::string &name, const std::string &bytes) {
    std::ofstream(d.path / name, std::ios::binary) << bytes;
    dealii::ParameterHandler prm;
    geohybrid::apps::declare_dem_parameters(prm);
    return guard_error_of([&] { geohybrid::apps::parse_input_file(prm, (d.path / name).string()); });
  };
  for (const auto &[name, bytes] : {std::pair<std::string, std::string>{"empty.prm", ""},
                                    {"comments.prm", "# nothing set yet\n\n   \n"},
                                    {"empty.json", "{ }\n"}})
    {
      const std::string message = message_of(name, bytes);
      EXPECT_NE(message.find("input file '" + (d.path / name).string() + "' is empty"), std::string::npos) << message;
    }
  const std::string binary = message_of("run.prm", std::string("\x7f" "ELF\x02\x01\x01\0\0\0set \xff\xfe", 16));
  EXPECT_NE(binary.find("is not a text file (a control byte at offset 0)"), std::string::npos) << binary;
  EXPECT_EQ(binary.find("ELF"), std::string::npos) << binary;
  EXPECT_EQ(message_of("fine.prm", "set threads = 1\n"), "");
}

// An output directory that cannot be made (under a file, or in /proc, where even root cannot
// write) is refused before the run, naming it, in dem and pullout alike.
TEST(OutputDirectory, AnUnwritablePathIsRefusedBeforeAnythingIsWritten)
{
  geohybrid::testing::TemporaryDirectory d("unwritable");
  std::ofstream(d.path / "a_file") << "not a directory\n";
  const std::string input = geohybrid::testing::write_tiny_pullout_input(d.path);
  for (const std::string &out : {(d.path / "a_file" / "out").string(), std::string("/proc/geohybrid_unwritable")})
    {
      const std::string pullout = guard_error_of(
        [&] { geohybrid::apps::run_pullout_command(input, false, {{"output directory", out}}); });
      EXPECT_NE(pullout.find("cannot create output directory '" + out + "'"), std::string::npos) << pullout;
      const fs::path dem = d.path / "dem.prm";
      std::ofstream(dem) << "set output directory = " << out << "\n";
      const std::string scene = guard_error_of([&] { geohybrid::apps::run_dem_command(dem.string(), false); });
      EXPECT_NE(scene.find("cannot create output directory '" + out + "'"), std::string::npos) << scene;
    }
  EXPECT_FALSE(fs::exists(d.path / "out")); // the tiny input's own directory: nothing made there either
}

// A run that fails ends its progress line where it stands: a pull that fails at 0 mm does not
// read 100 % (fem mode's implicit solver stopping at its first increment).
TEST(ProgressReport, StopDoesNotReadFullWhenTheRunFails)
{
  const auto said_by = [](bool fails) {
    testing::internal::CaptureStderr();
    geohybrid::apps::ProgressReport progress("pulling", 0.05);
    progress.update(0.0);
    if (fails)
      progress.stop();
    else
      progress.finish();
    return testing::internal::GetCapturedStderr();
  };
  const std::string failed = said_by(true), finished = said_by(false);
  EXPECT_EQ(failed.find("100%"), std::string::npos) << failed;
  EXPECT_NE(finished.find("pulling: 100%"), std::string::npos) << finished;
}
