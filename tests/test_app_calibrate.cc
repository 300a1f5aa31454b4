// `geohybrid calibrate` end to end on a tiny sample (200 clusters, one confinement, 3 % strain):
// targets measured once with known micro-parameters are met from a start several degrees and a
// factor 2 away, the known parameters are recovered, the fragment parses and reproduces the
// run; remake mode is `geohybrid biaxial`; out-of-reach targets and bad input are refused.
#include "apps/biaxial_command.h"
#include "apps/summary.h"
#include "apps/calibrate_command.h"
#include "apps/contact_parameters.h"
#include "temporary_directory.h"
#include "text_file.h"

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <sstream>

namespace fs = std::filesystem;
using geohybrid::testing::read_text;
using geohybrid::testing::TemporaryDirectory;

namespace
{
// The sample and test shared by every case; the particle and wall contacts are the starting
// guess: delta = 14 deg, kn = 3.5e7 N/m/m (walls as stiff as the particles).
std::string sample_and_test(const fs::path &output)
{
  return "set output directory = " + output.string() + "\n" +
         "set threads = 1\n"
         "subsection Sample\n  set number of particles = 200\n  set width = 0.05\n  set height = 0.08\n"
         "  set porosity tolerance = 0.01\n  set seed = 1\nend\n"
         "subsection Particle contact\n  set friction angle = 14\n  set normal stiffness = 3.5e7\n"
         "  set shear stiffness = 1.75e7\nend\n"
         "subsection Wall contact\n  set normal stiffness = 3.5e7\n  set shear stiffness = 1.75e7\nend\n"
         "subsection Test\n  set confining stresses = 20e3\n  set inertial number = 8e-4\n"
         "  set final axial strain = 0.03\n  set record interval = 1e-4\nend\n";
}

std::string write_file(const fs::path &file, const std::string &text)
{
  std::ofstream(file) << text;
  return file.string();
}

std::string error_of(const std::function<int()> &run)
{
  try
    {
      run();
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}

/// The rows of a CSV file with a header, as numbers (an empty field is NaN).
std::vector<std::vector<double>> read_rows(const fs::path &file)
{
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line))
    {
      std::vector<double> row;
      std::stringstream fields(line);
      std::string field;
      while (std::getline(fields, field, ','))
        row.push_back(field.empty() ? std::nan("") : std::stod(field));
      rows.push_back(row);
    }
  return rows;
}

/// A number of summary.json (NaN if absent or null).
double summary_value(const fs::path &file, const std::string &key)
{
  const nlohmann::json summary = geohybrid::apps::read_summary(file);
  const auto found = summary.find(key);
  return found == summary.end() || !found->is_number() ? std::nan("") : found->get<double>();
}

// calibration.csv columns
enum Column
{
  iteration,
  friction_angle,
  normal_stiffness,
  stiffness_ratio,
  peak_friction_angle,
  young_modulus,
  poisson_ratio,
  friction_angle_error,
  young_modulus_error,
  poisson_ratio_error,
  converged
};

// Measured once on this sample (reused mode: REDF with the starting parameters, then the laws
// switched) with delta = 20 deg, kn = 7e7 N/m/m, ks/kn = 0.5 and walls kn = 7e7, ks = 3.5e7:
// phi' = 38.488 deg, E = 26.674 MPa (40.219 deg and 27.513 MPa before REDF counted its jammed
// steps in all; 42.9 deg and 18.6 MPa before the dense-packing time step, 31.2 deg and 15.3 MPa
// with it but before faster REDF growth: a 200-cluster sample's peak hangs on details of its REDF
// history). To measure again after a change of the DEM's numerics: dem::make_redf_sample with the
// spec of sample_and_test() (20 kPa), dem::change_contact_laws to those laws at 20 kPa,
// dem::run_biaxial_test with the Test subsection (mean diameter as in geohybrid biaxial), then
// dem::analyse_biaxial_curves.
constexpr double known_friction = 20.0, known_kn = 7e7;
constexpr double target_phi = 38.49, target_E = 26.67e6;
} // namespace

TEST(CalibrateCommand, RecoversKnownParametersAndWritesAFragment)
{
  TemporaryDirectory d("test_app_calibrate");
  const std::string calibration = "subsection Calibration\n  set target friction angle = 38.49\n"
                                  "  set target Young modulus = 26.67e6\n  set friction angle tolerance = 1\n"
                                  "  set Young modulus tolerance = 0.1\n  set maximum iterations = 8\nend\n";
  const std::string input = write_file(d.path / "calibrate.prm", sample_and_test(d.path / "out") + calibration);
  ASSERT_EQ(error_of([&] { return geohybrid::apps::run_calibrate_command(input, false); }), "");

  const std::vector<std::vector<double>> rows = read_rows(d.path / "out" / "calibration.csv");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_LE(rows.size(), 8u);
  // The start was off, the end is within tolerance, and each row's errors are its measurements'.
  EXPECT_LT(rows.front()[friction_angle_error], -1.0);
  EXPECT_LT(rows.front()[young_modulus_error], -0.1);
  for (std::size_t k = 0; k < rows.size(); ++k)
    {
      EXPECT_EQ(rows[k][iteration], k + 1.0);
      EXPECT_NEAR(rows[k][friction_angle_error], rows[k][peak_friction_angle] - target_phi, 1e-9);
      EXPECT_NEAR(rows[k][young_modulus_error], rows[k][young_modulus] / target_E - 1.0, 1e-9);
      EXPECT_TRUE(std::isnan(rows[k][poisson_ratio_error])); // not targeted
      EXPECT_EQ(rows[k][stiffness_ratio], 0.5);                // held
      EXPECT_EQ(rows[k][converged], k + 1 == rows.size() ? 1.0 : 0.0);
    }
  const std::vector<double> &last = rows.back();
  EXPECT_NEAR(last[peak_friction_angle], target_phi, 1.0);
  EXPECT_NEAR(last[young_modulus], target_E, 0.1 * target_E);
  // The targets came from known parameters, and on one fabric the response is smooth: they are
  // recovered, the friction well (phi' moves about 1.4 deg per degree of friction here), kn
  // poorly: on this sample E varies little between kn = 5.1e7 with 21.4 deg and 7e7 with 20 deg
  // (26.7 MPa), so the calibration stops at 5.1e7 (measured); 40 % catches a kn
  // that went the wrong way or a factor 2 off. (On the sample made before faster REDF growth it
  // was recovered within 20 %.)
  EXPECT_NEAR(last[friction_angle], known_friction, 1.5);
  EXPECT_NEAR(last[normal_stiffness], known_kn, 0.4 * known_kn);

  // The fragment parses through an include and holds exactly the last iteration's values.
  dealii::ParameterHandler prm;
  prm.enter_subsection("Particle contact");
  geohybrid::apps::declare_contact_parameters(prm, geohybrid::dem::ContactParameters{});
  prm.leave_subsection();
  const fs::path fragment = d.path / "out" / "calibrated_soil.prm";
  ASSERT_TRUE(fs::exists(fragment));
  EXPECT_NE(read_text(fragment).find("# Targets:  peak friction angle 38.49 +/- 1 deg"), std::string::npos);
  prm.parse_input(write_file(d.path / "soil.prm", "include " + fragment.string() + "\n"));
  prm.enter_subsection("Particle contact");
  const geohybrid::dem::ContactParameters soil =
    geohybrid::apps::parse_contact_parameters(prm, "the calibrated fragment");
  prm.leave_subsection();
  EXPECT_NEAR(soil.friction_angle_deg, last[friction_angle], 1e-9);
  EXPECT_NEAR(soil.normal_stiffness, last[normal_stiffness], 1e-9 * known_kn);
  EXPECT_NEAR(soil.shear_stiffness, 0.5 * last[normal_stiffness], 1e-9 * known_kn);
  EXPECT_EQ(soil.shear_strength, 0.0);

  const fs::path summary = d.path / "out" / "summary.json";
  EXPECT_EQ(summary_value(summary, "converged"), 1.0);
  EXPECT_EQ(summary_value(summary, "iterations"), static_cast<double>(rows.size()));
  // The summary keeps every digit of the double, calibration.csv 12: equal to 1e-10.
  EXPECT_NEAR(summary_value(summary, "peak_friction_angle_deg"), last[peak_friction_angle],
              1e-10 * last[peak_friction_angle]);
  EXPECT_EQ(summary_value(summary, "contact_friction_angle_deg"), soil.friction_angle_deg);

  // Same input, same numbers.
  const std::string again = write_file(d.path / "again.prm", sample_and_test(d.path / "again") + calibration);
  ASSERT_EQ(error_of([&] { return geohybrid::apps::run_calibrate_command(again, false); }), "");
  const std::vector<std::vector<double>> rows_again = read_rows(d.path / "again" / "calibration.csv");
  ASSERT_EQ(rows_again.size(), rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (int c = friction_angle; c <= young_modulus_error; ++c)
      EXPECT_EQ(rows_again[k][c], rows[k][c]) << "row " << k << " column " << c;
}

// The three targets together, from delta = 20 deg, kn = 7e7 N/m/m, ks/kn = 0.25 on the same
// reused sample (measured once: phi' = 37.867 deg, E = 23.943 MPa, nu = 0.676; ks/kn = 0.5 gives
// nu = 0.631; before REDF counted its jammed steps in all: 40.112 deg, 25.183 MPa, 0.632 and 0.611: the initial Poisson ratio of this dense sample includes
// dilation, far above the hexagonal packing's 0 to 1/3).
TEST(CalibrateCommand, AlsoMeetsAPoissonRatio)
{
  TemporaryDirectory d("test_app_calibrate");
  const std::string input = write_file(
    d.path / "calibrate.prm", sample_and_test(d.path / "out") +
                                "subsection Calibration\n  set target friction angle = 37.87\n"
                                "  set target Young modulus = 23.94e6\n  set target Poisson ratio = 0.676\n"
                                "  set friction angle tolerance = 1\n  set Young modulus tolerance = 0.1\n"
                                "  set Poisson ratio tolerance = 0.02\n  set maximum iterations = 8\nend\n");
  ASSERT_EQ(error_of([&] { return geohybrid::apps::run_calibrate_command(input, false); }), "");
  const std::vector<std::vector<double>> rows = read_rows(d.path / "out" / "calibration.csv");
  ASSERT_FALSE(rows.empty());
  EXPECT_LT(rows.front()[poisson_ratio_error], -0.1); // the start (14 deg, 3.5e7, 0.5) gives 0.34
  const std::vector<double> &last = rows.back();
  EXPECT_EQ(last[converged], 1.0);
  EXPECT_NEAR(last[peak_friction_angle], 37.87, 1.0);
  EXPECT_NEAR(last[young_modulus], 23.94e6, 0.1 * 23.94e6);
  EXPECT_NEAR(last[poisson_ratio], 0.676, 0.02);
  EXPECT_NEAR(last[poisson_ratio_error], last[poisson_ratio] - 0.676, 1e-9);
  // The stiffness ratio is met, not recovered: on this sample nu moves only 0.008 per 0.1 of
  // ks/kn (0.631 at 0.5, 0.676 at 0.25, measured at kn = 7e7), so the 0.02 tolerance on nu admits
  // a wide band of ks/kn (the calibration stopped at 0.38, with kn 7.9e7). It moved the right way
  // from the start.
  EXPECT_LT(last[stiffness_ratio], 0.5);
  // phi' moves about 0.75 deg per degree of friction, and with ks/kn: the 1 deg tolerance on phi'
  // leaves about 2 deg of friction (measured: 19.7 deg recovered).
  EXPECT_NEAR(last[friction_angle], 20.0, 2.0);
}

// In remake mode an iteration is `geohybrid biaxial` with the guess: targets taken from a biaxial
// run of the starting parameters are met at the first iteration, with the same numbers.
TEST(CalibrateCommand, RemakeModeIsTheBiaxialCommand)
{
  TemporaryDirectory d("test_app_calibrate");
  const std::string biaxial = write_file(d.path / "biaxial.prm", sample_and_test(d.path / "biaxial"));
  ASSERT_EQ(error_of([&] { return geohybrid::apps::run_biaxial_command(biaxial, false); }), "");
  const double phi = summary_value(d.path / "biaxial" / "summary.json", "peak_friction_angle_deg");
  const double E = summary_value(d.path / "biaxial" / "summary.json", "young_modulus_Pa");
  ASSERT_TRUE(std::isfinite(phi) && std::isfinite(E));

  std::ostringstream calibration;
  calibration << std::setprecision(17) << "subsection Calibration\n  set sample = remake\n"
              << "  set target friction angle = " << phi << "\n  set target Young modulus = " << E
              << "\n  set maximum iterations = 1\nend\n";
  const std::string input = write_file(d.path / "calibrate.prm", sample_and_test(d.path / "out") + calibration.str());
  ASSERT_EQ(error_of([&] { return geohybrid::apps::run_calibrate_command(input, false); }), "");
  const std::vector<std::vector<double>> rows = read_rows(d.path / "out" / "calibration.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0][converged], 1.0);
  EXPECT_NEAR(rows[0][peak_friction_angle], phi, 1e-9);
  EXPECT_NEAR(rows[0][young_modulus], E, 1e-9 * E);
}

// A peak friction angle of 75 deg is beyond what a contact friction of 89 deg gives on this
// sample: the run stops with that message, keeps its iterations and writes no result.
TEST(CalibrateCommand, OutOfReachTargetFailsClearly)
{
  TemporaryDirectory d("test_app_calibrate");
  const std::string input =
    write_file(d.path / "calibrate.prm", sample_and_test(d.path / "out") +
                                           "subsection Calibration\n  set target friction angle = 75\n"
                                           "  set target Young modulus = 18.61e6\nend\n");
  const std::string message = error_of([&] { return geohybrid::apps::run_calibrate_command(input, false); });
  EXPECT_NE(message.find("calibrate.prm"), std::string::npos) << message;
  EXPECT_NE(message.find("the target friction angle 75 deg is out of reach: a contact friction angle of 89 deg gives"),
            std::string::npos)
    << message;
  EXPECT_FALSE(fs::exists(d.path / "out" / "summary.json"));
  EXPECT_FALSE(fs::exists(d.path / "out" / "calibrated_soil.prm"));
  const std::vector<std::vector<double>> rows = read_rows(d.path / "out" / "calibration.csv");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows.back()[friction_angle], 89.0);
  EXPECT_LT(rows.back()[peak_friction_angle], 75.0);
}

TEST(CalibrateCommand, BadInputNamesTheParameterAndFile)
{
  TemporaryDirectory d("test_app_calibrate");
  struct Case
  {
    std::string calibration, expected;
  };
  const std::string targets = "  set target friction angle = 38.4\n  set target Young modulus = 20e6\n";
  for (const Case &c :
       {Case{"  set target Young modulus = 20e6\n", "'Calibration/target friction angle' is missing"},
        Case{"  set target friction angle = 38.4\n", "'Calibration/target Young modulus' is missing"},
        Case{targets + "  set target Young modulus = -20e6\n", "'Calibration/target Young modulus' = -20000000 must be positive"},
        Case{targets + "  set target friction angle = -5\n", "'Calibration/target friction angle' = -5 must lie between 0 and 90"},
        Case{targets + "  set target friction angle = steep\n", "'Calibration/target friction angle' = 'steep' is not a number"},
        Case{targets + "  set friction angle tolerance = 0\n", "'Calibration/friction angle tolerance' = 0 must be positive"},
        Case{targets + "  set Young modulus tolerance = -0.05\n", "'Calibration/Young modulus tolerance' = -0.05 must be positive"},
        Case{targets + "  set target Poisson ratio = 1.5\n", "'Calibration/target Poisson ratio' = 1.5 must be below 1"},
        Case{targets + "  set fragment file = ../soil.prm\n", "'Calibration/fragment file' = '../soil.prm' must be a plain file name"}})
    {
      const std::string input =
        write_file(d.path / "bad.prm", sample_and_test(d.path / "out") + "subsection Calibration\n" + c.calibration + "end\n");
      const std::string message = error_of([&] { return geohybrid::apps::run_calibrate_command(input, false); });
      EXPECT_NE(message.find(c.expected), std::string::npos) << "input: " << c.calibration << "\nmessage: " << message;
      EXPECT_NE(message.find("input file '" + input + "'"), std::string::npos) << message;
      EXPECT_FALSE(fs::exists(d.path / "out")) << "nothing is written before the input is checked";
    }
}
