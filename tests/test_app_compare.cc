// `geohybrid compare`: two result directories (fabricated here with the pull-out output contract)
// overlaid in one PNG; a missing directory, a directory without pullout_curve.csv, a CSV with the
// wrong columns or a summary without its keys are refused with the directory named.
#include "apps/compare_command.h"
#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using geohybrid::apps::compare_pullout_runs;
using geohybrid::apps::read_pullout_run;
using geohybrid::apps::run_compare_command;
using geohybrid::testing::TemporaryDirectory;

namespace
{
/// A result directory with a curve T = T_max (1 - exp(-d / d0)) and its summary.
fs::path fabricate_run(const fs::path &root, const std::string &name, const std::string &mode, double t_max_kN,
                       const std::string &header = "head_displacement_m,head_tension_kN_per_m")
{
  const fs::path d = root / name;
  fs::create_directories(d);
  std::ofstream csv(d / "pullout_curve.csv");
  csv << header << "\n";
  for (int k = 0; k <= 60; ++k)
    csv << 1e-3 * k << "," << t_max_kN * (1.0 - std::exp(-k / 8.0)) << "\n";
  std::ofstream(d / "summary.json") << "{\n  \"T_max_kN_per_m\": " << t_max_kN << ",\n  \"mode\": \"" << mode
                                    << "\",\n  \"wall_time_s\": 12.5\n}\n";
  return d;
}

std::string error_of(const std::vector<fs::path> &directories, const fs::path &png)
{
  try
    {
      compare_pullout_runs(directories, png);
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}
} // namespace

TEST(CompareCommand, OverlaysTwoRunsInOnePng)
{
  TemporaryDirectory root("compare");
  const fs::path dem = fabricate_run(root.path, "runout_h040_dem", "dem", 41.2);
  const fs::path fem = fabricate_run(root.path, "runout_h040_fem", "fem", 38.7);
  const fs::path png = root.path / "plots" / "comparison.png";
  const auto records = compare_pullout_runs({dem, fem}, png);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].mode, "dem");
  EXPECT_EQ(records[1].mode, "fem");
  EXPECT_DOUBLE_EQ(records[0].max_head_tension_kN, 41.2);
  EXPECT_DOUBLE_EQ(records[1].max_head_tension_kN, 38.7);
  EXPECT_EQ(records[0].n_points, 61u);
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 1000u);
  // The gnuplot script beside it carries the legend: directory name and mode.
  std::ifstream script(png.string() + ".gp");
  std::stringstream text;
  text << script.rdbuf();
  EXPECT_NE(text.str().find("runout_h040_dem (dem"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("runout_h040_fem (fem"), std::string::npos) << text.str();

  // The command line does the same, with --output.
  const fs::path png2 = root.path / "cli.png";
  EXPECT_EQ(run_compare_command({dem.string(), fem.string(), "--output", png2.string()}), 0);
  EXPECT_GT(fs::file_size(png2), 1000u);
}

TEST(CompareCommand, BadDirectoriesAreNamed)
{
  TemporaryDirectory root("compare_bad");
  const fs::path good = fabricate_run(root.path, "good_run", "dem", 40.0);
  const fs::path png = root.path / "out.png";

  // Missing directory.
  const fs::path missing = root.path / "no_such_run";
  std::string e = error_of({good, missing}, png);
  EXPECT_NE(e.find("'" + missing.string() + "'"), std::string::npos) << e;
  EXPECT_NE(e.find("does not exist"), std::string::npos) << e;

  // A directory without pullout_curve.csv.
  const fs::path empty = root.path / "empty_run";
  fs::create_directories(empty);
  e = error_of({good, empty}, png);
  EXPECT_NE(e.find("'" + empty.string() + "'"), std::string::npos) << e;
  EXPECT_NE(e.find("pullout_curve.csv"), std::string::npos) << e;

  // Wrong columns (tension in N/m instead of kN/m).
  const fs::path wrong = fabricate_run(root.path, "wrong_columns", "fem", 40.0, "head_displacement_m,head_tension_N_per_m");
  e = error_of({good, wrong}, png);
  EXPECT_NE(e.find("'" + wrong.string() + "'"), std::string::npos) << e;
  EXPECT_NE(e.find("head_tension_N_per_m"), std::string::npos) << e;

  // A summary without mode.
  const fs::path no_mode = fabricate_run(root.path, "no_mode", "fem", 40.0);
  std::ofstream(no_mode / "summary.json") << "{\n  \"T_max_kN_per_m\": 40\n}\n";
  e = error_of({no_mode}, png);
  EXPECT_NE(e.find("\"mode\""), std::string::npos) << e;
  EXPECT_NE(e.find(no_mode.string()), std::string::npos) << e;

  // A row that is not two numbers.
  const fs::path garbled = fabricate_run(root.path, "garbled", "dem", 40.0);
  std::ofstream(garbled / "pullout_curve.csv", std::ios::app) << "0.07,nan-ish\n";
  e = error_of({garbled}, png);
  EXPECT_NE(e.find("line 63"), std::string::npos) << e;

  // No PNG was made by any of the failed calls; not a .png; no directories.
  EXPECT_FALSE(fs::exists(png));
  EXPECT_NE(error_of({good}, root.path / "out.jpg").find("out.jpg"), std::string::npos);
  EXPECT_THROW(run_compare_command({"--output", png.string()}), std::runtime_error);
  EXPECT_THROW(run_compare_command({good.string(), "--output"}), std::runtime_error);
}

// A summary as nlohmann-json writes one, nested and with values across lines (a list of
// warnings before the keys, the tension on the line after its key): the old line-wise reader took
// the "mode" inside a warning and found no number after "T_max_kN_per_m":. A summary that is not
// JSON is refused naming the file.
TEST(CompareCommand, ReadsANestedSummaryThroughTheJsonLibrary)
{
  TemporaryDirectory root("compare_json");
  const fs::path run = fabricate_run(root.path, "nested", "dem", 41.2);
  std::ofstream(run / "summary.json")
    << "{\"warnings\": [\"\\\"mode\\\": \\\"fem\\\" is not what this says\",\n  \"a second one\"],\n"
       "  \"T_max_kN_per_m\":\n     41.25,\n  \"mode\": \"hybrid\"}\n";
  const auto record = read_pullout_run(run);
  EXPECT_EQ(record.mode, "hybrid");
  EXPECT_EQ(record.max_head_tension_kN, 41.25);
  ASSERT_EQ(record.warnings.size(), 2u);
  EXPECT_EQ(record.warnings[1], "a second one");

  std::ofstream(run / "summary.json") << "{\"mode\": \"dem\", \"T_max_kN_per_m\": 41.2,\n"; // cut short
  const std::string e = error_of({run}, root.path / "out.png");
  EXPECT_NE(e.find("not valid JSON"), std::string::npos) << e;
  EXPECT_NE(e.find((run / "summary.json").string()), std::string::npos) << e;
}
