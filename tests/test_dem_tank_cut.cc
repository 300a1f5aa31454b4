// A region cut out of a filled pull-out tank (dem/laboratory/tank_cut.h): the grains whose centres
// lie in it, moved into its frame, the sheet with them, the region's walls clear of them; and the
// regions that cannot be cut refused by name.
#include "dem/laboratory/tank_cut.h"
#include "small_pullout_tank.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

using namespace geohybrid::dem;

namespace
{
/// The small tank's region [x0, 0.16] x [y0, y0 + height], in its own frame, with lifts that put
/// the sheet on a boundary.
PullOutTankSpec region_of(const PullOutTankSpec &tank, double x0, double y0, double height)
{
  PullOutTankSpec region = tank;
  region.geometry.tank_length = tank.geometry.tank_length - x0;
  region.geometry.fill_height = height;
  region.geometry.cover = y0 + height - tank.geometry.sheet_level();
  region.filling.n_layers = 2;
  return region;
}

} // namespace

// The small tank (0.16 m x 0.1 m, the sheet at 0.05 m) cut to [0.03, 0.16] x [0.02, 0.08]: every
// grain whose centre lies inside is kept and no other, each moved by the region's origin exactly
// and at rest; the sheet moved the same way, its clamp still through the front wall's slot, moved
// with it; the base and the left wall just clear of the grains the cut left standing past them,
// the front wall at the region's side, the lid above everything. About 1 s (the fill).
TEST(TankCut, KeepsTheGrainsWhoseCentresLieInsideMovedIntoTheRegionsFrame)
{
  const PullOutTankSpec spec = geohybrid::testing::small_pullout_tank();
  const PullOutTank tank = fill_pull_out_tank(spec);
  const double x0 = 0.03, y0 = 0.02, x1 = spec.geometry.tank_length, y1 = 0.08;
  const PullOutTankSpec region = region_of(spec, x0, y0, y1 - y0);
  const PullOutTank cut = cut_pull_out_tank(tank, spec.geometry.tank_length, region, Vec2(x0, y0), "test");

  const ParticleSet &all = tank.tank.system.particles(), &kept = cut.tank.system.particles();
  std::map<std::int64_t, std::size_t> by_id;
  for (std::size_t b = 0; b < kept.n_bodies(); ++b)
    by_id[kept.body_id[b]] = b;
  ASSERT_EQ(by_id.size(), kept.n_bodies()) << "ids are unique";
  std::size_t inside = 0;
  for (std::size_t b = 0; b < all.n_bodies(); ++b)
    {
      const bool in = all.x[b] >= x0 && all.x[b] <= x1 && all.y[b] >= y0 && all.y[b] <= y1;
      const auto found = by_id.find(all.body_id[b]);
      ASSERT_EQ(found != by_id.end(), in) << "body " << b;
      if (!in)
        continue;
      ++inside;
      const std::size_t k = found->second;
      EXPECT_EQ(kept.x[k], all.x[b] - x0);
      EXPECT_EQ(kept.y[k], all.y[b] - y0);
      EXPECT_EQ(kept.rotation[k], all.rotation[b]);
      EXPECT_EQ(kept.mass[k], all.mass[b]);
      EXPECT_EQ(kept.vx[k], 0.0);
      EXPECT_EQ(kept.omega[k], 0.0);
      for (std::uint32_t d = 0; d < kept.n_discs[k]; ++d)
        {
          EXPECT_NEAR(kept.disc_x[kept.first_disc[k] + d], all.disc_x[all.first_disc[b] + d] - x0, 1e-15);
          EXPECT_NEAR(kept.disc_y[kept.first_disc[k] + d], all.disc_y[all.first_disc[b] + d] - y0, 1e-15);
        }
    }
  EXPECT_GT(inside, all.n_bodies() / 3);
  EXPECT_LT(inside, all.n_bodies());

  const SparSheet &before = tank.tank.system.sheets()[0], &after = cut.tank.system.sheets()[0];
  ASSERT_EQ(after.n_nodes(), before.n_nodes());
  for (std::size_t k = 0; k < before.n_nodes(); ++k)
    {
      EXPECT_EQ(after.x[k], before.x[k] - x0);
      EXPECT_EQ(after.y[k], before.y[k] - y0);
    }
  EXPECT_TRUE(after.is_kinematic(0)) << "the clamp";
  EXPECT_EQ(cut.sheet_level, tank.sheet_level - y0);
  EXPECT_EQ(cut.first_node_inside, tank.first_node_inside);
  EXPECT_EQ(cut.tank.slot_bottom, tank.tank.slot_bottom - y0);
  EXPECT_EQ(cut.tank.slot_top, tank.tank.slot_top - y0);
  double lowest = 0.0, leftmost = 0.0, highest = 0.0;
  for (std::size_t d = 0; d < kept.n_discs_total(); ++d)
    {
      lowest = std::min(lowest, kept.disc_y[d] - kept.disc_radius[d]);
      leftmost = std::min(leftmost, kept.disc_x[d] - kept.disc_radius[d]);
      highest = std::max(highest, kept.disc_y[d] + kept.disc_radius[d]);
    }
  EXPECT_LT(lowest, 0.0) << "grains cut by the base stand below it";
  EXPECT_LT(leftmost, 0.0) << "grains cut by the left side stand past it";
  const std::vector<Wall> &walls = cut.tank.system.walls();
  EXPECT_NEAR(walls[cut.tank.walls.base].start.y(), lowest, 1e-15);
  EXPECT_NEAR(walls[cut.tank.walls.left].start.x(), leftmost, 1e-15);
  EXPECT_NEAR(walls[cut.tank.walls.right].start.x(), x1 - x0, 1e-15);
  EXPECT_NEAR(walls[cut.tank.walls.right].end.y(), cut.tank.slot_bottom, 1e-15);
  EXPECT_GT(walls[cut.tank.walls.lid].start.y(), highest) << "the lid parked above the grains";

  // The contacts between kept grains, and with the sheet, keep their tangential forces.
  std::map<std::int64_t, bool> kept_id;
  for (std::size_t b = 0; b < kept.n_bodies(); ++b)
    kept_id[kept.body_id[b]] = true;
  const auto kept_disc = [&](std::uint32_t d) { return kept_id.count(all.body_id[all.disc_body[d]]) > 0; };
  const DemSystemState was = tank.tank.system.export_state(), now = cut.tank.system.export_state();
  double friction_was = 0.0, friction_now = 0.0, sheet_was = 0.0, sheet_now = 0.0;
  std::size_t pairs_was = 0;
  for (std::size_t k = 0; k < was.pairs.size(); ++k)
    if (kept_disc(was.pairs.disc_i[k]) && kept_disc(was.pairs.disc_j[k]))
      {
        ++pairs_was;
        friction_was += std::abs(was.pairs.state[k].tangential_force);
      }
  for (std::size_t k = 0; k < now.pairs.size(); ++k)
    friction_now += std::abs(now.pairs.state[k].tangential_force);
  for (std::size_t k = 0; k < was.sheet_contacts[0].size(); ++k)
    if (kept_disc(was.sheet_contacts[0].disc[k]))
      sheet_was += std::abs(was.sheet_contacts[0].state[k].tangential_force);
  for (std::size_t k = 0; k < now.sheet_contacts[0].size(); ++k)
    sheet_now += std::abs(now.sheet_contacts[0].state[k].tangential_force);
  EXPECT_EQ(now.pairs.size(), pairs_was);
  EXPECT_GT(friction_was, 0.0);
  EXPECT_EQ(friction_now, friction_was);
  EXPECT_GT(sheet_was, 0.0);
  EXPECT_EQ(sheet_now, sheet_was);
}

// A region that leaves the tank or misses its front wall, or one that leaves out part of the
// sheet, is refused, naming the caller's `where` (and the node).
TEST(TankCut, RegionsThatCannotBeCutAreRefused)
{
  const PullOutTankSpec spec = geohybrid::testing::small_pullout_tank();
  const PullOutTank tank = fill_pull_out_tank(spec);
  const auto message = [&](const PullOutTankSpec &region, const Vec2 &origin) {
    try
      {
        cut_pull_out_tank(tank, spec.geometry.tank_length, region, origin, "the test's region");
      }
    catch (const std::invalid_argument &e)
      {
        return std::string(e.what());
      }
    return std::string();
  };
  PullOutTankSpec short_of_the_wall = region_of(spec, 0.03, 0.02, 0.06);
  short_of_the_wall.geometry.tank_length -= 0.01;
  EXPECT_NE(message(short_of_the_wall, Vec2(0.03, 0.02)).find("the test's region: the region [0.03, 0.15]"),
            std::string::npos);
  EXPECT_NE(message(region_of(spec, 0.03, 0.02, 0.06), Vec2(0.03, -0.01)).find("must lie in the tank"),
            std::string::npos);
  // The sheet lies at 0.05 m: a region from 0.06 m up leaves it out.
  EXPECT_NE(message(region_of(spec, 0.03, 0.06, 0.04), Vec2(0.03, 0.06)).find("the test's region: the sheet's node"),
            std::string::npos);
}
