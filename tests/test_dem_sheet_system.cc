// The spar sheet in a system of grains: the energy balance (conserved, closed with interface
// friction and the clamp's work, a sheet laid during the run), 1 vs 2 threads, checkpoint resume
// and snapshots.
#include "dem/dem_system.h"
#include "dem/io/checkpoint.h"
#include "dem/io/snapshot_writer.h"

#include <hdf5.h>

#include "dem_sheet_scenes.h"
#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace geohybrid::dem;
using namespace geohybrid::testing::dem_sheet_scenes;
namespace fs = std::filesystem;

namespace
{
struct TemporaryDirectory : geohybrid::testing::TemporaryDirectory
{
  TemporaryDirectory() : geohybrid::testing::TemporaryDirectory("test_dem_sheet_system") {}
};

constexpr double scene_width = 0.2, scene_r_max = 5.0e-3;

struct SceneOptions
{
  double friction_deg = 20.0, restitution = 0.5, local_damping = 0.7, safety = 0.5, clamp_speed = 0.05;
  int n_threads = 1;
  bool lay_sheet = true; ///< false: the caller lays it later (lay_scene_sheet)
};

void lay_scene_sheet(DemSystem &system, const SceneOptions &o);

/// Four rows of discs and clusters (60 bodies, radii 3.5 to 5 mm, moving at up to 5 cm/s) resting
/// on a sheet that lies on the floor of a box (floor, left and right walls), the sheet's right end
/// clamped and pulled along the floor at `clamp_speed`. Contacts stiff enough (1e7 N/m/m) that
/// overlaps stay below 1 % of a radius, as in quasi-static runs. Deterministic: the same options
/// build the same system.
DemSystem sheet_scene(const SceneOptions &o)
{
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> radius(0.7 * scene_r_max, scene_r_max), velocity(-0.05, 0.05),
    angle(-pi, pi);
  const double pitch = 2.5 * scene_r_max, t = 1.0e-3;
  ParticleSet p;
  int k = 0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 15; ++i, ++k)
      {
        const Vec2 centre(0.01 + (i + 0.5) * pitch, t + scene_r_max + j * pitch);
        const std::size_t b =
          k % 7 == 0 ? p.add_two_disc_cluster(centre, 0.6 * scene_r_max, 0.54 * scene_r_max, 0.5 * scene_r_max,
                                              angle(generator), 2650.0)
                     : p.add_disc(centre, radius(generator), 2650.0);
        p.vx[b] = velocity(generator);
        p.vy[b] = velocity(generator);
      }
  DemSettings settings;
  settings.local_damping = o.local_damping;
  settings.time_step_safety = o.safety;
  settings.n_threads = o.n_threads;
  const LinearContactLaw law(contact_law(1.0e7, o.friction_deg, o.restitution));
  DemSystem system(std::move(p), law, settings);
  system.add_wall(Wall("floor", Vec2(0.0, 0.0), Vec2(scene_width, 0.0), law));
  system.add_wall(Wall("right", Vec2(scene_width, 0.0), Vec2(scene_width, 0.3), law));
  system.add_wall(Wall("left", Vec2(0.0, 0.3), Vec2(0.0, 0.0), law));
  if (o.lay_sheet)
    lay_scene_sheet(system, o);
  return system;
}

/// The scene's sheet, on the floor, its right end clamped.
void lay_scene_sheet(DemSystem &system, const SceneOptions &o)
{
  const double t = 1.0e-3;
  const double interface_friction = o.friction_deg > 0.0 ? 25.6 : 0.0;
  SheetParameters parameters = sheet_parameters(1.0e4, 0.62, contact_law(1.0e7, interface_friction, o.restitution));
  parameters.thickness = t;
  SparSheet sheet("sheet", straight_nodes(Vec2(0.02, 0.5 * t), Vec2(0.18, 0.5 * t), 32), parameters); // on the floor
  sheet.set_mass_scaling(system.required_sheet_mass_scaling(sheet));
  sheet.prescribe_velocity(32, Vec2(o.clamp_speed, 0.0));
  system.add_sheet(sheet);
}

double stored(const EnergyBudget &e) { return e.kinetic + e.gravitational + e.elastic + e.sheet_kinetic + e.sheet_elastic; }

struct BalanceRun
{
  double max_error = 0.0, scale = 0.0;
  EnergyBudget start, end;
};

BalanceRun run_balance(const SceneOptions &o, int n_steps)
{
  DemSystem system = sheet_scene(o);
  system.step();
  BalanceRun r;
  r.start = system.energy();
  r.scale = stored(r.start);
  for (int k = 0; k < n_steps; ++k)
    {
      system.step();
      r.max_error = std::max(r.max_error, std::abs(system.energy().total() - r.start.total()));
    }
  r.end = system.energy();
  return r;
}
} // namespace

// Without dissipation (no friction, no dashpot, no damping, the clamp at rest), kinetic +
// gravitational + elastic energy of discs and sheet is conserved up to the integrator's error:
// measured 4.7e-5, 1.7e-5, 3.6e-6 of the stored energy at dt = 2e-5, 1e-5, 5e-6 s.
// 2e-4 at 1e-5 s leaves a factor 10.
TEST(SheetEnergy, ConservedWithoutDissipation)
{
  SceneOptions o;
  o.friction_deg = 0.0;
  o.restitution = 1.0;
  o.local_damping = 0.0;
  o.clamp_speed = 0.0;
  o.safety = 0.2; // dt = 9.4e-6 s (the critical step, 4.7e-5 s, is set by the clusters)
  const BalanceRun r = run_balance(o, 4000);
  EXPECT_EQ(r.end.interface_friction_dissipated, 0.0);
  EXPECT_EQ(r.end.friction_dissipated, 0.0);
  EXPECT_EQ(r.end.local_damping_dissipated, 0.0);
  EXPECT_GT(r.end.sheet_elastic + r.end.sheet_kinetic, 0.0);
  EXPECT_LT(r.max_error, 2e-4 * r.scale);
}

// With interface and wall friction, dashpots, local damping on discs and nodes and the clamp pulling
// the sheet out from under the discs: what the stored energy loses plus the clamp's work is booked
// in the dissipation terms, so total() stays constant: measured 2.4e-5, 9.6e-6, 3.1e-6 of the
// stored energy at dt = 2e-5, 1e-5, 5e-6 s. The clamp supplies 17 % of the stored energy
// and the interface friction dissipates 0.17 %: leaving either out of the books breaks the 2e-4
// tolerance several times over.
TEST(SheetEnergy, ClosesWithInterfaceFrictionAndClampWork)
{
  SceneOptions o;
  o.safety = 0.2; // dt = 9.4e-6 s
  const BalanceRun r = run_balance(o, 6000);
  EXPECT_GT(r.end.interface_friction_dissipated, 1e-3 * r.scale);
  EXPECT_GT(r.end.boundary_work, 0.1 * r.scale);
  EXPECT_GT(r.end.sheet_elastic, 0.0);
  EXPECT_GT(r.end.viscous_dissipated, 0.0);
  EXPECT_LT(r.max_error, 2e-4 * r.scale);
}

// A sheet laid during a run (as while a tank is filled) brings its energy with it, booked as boundary
// work: total() does not jump, and the balance closes afterwards as for a sheet laid at the start.
TEST(SheetEnergy, SheetLaidDuringTheRun)
{
  SceneOptions o;
  o.safety = 0.2;
  o.lay_sheet = false;
  DemSystem system = sheet_scene(o);
  system.step();
  system.step();
  const EnergyBudget before = system.energy();
  lay_scene_sheet(system, o);
  const EnergyBudget after = system.energy();
  EXPECT_NE(after.gravitational, before.gravitational);
  EXPECT_NEAR(after.total(), before.total(), 1e-12 * stored(before));
  double max_error = 0.0;
  for (int k = 0; k < 3000; ++k)
    {
      system.step();
      max_error = std::max(max_error, std::abs(system.energy().total() - before.total()));
    }
  EXPECT_GT(system.n_touching_sheet_contacts(), 5u);
  EXPECT_LT(max_error, 2e-4 * stored(before));
}

// Same input, 1 and 2 threads: every position, velocity, sheet node and tension bit for bit.
TEST(SheetThreads, OneAndTwoThreadsBitForBit)
{
  SceneOptions o;
  DemSystem one = sheet_scene(o);
  o.n_threads = 2;
  DemSystem two = sheet_scene(o);
  one.run_steps(3000);
  two.run_steps(3000);
  EXPECT_GT(one.n_touching_sheet_contacts(), 10u);
  EXPECT_EQ(one.particles().x, two.particles().x);
  EXPECT_EQ(one.particles().vy, two.particles().vy);
  EXPECT_EQ(one.particles().omega, two.particles().omega);
  const SparSheet &a = one.sheets()[0], &b = two.sheets()[0];
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.tension, b.tension);
  EXPECT_EQ(a.reaction_x, b.reaction_x);
  EXPECT_EQ(one.energy().total(), two.energy().total());
  EXPECT_EQ(one.energy().interface_friction_dissipated, two.energy().interface_friction_dissipated);
}

namespace
{
void expect_same_sheets(const DemSystemState &a, const DemSystemState &b)
{
  ASSERT_EQ(a.sheets.size(), b.sheets.size());
  for (std::size_t k = 0; k < a.sheets.size(); ++k)
    {
      const SparSheet &u = a.sheets[k], &v = b.sheets[k];
      EXPECT_EQ(u.name(), v.name());
      EXPECT_EQ(u.axial_stiffness(), v.axial_stiffness());
      EXPECT_EQ(u.thickness(), v.thickness());
      EXPECT_EQ(u.parameters().areal_mass, v.parameters().areal_mass);
      EXPECT_EQ(u.parameters().mass_scaling, v.parameters().mass_scaling);
      EXPECT_EQ(u.interface_law().friction_coefficient(), v.interface_law().friction_coefficient());
      EXPECT_EQ(u.interface_law().damping_ratio(), v.interface_law().damping_ratio());
      for (auto member : {&SparSheet::x, &SparSheet::y, &SparSheet::vx, &SparSheet::vy, &SparSheet::fx, &SparSheet::fy,
                          &SparSheet::mass, &SparSheet::inverse_mass, &SparSheet::gravitational_mass,
                          &SparSheet::damping_fx, &SparSheet::damping_fy, &SparSheet::reaction_x,
                          &SparSheet::reaction_y, &SparSheet::load_x, &SparSheet::load_y, &SparSheet::rest_length,
                          &SparSheet::tension})
        EXPECT_EQ(u.*member, v.*member);
      const SheetContacts &c = a.sheet_contacts[k], &d = b.sheet_contacts[k];
      EXPECT_EQ(c.disc, d.disc);
      EXPECT_EQ(c.segment, d.segment);
      ASSERT_EQ(c.state.size(), d.state.size());
      for (std::size_t q = 0; q < c.state.size(); ++q)
        {
          EXPECT_EQ(c.state[q].tangential_force, d.state[q].tangential_force);
          EXPECT_EQ(c.state[q].touching, d.state[q].touching);
          EXPECT_EQ(c.state[q].bonded, d.state[q].bonded);
          EXPECT_EQ(c.state[q].dashpot_force, d.state[q].dashpot_force);
        }
      EXPECT_EQ(c.position, d.position);
      EXPECT_EQ(c.overlap, d.overlap);
      EXPECT_EQ(c.counted, d.counted);
      EXPECT_EQ(c.force_x, d.force_x);
      EXPECT_EQ(c.force_y, d.force_y);
      EXPECT_EQ(c.elastic_normal_force, d.elastic_normal_force);
      EXPECT_EQ(c.friction_work, d.friction_work);
      EXPECT_EQ(c.viscous_work, d.viscous_work);
      EXPECT_EQ(c.node_x_at_rebuild, d.node_x_at_rebuild);
      EXPECT_EQ(c.node_y_at_rebuild, d.node_y_at_rebuild);
      ASSERT_EQ(c.walls.size(), d.walls.size());
      for (std::size_t w = 0; w < c.walls.size(); ++w)
        {
          EXPECT_EQ(c.walls[w].node, d.walls[w].node);
          EXPECT_EQ(c.walls[w].force_x, d.walls[w].force_x);
          EXPECT_EQ(c.walls[w].force_y, d.walls[w].force_y);
          EXPECT_EQ(c.walls[w].elastic_normal_force, d.walls[w].elastic_normal_force);
          for (std::size_t q = 0; q < c.walls[w].state.size(); ++q)
            EXPECT_EQ(c.walls[w].state[q].tangential_force, d.walls[w].state[q].tangential_force);
        }
    }
}
} // namespace

// A run continued from a checkpoint in a freshly built system is the straight run, bit for bit,
// sheets included; and a state written and read back is the same state.
TEST(SheetCheckpoint, ResumedRunIsBitForBitTheStraightRun)
{
  TemporaryDirectory directory;
  const fs::path file = directory.path / "checkpoint.h5";
  const SceneOptions o;
  DemSystem straight = sheet_scene(o);
  straight.run_steps(3200);
  {
    DemSystem first = sheet_scene(o);
    first.run_steps(1600);
    const DemSystemState saved = first.export_state();
    EXPECT_GT(first.n_touching_sheet_contacts(), 5u);
    std::size_t node_wall = 0;
    for (const SheetWallContacts &w : saved.sheet_contacts[0].walls)
      for (const ContactState &s : w.state)
        node_wall += s.touching;
    EXPECT_GT(node_wall, 5u); // the sheet lies on the floor
    write_checkpoint(saved, file);
    expect_same_sheets(saved, read_checkpoint(file));
  }
  DemSystem resumed = sheet_scene(o);
  resumed.restore_state(read_checkpoint(file));
  resumed.run_steps(1600);
  const DemSystemState a = straight.export_state(), b = resumed.export_state();
  expect_same_sheets(a, b);
  EXPECT_EQ(a.particles.x, b.particles.x);
  EXPECT_EQ(a.particles.vx, b.particles.vx);
  EXPECT_EQ(a.pairs.disc_j, b.pairs.disc_j);
  const EnergyBudget e = straight.energy(), f = resumed.energy();
  EXPECT_EQ(e.total(), f.total());
  EXPECT_EQ(e.sheet_kinetic, f.sheet_kinetic);
  EXPECT_EQ(e.sheet_elastic, f.sheet_elastic);
  EXPECT_EQ(e.interface_friction_dissipated, f.interface_friction_dissipated);
  EXPECT_EQ(e.boundary_work, f.boundary_work);
}

namespace
{
template <typename T>
std::vector<T> read_dataset(hid_t file, const std::string &name, hid_t memory_type)
{
  const hid_t set = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(set, 0) << name;
  if (set < 0)
    return {};
  const hid_t space = H5Dget_space(set);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<T> values(static_cast<std::size_t>(n));
  if (n > 0)
    H5Dread(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(set);
  return values;
}
} // namespace

// A snapshot holds the sheet's nodes, segments, tension and its contacts as the system had them,
// and the .xdmf lists the sheet grid for ParaView.
TEST(SheetOutput, SnapshotHoldsNodesTensionAndContacts)
{
  TemporaryDirectory directory;
  DemSystem system = sheet_scene(SceneOptions{});
  system.run_steps(1200);
  SnapshotWriter writer(directory.path, "particles");
  writer.write(system);
  const SparSheet &sheet = system.sheets()[0];
  const hid_t file = H5Fopen((directory.path / "particles.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const auto position = read_dataset<double>(file, "snapshot_000000/sheets/position", H5T_NATIVE_DOUBLE);
  const auto tension = read_dataset<double>(file, "snapshot_000000/sheets/tension", H5T_NATIVE_DOUBLE);
  const auto connectivity = read_dataset<std::int64_t>(file, "snapshot_000000/sheets/connectivity", H5T_NATIVE_INT64);
  const auto contact_force = read_dataset<double>(file, "snapshot_000000/sheet_contacts/normal_force", H5T_NATIVE_DOUBLE);
  H5Fclose(file);
  ASSERT_EQ(position.size(), 3 * sheet.n_nodes());
  ASSERT_EQ(tension.size(), sheet.n_segments());
  for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
    {
      EXPECT_EQ(position[3 * k], sheet.x[k]);
      EXPECT_EQ(position[3 * k + 1], sheet.y[k]);
    }
  for (std::size_t k = 0; k < sheet.n_segments(); ++k)
    {
      EXPECT_EQ(tension[k], sheet.tension[k]);
      EXPECT_EQ(connectivity[2 * k], static_cast<std::int64_t>(k));
      EXPECT_EQ(connectivity[2 * k + 1], static_cast<std::int64_t>(k + 1));
    }
  EXPECT_GT(*std::max_element(tension.begin(), tension.end()), 0.0);
  EXPECT_EQ(contact_force.size(), system.n_touching_sheet_contacts());
  std::ifstream xdmf(directory.path / "particles.xdmf");
  std::stringstream text;
  text << xdmf.rdbuf();
  EXPECT_NE(text.str().find("Grid Name=\"sheets\""), std::string::npos);
  EXPECT_NE(text.str().find("sheets/tension"), std::string::npos);
  EXPECT_NE(text.str().find("Grid Name=\"sheet_contacts\""), std::string::npos);
}

