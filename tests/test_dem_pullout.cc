// The pull-out tank (dem/pullout_tank.h): geometry checks that name the parameter, the sheet's
// polyline, the grains' density for the sand's unit weight, and a small tank filled with its sheet
// laid at its depth and pulled a short distance: the head tension rises to a plateau set by the
// interface friction on both faces of the sheet.
#include "dem/measurements.h"
#include "dem/pullout_tank.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace geohybrid::dem;

namespace
{
/// Expects `f` to throw std::invalid_argument whose message names `parameter`.
template <typename F>
void expect_refused_naming(F f, const std::string &parameter)
{
  try
    {
      f();
      ADD_FAILURE() << "not refused: expected an error naming '" << parameter << "'";
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("'" + parameter + "'"), std::string::npos) << e.what();
    }
}

/// A small tank: 0.16 m long, 0.1 m of soil in two lifts, a simple run-out L = 0.1 m under
/// H = 0.05 m, 400 two-disc clusters of sizes 0.8 to 1 (about 7 mm: seven grains per lift),
/// porosity 0.25 (a lift this thin with a sheet on it does not reach 0.2), Table 5 contacts.
PullOutTankSpec small_tank(int n_threads)
{
  PullOutTankSpec s;
  s.geometry.tank_length = 0.16;
  s.geometry.fill_height = 0.1;
  s.geometry.cover = 0.05;
  s.geometry.anchorage_length = 0.1;
  s.geometry.clamp_offset = 0.01;
  s.max_segment_length = 0.01;
  s.filling.n_layers = 2;
  s.filling.n_particles = 400;
  s.filling.size_distribution = SizeDistribution::uniform(0.8);
  s.filling.target_porosity = 0.25;
  s.filling.growth_stress = 20e3;
  s.filling.equilibrium_unbalanced_ratio = 1e-3;
  s.filling.seed = 3;
  s.filling.n_threads = n_threads;
  return s;
}
} // namespace

TEST(PullOutGeometry, BadGeometryRefusedNamingTheParameter)
{
  const std::string where = "test";
  PullOutGeometry g;
  EXPECT_NO_THROW(g.validate(where));
  PullOutGeometry bad = g;
  bad.cover = 0.7; // deeper than the fill: the sheet is below the tank's base
  expect_refused_naming([&] { bad.validate(where); }, "Anchorage/H");
  bad = g;
  bad.anchorage_length = 1.6; // through the back wall
  expect_refused_naming([&] { bad.validate(where); }, "Anchorage/L");
  bad = g;
  bad.anchorage = Anchorage::wrap_around;
  bad.upper_length = 2.0; // longer than the tank
  expect_refused_naming([&] { bad.validate(where); }, "Anchorage/B");
  bad.upper_length = 0.25;
  EXPECT_NO_THROW(bad.validate(where)); // D1 + D2 = 0.4 = H
  bad.return_height = 0.3;              // H != D1 + D2
  expect_refused_naming([&] { bad.validate(where); }, "Anchorage/H");
  bad = g;
  bad.tank_length = -1.0;
  expect_refused_naming([&] { bad.validate(where); }, "Tank/length");
  bad = g;
  bad.wall_friction_deg = 90.0;
  expect_refused_naming([&] { bad.validate(where); }, "Tank/wall friction angle");

  PullOutTankSpec spec;
  spec.filling.n_layers = 4; // layers 0.15 m thick: no boundary at the sheet level 0.2 m
  expect_refused_naming([&] { spec.validate(where); }, "Filling/number of layers");
  spec.filling.n_layers = 6;
  EXPECT_NO_THROW(spec.validate(where));
}

TEST(PullOutGeometry, SheetPolylineOfBothAnchorages)
{
  PullOutGeometry g; // front wall at 1.5 m, clamp 0.02 m outside
  std::vector<Vec2> c = g.sheet_corners(0.2);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], Vec2(1.52, 0.2));
  EXPECT_NEAR(c[1].x(), 0.5, 1e-15); // L = 1 m into the soil
  EXPECT_EQ(c[1].y(), 0.2);
  g.anchorage = Anchorage::wrap_around;
  g.upper_length = 0.25;
  c = g.sheet_corners(0.2);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_NEAR(c[2].x(), 0.5, 1e-15); // the return, D1 = 0.2 m up
  EXPECT_NEAR(c[2].y(), 0.4, 1e-15);
  EXPECT_NEAR(c[3].x(), 0.75, 1e-15); // the upper part, B = 0.25 m back towards the front
  EXPECT_NEAR(c[3].y(), 0.4, 1e-15);
  EXPECT_NEAR(g.fill_height - c[3].y(), g.upper_cover, 1e-15); // D2 below the surface
}

TEST(PullOutGeometry, GrainDensityGivesTheSandsUnitWeight)
{
  // Sand 1: 15.2 kN/m3 at porosity 0.2 (Table 1, Table 5): 15.2e3 / (9.81 x 0.8) = 1936.8 kg/m3.
  EXPECT_NEAR(solid_density_for_unit_weight(15.2e3, 0.2, 9.81), 1936.79, 0.01);
  PullOutTankSpec spec;
  EXPECT_NEAR(spec.resolved_filling().density, 1936.79, 0.01);
  EXPECT_EQ(spec.resolved_filling().wall_contact.friction_angle_deg, 28.0);
  EXPECT_EQ(spec.resolved_filling().sheet->layers_below, 2u); // 0.2 m of soil in 0.1 m lifts
}

// The small tank pulled 4 mm at 5 mm/s. Before the pull the soil presses the sheet with about
// gamma H (side-wall friction carries some of the weight). While the whole sheet slides, each
// interface contact is on its Coulomb limit, so the head tension is tan(delta) times the normal
// force on both faces (the sheet's weight and the node-wall forces are negligible). T_max must
// therefore exceed the one-face value sigma_v L tan(delta) and stay below both faces at that
// stress with the dilatancy of a dense sand (a factor 2 on sigma_v: stated bound 4 sigma_v L
// tan(delta)). Results are the same on 1 and 2 threads, bit for bit.
//
// DISABLED: too slow for CI (each fill of this tank takes 55-95 s on one thread: REDF in thin
// lifts, the lift over the sheet slowest). Run it with --gtest_also_run_disabled_tests.
// At 20 mm/s (without the start ramp) T exceeded tan(delta) N by up to 2 x: the rate effect of
// local damping and inertia; at 5 mm/s the plateau is the friction on both faces.
TEST(PullOutTank, DISABLED_SmallTankPlateauAboveOneFaceFrictionAndThreadIndependent)
{
  std::vector<std::vector<PullPoint>> curves;
  for (const int n_threads : {1, 2})
    {
      const PullOutTankSpec spec = small_tank(n_threads);
      PullOutTank tank = fill_pull_out_tank(spec);
      DemSystem &system = tank.tank.system;
      ASSERT_EQ(system.sheets().size(), 1u);
      EXPECT_EQ(system.particles().n_bodies(), spec.filling.n_particles);
      // Sheet laid on the lift: within two grains above the nominal level.
      EXPECT_GT(tank.sheet_level, spec.geometry.sheet_level());
      EXPECT_LT(tank.sheet_level, spec.geometry.sheet_level() + 0.015);
      // No grain escaped through the slot.
      for (std::size_t d = 0; d < system.particles().n_discs_total(); ++d)
        ASSERT_LT(system.particles().disc_x[d], spec.geometry.tank_length);

      const SheetLevelStress before = measure_sheet_level_stress(system, tank, spec.geometry, 0.02);
      const double gamma_H = spec.unit_weight * (spec.geometry.fill_height - tank.sheet_level);
      EXPECT_GT(before.top_face, 0.5 * gamma_H);
      EXPECT_LT(before.top_face, 1.2 * gamma_H);
      const double mu = std::tan(degrees_to_radians(spec.sheet.interface.friction_angle_deg));
      const double one_face = before.top_face * spec.geometry.anchorage_length * mu;

      PullSpec pull;
      pull.rate = 0.005;
      pull.final_displacement = 0.004;
      pull.record_interval = 0.0005;
      double plateau_ratio_sum = 0.0;
      int plateau_samples = 0;
      const std::vector<PullPoint> curve = pull_out(system, pull, [&](const PullPoint &p, const DemSystem &s) {
        if (p.head_displacement > 0.002)
          {
            const SheetLevelStress now = measure_sheet_level_stress(s, tank, spec.geometry, 0.02);
            plateau_ratio_sum += p.head_tension / (mu * now.normal_force_both_faces);
            ++plateau_samples;
          }
      });
      ASSERT_EQ(curve.size(), 9u);
      // The pull stops at the first step past the end: within one step's travel of it.
      EXPECT_NEAR(curve.back().head_displacement, 0.004, pull.rate * system.time_step());
      double T_max = 0.0;
      for (const PullPoint &p : curve)
        T_max = std::max(T_max, p.head_tension);
      EXPECT_GT(T_max, one_face);
      EXPECT_LT(T_max, 4.0 * one_face);
      // The curve rises: the first point is the tension of the laid sheet (stretched a little by
      // the grains grown over it), below T_max.
      EXPECT_LT(curve.front().head_tension, 0.5 * T_max);
      // On the plateau the tension is the friction on both faces.
      ASSERT_GT(plateau_samples, 0);
      EXPECT_NEAR(plateau_ratio_sum / plateau_samples, 1.0, 0.25);
      curves.push_back(curve);
    }
  ASSERT_EQ(curves[0].size(), curves[1].size());
  for (std::size_t k = 0; k < curves[0].size(); ++k)
    {
      EXPECT_EQ(curves[0][k].head_displacement, curves[1][k].head_displacement);
      EXPECT_EQ(curves[0][k].head_tension, curves[1][k].head_tension);
    }
}
