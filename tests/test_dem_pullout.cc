// The pull-out tank (dem/laboratory/pullout_tank.h): geometry checks that name the parameter, the
// sheet's polyline, the grains' density for the sand's unit weight, and a small tank filled with
// its sheet laid at its depth and pulled a short distance: the head tension rises to a plateau set
// by the interface friction on both faces of the sheet.
#include "dem/laboratory/pullout_fields.h"
#include "dem/laboratory/pullout_tank.h"
#include "dem/measurements.h"
#include "small_pullout_tank.h"

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

// The fill with its sheet gives the same numbers on 1 and 2 threads, bit for bit (every
// grain, every sheet node), so that the pull-out test below may pull one filled tank on both.
// Settled loosely (unbalanced-force ratio 1e-2) to keep it short: every stage of the fill runs.
TEST(PullOutTank, FillWithSheetSameOnOneAndTwoThreads)
{
  std::vector<DemSystemState> states;
  for (const int n_threads : {1, 2})
    {
      PullOutTankSpec spec = geohybrid::testing::small_pullout_tank(n_threads);
      spec.filling.equilibrium_unbalanced_ratio = 1e-2;
      states.push_back(fill_pull_out_tank(spec).tank.system.export_state());
    }
  const ParticleSet &a = states[0].particles, &b = states[1].particles;
  ASSERT_EQ(a.n_bodies(), b.n_bodies());
  EXPECT_EQ(states[0].step_count, states[1].step_count);
  for (std::size_t k = 0; k < a.n_bodies(); ++k)
    {
      ASSERT_EQ(a.x[k], b.x[k]) << "body " << k;
      ASSERT_EQ(a.y[k], b.y[k]) << "body " << k;
      ASSERT_EQ(a.vx[k], b.vx[k]) << "body " << k;
      ASSERT_EQ(a.omega[k], b.omega[k]) << "body " << k;
    }
  ASSERT_EQ(states[0].sheets.size(), 1u);
  ASSERT_EQ(states[1].sheets.size(), 1u);
  const SparSheet &sa = states[0].sheets[0], &sb = states[1].sheets[0];
  ASSERT_EQ(sa.n_nodes(), sb.n_nodes());
  for (std::size_t k = 0; k < sa.n_nodes(); ++k)
    {
      EXPECT_EQ(sa.x[k], sb.x[k]) << "node " << k;
      EXPECT_EQ(sa.y[k], sb.y[k]) << "node " << k;
    }
}

// The small tank pulled 2.5 mm at 5 mm/s. Before the pull the soil presses the sheet with about
// gamma H (side-wall friction carries some of the weight). The pull mobilises the interface
// friction on both faces, and the normal force rises (the grains dilate as they are dragged),
// so T_max must exceed the one-face value sigma_v L tan(delta); a factor 2 on sigma_v from
// dilatancy on both faces bounds it: 4 sigma_v L tan(delta).
//
// Where the head tension comes from (head_tension_parts): the clamp's reaction equals the sum of
// the interface friction, the pull-direction components of the interface normal forces, the
// node-wall forces and the sheet's inertia to round-off (1e-9) at every recorded point; and the
// interface friction never exceeds tan(delta) times the elastic normal force (each contact is
// capped by its Coulomb limit, friction handed across nodes included). Measured (seed 3, 1
// thread, every 0.5 mm past 1 mm): friction 55-72 N/m, normal components -1.6 to 0 N/m,
// node-wall 0 (the front wall does not touch the sheet), inertia within +/-1 N/m.
//
// An earlier version of this test asked T = tan(delta) N within 25 % on the plateau and measured
// 1.26: the normal force left out the segment through the slot (fixed in
// measure_sheet_level_stress), where the grains press the sheet hardest. Measured correctly, T is
// below tan(delta) N: the mean of T over the mean of tan(delta) N for u > 1 mm, sampled every 0.1
// mm, was 0.79 and 0.71 (seeds 3 and 4; with a 20 kPa growth stress 0.80, 0.70, 0.84 for seeds
// 3, 4, 5, and 0.79, 1.02, 0.91 with a grain friction of 30 degrees instead of 10).
// Not all contacts slide at once: the sheet sticks and slips, and grains dragged with it shear
// the soil next to it instead, whose friction angle (about 24 degrees at this grain friction,
// issue 3) is below the interface's 25.6. So that check was wrong for this soil and is replaced
// by the decomposition and the Coulomb bound; the ratio is printed.
//
// The pull is then repeated on 2 threads from the same filled tank (the fill's own thread
// independence is the test above), over its first millimetre: the same curve, bit for bit.
TEST(PullOutTank, SmallTankPlateauAboveOneFaceFrictionAndThreadIndependent)
{
  const PullOutTankSpec spec = geohybrid::testing::small_pullout_tank(1);
  const PullOutTank tank = fill_pull_out_tank(spec);
  const DemSystem &filled = tank.tank.system;
  ASSERT_EQ(filled.sheets().size(), 1u);
  EXPECT_EQ(filled.particles().n_bodies(), spec.filling.n_particles);
  // Sheet laid on the levelled lift: above the nominal level, by less than half a grain.
  EXPECT_GT(tank.sheet_level, spec.geometry.sheet_level());
  EXPECT_LT(tank.sheet_level, spec.geometry.sheet_level() + 0.004);
  // No grain escaped through the slot.
  for (std::size_t d = 0; d < filled.particles().n_discs_total(); ++d)
    ASSERT_LT(filled.particles().disc_x[d], spec.geometry.tank_length);

  const SheetLevelStress before = measure_sheet_level_stress(filled, tank, spec.geometry, 0.02);
  const double gamma_H = spec.unit_weight * (spec.geometry.fill_height - tank.sheet_level);
  EXPECT_GT(before.top_face, 0.5 * gamma_H);
  EXPECT_LT(before.top_face, 1.2 * gamma_H);
  const double mu = std::tan(degrees_to_radians(spec.sheet.interface.friction_angle_deg));
  const double one_face = before.top_face * spec.geometry.anchorage_length * mu;
  std::cout << "sheet at " << tank.sheet_level << " m, sigma_v top " << before.top_face << " Pa, bottom "
            << before.bottom_face << " Pa, gamma H " << gamma_H << " Pa, one-face friction " << one_face << " N/m\n";

  PullSpec pull;
  pull.rate = 0.005;
  pull.final_displacement = 0.0025;
  pull.record_interval = 0.0001;
  double plateau_T = 0.0, plateau_friction_limit = 0.0;
  DemSystem one_thread = with_threads(filled, 1);
  const std::vector<PullPoint> curve = pull_out(one_thread, pull, [&](const PullPoint &p, const DemSystem &s) {
    const HeadTensionParts parts = head_tension_parts(s);
    EXPECT_NEAR(parts.sum(), parts.reaction, 1e-9 * (std::abs(parts.reaction) + 1.0)) << "at " << p.head_displacement;
    EXPECT_LE(parts.tangential_force, mu * parts.elastic_normal_force * (1.0 + 1e-12)) << "at " << p.head_displacement;
    EXPECT_LE(std::abs(parts.interface_friction), parts.tangential_force * (1.0 + 1e-12));
    if (std::abs(p.head_displacement - std::round(p.head_displacement / 0.0005) * 0.0005) < 1e-6)
      std::cout << "u " << p.head_displacement << " m: T " << p.head_tension << " N/m (mean over the interval); now "
              << parts.reaction << " = friction " << parts.interface_friction << " + normal " << parts.interface_normal
              << " + node-wall " << parts.node_wall << " + inertia " << parts.inertia << " + damping " << parts.damping
              << "; tan(delta) N " << mu * parts.normal_force << '\n';
    if (p.head_displacement > 0.0009)
      {
        const SheetLevelStress now = measure_sheet_level_stress(s, tank, spec.geometry, 0.02);
        plateau_T += parts.reaction;
        plateau_friction_limit += mu * now.normal_force_both_faces;
      }
  });
  ASSERT_EQ(curve.size(), 26u);
  // The pull stops at the first step past the end: within one step's travel of it.
  EXPECT_NEAR(curve.back().head_displacement, pull.final_displacement, pull.rate * one_thread.time_step());
  double T_max = 0.0;
  for (const PullPoint &p : curve)
    T_max = std::max(T_max, p.head_tension);
  EXPECT_GT(T_max, one_face);
  EXPECT_LT(T_max, 4.0 * one_face);
  // The curve rises: the first point is the tension of the laid sheet (stretched a little by
  // the grains grown over it), below T_max.
  EXPECT_LT(curve.front().head_tension, 0.5 * T_max);
  std::cout << "T_max " << T_max << " N/m = " << T_max / one_face << " x one face; plateau T / (tan(delta) N) "
            << plateau_T / plateau_friction_limit << '\n';

  // The same pull on 2 threads, from the same filled tank, over its first millimetre.
  pull.final_displacement = 0.001;
  DemSystem two_threads = with_threads(filled, 2);
  const std::vector<PullPoint> curve_2 = pull_out(two_threads, pull);
  ASSERT_EQ(curve_2.size(), 11u);
  for (std::size_t k = 0; k < curve_2.size(); ++k)
    {
      EXPECT_EQ(curve_2[k].head_displacement, curve[k].head_displacement) << "point " << k;
      EXPECT_EQ(curve_2[k].head_tension, curve[k].head_tension) << "point " << k;
    }
}

// The field outputs (dem/laboratory/pullout_fields.h) on sets whose answers are known.
TEST(PullOutFields, DisplacementsUpliftAndForceNetworkOfKnownMoves)
{
  // Two columns of three discs (radius 5 mm, 10 mm apart) and a cluster on the right; then the
  // left column rises by 1 mm, the cluster moves by (2, -0.5) mm, the right column stays.
  ParticleSet start;
  for (int column = 0; column < 2; ++column)
    for (int row = 0; row < 3; ++row)
      start.add_disc(Vec2(0.005 + 0.01 * column, 0.005 + 0.01 * row), 0.005, 2000.0);
  start.add_two_disc_cluster(Vec2(0.03, 0.01), 0.005, 0.0045, 0.0095, 0.0, 2000.0);
  ParticleSet now = start;
  const auto move = [&](std::size_t b, const Vec2 &d) {
    now.x[b] += d.x();
    now.y[b] += d.y();
    for (std::uint32_t k = now.first_disc[b]; k < now.first_disc[b] + now.n_discs[b]; ++k)
      {
        now.disc_x[k] += d.x();
        now.disc_y[k] += d.y();
      }
  };
  for (std::size_t b = 0; b < 3; ++b)
    move(b, Vec2(0.0, 0.001));
  move(6, Vec2(0.002, -0.0005));
  now.vx[6] = 0.25;

  const std::vector<GrainDisplacement> grains = grain_displacements(start, now);
  ASSERT_EQ(grains.size(), 7u);
  for (std::size_t b = 0; b < 7; ++b)
    {
      EXPECT_EQ(grains[b].body_id, start.body_id[b]);
      EXPECT_EQ(grains[b].x0, start.x[b]);
      EXPECT_EQ(grains[b].y, now.y[b]);
      EXPECT_EQ(grains[b].dx, now.x[b] - start.x[b]);
      EXPECT_EQ(grains[b].dy, now.y[b] - start.y[b]);
    }
  EXPECT_NEAR(grains[0].dy, 0.001, 1e-15);
  EXPECT_NEAR(grains[6].dx, 0.002, 1e-15);
  EXPECT_NEAR(grains[6].dy, -0.0005, 1e-15);
  EXPECT_EQ(grains[6].vx, 0.25);
  EXPECT_EQ(grains[4].dx, 0.0);

  // Strips 10 mm wide over 40 mm: the top disc of each column, then the cluster.
  const std::vector<SurfacePoint> surface = surface_uplift(start, now, 0.04, 0.01);
  ASSERT_EQ(surface.size(), 3u); // the fourth strip holds no centre
  EXPECT_EQ(surface[0].body_id, start.body_id[2]);
  EXPECT_NEAR(surface[0].top0, 0.03, 1e-15);
  EXPECT_NEAR(surface[0].uplift, 0.001, 1e-15);
  EXPECT_EQ(surface[1].body_id, start.body_id[5]);
  EXPECT_EQ(surface[1].uplift, 0.0);
  EXPECT_EQ(surface[2].body_id, start.body_id[6]);
  EXPECT_NEAR(surface[2].uplift, -0.0005, 1e-15);
  EXPECT_THROW(surface_uplift(start, now, 0.04, 0.0), std::invalid_argument);
  ParticleSet fewer;
  fewer.add_disc(Vec2(0.0, 0.0), 0.005, 2000.0);
  EXPECT_THROW(grain_displacements(start, fewer), std::invalid_argument);

  // Two discs overlapping by 0.1 mm: one chain, kn * overlap.
  ParticleSet pair;
  pair.add_disc(Vec2(0.0, 0.0), 0.005, 2000.0);
  pair.add_disc(Vec2(0.0099, 0.0), 0.005, 2000.0);
  ContactParameters contact;
  contact.normal_stiffness = 1e7;
  DemSettings settings;
  settings.gravity = Vec2::Zero();
  DemSystem system(pair, LinearContactLaw(contact), settings);
  system.initialise_forces();
  const std::vector<ForceChain> network = contact_force_network(system);
  ASSERT_EQ(network.size(), 1u);
  EXPECT_NEAR(network[0].normal_force, 1e7 * 1e-4, 1e-6);
  EXPECT_EQ(network[0].x1, 0.0);
  EXPECT_EQ(network[0].x2, 0.0099);
}
