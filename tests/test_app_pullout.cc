// `geohybrid pullout` end to end on a tiny tank: the output contract (pullout_curve.csv with its
// exact columns, summary.json keys, the sheet's displacements and tension profiles), the soil
// taken from a `geohybrid calibrate` fragment, and bad input refused naming the entry; seeds
// averaged, and the soil's fields at chosen displacements. A pull stopped and resumed:
// test_app_pullout_resume.cc.
#include "apps/pullout_command.h"
#include "apps/pullout_output.h"
#include "apps/pullout_seeds.h"
#include "pullout_forces_check.h"
#include "temporary_directory.h"
#include "text_file.h"
#include "tiny_pullout_input.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace fs = std::filesystem;
using geohybrid::testing::lines_of;
using geohybrid::testing::numbers_of;

namespace
{
fs::path test_directory()
{
  return geohybrid::testing::fresh_directory("test_app_pullout_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
}

/// The small tank of test_dem_pullout.cc, pulled 2 mm; the soil from a calibrate fragment.
std::string write_input(const fs::path &directory, const std::string &extra)
{
  std::ofstream(directory / "calibrated_soil.prm")
    << "subsection Particle contact\n  set normal stiffness = 1e7\n  set shear stiffness = 5e6\n"
    << "  set friction angle = 10\n  set shear strength = 0\n  set tensile strength = 0\nend\n";
  const fs::path file = directory / "pullout.prm";
  std::ofstream(file) << "set output directory = " << (directory / "out").string() << "\n"
                      << "set threads = 1\nset mode = dem\n"
                      << "subsection Tank\n  set length = 0.16\n  set fill height = 0.1\n  set clamp offset = 0.01\nend\n"
                      << "subsection Anchorage\n  set H = 0.05\n  set L = 0.1\nend\n"
                      << "subsection Sheet\n  subsection Interface\n    set normal stiffness = 1e7\n"
                      << "    set shear stiffness = 5e6\n  end\nend\n"
                      << "subsection Soil\n  include " << (directory / "calibrated_soil.prm").string() << "\nend\n"
                      << "subsection Filling\n  set number of particles = 400\n  set number of layers = 2\n"
                      << "  set size ratio = 0.8\n  set target porosity = 0.25\n  set growth stress = 5e3\n"
                      << "  set equilibrium unbalanced ratio = 1e-3\n  set seed = 3\nend\n"
                      << "subsection Pull\n  set rate = 0.02\n  set final displacement = 0.002\n"
                      << "  set record interval = 0.0005\n  set tension profiles at = 0.001, 0.002\nend\n"
                      << "subsection Output\n  set experimental T_max = 0.2\nend\n"
                      << extra;
  return file.string();
}

std::string error_of(const std::string &file)
{
  try
    {
      geohybrid::apps::run_pullout_command(file, false);
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}
} // namespace

// Soft contacts (kn = 1e7 N/m/m, grains and interface) and a 5 kPa growth stress, as in
// test_dem_pullout.cc: about 5 s of CPU (Table 5's kn = 7e7 and 20 kPa took 16 s, measured).
TEST(PullOutCommand, WritesTheContract)
{
  const fs::path d = test_directory();
  ASSERT_EQ(error_of(write_input(d, "")), "");
  const fs::path out = d / "out";
  const std::vector<std::string> curve = lines_of(out / "pullout_curve.csv");
  ASSERT_EQ(curve.size(), 1u + 5u); // header, the start and four intervals of 0.5 mm
  EXPECT_EQ(curve[0], "head_displacement_m,head_tension_kN_per_m");
  double u = 0.0, T = 0.0;
  char comma = 0;
  std::istringstream(curve.back()) >> u >> comma >> T;
  EXPECT_NEAR(u, 0.002, 1e-6); // the pull stops at the first step past the end
  EXPECT_GT(T, 0.0);
  // Per sheet width: b = 0.5 m, so half the tension per metre.
  const std::vector<std::string> sheet = lines_of(out / "pullout_curve_sheet.csv");
  ASSERT_EQ(sheet.size(), curve.size());
  double u_b = 0.0, T_b = 0.0;
  std::istringstream(sheet.back()) >> u_b >> comma >> T_b;
  EXPECT_NEAR(T_b, 0.5 * T, 1e-6 * T);
  const std::vector<std::string> moves = lines_of(out / "sheet_displacements.csv");
  ASSERT_EQ(moves.size(), curve.size());
  EXPECT_EQ(moves[0], "head_displacement_m,beginning_displacement_m,middle_displacement_m,end_displacement_m");
  const std::vector<std::string> profiles = lines_of(out / "sheet_tension.csv");
  EXPECT_EQ(profiles[0], "head_displacement_m,node,arc_length_m,x_m,y_m,tension_kN_per_m");
  EXPECT_EQ((profiles.size() - 1) % 2, 0u); // two profiles of one row per segment
  EXPECT_GT(profiles.size(), 20u);

  std::stringstream summary;
  summary << std::ifstream(out / "summary.json").rdbuf();
  for (const char *key : {"T_max_kN_per_m", "n_particles", "wall_time_s", "mode", "sigma_v_top_face_Pa", "gamma_H_Pa",
                          "experimental_T_max_kN_per_m", "T_max_difference_percent"})
    EXPECT_NE(summary.str().find(std::string("\"") + key + "\""), std::string::npos) << key;
  EXPECT_NE(summary.str().find("\"mode\": \"dem\""), std::string::npos) << summary.str();
  EXPECT_NE(summary.str().find("\"n_particles\": 400"), std::string::npos) << summary.str();
  EXPECT_TRUE(fs::exists(out / "parameters.prm"));

  geohybrid::testing::expect_pullout_forces_add_up(out);
  fs::remove_all(d);
}

// A full disk (/dev/full: every write fails with ENOSPC) stops the run at the first row it cannot
// write, with an error naming the file (the curve files are flushed at every point), instead of
// leaving them empty or failing only at the end.
TEST(PullOutCommand, FullDiskNamesTheFile)
{
  if (!fs::exists("/dev/full"))
    GTEST_SKIP() << "no /dev/full on this system";
  const fs::path d = test_directory();
  for (const char *name : {"pullout_curve.csv", "sheet_tension.csv"})
    {
      fs::remove_all(d / name);
      fs::create_symlink("/dev/full", d / name);
      try
        {
          geohybrid::apps::PulloutOutput output(d, 0.5, {0.001});
          output.add_point(0.0, 0.0, {{0.0, 0.0, 0.0}});
          ADD_FAILURE() << "writing to a full " << name << " was not refused";
        }
      catch (const std::runtime_error &e)
        {
          EXPECT_NE(std::string(e.what()).find((d / name).string()), std::string::npos) << e.what();
          EXPECT_NE(std::string(e.what()).find("disk full"), std::string::npos) << e.what();
        }
      fs::remove(d / name);
    }
  fs::remove_all(d);
}

TEST(PullOutCommand, BadInputNamesTheEntry)
{
  const fs::path d = test_directory();
  struct Case
  {
    std::string extra, expected;
  };
  // mode = fem with bad input: tests/test_app_pullout_fem.cc; mode = hybrid: test_app_pullout_hybrid.cc.
  // This tank is too small for the default margin's box to leave any continuum.
  for (const Case &c : {Case{"set mode = hybrid\n", "'Hybrid/DEM region margin'"},
                        Case{"subsection Anchorage\n  set L = 0.3\nend\n", "'Anchorage/L'"},
                        Case{"subsection Anchorage\n  set type = wrap-around\n  set D1 = 0.03\n  set D2 = 0.03\n"
                             "  set B = 0.05\nend\n",
                             "'Anchorage/H'"},
                        Case{"subsection Anchorage\n  set type = wrap-around\n  set D1 = 0.02\n  set D2 = 0.03\n"
                             "  set B = 0.2\nend\n",
                             "'Anchorage/B'"},
                        Case{"subsection Filling\n  set number of layers = 3\nend\n", "'Filling/number of layers'"},
                        Case{"subsection Output\n  set experimental T_max = abc\nend\n", "experimental T_max"},
                        Case{"subsection Pull\n  set grain local damping = 1.2\nend\n", "'Pull/grain local damping'"},
                        Case{"subsection Pull\n  set grain local damping = low\nend\n", "'Pull/grain local damping'"}})
    {
      const std::string message = error_of(write_input(d, c.extra));
      EXPECT_NE(message.find(c.expected), std::string::npos) << c.extra << " -> " << message;
      EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
    }
  fs::remove_all(d);
}

namespace
{
std::string write_tiny_input(const fs::path &directory) { return geohybrid::testing::write_tiny_pullout_input(directory); }

std::string contents_of_summary(const fs::path &run) { return geohybrid::testing::read_text(run / "summary.json"); }

/// The number a flat summary.json gives `key` (NaN if it has none).
double json_number(const fs::path &file, const std::string &key)
{
  std::stringstream text;
  text << std::ifstream(file).rdbuf();
  const std::string s = text.str();
  const auto at = s.find("\"" + key + "\": ");
  if (at == std::string::npos)
    return std::nan("");
  return std::stod(s.substr(at + key.size() + 4));
}
} // namespace

// `--seeds 2`: two fills (seeds 3 and 4), each with its full contract in seed_<s>/, and the
// curve averaged row by row: the mean, min, max and sample standard deviation of the two seeds'
// head tensions (to the 10 digits the CSV files hold), T_max the mean of the two T_max.
TEST(PullOutCommand, SeedsAverageTheCurves)
{
  const fs::path d = test_directory();
  const std::string input = write_tiny_input(d);
  EXPECT_THROW(geohybrid::apps::run_pullout_seeds(input, 0), std::invalid_argument);
  EXPECT_FALSE(fs::exists(d / "out"));
  // A sheet longer than the tank: refused by name before the parent directory is written.
  {
    std::ofstream(d / "bad.prm") << "include " << input << "\nsubsection Anchorage\n  set L = 5\nend\n";
    try
      {
        geohybrid::apps::run_pullout_seeds((d / "bad.prm").string(), 2);
        ADD_FAILURE() << "a 5 m sheet was accepted";
      }
    catch (const std::invalid_argument &e)
      {
        EXPECT_NE(std::string(e.what()).find("'Anchorage/L'"), std::string::npos) << e.what();
      }
    EXPECT_FALSE(fs::exists(d / "out"));
  }
  ASSERT_EQ(geohybrid::apps::run_pullout_seeds(input, 2), 0);
  const fs::path out = d / "out";
  for (const char *seed : {"seed_3", "seed_4"})
    {
      EXPECT_TRUE(fs::exists(out / seed / "summary.json")) << seed;
      EXPECT_EQ(lines_of(out / seed / "pullout_curve.csv")[0], "head_displacement_m,head_tension_kN_per_m");
    }
  EXPECT_EQ(lines_of(out / "pullout_curve.csv")[0],
            "head_displacement_m,head_tension_kN_per_m,head_tension_min_kN_per_m,head_tension_max_kN_per_m,"
            "head_tension_std_kN_per_m");
  const auto mean = numbers_of(out / "pullout_curve.csv"), a = numbers_of(out / "seed_3" / "pullout_curve.csv"),
             b = numbers_of(out / "seed_4" / "pullout_curve.csv");
  ASSERT_EQ(mean.size(), 5u); // the start and four intervals of 0.25 mm
  ASSERT_EQ(a.size(), mean.size());
  ASSERT_EQ(b.size(), mean.size());
  bool seeds_differ = false;
  for (std::size_t r = 0; r < mean.size(); ++r)
    {
      ASSERT_EQ(mean[r].size(), 5u);
      const double tolerance = 1e-9 * (std::abs(a[r][1]) + std::abs(b[r][1])) + 1e-15;
      EXPECT_NEAR(mean[r][0], 0.5 * (a[r][0] + b[r][0]), 1e-12) << "row " << r;
      EXPECT_NEAR(mean[r][1], 0.5 * (a[r][1] + b[r][1]), tolerance) << "row " << r;
      EXPECT_NEAR(mean[r][2], std::min(a[r][1], b[r][1]), tolerance) << "row " << r;
      EXPECT_NEAR(mean[r][3], std::max(a[r][1], b[r][1]), tolerance) << "row " << r;
      EXPECT_NEAR(mean[r][4], std::abs(a[r][1] - b[r][1]) / std::sqrt(2.0), tolerance) << "row " << r;
      seeds_differ = seeds_differ || a[r][1] != b[r][1];
    }
  EXPECT_TRUE(seeds_differ); // two fills, not one twice
  const double T3 = json_number(out / "seed_3" / "summary.json", "T_max_kN_per_m"),
               T4 = json_number(out / "seed_4" / "summary.json", "T_max_kN_per_m");
  EXPECT_NEAR(json_number(out / "summary.json", "T_max_kN_per_m"), 0.5 * (T3 + T4), 1e-10 * (T3 + T4));
  EXPECT_NEAR(json_number(out / "summary.json", "T_max_std_kN_per_m"), std::abs(T3 - T4) / std::sqrt(2.0),
              1e-10 * (T3 + T4));
  EXPECT_EQ(json_number(out / "summary.json", "n_seeds"), 2.0);
  EXPECT_EQ(json_number(out / "summary.json", "n_particles"), 400.0);
  std::stringstream summary;
  summary << std::ifstream(out / "summary.json").rdbuf();
  EXPECT_NE(summary.str().find("\"seeds\": \"3, 4\""), std::string::npos) << summary.str();
  // Each seed's summary holds the hash of its own input: the file's for seed 3, seed 4's for seed 4.
  std::ofstream(d / "seed_4.prm") << "include " << input << "\nsubsection Filling\n  set seed = 4\nend\n";
  EXPECT_NE(contents_of_summary(out / "seed_3").find("\"parameters_hash\": \"" +
                                                      geohybrid::apps::check_pullout_input(input) + "\""),
            std::string::npos);
  EXPECT_NE(contents_of_summary(out / "seed_4").find("\"parameters_hash\": \"" +
                                                      geohybrid::apps::check_pullout_input((d / "seed_4.prm").string()) + "\""),
            std::string::npos);
  EXPECT_NE(summary.str().find("\"mode\": \"dem\""), std::string::npos) << summary.str();
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0)
    {
      EXPECT_TRUE(fs::exists(out / "pullout_curve.png"));
    }
  fs::remove_all(d);
}

// The soil's fields (Figures 10-12) at two head displacements of the tiny run: the grains'
// displacements since the start of the pull (x - x0, the same start in both files), the force
// network, three snapshots (the start and the two displacements) and the surface uplift, whose
// grains rise as those grains do in the displacement field.
TEST(PullOutCommand, WritesTheFieldsAtChosenDisplacements)
{
  const fs::path d = test_directory();
  const std::string input = write_tiny_input(d);
  std::ofstream(input, std::ios::app) << "subsection Output\n  set field outputs at = 0.001, 0.0005\nend\n";
  ASSERT_EQ(error_of(input), "");
  const fs::path out = d / "out";
  const auto half = numbers_of(out / "grain_displacements_u0.5mm.csv"),
             full = numbers_of(out / "grain_displacements_u1mm.csv");
  EXPECT_EQ(lines_of(out / "grain_displacements_u1mm.csv")[0],
            "body_id,x0_m,y0_m,x_m,y_m,dx_m,dy_m,vx_m_per_s,vy_m_per_s");
  ASSERT_EQ(half.size(), 400u);
  ASSERT_EQ(full.size(), 400u);
  double largest = 0.0;
  for (std::size_t b = 0; b < full.size(); ++b)
    {
      ASSERT_EQ(full[b].size(), 9u);
      EXPECT_EQ(full[b][0], half[b][0]); // the same body
      EXPECT_EQ(full[b][1], half[b][1]); // from the same start
      EXPECT_EQ(full[b][2], half[b][2]);
      EXPECT_NEAR(full[b][5], full[b][3] - full[b][1], 1e-12) << "body " << full[b][0];
      EXPECT_NEAR(full[b][6], full[b][4] - full[b][2], 1e-12) << "body " << full[b][0];
      largest = std::max(largest, std::hypot(full[b][5], full[b][6]));
    }
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(largest, 0.001); // no grain moves farther than the head
  const auto network = numbers_of(out / "force_network_u1mm.csv");
  EXPECT_GT(network.size(), 400u); // a connected packing: more contacts than grains
  for (const auto &chain : network)
    EXPECT_GE(chain[4], 0.0);
  std::stringstream xdmf;
  xdmf << std::ifstream(out / "pullout_fields.xdmf").rdbuf();
  EXPECT_NE(xdmf.str().find("snapshot_000002"), std::string::npos);
  EXPECT_EQ(xdmf.str().find("snapshot_000003"), std::string::npos);
  EXPECT_EQ(lines_of(out / "surface_uplift.csv")[0], "body_id,x_m,surface_y_m,uplift_m_at_0.5mm,uplift_m_at_1mm");
  const auto surface = numbers_of(out / "surface_uplift.csv");
  EXPECT_GT(surface.size(), 8u); // strips of two discs (about 11 mm) across 0.16 m
  for (const auto &point : surface)
    {
      const auto grain = std::find_if(full.begin(), full.end(), [&](const auto &row) { return row[0] == point[0]; });
      ASSERT_NE(grain, full.end());
      EXPECT_NEAR(point[4], (*grain)[6], 1e-12);
      EXPECT_GT(point[2], 0.08); // the surface of a 0.1 m fill
    }
  fs::remove_all(d);
}
