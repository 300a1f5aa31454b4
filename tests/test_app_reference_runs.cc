// A demonstration run beside the same case at full size (issue 23, part 5): the seeds' curves of a
// directory of finished runs averaged row by row, their T_max and the mean curve's; refused with
// the entry, the file and the directory named when they are not there or not the same pull; and a
// tiny pull-out that says in its summary, plot and last lines that it is a demonstration.
#include "apps/pullout_command.h"
#include "apps/reference_runs.h"
#include "apps/summary.h"
#include "temporary_directory.h"
#include "tiny_pullout_input.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace fs = std::filesystem;
namespace apps = geohybrid::apps;
using geohybrid::testing::TemporaryDirectory;

namespace
{
/// A finished run in `d`: T = a + b sin(k u / 4 mm) at u = 0, 0.5, ... 10 mm (21 rows), its summary.
void fabricate_seed(const fs::path &d, double a, double b, int k, int rows = 21)
{
  fs::create_directories(d);
  std::ofstream csv(d / "pullout_curve.csv");
  csv << std::setprecision(15) << "head_displacement_m,head_tension_kN_per_m\n";
  double T_max = -1e300;
  for (int r = 0; r < rows; ++r)
    {
      const double u = 5e-4 * r, T = a + b * std::sin(k * u / 4e-3);
      csv << u << ',' << T << '\n';
      T_max = std::max(T_max, T);
    }
  std::ofstream(d / "summary.json") << std::setprecision(15) << "{\n  \"T_max_kN_per_m\": " << T_max
                                    << ",\n  \"mode\": \"dem\",\n  \"n_particles\": 12500\n}\n";
}

std::string error_of(const fs::path &directory)
{
  try
    {
      apps::read_reference_runs(directory, "case.prm: parameter 'Output/full-size runs'");
    }
  catch (const std::invalid_argument &e)
    {
      return e.what();
    }
  return "";
}
} // namespace

TEST(ReferenceRuns, MeanCurveAndItsMaximum)
{
  TemporaryDirectory root("reference_runs");
  // seed10 sorts after seed2 by its number, not its name; the directory "notes" is not a seed.
  fabricate_seed(root.path / "seed1", 10.0, 2.0, 1);
  fabricate_seed(root.path / "seed2", 11.0, 2.0, 2);
  fabricate_seed(root.path / "seed10", 12.0, 2.0, 3);
  fs::create_directories(root.path / "notes");
  const apps::ReferenceRuns runs = apps::read_reference_runs(root.path, "here");
  ASSERT_EQ(runs.seeds.size(), 3u);
  EXPECT_EQ(runs.seeds[2].directory.filename(), "seed10");
  EXPECT_EQ(runs.mean_curve.size(), 21u);
  EXPECT_DOUBLE_EQ(runs.clusters, 12500.0);
  // Each seed's maximum: a + b at the first row where sin(k u / 4 mm) is largest on the grid.
  double expected_mean_of_maxima = 0.0, expected_max_of_mean = 0.0;
  for (int s = 0; s < 3; ++s)
    {
      double m = -1e300;
      for (int r = 0; r < 21; ++r)
        m = std::max(m, 10.0 + s + 2.0 * std::sin((s + 1) * 5e-4 * r / 4e-3));
      expected_mean_of_maxima += m / 3.0;
    }
  for (int r = 0; r < 21; ++r)
    {
      double mean = 0.0;
      for (int s = 0; s < 3; ++s)
        mean += (10.0 + s + 2.0 * std::sin((s + 1) * 5e-4 * r / 4e-3)) / 3.0;
      expected_max_of_mean = std::max(expected_max_of_mean, mean);
      EXPECT_NEAR(runs.mean_curve[r][1], mean, 1e-9) << "row " << r; // the CSV's 15 digits
      EXPECT_NEAR(runs.mean_curve[r][0], 5e-4 * r, 1e-12);
    }
  EXPECT_NEAR(runs.T_max.mean, expected_mean_of_maxima, 1e-9);
  EXPECT_NEAR(runs.T_max_of_mean_curve, expected_max_of_mean, 1e-9);
  // The fluctuating seeds peak at different displacements: the mean curve's maximum is lower.
  EXPECT_LT(runs.T_max_of_mean_curve, runs.T_max.mean - 0.1);
}

TEST(ReferenceRuns, RefusesWhatIsNotTheSamePull)
{
  TemporaryDirectory root("reference_runs_bad");
  std::string e = error_of(root.path / "absent");
  EXPECT_NE(e.find("'Output/full-size runs'"), std::string::npos) << e;
  EXPECT_NE(e.find("absent' does not exist"), std::string::npos) << e;
  e = error_of(root.path);
  EXPECT_NE(e.find("holds no finished runs"), std::string::npos) << e;

  fabricate_seed(root.path / "seed1", 10.0, 1.0, 1);
  fabricate_seed(root.path / "seed2", 10.0, 1.0, 1, 15);
  e = error_of(root.path);
  EXPECT_NE(e.find("has 15 rows"), std::string::npos) << e;
  EXPECT_NE(e.find("not the same pull"), std::string::npos) << e;

  fs::remove(root.path / "seed2" / "summary.json");
  e = error_of(root.path);
  EXPECT_NE(e.find("has no summary.json"), std::string::npos) << e;
  EXPECT_NE(e.find("seed2"), std::string::npos) << e;
}

TEST(ReferenceRuns, ADemonstrationSaysSo)
{
  TemporaryDirectory root("demonstration");
  const fs::path full = root.path / "full_size";
  fabricate_seed(full / "seed1", 14.0, 1.0, 1, 5);
  fabricate_seed(full / "seed2", 13.0, 1.0, 2, 5);
  const std::string input = geohybrid::testing::write_tiny_pullout_input(root.path);
  std::ofstream(input, std::ios::app) << "subsection Output\n  set demonstration = soft soil, 400 clusters: don't compare\n"
                                      << "  set full-size runs = " << full.string() << "\nend\n";
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::run_pullout_command(input, false), 0);
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_NE(printed.find("a DEMONSTRATION of the workflow, not a result: soft soil, 400 clusters: don't compare"), std::string::npos)
    << printed;
  EXPECT_NE(printed.find("the same case at full size"), std::string::npos) << printed;

  const fs::path out = root.path / "out";
  const nlohmann::json summary = apps::read_summary(out / "summary.json");
  EXPECT_EQ(summary.at("demonstration").get<std::string>(), "soft soil, 400 clusters: don't compare");
  const apps::ReferenceRuns runs = apps::read_reference_runs(full, "here");
  EXPECT_DOUBLE_EQ(summary.at("full_size_T_max_kN_per_m").get<double>(), runs.T_max.mean);
  EXPECT_DOUBLE_EQ(summary.at("full_size_T_max_of_mean_curve_kN_per_m").get<double>(), runs.T_max_of_mean_curve);
  EXPECT_EQ(summary.at("full_size_n_seeds").get<double>(), 2.0);
  EXPECT_TRUE(fs::exists(out / "reference_curve.csv"));
  std::ifstream script(out / "pullout_curve.png.gp");
  std::stringstream text;
  text << script.rdbuf();
  // The apostrophe is doubled in gnuplot's quotes, and the plot is drawn.
  EXPECT_NE(text.str().find("DEMONSTRATION, not a result: soft soil, 400 clusters: don''t compare"), std::string::npos)
    << text.str();
  EXPECT_GT(fs::file_size(out / "pullout_curve.png"), 1000u);
  EXPECT_NE(text.str().find("reference_curve.csv"), std::string::npos) << text.str();

  // Neither entry is physics: the hash is the plain run's.
  fs::create_directories(root.path / "plain");
  const std::string plain = geohybrid::testing::write_tiny_pullout_input(root.path / "plain");
  EXPECT_EQ(apps::check_pullout_input(plain), apps::check_pullout_input(input));
}
