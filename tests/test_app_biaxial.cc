// `geohybrid biaxial` end to end on a tiny sample: the output contract (summary.json keys, one
// CSV per confinement) and bad input refused with the parameter named, before any output.
#include "apps/biaxial_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace
{
fs::path test_directory()
{
  const fs::path d = fs::temp_directory_path() /
                     ("geohybrid_test_app_biaxial_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string write_input(const fs::path &directory, const std::string &extra)
{
  const fs::path file = directory / "biaxial.prm";
  std::ofstream(file) << "set output directory = " << (directory / "out").string() << "\n"
                      << "set threads = 1\n"
                      << "subsection Sample\n  set number of particles = 200\n  set width = 0.05\n"
                      << "  set height = 0.08\n  set porosity tolerance = 0.01\nend\n"
                      << "subsection Test\n  set confining stresses = 20e3, 50e3\n  set inertial number = 1e-3\n"
                      << "  set final axial strain = 0.02\n  set record interval = 0.001\nend\n"
                      << extra;
  return file.string();
}

std::string error_of(const std::string &file)
{
  try
    {
      geohybrid::apps::run_biaxial_command(file, false);
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}
} // namespace

TEST(BiaxialCommand, WritesTheContract)
{
  const fs::path d = test_directory();
  ASSERT_EQ(error_of(write_input(d, "")), "");
  std::ifstream in(d / "out" / "summary.json");
  std::stringstream text;
  text << in.rdbuf();
  for (const char *key : {"peak_friction_angle_deg", "residual_friction_angle_deg", "cohesion_Pa", "young_modulus_Pa",
                          "poisson_ratio", "porosity", "dilatancy_angle_deg"})
    EXPECT_NE(text.str().find(std::string("\"") + key + "\""), std::string::npos) << key;
  EXPECT_TRUE(fs::exists(d / "out" / "biaxial_20kPa.csv"));
  EXPECT_TRUE(fs::exists(d / "out" / "biaxial_50kPa.csv"));
  EXPECT_TRUE(fs::exists(d / "out" / "parameters.prm"));
  fs::remove_all(d);
}

TEST(BiaxialCommand, BadInputNamesTheParameter)
{
  const fs::path d = test_directory();
  struct Case
  {
    std::string extra, expected;
  };
  for (const Case &c : {Case{"subsection Test\n  set top wall speed = 0\nend\n", "top wall speed"},
                        Case{"subsection Sample\n  set target porosity = 0.01\nend\n", "target porosity"},
                        Case{"subsection Particle contact\n  set normal stiffness = -1\nend\n", "normal stiffness"},
                        Case{"subsection Sample\n  set number of particles = 2\nend\n", "more particles or a larger box"},
                        Case{"subsection Test\n  set confining stresses = \nend\n", "confining stresses"}})
    {
      const std::string message = error_of(write_input(d, c.extra));
      EXPECT_NE(message.find(c.expected), std::string::npos) << "input: " << c.extra << "\nmessage: " << message;
      EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
    }
  fs::remove_all(d);
}
