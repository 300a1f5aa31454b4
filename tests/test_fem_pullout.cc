// The pure-continuum pull-out test (fem/pullout_problem.h) on a small rectangular tank of elastic
// soil under gravity and a surcharge: the head tension rises monotonically to the interface limit
// 2 sigma_v tan(delta) L (sigma_v the geostatic stress at the sheet's depth), the curve does not
// change when the pull rate is halved (quasi-static), and bad input is refused by name.
#include "fem/pullout_problem.h"
#include "test_fem_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

using namespace geohybrid::fem;
using namespace geohybrid::fem::testing;

namespace
{
struct SmallTank
{
  Mesh mesh{MPI_COMM_WORLD};
  SmallTank() { make_rectangular_tank(mesh, 0.6, 0.4, 12, 8); }
};

double interface_limit(const PulloutProblemParameters &p, double sigma_v)
{
  return 2.0 * sigma_v * std::tan(degrees_to_radians(p.sheet.interface.friction_angle_deg)) * p.sheet_length;
}

/// T at head displacement d, linear between the curve's points.
double tension_at(const std::vector<PulloutCurvePoint> &curve, double d)
{
  for (std::size_t i = 1; i < curve.size(); ++i)
    if (curve[i].head_displacement >= d)
      {
        const auto &a = curve[i - 1], &b = curve[i];
        const double w = (d - a.head_displacement) / (b.head_displacement - a.head_displacement);
        return a.head_tension + w * (b.head_tension - a.head_tension);
      }
  return curve.back().head_tension;
}

void print(const char *what, const PulloutResult &r)
{
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return;
  std::cout << what << ": T_max " << r.max_head_tension << " N/m, sigma_v " << r.vertical_stress_at_sheet
            << " Pa, " << r.n_steps << " steps of " << r.time_step << " s, sheet mass scaling "
            << r.sheet_mass_scaling << "; curve (mm, N/m):";
  for (std::size_t i = 0; i < r.curve.size(); i += 2)
    std::cout << " (" << 1e3 * r.curve[i].head_displacement << ", " << r.curve[i].head_tension << ")";
  std::cout << std::endl;
}
} // namespace

TEST(PulloutProblem, ElasticTankReachesTheInterfaceLimitMonotonically)
{
  SmallTank tank;
  const auto parameters = small_pullout_tank(0.004);
  PulloutProblem problem(tank.mesh, parameters);
  const PulloutResult r = problem.run();
  print("pull-out, 4 mm/s", r);
  // The interface itself (the sum of its shear forces on the sheet, last step) sits at the limit:
  // the normal stress it reads is sigma_v on the mean.
  const double resistance = -problem.solver().sheet()->interface_resultant()[0];

  // The geostatic stress at the sheet: q + gamma H.
  EXPECT_NEAR(r.vertical_stress_at_sheet, 30e3 + 15.2e3 * 0.225, 1e-6);
  EXPECT_DOUBLE_EQ(r.tank_length, 0.6);
  EXPECT_DOUBLE_EQ(r.tank_height, 0.4);
  const double limit = interface_limit(parameters, r.vertical_stress_at_sheet);
  // Measured: T_max +1.1 % (the clamp carries, besides the interface, the local damping's drag on
  // the sliding sheet), the interface's own resistance +0.7 % (the 50 mm cells).
  EXPECT_NEAR(r.max_head_tension, limit, 0.015 * limit);
  EXPECT_NEAR(resistance, limit, 0.01 * limit);

  // One point per 0.5 mm over 12 mm, from the unloaded sheet.
  ASSERT_EQ(r.curve.size(), 25u);
  EXPECT_NEAR(r.curve.front().head_displacement, 0.0, 1e-15);
  EXPECT_NEAR(r.curve.front().head_tension, 0.0, 1e-9 * limit);
  EXPECT_NEAR(r.curve.back().head_displacement, 0.012, 0.5e-3);

  // Rising: every point above the last until the curve reaches 97 % of T_max (the plateau), and
  // the plateau's points within 1.5 % of the limit from there on.
  std::size_t i = 1;
  for (; i < r.curve.size() && r.curve[i].head_tension < 0.97 * r.max_head_tension; ++i)
    EXPECT_GT(r.curve[i].head_tension, r.curve[i - 1].head_tension) << "point " << i;
  ASSERT_LT(i, r.curve.size());
  EXPECT_GT(i, 3u) << "the curve should rise over several points, not jump to the plateau";
  for (; i < r.curve.size(); ++i)
    EXPECT_NEAR(r.curve[i].head_tension, limit, 0.015 * limit) << "point " << i;
}

// Quasi-static: at half the rate (twice the steps) the curve is the same to within 1 % of T_max
// at every head displacement.
TEST(PulloutProblem, HalvingThePullRateLeavesTheCurveUnchanged)
{
  SmallTank tank_a, tank_b;
  const PulloutResult fast = PulloutProblem(tank_a.mesh, small_pullout_tank(0.004)).run();
  const PulloutResult slow = PulloutProblem(tank_b.mesh, small_pullout_tank(0.002)).run();
  print("pull-out, 2 mm/s", slow);
  double largest = 0.0;
  for (double d = 0.25e-3; d <= 0.0115; d += 0.25e-3)
    largest = std::max(largest, std::abs(tension_at(fast.curve, d) - tension_at(slow.curve, d)));
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "rate halved: largest difference " << largest << " N/m = " << largest / fast.max_head_tension
              << " of T_max; T_max " << fast.max_head_tension << " vs " << slow.max_head_tension << " N/m"
              << std::endl;
  EXPECT_LT(largest, 0.01 * fast.max_head_tension);
  EXPECT_NEAR(slow.max_head_tension, fast.max_head_tension, 0.005 * fast.max_head_tension);
}

TEST(PulloutProblem, BadInputIsRefusedByName)
{
  SmallTank tank;
  const auto refused = [&](PulloutProblemParameters p, const std::string &name) {
    try
      {
        PulloutProblem problem(tank.mesh, p, "pull-out test");
        ADD_FAILURE() << "accepted bad '" << name << "'";
      }
    catch (const std::invalid_argument &e)
      {
        const std::string what = e.what();
        EXPECT_NE(what.find("'" + name + "'"), std::string::npos) << what;
        EXPECT_NE(what.find("pull-out test"), std::string::npos) << what;
      }
  };
  auto p = small_pullout_tank(0.004);
  p.sheet_length = 0.7; // the tank is 0.6 m long
  refused(p, "sheet length L");
  p = small_pullout_tank(0.004);
  p.sheet_depth = 0.4; // at the bottom
  refused(p, "sheet depth H");
  p.sheet_depth = -0.1;
  refused(p, "sheet depth H");
  p = small_pullout_tank(0.004);
  p.pull_rate = 0.0;
  refused(p, "pull rate");
  p = small_pullout_tank(0.004);
  p.output_interval = 0.1; // above the final displacement
  refused(p, "output interval");
  p = small_pullout_tank(0.004);
  p.final_displacement = -1.0;
  refused(p, "final displacement");
  p = small_pullout_tank(0.004);
  p.sheet.axial_stiffness = -1.0;
  refused(p, "axial stiffness J");
  p = small_pullout_tank(0.004);
  p.sheet.interface.friction_angle_deg = 95.0;
  refused(p, "interface friction angle");
  p = small_pullout_tank(0.004);
  p.soil.young_modulus = -1.0;
  EXPECT_THROW(PulloutProblem(tank.mesh, p), std::invalid_argument);
  p = small_pullout_tank(0.004);
  p.snapshot_directory = "somewhere";
  refused(p, "snapshot interval");
}

// VTU snapshots: one before the pull and one per snapshot interval of head displacement.
TEST(PulloutProblem, WritesSnapshotsAtTheirInterval)
{
  SmallTank tank;
  auto p = small_pullout_tank(0.004);
  p.final_displacement = 0.002;
  p.snapshot_interval = 0.001;
  const auto directory = std::filesystem::temp_directory_path() / "geohybrid_test_fem_pullout_snapshots";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  p.snapshot_directory = directory.string();
  const PulloutResult r = PulloutProblem(tank.mesh, p).run();
  ASSERT_EQ(r.snapshots.size(), 3u); // 0, 1 and 2 mm
  for (const auto &record : r.snapshots)
    EXPECT_TRUE(std::filesystem::exists(record)) << record;
  std::filesystem::remove_all(directory);
}
