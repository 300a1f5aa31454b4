// `geohybrid pullout` end to end on a tiny tank: the output contract (pullout_curve.csv with its
// exact columns, summary.json keys, the sheet's displacements and tension profiles), the soil
// taken from a `geohybrid calibrate` fragment, and bad input refused naming the entry.
#include "apps/pullout_command.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace fs = std::filesystem;

namespace
{
fs::path test_directory()
{
  const fs::path d = fs::temp_directory_path() /
                     ("geohybrid_test_app_pullout_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// The small tank of test_dem_pullout.cc, pulled 2 mm; the soil from a calibrate fragment.
std::string write_input(const fs::path &directory, const std::string &extra)
{
  std::ofstream(directory / "calibrated_soil.prm")
    << "subsection Particle contact\n  set normal stiffness = 7e7\n  set shear stiffness = 3.5e7\n"
    << "  set friction angle = 10\n  set shear strength = 0\n  set tensile strength = 0\nend\n";
  const fs::path file = directory / "pullout.prm";
  std::ofstream(file) << "set output directory = " << (directory / "out").string() << "\n"
                      << "set threads = 1\nset mode = dem\n"
                      << "subsection Tank\n  set length = 0.16\n  set fill height = 0.1\n  set clamp offset = 0.01\nend\n"
                      << "subsection Anchorage\n  set H = 0.05\n  set L = 0.1\nend\n"
                      << "subsection Soil\n  include " << (directory / "calibrated_soil.prm").string() << "\nend\n"
                      << "subsection Filling\n  set number of particles = 400\n  set number of layers = 2\n"
                      << "  set size ratio = 0.8\n  set target porosity = 0.25\n  set growth stress = 20e3\n"
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

std::vector<std::string> lines_of(const fs::path &file)
{
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}
} // namespace

// About a minute (measured 57 s on 1 thread, the filling 55 s of it).
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
  fs::remove_all(d);
}

TEST(PullOutCommand, BadInputNamesTheEntry)
{
  const fs::path d = test_directory();
  struct Case
  {
    std::string extra, expected;
  };
  // mode = fem with bad input: tests/test_app_pullout_fem.cc.
  for (const Case &c : {Case{"set mode = hybrid\n", "'mode' = hybrid is not yet available"},
                        Case{"subsection Anchorage\n  set L = 0.3\nend\n", "'Anchorage/L'"},
                        Case{"subsection Anchorage\n  set type = wrap-around\n  set D1 = 0.03\n  set D2 = 0.03\n"
                             "  set B = 0.05\nend\n",
                             "'Anchorage/H'"},
                        Case{"subsection Anchorage\n  set type = wrap-around\n  set D1 = 0.02\n  set D2 = 0.03\n"
                             "  set B = 0.2\nend\n",
                             "'Anchorage/B'"},
                        Case{"subsection Filling\n  set number of layers = 3\nend\n", "'Filling/number of layers'"},
                        Case{"subsection Output\n  set experimental T_max = abc\nend\n", "experimental T_max"}})
    {
      const std::string message = error_of(write_input(d, c.extra));
      EXPECT_NE(message.find(c.expected), std::string::npos) << c.extra << " -> " << message;
      EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
    }
  fs::remove_all(d);
}
