// The hybrid pull-out (issue 6, coupling/hybrid_pullout.h): particles only in a box round the
// anchorage, the continuum elsewhere, tied across the band; its box, its refusals, and a small
// tank pulled.
#include "small_hybrid_tank.h"
#include "test_coupling_support.h"

#include "coupling/hybrid_pullout.h"
#include "dem/measurements.h"
#include "dem/conventions.h"

#include <gtest/gtest.h>

#include <optional>

#include <cmath>
#include <iostream>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
/// The paper's tank (1.5 m x 0.6 m, run-out L = 1 m under H = 0.4 m, 25,000 clusters), a
/// 0.1 m margin.
HybridPullOutSpec full_size_spec()
{
  HybridPullOutSpec s;
  s.tank.filling.n_layers = 3;
  s.tank.filling.n_particles = 25000;
  s.region.margin = 0.1;
  return s;
}

TEST(ParticleBox, SpansTheSheetAndTheMarginInWholeLifts)
{
  const ParticleBox box = particle_box(full_size_spec(), "test");
  // Sheet at y = 0.2 from x = 0.5 to the front wall at 1.5: the box [0.4, 1.5] x [0.1, 0.3], one
  // lift of 0.1 m below the sheet and one above (automatic lifts: 25,000 clusters make grains
  // up to 11 mm, too large for 0.05 m lifts; tests/test_coupling_particle_box.cc).
  EXPECT_NEAR(box.x0, 0.4, 1e-12);
  EXPECT_NEAR(box.x1, 1.5, 1e-12);
  EXPECT_NEAR(box.y0, 0.1, 1e-12);
  EXPECT_NEAR(box.y1, 0.3, 1e-12);
  EXPECT_TRUE(box.left_shared && box.bottom_shared && box.top_shared);
  EXPECT_EQ(box.n_lifts, 2u);
  EXPECT_EQ(box.n_particles, 25000u * 11u * 2u / 90u); // 0.22 m^2 of 0.9 m^2
  EXPECT_NEAR(box.box_tank.geometry.cover, 0.1, 1e-12);
  EXPECT_NEAR(box.box_tank.geometry.sheet_level(), 0.1, 1e-12);

  // The wrap-around (D1 = 0.2, B = 0.25): the box reaches the margin above its upper part.
  HybridPullOutSpec wrap = full_size_spec();
  wrap.tank.geometry.anchorage = dem::Anchorage::wrap_around;
  wrap.tank.geometry.return_height = 0.2;
  wrap.tank.geometry.upper_cover = 0.2;
  wrap.tank.geometry.upper_length = 0.25;
  const ParticleBox w = particle_box(wrap, "test");
  EXPECT_NEAR(w.y1, 0.5, 1e-12);
  EXPECT_NEAR(w.box_tank.geometry.upper_cover, 0.1, 1e-12);
  EXPECT_EQ(w.n_lifts, 4u);

  // Down to the base: the base is the tank's, not shared.
  HybridPullOutSpec deep = full_size_spec();
  deep.region.margin = 0.25;
  const ParticleBox d = particle_box(deep, "test");
  EXPECT_FALSE(d.bottom_shared);
  EXPECT_NEAR(d.y0, 0.0, 1e-12);
}

// The box's soil is made as the tank's would be at its place: a floor inside the tank's first
// lift stands for the tank's base, whose loose band that lift's porosity counts; a floor higher
// up has soil below it in the tank, and the box's first lift is measured a band above it
// (TankFillingSpec::soil_continues_below). The top is the soil's surface or it is shared.
TEST(ParticleBox, FirstLiftMeasuredAboveItsFloorOnlyWhereTheTankHasSoilBelow)
{
  const ParticleBox in_first_lift = particle_box(full_size_spec(), "test"); // floor 0.1 m, first lift to 0.2 m
  EXPECT_TRUE(in_first_lift.bottom_shared);
  EXPECT_FALSE(in_first_lift.box_tank.filling.soil_continues_below);
  EXPECT_TRUE(in_first_lift.box_tank.filling.soil_continues_above);

  HybridPullOutSpec deep = full_size_spec(); // 1.0 m of fill in lifts of 0.2 m, the sheet at 0.6 m
  deep.tank.geometry.fill_height = 1.0;
  deep.tank.filling.n_layers = 5;
  deep.tank.filling.n_particles = 40000;
  const ParticleBox above = particle_box(deep, "test");
  EXPECT_NEAR(above.y0, 0.5, 1e-12);
  EXPECT_TRUE(above.box_tank.filling.soil_continues_below);
}

TEST(ParticleBox, RefusesAMarginThatLeavesNoContinuumAndBadInput)
{
  HybridPullOutSpec whole = full_size_spec();
  whole.region.margin = 1.0;
  EXPECT_NE(invalid_argument_message([&] { particle_box(whole, "test.prm"); }).find("DEM region margin"), std::string::npos);
  HybridPullOutSpec negative = full_size_spec();
  negative.region.margin = -0.1;
  EXPECT_NE(invalid_argument_message([&] { particle_box(negative, "test.prm"); }).find("DEM region margin"), std::string::npos);
  // Method 3 has no band: the sheet cannot cross into the continuum with it.
  HybridPullOutSpec interface = full_size_spec();
  interface.region.method = InterfaceCoupling{};
  interface.region.dem_region_length = 0.5;
  EXPECT_NE(invalid_argument_message([&] { particle_box(interface, "test.prm"); }).find("coupling method"), std::string::npos);
}

/// A small tank: 0.4 m x 0.2 m, the sheet 0.25 m long at 0.1 m depth, grains of about 4 mm (4,000
/// in the whole tank, about 1,500 in the box), the soft contacts of the DEM pull-out tests.
HybridPullOutSpec small_spec(const CouplingMethod &method)
{
  HybridPullOutSpec s = small_hybrid_tank(4000, 0.05);
  s.region.lift_thickness = 0.05;
  s.region.method = method;
  return s;
}

TEST(HybridPullOut, SmallTankCarriesTheOverburdenThroughTheBandAndPulls)
{
  const HybridPullOutSpec spec = small_spec(LagrangeMultiplierCoupling{});
  HybridPullOut hybrid(spec, "test");
  const HybridSetUp &s = hybrid.set_up();
  std::cout << "hybrid: " << s.n_particles << " particles (" << s.n_tied << " tied, " << s.n_driven << " driven), "
            << s.n_cells << " cells; band " << s.band_width << " m, pad " << s.pad << " m, cells " << s.cell_size
            << " m; fill " << s.fill_steps << " steps, settled in " << s.settling_steps << " (ratio "
            << s.settled_unbalanced_ratio << "), dt " << s.time_step << " s (the particles alone: " << s.particle_time_step
            << " s)" << std::endl;
  const ParticleBox &box = hybrid.box();
  const dem::PullOutTank &tank = hybrid.particles();
  // The fill's cost in steps counts every lift of the box (as the dem mode's does), not only the
  // last lift's system (which restarts its count): the summary's n_fill_steps was that before.
  ASSERT_GE(tank.tank.layers.size(), 2u);
  std::uint64_t every_lift = tank.n_final_settling_steps;
  for (const dem::TankLayer &layer : tank.tank.layers)
    every_lift += layer.n_growth_steps + layer.n_settling_steps;
  EXPECT_EQ(s.fill_steps, every_lift);
  EXPECT_GT(s.fill_steps, tank.tank.system.step_count());
  const dem::SheetLevelStress stress =
    dem::measure_sheet_level_stress(hybrid.particle_system(), tank, box.box_tank.geometry, 0.02);
  const double gamma_H = spec.tank.unit_weight * (spec.tank.geometry.fill_height - (box.y0 + tank.sheet_level));
  std::cout << "sigma_v on the sheet's top face " << stress.top_face << " Pa, Love-Weber above " << stress.love_weber_above
            << " Pa, gamma H " << gamma_H << " Pa" << std::endl;
  EXPECT_GT(stress.love_weber_above, 0.8 * gamma_H);
  EXPECT_LT(stress.love_weber_above, 1.2 * gamma_H);

  // 1.2 mm: past one face's friction, the check below (measured: T crosses it at 0.8 mm, 1.36 x
  // one face at 1.2 mm, 1.53 x at most when pulled to 2 mm).
  dem::PullSpec pull;
  pull.rate = 0.005;
  pull.final_displacement = 0.0012;
  pull.record_interval = 0.0002;
  const double mu = std::tan(dem::degrees_to_radians(spec.tank.sheet.interface.friction_angle_deg));
  const std::vector<dem::PullPoint> curve = hybrid.pull(pull, [&](const dem::PullPoint &p) {
    const dem::HeadTensionParts parts = dem::head_tension_parts(hybrid.particle_system());
    std::cout << "u " << p.head_displacement << " m: T " << p.head_tension << " N/m; tan(delta) N "
              << mu * parts.normal_force << " N/m" << std::endl;
  });
  ASSERT_EQ(curve.size(), 7u);
  double T_max = 0.0;
  for (const dem::PullPoint &p : curve)
    T_max = std::max(T_max, p.head_tension);
  const double one_face = gamma_H * spec.tank.geometry.anchorage_length * mu;
  std::cout << "T_max " << T_max << " N/m = " << T_max / one_face << " x one face" << std::endl;
  EXPECT_GT(T_max, one_face);
  EXPECT_LT(T_max, 4.0 * one_face);
}

// Method 3 in the pull-out: no band, the continuum's edges round the box are walls the grains
// touch with their own law; the continuum's hole starts at the box's settled top surface (the lid's
// height under the overburden: at the lift's top the continuum fell 1.8 mm onto the grains, past
// the interface's small-strain limit). The overburden reaches the sheet through the interface,
// the contact forces on the two sides cancel, the energy balance closes. Measured (seed 3): sigma_v
// on the sheet's top face -6.7 % of gamma H (method 1: +2.1 %); the coupling forces cancel to
// 7e-15 N/m of 434 N/m; balance 1.1e-4 over 1 mm; T_max at 2 mm 183 N/m against pure DEM's 228, method 1's 244
// and method 2's 229 N/m (the app's runs: bench/RESULTS.md): the flat interface with the grains'
// contact friction is smoother than the soil it replaces.
TEST(HybridPullOut, InterfaceCouplingCarriesTheOverburdenAndBalances)
{
  const HybridPullOutSpec spec = small_spec(InterfaceCoupling{});
  HybridPullOut hybrid(spec, "test");
  const HybridSetUp &s = hybrid.set_up();
  EXPECT_EQ(s.n_tied, 0u);
  EXPECT_EQ(s.n_driven, 0u);
  ASSERT_NE(hybrid.stepper().interface_wall(), nullptr);
  const ParticleBox &box = hybrid.box();
  const dem::PullOutTank &tank = hybrid.particles();
  const dem::SheetLevelStress stress =
    dem::measure_sheet_level_stress(hybrid.particle_system(), tank, box.box_tank.geometry, 0.02);
  const double gamma_H = spec.tank.unit_weight * (spec.tank.geometry.fill_height - (box.y0 + tank.sheet_level));
  std::cout << "method 3: sigma_v on the sheet's top face " << stress.top_face << " Pa, gamma H " << gamma_H << " Pa; "
            << s.n_cells << " cells, dt " << s.time_step << " s (the particles' own " << s.particle_time_step << " s)"
            << std::endl;
  EXPECT_NEAR(stress.top_face, gamma_H, 0.15 * gamma_H);

  dem::PullSpec pull;
  pull.rate = 0.005;
  pull.final_displacement = 0.001;
  pull.record_interval = 0.0005;
  std::optional<CouplingDiagnostics> start;
  double largest_balance_error = 0.0, largest_imbalance = 0.0, largest_force = 0.0;
  const std::vector<dem::PullPoint> curve = hybrid.pull(pull, [&](const dem::PullPoint &) {
    const CouplingDiagnostics d = hybrid.stepper().diagnostics();
    if (!start)
      start = d;
    largest_balance_error = std::max(largest_balance_error, std::abs(energy_balance_error(*start, d)));
    largest_imbalance = std::max(largest_imbalance, (d.forces.on_particles + d.forces.on_continuum).norm());
    largest_force = std::max(largest_force, d.forces.on_particles.norm());
  });
  const double mu = std::tan(dem::degrees_to_radians(spec.tank.sheet.interface.friction_angle_deg));
  const double one_face = gamma_H * spec.tank.geometry.anchorage_length * mu;
  std::cout << "method 3: T at 1 mm " << curve.back().head_tension << " N/m (one face " << one_face
            << "); balance " << largest_balance_error << "; coupling forces " << largest_imbalance << " of "
            << largest_force << " N/m" << std::endl;
  EXPECT_GT(largest_force, 0.0);
  EXPECT_LT(largest_imbalance, 1e-10 * largest_force);
  EXPECT_LT(largest_balance_error, 1e-3);
  EXPECT_GT(curve.back().head_tension, 0.5 * one_face);
}

// The sheet crossing into the continuum (HybridRegionSpec::dem_region_length): the box only
// 0.15 m long, the sheet cut at the core's edge and its last 0.1 m and more held by the
// continuum's interface. Each part's forces balance: the DEM part's head reaction is its contacts'
// forces plus the joining segment's tension; the continuum part's interface holds that tension.
// The coupled energy balance closes with the continuum's sheet in it (its truss, its interface,
// the crossing's force: SheetEnergyLedger): measured 8.8e-5 at most over the pull, against 0.37
// with the sheet left out.
TEST(HybridPullOut, SheetCrossesIntoTheContinuumAndEachPartBalances)
{
  HybridPullOutSpec spec = small_spec(LagrangeMultiplierCoupling{});
  spec.region.dem_region_length = 0.15;
  HybridPullOut hybrid(spec, "test");
  const HybridSetUp &s = hybrid.set_up();
  const ParticleBox &box = hybrid.box();
  const double core_edge = box.x0 + s.pad + s.band_width; // in the tank's frame
  const double segment = spec.tank.max_segment_length;
  std::cout << "crossing at x = " << s.crossing_x << " m (core edge " << core_edge << " m); " << s.n_sheet_nodes_particles
            << " sheet nodes in the particles, " << s.n_sheet_nodes_continuum << " in the continuum" << std::endl;
  EXPECT_NEAR(box.x0, 0.25, 1e-12);
  // The joining segment's DEM end is the last node in the core (x >= its edge), within a segment of it.
  EXPECT_GE(s.crossing_x, core_edge - 1e-12);
  EXPECT_LT(s.crossing_x, core_edge + 1.01 * segment);
  ASSERT_NE(hybrid.stepper().sheet_crossing(), nullptr);
  EXPECT_EQ(hybrid.particle_system().sheets()[0].n_nodes(), s.n_sheet_nodes_particles);
  // The continuum's part runs from the core's edge to the sheet's end at x = 0.15 m.
  const fem::EmbeddedSheet &continuum_sheet = *hybrid.continuum().sheet();
  EXPECT_EQ(continuum_sheet.sheet().n_nodes(), s.n_sheet_nodes_continuum);
  const double continuum_length = s.crossing_x - 0.15;
  double drawn = 0.0;
  for (std::size_t k = 0; k < continuum_sheet.sheet().n_segments(); ++k)
    drawn += continuum_sheet.sheet().rest_length(k);
  EXPECT_NEAR(drawn, continuum_length - hybrid.stepper().sheet_crossing()->rest_length(), 2e-3);

  // The box settled under the soil above it before the coupling (its lid servo-controlled to
  // gamma (fill - y1)), with the sheet already cut, so the grains closed the cut-off nodes' gap
  // in the pad and the band then: the continuum's part of the sheet starts at its overburden.
  // (Tied first, the band's grains falling into the gap strained its cells: a full-size bench
  // measured 18.6 kPa at the first node against gamma H = 2.3 kPa; and the box, loaded only once
  // tied, settled more than the continuum beside it, which then carried +36 %.) Measured here:
  // +24 % at the first node (in the band, where the box's edge still concentrates the stress),
  // within 1 % from 0.08 m behind the box's back, +6.2 % on the mean; asked: 30 % and 10 %.
  const double overburden = spec.tank.unit_weight * (spec.tank.geometry.fill_height - box.y1);
  EXPECT_NEAR(s.overburden, overburden, 1e-9 * overburden);
  EXPECT_NEAR(s.overburden_reached, overburden, 0.01 * overburden);
  const double gamma_H = spec.tank.unit_weight * spec.tank.geometry.cover;
  double mean_confinement = 0.0;
  for (std::size_t k = 0; k < continuum_sheet.sheet().n_nodes(); ++k)
    {
      const double confinement = -continuum_sheet.interface_normal_stress(k);
      std::cout << "settled: continuum sheet node at x = " << continuum_sheet.node_position(k)[0] + box.x0
                << " m: sigma_nn " << confinement << " Pa (gamma H " << gamma_H << " Pa)" << std::endl;
      EXPECT_NEAR(confinement, gamma_H, 0.3 * gamma_H);
      mean_confinement += confinement / static_cast<double>(continuum_sheet.sheet().n_nodes());
    }
  EXPECT_NEAR(mean_confinement, gamma_H, 0.1 * gamma_H);

  dem::PullSpec pull;
  pull.rate = 0.005;
  pull.final_displacement = 0.002;
  pull.record_interval = 0.0005;
  std::optional<CouplingDiagnostics> start;
  double largest_balance_error = 0.0, largest_without_sheet = 0.0;
  hybrid.pull(pull, [&](const dem::PullPoint &p) {
    // The coupled energy balance over the pull, the continuum's sheet in it; and without it.
    const CouplingDiagnostics d = hybrid.stepper().diagnostics();
    if (!start)
      start = d;
    const double balance_error = energy_balance_error(*start, d);
    CouplingDiagnostics without = d;
    without.continuum_sheet_ledger = start->continuum_sheet_ledger;
    const double without_sheet = energy_balance_error(*start, without);
    largest_balance_error = std::max(largest_balance_error, std::abs(balance_error));
    largest_without_sheet = std::max(largest_without_sheet, std::abs(without_sheet));
    const fem::SheetEnergyLedger &sheet_ledger = d.continuum_sheet_ledger;
    std::cout << "u " << p.head_displacement << " m: energy balance " << balance_error << " (without the continuum's "
              << "sheet " << without_sheet << "); the continuum's sheet: truss " << sheet_ledger.truss_work
              << ", interface " << sheet_ledger.interface_work << ", crossing's load " << sheet_ledger.load_work
              << " J/m, its own balance " << sheet_ledger.balance() << std::endl;
    EXPECT_NEAR(sheet_ledger.balance(), 0.0, 1e-9 * std::max(1e-3, std::abs(sheet_ledger.load_work)));
    const SheetCrossing &crossing = *hybrid.stepper().sheet_crossing();
    const dem::SparSheet &sheet = hybrid.particle_system().sheets()[0];
    const std::size_t c = crossing.dem_node();
    const dealii::Point<fem::dim> far = continuum_sheet.node_position(0);
    const double e_x = (far[0] - sheet.x[c]) / std::hypot(far[0] - sheet.x[c], far[1] - sheet.y[c]);
    const dem::HeadTensionParts parts = dem::head_tension_parts(hybrid.particle_system());
    const double continuum_holds = -continuum_sheet.interface_resultant()[0];
    std::cout << "u " << p.head_displacement << " m: T " << p.head_tension << " N/m (recorded), head reaction "
              << parts.reaction << " N/m = DEM part " << parts.sum()
              << " + joining segment " << -crossing.tension() * e_x << "; the continuum's interface holds "
              << continuum_holds << " N/m" << std::endl;
    if (p.head_displacement < 0.001)
      return;
    // The DEM part's balance is exact (the same force evaluation).
    EXPECT_NEAR(parts.reaction, parts.sum() - crossing.tension() * e_x, 1e-6 * parts.reaction);
    // The continuum part: its interface holds the joining tension, but for its inertia and
    // damping (mass-scaled nodes).
    EXPECT_GT(crossing.tension(), 0.0);
    EXPECT_NEAR(continuum_holds, crossing.tension(), 0.15 * crossing.tension());
  });
  std::cout << "largest energy balance error " << largest_balance_error << " (without the continuum's sheet "
            << largest_without_sheet << ")" << std::endl;
  EXPECT_LT(largest_balance_error, 1e-3);
}
} // namespace
