// The lift cache (dem/laboratory/lift_cache.h): a lift below the first sheet taken from the cache
// is bit for bit the lift the fill makes, so the filled tank is too; a setting the lift does not
// read (the sheet's) shares it, one it reads (the grains' friction) does not.
#include "dem/laboratory/lift_cache.h"
#include "dem/laboratory/pullout_tank.h"
#include "small_pullout_tank.h"
#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace geohybrid::dem;

namespace
{
/// The small run-out tank of test_dem_pullout.cc (small_pullout_tank.h), settled to an
/// unbalanced-force ratio of 1e-2 only: the check is bit for bit, not physics.
PullOutTankSpec small_tank(const std::filesystem::path &cache)
{
  PullOutTankSpec s = geohybrid::testing::small_pullout_tank();
  s.filling.equilibrium_unbalanced_ratio = 1e-2;
  s.filling.lift_cache_directory = cache;
  s.filling.lift_cache_version = "test";
  return s;
}

std::size_t files_in(const std::filesystem::path &directory)
{
  std::size_t n = 0;
  for ([[maybe_unused]] const auto &entry : std::filesystem::directory_iterator(directory))
    ++n;
  return n;
}

void expect_same_tank(const PullOutTank &a, const PullOutTank &b)
{
  const DemSystemState sa = a.tank.system.export_state(), sb = b.tank.system.export_state();
  const ParticleSet &p = sa.particles, &q = sb.particles;
  ASSERT_EQ(p.n_bodies(), q.n_bodies());
  EXPECT_EQ(sa.step_count, sb.step_count);
  EXPECT_EQ(sa.time_step, sb.time_step);
  for (std::size_t k = 0; k < p.n_bodies(); ++k)
    {
      ASSERT_EQ(p.x[k], q.x[k]) << "body " << k;
      ASSERT_EQ(p.y[k], q.y[k]) << "body " << k;
      ASSERT_EQ(p.rotation[k], q.rotation[k]) << "body " << k;
      ASSERT_EQ(p.vx[k], q.vx[k]) << "body " << k;
      ASSERT_EQ(p.omega[k], q.omega[k]) << "body " << k;
      ASSERT_EQ(p.fx[k], q.fx[k]) << "body " << k;
    }
  ASSERT_EQ(sa.sheets.size(), 1u);
  ASSERT_EQ(sb.sheets.size(), 1u);
  ASSERT_EQ(sa.sheets[0].n_nodes(), sb.sheets[0].n_nodes());
  for (std::size_t k = 0; k < sa.sheets[0].n_nodes(); ++k)
    {
      EXPECT_EQ(sa.sheets[0].x[k], sb.sheets[0].x[k]) << "node " << k;
      EXPECT_EQ(sa.sheets[0].y[k], sb.sheets[0].y[k]) << "node " << k;
    }
  ASSERT_EQ(a.tank.layers.size(), b.tank.layers.size());
  for (std::size_t k = 0; k < a.tank.layers.size(); ++k)
    {
      EXPECT_EQ(a.tank.layers[k].n_growth_steps, b.tank.layers[k].n_growth_steps) << "layer " << k;
      EXPECT_EQ(a.tank.layers[k].n_settling_steps, b.tank.layers[k].n_settling_steps) << "layer " << k;
      EXPECT_EQ(a.tank.layers[k].growth_friction_deg, b.tank.layers[k].growth_friction_deg) << "layer " << k;
      EXPECT_EQ(a.tank.layers[k].porosity, b.tank.layers[k].porosity) << "layer " << k;
    }
}
} // namespace

TEST(LiftCache, ATakenLiftMakesTheSameTankBitForBit)
{
  const geohybrid::testing::TemporaryDirectory cache("lift_cache");
  // With a cold cache the fill makes every lift (the keeping comes after a lift is made).
  const PullOutTank kept = fill_pull_out_tank(small_tank(cache.path));
  ASSERT_EQ(files_in(cache.path), 1u) << "one lift below the sheet";
  EXPECT_FALSE(kept.tank.layers[0].from_cache);
  const PullOutTank taken = fill_pull_out_tank(small_tank(cache.path)); // takes it
  EXPECT_TRUE(taken.tank.layers[0].from_cache);
  EXPECT_FALSE(taken.tank.layers[1].from_cache) << "the lift above the sheet is never kept";
  expect_same_tank(kept, taken);

  // The sheet's settings do not reach the lift below it: the same lift is taken.
  PullOutTankSpec stiffer_sheet = small_tank(cache.path);
  stiffer_sheet.sheet.axial_stiffness *= 2.0;
  stiffer_sheet.sheet.interface.friction_angle_deg += 5.0;
  EXPECT_TRUE(fill_pull_out_tank(stiffer_sheet).tank.layers[0].from_cache);
  EXPECT_EQ(files_in(cache.path), 1u);

  // The grains' friction does: a lift of its own.
  PullOutTankSpec rougher = small_tank(cache.path);
  rougher.filling.particle_contact.friction_angle_deg += 5.0;
  EXPECT_FALSE(fill_pull_out_tank(rougher).tank.layers[0].from_cache);
  EXPECT_EQ(files_in(cache.path), 2u);
}

TEST(LiftCache, AFileOfAnotherLiftIsRefusedNamingIt)
{
  const geohybrid::testing::TemporaryDirectory cache("lift_cache_other");
  const PullOutTankSpec spec = small_tank(cache.path);
  fill_pull_out_tank(spec);
  ASSERT_EQ(files_in(cache.path), 1u);
  const std::filesystem::path file = std::filesystem::directory_iterator(cache.path)->path();
  TankLayer layer;
  EXPECT_EQ(load_lift(cache.path / "lift_0000000000000001.h5", 1, layer), std::nullopt) << "no such file: none";
  try
    {
      load_lift(file, 1, layer); // the file under another key's name
      ADD_FAILURE() << "a lift of another key was taken";
    }
  catch (const std::runtime_error &e)
    {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
}
