// Every command on a full disk (issue 24): the real program, in a child process, stops at the
// first record it cannot write with status 1 and one error naming that file, never a crash, and
// leaves no summary.json, so that no run cut short looks finished (dem/io/checked_output.h).
//
// Two ways to fill the disk without root or a mount. A file-size limit on the child
// (geohybrid_child.h): every write beyond it fails with EFBIG as on a full disk with ENOSPC,
// through the same write(2); the limit lies between the size of the files written before the one
// under test and the size that file would reach, so that it is the one that fails. Or /dev/full
// (every write fails with ENOSPC) in place of a file, where the command does not refuse it as
// another run's: sweep.csv in a sweep's directory. Or, for a file smaller than others written
// before it (summary.json, a calibration's fragment), a disk full for that file's name only
// (full_disk_preload.cc): it is created, and every write to it fails with ENOSPC.
#include "geohybrid_child.h"
#include "sweep_test_inputs.h"
#include "temporary_directory.h"
#include "text_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
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

/// A biaxial test of 200 particles at one confinement to 1 % strain (a few seconds), a point of its
/// curve every `record_interval` of axial strain, into `out`: the entries.
std::string biaxial_entries(const fs::path &out, double record_interval)
{
  std::ostringstream entries;
  entries << "set output directory = " << out.string() << "\n"
          << "set threads = 1\n"
          << "subsection Sample\n  set number of particles = 200\n  set width = 0.05\n"
          << "  set height = 0.08\n  set porosity tolerance = 0.01\nend\n"
          << "subsection Test\n  set confining stresses = 20e3\n  set inertial number = 1e-3\n"
          << "  set final axial strain = 0.01\n  set record interval = " << record_interval << "\nend\n";
  return entries.str();
}

/// That biaxial test as `directory`/biaxial.prm; returns its path.
std::string write_biaxial_input(const fs::path &directory, const fs::path &out, double record_interval)
{
  const fs::path file = directory / "biaxial.prm";
  std::ofstream(file) << biaxial_entries(out, record_interval);
  return file.string();
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
  const int status = geohybrid::testing::run_geohybrid_with_file_size_limit(
    {"biaxial", write_biaxial_input(d, out, 1.1e-4)}, d / "biaxial.log", 6 << 10);
  expect_stopped_at(status, d / "biaxial.log", out / "biaxial_20kPa.csv", out);
}

// The biaxial's continuum fragment (continuum_soil.prm, which a fem or hybrid pull-out includes)
// on a disk full for its name: the run stops naming it, with no summary.json, and leaves no
// fragment. An empty one was left behind, which an input including it reads as the continuum's
// defaults.
TEST(FullDiskCommands, BiaxialStopsAtItsContinuumFragment)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "out";
  const int status = geohybrid::testing::run_geohybrid_with_full_files(
    {"biaxial", write_biaxial_input(d, out, 1e-4)}, d / "biaxial.log", "continuum_soil.prm,continuum_soil.prm.tmp");
  expect_stopped_at(status, d / "biaxial.log", out / "continuum_soil.prm", out);
  EXPECT_FALSE(fs::exists(out / "continuum_soil.prm"));
  EXPECT_FALSE(fs::exists(out / "continuum_soil.prm.tmp"));
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

// The fem pull-out of sweep_test_inputs.h (about a second): its files but one are written before
// pullout_curve.png, and summary.json after it. gnuplot, the program's child, inherits the limit:
// cairo's writes fail under it, and gnuplot exited 0 with the PNG cut short, so the run ended
// with status 0 and a summary.json beside a broken figure. The limit is set halfway between the
// largest other file and the whole PNG of a first run without one, so that only the PNG meets it.
TEST(FullDiskCommands, FemPulloutStopsAtItsPlot)
{
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no gnuplot: no PNG is written";
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, whole = d / "base_out", out = d / "cut";
  const std::string input = geohybrid::testing::write_fem_base_input(d);
  // A title and a marked T_max make the PNG about 5 kB larger than the resolved parameters.prm
  // (20 kB of documented entries); without them the two differed by 50 bytes, either way.
  std::ofstream(input, std::ios::app) << "subsection Output\n  set experimental T_max = 0.5\n"
                                      << "  set demonstration = a test of a full disk\nend\n";
  ASSERT_EQ(geohybrid::testing::run_geohybrid({"pullout", input}, d / "whole.log"), 0) << read_text(d / "whole.log");
  std::uintmax_t largest_other = 0;
  for (const auto &entry : fs::directory_iterator(whole))
    if (entry.path().filename() != "pullout_curve.png")
      largest_other = std::max(largest_other, fs::file_size(entry.path()));
  const std::uintmax_t png = fs::file_size(whole / "pullout_curve.png");
  ASSERT_GT(png, largest_other + 256) << "the PNG must be the largest file for the limit to pick it";
  std::string cut_input = read_text(input);
  cut_input.replace(cut_input.find(whole.string()), whole.string().size(), out.string());
  std::ofstream(d / "cut.prm") << cut_input;
  const int status = geohybrid::testing::run_geohybrid_with_file_size_limit(
    {"pullout", (d / "cut.prm").string()}, d / "cut.log", static_cast<std::size_t>((largest_other + png) / 2));
  expect_stopped_at(status, d / "cut.log", out / "pullout_curve.png", out);
}

// The same fem pull-out on a finer mesh with a snapshot every mm: the second snapshot's piece
// (snapshots/pullout_0001.0.vtu) is the largest file, over the limit set halfway between it and
// the largest other file of a first run without one. deal.II's writer threw its ExcIO with a stack
// trace and no file named; now one error names the piece.
TEST(FullDiskCommands, FemPulloutStopsAtASnapshot)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, whole = d / "base_out", out = d / "cut";
  const std::string base = read_text(geohybrid::testing::write_fem_base_input(d));
  const auto input_into = [&](const fs::path &output, const fs::path &file) {
    std::string text = base;
    text.replace(text.find(whole.string()), whole.string().size(), output.string());
    const std::string cells = "set cell size = 0.05";
    text.replace(text.find(cells), cells.size(), "set cell size = 0.025\n  set snapshot interval = 0.001");
    std::ofstream(file) << text;
    return file.string();
  };
  ASSERT_EQ(geohybrid::testing::run_geohybrid({"pullout", input_into(whole, d / "whole.prm")}, d / "whole.log"), 0)
    << read_text(d / "whole.log");
  const fs::path piece = fs::path("snapshots") / "pullout_0001.0.vtu";
  std::uintmax_t largest_other = 0;
  for (const auto &entry : fs::recursive_directory_iterator(whole))
    if (entry.is_regular_file() && entry.path().filename().string().rfind("pullout_000", 0) != 0)
      largest_other = std::max(largest_other, fs::file_size(entry.path()));
  largest_other = std::max(largest_other, fs::file_size(whole / "snapshots" / "pullout_0000.0.vtu"));
  const std::uintmax_t vtu = fs::file_size(whole / piece);
  ASSERT_GT(vtu, largest_other + 256) << "the second snapshot must be the largest file before it";
  const int status = geohybrid::testing::run_geohybrid_with_file_size_limit(
    {"pullout", input_into(out, d / "cut.prm")}, d / "cut.log", static_cast<std::size_t>((largest_other + vtu) / 2));
  expect_stopped_at(status, d / "cut.log", out / piece, out);
}

// A fem design (sweep_test_inputs.h's base input, three values of L): its members and its table
// are written, then its figure, design.png, the largest of its files: the limit, halfway between
// it and the next largest of a first run without one, stops the design there, naming it, with no
// summary.json that gives an answer. (design.csv on /dev/full cannot be tried: a design refuses a
// directory that holds another run's table.)
TEST(FullDiskCommands, DesignStopsAtItsFigure)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, whole = d / "whole", out = d / "cut";
  geohybrid::testing::write_fem_base_input(d);
  const auto design_into = [&](const fs::path &output, const std::string &name) {
    std::ofstream(d / name) << "set base input = base.prm\nset output directory = " << output.string() << "\n"
                            << "subsection Design\n  set entry = L\n  set minimum = 0.1\n  set maximum = 0.5\n"
                            << "  set target T_max = 3\n  set tolerance = 0.39\nend\n";
    return (d / name).string();
  };
  ASSERT_EQ(geohybrid::testing::run_geohybrid({"design", design_into(whole, "whole.prm")}, d / "whole.log"), 0)
    << read_text(d / "whole.log");
  std::uintmax_t largest_other = 0;
  for (const auto &entry : fs::recursive_directory_iterator(whole))
    if (entry.is_regular_file() && entry.path() != whole / "design.png")
      largest_other = std::max(largest_other, fs::file_size(entry.path()));
  const std::uintmax_t png = fs::file_size(whole / "design.png");
  ASSERT_GT(png, largest_other + 256) << "the design's figure must be its largest file for the limit to pick it";
  const int status = geohybrid::testing::run_geohybrid_with_file_size_limit(
    {"design", design_into(out, "cut.prm")}, d / "cut.log", static_cast<std::size_t>((largest_other + png) / 2));
  expect_stopped_at(status, d / "cut.log", out / "design.png", out);
}

// The report of a finished fem run: the page inlines the run's PNG (some 20 KB), so it outgrows a
// limit of 8 KB. One error names the page; a page cut short would look like a report whose last
// sections are missing.
TEST(FullDiskCommands, ReportStopsAtItsPage)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, run = d / "base_out", page = d / "page" / "report.html";
  const std::string input = geohybrid::testing::write_fem_base_input(d);
  ASSERT_EQ(geohybrid::testing::run_geohybrid({"pullout", input}, d / "run.log"), 0) << read_text(d / "run.log");
  const int status = geohybrid::testing::run_geohybrid_with_file_size_limit(
    {"report", run.string(), "--output", page.string()}, d / "report.log", 8 << 10);
  expect_stopped_at(status, d / "report.log", page, page.parent_path());
}

// The fem pull-out of sweep_test_inputs.h (about a second) on a disk full for summary.json, its
// last file (written to a temporary, then renamed). The error named the temporary,
// summary.json.tmp, and left it behind, empty; now it names summary.json and leaves neither.
TEST(FullDiskCommands, FemPulloutStopsAtItsSummary)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "base_out";
  const std::string input = geohybrid::testing::write_fem_base_input(d);
  const int status = geohybrid::testing::run_geohybrid_with_full_files({"pullout", input}, d / "run.log",
                                                                        "summary.json.tmp,summary.json");
  expect_stopped_at(status, d / "run.log", out / "summary.json", out);
  EXPECT_FALSE(fs::exists(out / "summary.json.tmp"));
  EXPECT_GT(fs::file_size(out / "pullout_curve.csv"), 100u) << "the run itself must have finished";
}

namespace
{
/// A calibration of the biaxial test above (200 particles, one confinement, 1 % strain), whose loose
/// tolerances are met at its first campaign: it then writes its fragment and summary.json.
std::string write_calibrate_input(const fs::path &directory, const fs::path &out)
{
  const fs::path file = directory / "calibrate.prm";
  std::ofstream(file) << biaxial_entries(out, 1e-4) << "subsection Calibration\n  set target friction angle = 30\n"
                      << "  set target Young modulus = 20e6\n  set friction angle tolerance = 89\n"
                      << "  set Young modulus tolerance = 1000\n  set maximum iterations = 1\nend\n";
  return file.string();
}
} // namespace

// The calibration's fragment on a full disk: the calibration stops naming it, with no
// summary.json, and leaves no fragment. An empty one was left behind, which an input including it
// reads without complaint, as the contact laws' defaults.
TEST(FullDiskCommands, CalibrateStopsAtItsFragment)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "out";
  const int status = geohybrid::testing::run_geohybrid_with_full_files(
    {"calibrate", write_calibrate_input(d, out)}, d / "calibrate.log", "calibrated_soil.prm,calibrated_soil.prm.tmp");
  expect_stopped_at(status, d / "calibrate.log", out / "calibrated_soil.prm", out);
  EXPECT_FALSE(fs::exists(out / "calibrated_soil.prm"));
  EXPECT_FALSE(fs::exists(out / "calibrated_soil.prm.tmp"));
  EXPECT_EQ(geohybrid::testing::lines_of(out / "calibration.csv").size(), 2u) << "header and the one iteration";
}

// The calibration's table of iterations on a full disk: it stops at the header, before the first
// campaign, naming it.
TEST(FullDiskCommands, CalibrateStopsAtItsTable)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "out";
  const int status = geohybrid::testing::run_geohybrid_with_full_files({"calibrate", write_calibrate_input(d, out)},
                                                                        d / "calibrate.log", "calibration.csv");
  expect_stopped_at(status, d / "calibrate.log", out / "calibration.csv", out);
  EXPECT_FALSE(fs::exists(out / "calibrated_soil.prm"));
}

// The calibration's summary.json on a full disk, after its fragment: as the pull-out's.
TEST(FullDiskCommands, CalibrateStopsAtItsSummary)
{
  const geohybrid::testing::TemporaryDirectory directory("test_app_full_disk");
  const fs::path d = directory.path, out = d / "out";
  const int status = geohybrid::testing::run_geohybrid_with_full_files(
    {"calibrate", write_calibrate_input(d, out)}, d / "calibrate.log", "summary.json.tmp,summary.json");
  expect_stopped_at(status, d / "calibrate.log", out / "summary.json", out);
  EXPECT_FALSE(fs::exists(out / "summary.json.tmp"));
}
