// `geohybrid biaxial` end to end on a tiny sample: the output contract (summary.json keys, one
// CSV per confinement) and bad input refused with the parameter named, before any output.
#include "apps/biaxial_command.h"
#include "apps/output_guard.h"
#include "apps/pullout_fem_mode.h"
#include "dem/laboratory/biaxial_test.h"
#include "temporary_directory.h"
#include "text_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using geohybrid::testing::read_text;

namespace
{
fs::path test_directory()
{
  return geohybrid::testing::fresh_directory("test_app_biaxial_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
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

  // The continuum with the same response: dem::continuum_equivalent of the summary's figures, as
  // a fragment that a pull-out input's subsection Continuum takes (declared as geohybrid pullout
  // declares it), so that its fem mode runs the soil its dem mode runs.
  const auto value = [&](const std::string &key) {
    const auto at = text.str().find("\"" + key + "\": ");
    return at == std::string::npos ? std::nan("") : std::stod(text.str().substr(at + key.size() + 4));
  };
  geohybrid::dem::BiaxialParameters measured;
  measured.young_modulus = value("young_modulus_Pa");
  measured.poisson_ratio = value("poisson_ratio");
  measured.peak_friction_angle_deg = value("peak_friction_angle_deg");
  measured.cohesion = value("cohesion_Pa");
  measured.dilatancy_angle_deg = value("dilatancy_angle_deg");
  const geohybrid::dem::ContinuumEquivalent expected = geohybrid::dem::continuum_equivalent(measured);
  ASSERT_TRUE(expected.invalid_reason.empty()) << expected.invalid_reason;
  ASSERT_TRUE(fs::exists(d / "out" / "continuum_soil.prm"));
  dealii::ParameterHandler prm;
  geohybrid::apps::declare_continuum_parameters(prm);
  prm.parse_input((d / "out" / "continuum_soil.prm").string());
  prm.enter_subsection("Continuum");
  EXPECT_EQ(prm.get("soil model"), "Mohr-Coulomb");
  // The summary carries 12 digits, the fragment 12: the same numbers to 1e-10.
  EXPECT_NEAR(prm.get_double("Young modulus"), expected.young_modulus, 1e-10 * expected.young_modulus);
  EXPECT_NEAR(prm.get_double("Poisson ratio"), expected.poisson_ratio, 1e-10);
  EXPECT_NEAR(prm.get_double("friction angle"), expected.friction_angle_deg, 1e-9);
  EXPECT_NEAR(prm.get_double("cohesion"), expected.cohesion, 1e-9 * std::max(1.0, expected.cohesion));
  EXPECT_NEAR(prm.get_double("dilatancy angle"), expected.dilatancy_angle_deg, 1e-9);
  prm.leave_subsection();
  std::cout << "continuum of the tiny sample: E " << expected.young_modulus << " Pa, nu " << expected.poisson_ratio
            << ", phi " << expected.friction_angle_deg << " deg, c " << expected.cohesion << " Pa, psi "
            << expected.dilatancy_angle_deg << " deg (biaxial E_2D " << measured.young_modulus << ", nu_2D "
            << measured.poisson_ratio << ")" << std::endl;
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

// 'Sample/sample file': the first run makes the sample and saves it, the second reads it (on two
// threads, the tests side by side) and gives the same curves; a sample file made with another seed
// is refused, naming the parameter, the file and the setting, before any output.
TEST(BiaxialCommand, SampleFileIsMadeOnceAndReused)
{
  const fs::path d = test_directory();
  const fs::path sample = d / "sample.h5";
  const std::string with_file = "subsection Sample\n  set sample file = " + sample.string() + "\nend\n";
  ASSERT_EQ(error_of(write_input(d, with_file)), "");
  ASSERT_TRUE(fs::exists(sample));
  const std::string first_20 = read_text(d / "out" / "biaxial_20kPa.csv");
  const std::string first_50 = read_text(d / "out" / "biaxial_50kPa.csv");
  EXPECT_GT(first_20.size(), 500u);
  const auto written = fs::last_write_time(sample);

  geohybrid::apps::set_overwrite_output(true); // the second run replaces the first one's files
  const std::string second = error_of(write_input(d, with_file + "set threads = 2\n"));
  geohybrid::apps::set_overwrite_output(false);
  ASSERT_EQ(second, "");
  EXPECT_EQ(fs::last_write_time(sample), written); // read, not made again
  EXPECT_EQ(read_text(d / "out" / "biaxial_20kPa.csv"), first_20);
  EXPECT_EQ(read_text(d / "out" / "biaxial_50kPa.csv"), first_50);
  EXPECT_NE(read_text(d / "out" / "summary.json").find(sample.string()), std::string::npos);

  fs::remove(d / "out" / "summary.json");
  // Refused for its sample before the directory is looked at.
  const std::string message =
    error_of(write_input(d, "subsection Sample\n  set seed = 2\n  set sample file = " + sample.string() + "\nend\n"));
  EXPECT_NE(message.find("input file"), std::string::npos) << message;
  EXPECT_NE(message.find("sample file"), std::string::npos) << message;
  EXPECT_NE(message.find(sample.string()), std::string::npos) << message;
  EXPECT_NE(message.find("seed: 1 stored, 2 wanted"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
  fs::remove_all(d);
}

// The campaign's layouts: on one thread the tests run one after the other; on two, two at a
// time, and when no test is left to start the one still running takes the thread of the one that
// finished (its system moved to two threads mid-run). Every curve is the same, bit for bit.
TEST(BiaxialCommand, CurvesDoNotDependOnTheThreadLayout)
{
  geohybrid::apps::BiaxialCampaign campaign;
  campaign.sample.n_particles = 200;
  campaign.sample.width = 0.05;
  campaign.sample.height = 0.08;
  campaign.sample.porosity_tolerance = 0.01;
  campaign.sample.particle_contact.normal_stiffness = 7e7;
  campaign.sample.particle_contact.shear_stiffness = 3.5e7;
  campaign.sample.particle_contact.friction_angle_deg = 10.0;
  campaign.sample.wall_contact = campaign.sample.particle_contact;
  campaign.sample.wall_contact.friction_angle_deg = 0.0;
  campaign.test.target_inertial_number = 1e-3;
  campaign.test.final_axial_strain = 0.015;
  campaign.test.ramp_strain = 0.005;
  campaign.test.record_interval = 0.001;
  campaign.confining_stresses = {20e3, 50e3, 30e3};

  campaign.sample.n_threads = 1;
  const std::vector<geohybrid::dem::BiaxialCurve> one = geohybrid::apps::run_biaxial_campaign(campaign, false);
  campaign.sample.n_threads = 2;
  const std::vector<geohybrid::dem::BiaxialCurve> two = geohybrid::apps::run_biaxial_campaign(campaign, false);
  ASSERT_EQ(one.size(), 3u);
  ASSERT_EQ(two.size(), 3u);
  int moved = 0;
  for (std::size_t t = 0; t < 3; ++t)
    {
      EXPECT_EQ(one[t].final_threads, 1);
      moved += two[t].final_threads == 2;
      EXPECT_EQ(two[t].consolidation_steps, one[t].consolidation_steps);
      EXPECT_EQ(two[t].compression_steps, one[t].compression_steps);
      ASSERT_EQ(two[t].points.size(), one[t].points.size());
      for (std::size_t k = 0; k < one[t].points.size(); ++k)
        {
          EXPECT_EQ(two[t].points[k].axial_strain, one[t].points[k].axial_strain) << "test " << t << ", point " << k;
          EXPECT_EQ(two[t].points[k].lateral_strain, one[t].points[k].lateral_strain) << "test " << t << ", point " << k;
          EXPECT_EQ(two[t].points[k].axial_stress, one[t].points[k].axial_stress) << "test " << t << ", point " << k;
          EXPECT_EQ(two[t].points[k].lateral_stress, one[t].points[k].lateral_stress) << "test " << t << ", point " << k;
        }
    }
  EXPECT_EQ(moved, 1); // the last test running took the freed thread
}
