// The particle box's lifts (coupling/particle_box.h, issue 26 "Defaults that work at full size"):
// automatic lifts against their rule (REDF refuses grains wider than a fifth of a lift; the
// automatic lifts keep 5 % room over that, and put the sheet and a wrap-around's upper part on
// lift boundaries), the former default kept where it worked, refusals that name the entry, the
// input file and a value that works, and a small tank that the former default refused set up.
#include "small_hybrid_tank.h"
#include "test_coupling_support.h"

#include "coupling/hybrid_pullout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
/// The paper's tank (1.5 m x 0.6 m, the sheet 0.2 m above the base under H = 0.4 m, L = 1 m),
/// the library's grains (two-disc clusters, size ratio 0.5, porosity 0.2: sand 1's fill), a
/// 0.1 m margin, automatic lifts; a wrap-around has D1 = 0.2 m and B = 0.25 m.
HybridPullOutSpec paper_tank(std::size_t n_particles, bool wrap = false)
{
  HybridPullOutSpec s;
  s.tank.filling.n_layers = 3;
  s.tank.filling.n_particles = n_particles;
  s.region.margin = 0.1;
  if (wrap)
    {
      s.tank.geometry.anchorage = dem::Anchorage::wrap_around;
      s.tank.geometry.return_height = 0.2;
      s.tank.geometry.upper_cover = 0.2;
      s.tank.geometry.upper_length = 0.25;
    }
  return s;
}

/// The rule's checks on an automatic box: lifts at least 5.25 of its largest grains (REDF's
/// fifth with the 5 % room; exact), the sheet on a lift boundary (to 1e-9 m).
void expect_the_rule(const ParticleBox &box)
{
  EXPECT_GE(box.lift_thickness, 5.0 * automatic_lift_room * box.largest_grain);
  const double lifts_below = box.box_tank.geometry.sheet_level() / box.lift_thickness;
  EXPECT_NEAR(lifts_below, std::round(lifts_below), 1e-9);
  EXPECT_NEAR(box.y1 - box.y0, static_cast<double>(box.n_lifts) * box.lift_thickness, 1e-9);
}

/// The number the refusal `message` suggests for 'Filling/number of particles' (0 if none).
std::size_t suggested_particles(const std::string &message)
{
  const std::string key = "set 'Filling/number of particles' to ";
  const auto at = message.find(key);
  return at == std::string::npos ? 0 : std::stoul(message.substr(at + key.size()));
}
} // namespace

// Many grains: the automatic lifts are the former default's (0.05 m), the same box, so an input
// that ran keeps its numbers.
TEST(ParticleBoxLifts, AutomaticKeepsTheFormerDefaultWhereItWorked)
{
  HybridPullOutSpec given = paper_tank(100000);
  given.region.lift_thickness = 0.05;
  const ParticleBox a = particle_box(paper_tank(100000), "test.prm"), g = particle_box(given, "test.prm");
  EXPECT_EQ(a.lift_thickness, g.lift_thickness);
  EXPECT_EQ(a.lift_thickness, 0.05);
  EXPECT_EQ(a.n_lifts, 4u);
  EXPECT_EQ(a.y0, g.y0);
  EXPECT_EQ(a.y1, g.y1);
  EXPECT_EQ(a.n_particles, g.n_particles);
  expect_the_rule(a);
}

// The case: the run-out with the paper's 25,000 clusters, grains up to 11 mm, which
// 0.05 m lifts refuse. The margin below the sheet becomes one 0.1 m lift; with a 0.05 m margin
// the box reaches past it, one lift as thin as the grains allow (to the millimetre and the 1 %
// steps above 5.25 grains: within 3 % + 1 mm of it).
TEST(ParticleBoxLifts, AutomaticLiftsAreTheThinnestTheRunOutsGrainsAllow)
{
  const ParticleBox box = particle_box(paper_tank(25000), "test.prm");
  // The fill's own figure for this box (main at 9ad9cec: "REDF: 6111 particles filling the tank
  // (1.1 m x 0.2 m in layers 0.05 m thick) at porosity 0.2 would be up to 0.0111681 m across").
  EXPECT_NEAR(box.largest_grain, 0.0111681, 1e-7);
  EXPECT_NEAR(box.lift_thickness, 0.1, 1e-12);
  EXPECT_NEAR(box.y0, 0.1, 1e-12);
  EXPECT_NEAR(box.y1, 0.3, 1e-12);
  EXPECT_EQ(box.n_lifts, 2u);
  expect_the_rule(box);

  HybridPullOutSpec narrow = paper_tank(25000);
  narrow.region.margin = 0.05;
  const ParticleBox n = particle_box(narrow, "test.prm");
  std::cout << "0.05 m margin: lifts of " << n.lift_thickness << " m for grains up to " << n.largest_grain << " m, the box ["
            << n.y0 << ", " << n.y1 << "] m high" << std::endl;
  expect_the_rule(n);
  EXPECT_LE(n.lift_thickness, 1.03 * 5.0 * automatic_lift_room * n.largest_grain + 1e-3);
  EXPECT_GT(n.lift_thickness, 0.05);
  EXPECT_NEAR(n.y0, 0.2 - n.lift_thickness, 1e-12); // one lift below the sheet, past the margin
  EXPECT_GE(n.y1 - 0.2, 0.05);                       // the margin above, in whole lifts
}

// The wrap-around: the lifts also put the upper part (0.2 m above the sheet) on a boundary. With
// 25,000 clusters, 0.1 m lifts; with 7,500 (the main job's grains, too few for its 0.1 m lifts),
// lifts of D1 = 0.2 m, the box down to the base and up to the surface.
TEST(ParticleBoxLifts, AutomaticLiftsPutTheUpperPartOnALiftBoundary)
{
  const ParticleBox box = particle_box(paper_tank(25000, true), "test.prm");
  EXPECT_NEAR(box.lift_thickness, 0.1, 1e-12);
  EXPECT_NEAR(box.y1, 0.5, 1e-12);
  expect_the_rule(box);
  const double upper = (box.box_tank.geometry.sheet_level() + 0.2) / box.lift_thickness;
  EXPECT_NEAR(upper, std::round(upper), 1e-9);

  const ParticleBox coarse = particle_box(paper_tank(7500, true), "test.prm");
  EXPECT_NEAR(coarse.lift_thickness, 0.2, 1e-12);
  EXPECT_NEAR(coarse.y0, 0.0, 1e-12);
  EXPECT_NEAR(coarse.y1, 0.6, 1e-12);
  EXPECT_TRUE(coarse.left_shared && !coarse.bottom_shared && !coarse.top_shared);
  expect_the_rule(coarse);
}

// A margin no one lift thickness fits (issue 26: the wrap-around needs 0.15 m): each part of the
// box in lifts of its own, the margin exact below the sheet, the sheet and the upper part on lift
// boundaries, every lift at least 5.25 of the box's largest grains, the whole tank's lifts (0.2 m)
// where they fit. The main job's grains (12,500 clusters): 0.15 m below, D1 = 0.2 m, and 0.2 m
// above the upper part to the surface, since the 0.05 m of continuum the margin would leave there
// is thinner than a lift. With 25,000 clusters and a 0.125 m margin the box stops 0.125 m above
// the upper part, under the continuum. Lifts evenly divided where the tank's do not fit: the
// margin of 0.15 m in a tank of 0.1 m lifts (which would leave a lift of 0.05 m below the sheet).
TEST(ParticleBoxLifts, AutomaticLiftsOfTheirOwnThicknessInEachPartOfTheBox)
{
  const auto expect_by_part = [](const ParticleBox &box, double margin, double top) {
    const dem::TankFillingSpec f = box.box_tank.resolved_filling();
    ASSERT_EQ(f.layer_tops.size(), box.n_lifts);
    EXPECT_NEAR(box.y0, 0.2 - margin, 1e-12);
    EXPECT_NEAR(box.y1, top, 1e-12);
    EXPECT_GE(dem::thinnest_layer(f), 5.0 * automatic_lift_room * box.largest_grain);
    EXPECT_NEAR(dem::thinnest_layer(f), box.lift_thickness, 1e-12);
    EXPECT_TRUE(dem::layers_below_level(f, margin, 1e-9).has_value());       // the sheet
    EXPECT_TRUE(dem::layers_below_level(f, margin + 0.2, 1e-9).has_value()); // the upper part
    EXPECT_NEAR(f.layer_tops.back(), box.y1 - box.y0, 1e-12);
  };
  HybridPullOutSpec wide = paper_tank(12500, true);
  wide.region.margin = 0.15;
  const ParticleBox main_grains = particle_box(wide, "test.prm");
  expect_by_part(main_grains, 0.15, 0.6);
  EXPECT_FALSE(main_grains.top_shared);
  EXPECT_EQ(main_grains.box_tank.filling.layer_tops, (std::vector<double>{0.15, 0.35, 0.55})); // the tank's lifts, cut

  HybridPullOutSpec thin_lifts = wide;
  thin_lifts.tank.filling.n_layers = 6;
  const ParticleBox even = particle_box(thin_lifts, "test.prm");
  expect_by_part(even, 0.15, 0.6);
  EXPECT_EQ(even.n_lifts, 5u); // 0.15 | 0.1 0.1 | 0.1 0.1

  HybridPullOutSpec fine = paper_tank(25000, true);
  fine.region.margin = 0.125;
  const ParticleBox fine_grains = particle_box(fine, "test.prm");
  expect_by_part(fine_grains, 0.125, 0.525);
  EXPECT_TRUE(fine_grains.top_shared);

  // Given lifts of one thickness that miss the upper part: the refusal names the automatic choice.
  wide.region.lift_thickness = 0.1;
  const std::string message = invalid_argument_message([&] { particle_box(wide, "main_job.prm"); });
  EXPECT_NE(message.find("'Hybrid/lift thickness' = auto gives each part of the box lifts of its own"), std::string::npos)
    << message;
}

// Given lifts still win and are checked: the refusal names the entry, the input file and the
// particles that would fill them (checked: they do), and the automatic lifts that would do.
// Too few grains for any lift: the refusal names the particles that would do (checked).
TEST(ParticleBoxLifts, RefusalsNameTheEntryTheFileAndAValueThatWorks)
{
  HybridPullOutSpec given = paper_tank(7500, true);
  given.region.lift_thickness = 0.1;
  const std::string message = invalid_argument_message([&] { particle_box(given, "main_job.prm"); });
  EXPECT_EQ(message.rfind("main_job.prm: parameter 'Hybrid/lift thickness' = 0.1 ", 0), 0u) << message;
  EXPECT_NE(message.find("'Hybrid/lift thickness' = auto (here 3 lifts of 0.2 m"), std::string::npos) << message;
  const std::size_t enough = suggested_particles(message);
  // 7,730 clusters make grains a fifth of 0.1 m (the example's comment); 5 % room on the grains'
  // size is 10 % on their number, then rounded up to a hundred.
  EXPECT_GE(enough, 7730u);
  EXPECT_LE(enough, 8700u);
  given.tank.filling.n_particles = enough;
  EXPECT_NO_THROW(particle_box(given, "main_job.prm"));
  // Cut out of a filled tank, the box is not filled: the lifts only shape it, as given.
  given.tank.filling.n_particles = 7500;
  given.region.box_cut_from_a_filled_tank = true;
  const ParticleBox cut = particle_box(given, "main_job.prm");
  EXPECT_NEAR(cut.lift_thickness, 0.1, 1e-12);
  EXPECT_NEAR(cut.y0, given.tank.geometry.sheet_level() - given.region.margin, 1e-12);

  // 2,000 clusters, grains up to 0.04 m: even one lift of the 0.2 m below the sheet is too thin.
  HybridPullOutSpec coarse = paper_tank(2000);
  const std::string none = invalid_argument_message([&] { particle_box(coarse, "coarse.prm"); });
  EXPECT_EQ(none.rfind("coarse.prm: parameter 'Filling/number of particles' = 2000 ", 0), 0u) << none;
  coarse.tank.filling.n_particles = suggested_particles(none);
  EXPECT_NO_THROW(particle_box(coarse, "coarse.prm")) << none;
}

// The small tank of the hybrid tests (0.4 m x 0.2 m, the sheet 0.25 m long under 0.1 m) with
// 1,500 grains up to 0.011 m: the former default's 0.05 m lifts are refused; the automatic ones
// (the 0.1 m margin below the sheet, to the base, in one lift) fill and the coupled model sets up.
TEST(ParticleBoxLifts, SmallTankTheFormerDefaultRefusedSetsUp)
{
  const HybridPullOutSpec s = small_hybrid_tank(1500, 0.1);

  HybridPullOutSpec former = s;
  former.region.lift_thickness = 0.05;
  EXPECT_NE(invalid_argument_message([&] { particle_box(former, "small.prm"); }).find("'Hybrid/lift thickness' = 0.05"),
            std::string::npos);

  const HybridPullOut hybrid(s, "small.prm");
  const ParticleBox &box = hybrid.box();
  std::cout << "small tank: " << box.n_particles << " particles, grains up to " << box.largest_grain << " m, "
            << box.n_lifts << " lifts of " << box.lift_thickness << " m" << std::endl;
  EXPECT_NEAR(box.lift_thickness, 0.1, 1e-12);
  EXPECT_EQ(box.n_lifts, 2u);
  EXPECT_EQ(hybrid.set_up().n_particles, box.n_particles);
  EXPECT_GT(hybrid.set_up().n_tied, 0u);
}
