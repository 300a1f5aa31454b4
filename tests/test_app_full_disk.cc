// Every command on a full disk (issue 24): the real program, in a child process, stops at the
// first record it cannot write with status 1 and one error naming that file, never a crash, and
// leaves no summary.json, so that no run cut short looks finished (dem/io/checked_output.h).
//
// Two ways to fill the disk without root or a mount. A file-size limit on the child
// (geohybrid_child.h): every write beyond it fails with EFBIG as on a full disk with ENOSPC,
// through the same write(2); the limit lies between the size of the files written before the one
// under test and the size that file would reach, so that it is the one that fails. Or /dev/full
// (every write fails with ENOSPC) in place of a file, where the command does not refuse it as
// another run's: sweep.csv in a sweep's directory.
#include "geohybrid_child.h"
#include "sweep_test_inputs.h"
#include "temporary_directory.h"
#include "text_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using geohybrid::testing::read_text;

namespace
{
/// How many times `word` stands in `text`.
std::size_t count_of(const std::string &text, const std::string &word)
{
  std::size_t n = 0;
  for (auto at = text.find(word); at != std::string::npos; at = text.find(word, at + word.size()))
    ++n;
  return n;
}

/// What a run stopped by a full disk leaves: status 1 (an error, not a crash: 139 is a
/// segmentation fault), one error, naming `file` and the full disk, and no summary.json in `out`.
void expect_stopped_at(int status, const fs::path &log, const fs::path &file, const fs::path &out)
{
  const std::string said = read_text(log);
  EXPECT_EQ(status, 1) << said;
  EXPECT_EQ(count_of(said, "error:"), 1u) << said;
  EXPECT_NE(said.find("cannot write " + file.string() + " (is the disk full"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}
} // namespace

// 60 discs settling, a row of time_series.csv every other step over 0.04 s: 1,588 rows, some
// 160 KB, against a limit of 64 KB. Written before them: parameters.prm (some 5 KB) and the first
// snapshot (particles.h5, some 22 KB; the last is written after the rows).
TEST(FullDiskCommands, DemStopsAtTheTimeSeries)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "out";
  std::ofstream(d / "dem.prm") << "set output directory = " << out.string() << "\n"
                               << "set threads = 1\n"
                               << "subsection Particles\n  set number of particles = 60\n"
                               << "  set minimum radius = 0.004\n  set maximum radius = 0.005\nend\n"
                               << "subsection Box\n  set width = 0.1\n  set height = 0.2\nend\n"
                               << "subsection Simulation\n  set end time = 0.04\n  set output interval = 2e-5\n"
                               << "  set snapshot interval = 0\n  set checkpoint interval = 0\nend\n";
  const int status =
    geohybrid::testing::run_geohybrid_with_file_size_limit({"dem", (d / "dem.prm").string()}, d / "dem.log", 64 << 10);
  expect_stopped_at(status, d / "dem.log", out / "time_series.csv", out);
  EXPECT_LE(fs::file_size(out / "time_series.csv"), 64u << 10);
}

// One confinement, a point of the curve every 1.1e-4 of axial strain over 0.01: biaxial_20kPa.csv,
// written after the test, is 7.6 KB, over a limit of 6 KB; parameters.prm, written before it, is
// 5.2 KB. The curve fits in the stream's buffer, so its write fails only at the close: the
// unflushed `if (!f)` after the rows missed it, and the run ended with status 0 and a
// summary.json beside a curve cut short.
TEST(FullDiskCommands, BiaxialStopsAtItsCurve)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "out";
  std::ofstream(d / "biaxial.prm") << "set output directory = " << out.string() << "\n"
                                   << "set threads = 1\n"
                                   << "subsection Sample\n  set number of particles = 200\n  set width = 0.05\n"
                                   << "  set height = 0.08\n  set porosity tolerance = 0.01\nend\n"
                                   << "subsection Test\n  set confining stresses = 20e3\n  set inertial number = 1e-3\n"
                                   << "  set final axial strain = 0.01\n  set record interval = 1.1e-4\nend\n";
  const int status = geohybrid::testing::run_geohybrid_with_file_size_limit({"biaxial", (d / "biaxial.prm").string()},
                                                                            d / "biaxial.log", 6 << 10);
  expect_stopped_at(status, d / "biaxial.log", out / "biaxial_20kPa.csv", out);
}

// The defaults (examples/coupling_test.prm) but 800 undamped steps, a few seconds: parameters.prm
// (some 4.7 KB) fits under a limit of 6 KB, energy_history.csv (7.3 KB, a row every 10 steps)
// does not. The whole table fits in the stream's buffer (8 KB), so its write fails only at the
// close: an unflushed `if (!out)` after the rows missed it, and the run went on to the next
// table with this one cut short.
TEST(FullDiskCommands, CouplingTestStopsAtItsEnergyHistory)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "out";
  std::ofstream(d / "coupling_test.prm") << "set output directory = " << out.string() << "\n"
                                         << "subsection Energy\n  set number of undamped steps = 800\nend\n";
  const int status = geohybrid::testing::run_geohybrid_with_file_size_limit(
    {"coupling-test", (d / "coupling_test.prm").string()}, d / "coupling_test.log", 6 << 10);
  expect_stopped_at(status, d / "coupling_test.log", out / "energy_history.csv", out);
}

// Two fem members of about a second each (sweep_test_inputs.h) finish; the sweep's table cannot
// be written (sweep.csv is /dev/full): the sweep stops naming it, not with a table that looks
// complete and is empty.
TEST(FullDiskCommands, SweepStopsAtItsTable)
{
  if (!fs::exists("/dev/full"))
    GTEST_SKIP() << "no /dev/full on this system";
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "sweep";
  geohybrid::testing::write_fem_base_input(d);
  const std::string input =
    geohybrid::testing::write_sweep_input(d, "base.prm", "  subsection Anchorage\n    set L = 0.3, 0.55\n  end\n");
  fs::create_directories(out);
  fs::create_symlink("/dev/full", out / "sweep.csv");
  const int status = geohybrid::testing::run_geohybrid({"sweep", input}, d / "sweep.log");
  expect_stopped_at(status, d / "sweep.log", out / "sweep.csv", out);
  EXPECT_TRUE(fs::exists(out / "L_0.3" / "summary.json")) << read_text(d / "sweep.log"); // the members finished
}
