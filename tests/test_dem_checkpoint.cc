// DEM checkpoints: a state written and read back is the same state, bit for bit, and a run
// continued from a checkpoint in a freshly built system is the straight run, bit for bit. A missing,
// damaged or foreign file is refused with a message naming it.
#include "dem/dem_system.h"
#include "dem/io/checkpoint.h"

#include <hdf5.h>

#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

using namespace geohybrid::dem;
namespace fs = std::filesystem;

namespace
{
struct TemporaryDirectory : geohybrid::testing::TemporaryDirectory
{
  TemporaryDirectory() : geohybrid::testing::TemporaryDirectory("test_dem_checkpoint") {}
};

constexpr double density = 2650.0, r_max = 0.005, kn = 1.0e6;
constexpr int n_x = 8, n_y = 6;
constexpr double pitch = 2.05 * r_max, width = n_x * pitch, height = n_y * pitch + 2.0 * r_max;

ContactParameters contact(double friction_deg, double strength)
{
  ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = 0.5 * kn;
  c.friction_angle_deg = friction_deg;
  c.restitution = 0.5;
  c.tensile_strength = strength;
  c.shear_strength = strength;
  c.bond_new_contacts = true; // cementing: contacts bond as they form
  return c;
}

/// 48 bodies near contact on a grid (every fifth a two-disc cluster) with random velocities, under
/// gravity, with local damping and weak bonds, in a box whose roof is servo-controlled to 2 kPa.
/// Called twice, it builds two identical systems (the construction inputs of a checkpointed run).
DemSystem deposition(int n_threads = 1)
{
  std::mt19937 generator(11);
  std::uniform_real_distribution<double> radius(0.92 * r_max, r_max), velocity(-0.1, 0.1), angle(-pi, pi);
  ParticleSet p;
  for (int j = 0, k = 0; j < n_y; ++j)
    for (int i = 0; i < n_x; ++i, ++k)
      {
        const Vec2 centre((i + 0.5) * pitch, (j + 0.5) * pitch);
        const std::size_t b =
          k % 5 == 0 ? p.add_two_disc_cluster(centre, 0.6 * r_max, 0.54 * r_max, 0.5 * r_max, angle(generator), density)
                     : p.add_disc(centre, radius(generator), density);
        p.vx[b] = velocity(generator);
        p.vy[b] = velocity(generator);
      }
  DemSettings settings;
  settings.local_damping = 0.7;
  settings.n_threads = n_threads;
  DemSystem system(std::move(p), LinearContactLaw(contact(20.0, 2.0)), settings);
  const LinearContactLaw wall_law(contact(10.0, 0.0));
  system.add_wall(Wall("floor", Vec2(0.0, 0.0), Vec2(width, 0.0), wall_law));
  system.add_wall(Wall("right", Vec2(width, 0.0), Vec2(width, height), wall_law));
  Wall roof("roof", Vec2(width, height), Vec2(0.0, height), wall_law);
  roof.control = WallControl::servo_stress;
  roof.servo.target_stress = 2.0e3;
  roof.servo.max_speed = 0.2;
  system.add_wall(roof);
  system.add_wall(Wall("left", Vec2(0.0, height), Vec2(0.0, 0.0), wall_law));
  return system;
}

void expect_same_states(const SoaVector<ContactState> &a, const SoaVector<ContactState> &b)
{
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t q = 0; q < a.size(); ++q)
    {
      EXPECT_EQ(a[q].tangential_force, b[q].tangential_force) << q;
      EXPECT_EQ(a[q].bonded, b[q].bonded) << q;
      EXPECT_EQ(a[q].touching, b[q].touching) << q;
      EXPECT_EQ(a[q].dashpot_force, b[q].dashpot_force) << q;
    }
}

void expect_same_law(const ContactParameters &a, const ContactParameters &b)
{
  EXPECT_EQ(a.normal_stiffness, b.normal_stiffness);
  EXPECT_EQ(a.shear_stiffness, b.shear_stiffness);
  EXPECT_EQ(a.friction_angle_deg, b.friction_angle_deg);
  EXPECT_EQ(a.shear_strength, b.shear_strength);
  EXPECT_EQ(a.tensile_strength, b.tensile_strength);
  EXPECT_EQ(a.restitution, b.restitution);
  EXPECT_EQ(a.bond_new_contacts, b.bond_new_contacts);
}

/// Every field of two states, compared exactly (EXPECT_EQ on doubles: bit for bit, NaN aside).
void expect_same(const DemSystemState &a, const DemSystemState &b)
{
  const ParticleSet &p = a.particles, &r = b.particles;
  EXPECT_EQ(p.body_id, r.body_id);
  EXPECT_EQ(p.x, r.x);
  EXPECT_EQ(p.y, r.y);
  EXPECT_EQ(p.rotation, r.rotation);
  EXPECT_EQ(p.vx, r.vx);
  EXPECT_EQ(p.vy, r.vy);
  EXPECT_EQ(p.omega, r.omega);
  EXPECT_EQ(p.fx, r.fx);
  EXPECT_EQ(p.fy, r.fy);
  EXPECT_EQ(p.torque, r.torque);
  EXPECT_EQ(p.mass, r.mass);
  EXPECT_EQ(p.inertia, r.inertia);
  EXPECT_EQ(p.inverse_mass, r.inverse_mass);
  EXPECT_EQ(p.inverse_inertia, r.inverse_inertia);
  EXPECT_EQ(p.first_disc, r.first_disc);
  EXPECT_EQ(p.n_discs, r.n_discs);
  EXPECT_EQ(p.disc_body, r.disc_body);
  EXPECT_EQ(p.disc_radius, r.disc_radius);
  EXPECT_EQ(p.disc_offset_x, r.disc_offset_x);
  EXPECT_EQ(p.disc_offset_y, r.disc_offset_y);
  EXPECT_EQ(p.disc_x, r.disc_x);
  EXPECT_EQ(p.disc_y, r.disc_y);

  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t w = 0; w < a.walls.size(); ++w)
    {
      const Wall &u = a.walls[w], &v = b.walls[w];
      EXPECT_EQ(u.name, v.name);
      EXPECT_EQ(u.start, v.start);
      EXPECT_EQ(u.end, v.end);
      expect_same_law(u.law.parameters(), v.law.parameters());
      EXPECT_EQ(u.control, v.control);
      EXPECT_EQ(u.velocity, v.velocity);
      EXPECT_EQ(u.servo.target_stress, v.servo.target_stress);
      EXPECT_EQ(u.servo.relaxation, v.servo.relaxation);
      EXPECT_EQ(u.servo.max_speed, v.servo.max_speed);
      EXPECT_EQ(u.force_from_particles, v.force_from_particles);
      EXPECT_EQ(u.n_contacts, v.n_contacts);
    }

  EXPECT_EQ(a.pairs.disc_i, b.pairs.disc_i);
  EXPECT_EQ(a.pairs.disc_j, b.pairs.disc_j);
  expect_same_states(a.pairs.state, b.pairs.state);
  EXPECT_EQ(a.pairs.force_x, b.pairs.force_x);
  EXPECT_EQ(a.pairs.force_y, b.pairs.force_y);
  EXPECT_EQ(a.pairs.torque_i, b.pairs.torque_i);
  EXPECT_EQ(a.pairs.torque_j, b.pairs.torque_j);
  EXPECT_EQ(a.pairs.elastic_normal_force, b.pairs.elastic_normal_force);
  EXPECT_EQ(a.pairs.friction_work, b.pairs.friction_work);
  EXPECT_EQ(a.pairs.viscous_work, b.pairs.viscous_work);

  ASSERT_EQ(a.wall_contacts.size(), b.wall_contacts.size());
  for (std::size_t w = 0; w < a.wall_contacts.size(); ++w)
    {
      const WallContacts &u = a.wall_contacts[w], &v = b.wall_contacts[w];
      EXPECT_EQ(u.disc, v.disc);
      expect_same_states(u.state, v.state);
      EXPECT_EQ(u.force_x, v.force_x);
      EXPECT_EQ(u.force_y, v.force_y);
      EXPECT_EQ(u.elastic_normal_force, v.elastic_normal_force);
      EXPECT_EQ(u.friction_work, v.friction_work);
      EXPECT_EQ(u.viscous_work, v.viscous_work);
    }

  EXPECT_EQ(a.wall_force_previous, b.wall_force_previous);
  EXPECT_EQ(a.disc_x_at_rebuild, b.disc_x_at_rebuild);
  EXPECT_EQ(a.disc_y_at_rebuild, b.disc_y_at_rebuild);
  EXPECT_EQ(a.wall_start_at_rebuild, b.wall_start_at_rebuild);
  EXPECT_EQ(a.damping_fx, b.damping_fx);
  EXPECT_EQ(a.damping_fy, b.damping_fy);
  EXPECT_EQ(a.damping_torque, b.damping_torque);

  const EnergyBudget &e = a.accumulated, &f = b.accumulated;
  EXPECT_EQ(e.kinetic, f.kinetic);
  EXPECT_EQ(e.gravitational, f.gravitational);
  EXPECT_EQ(e.elastic, f.elastic);
  EXPECT_EQ(e.friction_dissipated, f.friction_dissipated);
  EXPECT_EQ(e.viscous_dissipated, f.viscous_dissipated);
  EXPECT_EQ(e.local_damping_dissipated, f.local_damping_dissipated);
  EXPECT_EQ(e.boundary_work, f.boundary_work);

  EXPECT_EQ(a.time_step, b.time_step);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.skin, b.skin);
  EXPECT_EQ(a.step_count, b.step_count);
  EXPECT_EQ(a.n_rebuilds, b.n_rebuilds);
  EXPECT_EQ(a.n_broken_bonds, b.n_broken_bonds);
  EXPECT_EQ(a.rebuild_needed, b.rebuild_needed);
}

void expect_same_energy(const EnergyBudget &e, const EnergyBudget &f)
{
  EXPECT_EQ(e.kinetic, f.kinetic);
  EXPECT_EQ(e.gravitational, f.gravitational);
  EXPECT_EQ(e.elastic, f.elastic);
  EXPECT_EQ(e.friction_dissipated, f.friction_dissipated);
  EXPECT_EQ(e.viscous_dissipated, f.viscous_dissipated);
  EXPECT_EQ(e.local_damping_dissipated, f.local_damping_dissipated);
  EXPECT_EQ(e.boundary_work, f.boundary_work);
}

/// Runs `f` and returns the message of the std::runtime_error it throws ("" if none).
template <typename F>
std::string runtime_error_of(F &&f)
{
  try
    {
      f();
    }
  catch (const std::runtime_error &e)
    {
      return e.what();
    }
  return "";
}

constexpr int n_half = 1200; // the roof reaches the packing before that (checked below)
} // namespace

// 2N steps straight == N steps, checkpoint, a fresh system built from the same inputs, restore,
// N steps: every position, velocity, force, contact state and energy term is the same bit for bit.
TEST(Checkpoint, ContinuedRunIsBitForBitTheStraightRun)
{
  TemporaryDirectory directory;
  const fs::path file = directory.path / "checkpoint.h5";

  DemSystem straight = deposition();
  straight.run_steps(2 * n_half);

  {
    DemSystem first_half = deposition();
    first_half.run_steps(n_half);
    // The checkpoint catches the features the test claims: bonds, a cluster, a servo in contact.
    const DemSystemState saved = first_half.export_state();
    std::size_t bonded = 0;
    for (const ContactState &s : saved.pairs.state)
      bonded += s.bonded && s.touching;
    EXPECT_GT(bonded, 10u);
    EXPECT_GT(saved.n_broken_bonds, 0u);
    EXPECT_EQ(saved.particles.n_discs[0], 2u);
    EXPECT_GT(saved.walls[2].n_contacts, 0u);
    EXPECT_NE(saved.walls[2].velocity, Vec2::Zero());
    write_checkpoint(saved, file);
    EXPECT_FALSE(fs::exists(directory.path / "checkpoint.h5.tmp"));
  }

  DemSystem resumed = deposition();
  resumed.restore_state(read_checkpoint(file));
  EXPECT_EQ(resumed.step_count(), static_cast<std::uint64_t>(n_half));
  resumed.run_steps(n_half);

  expect_same(straight.export_state(), resumed.export_state());
  expect_same_energy(straight.energy(), resumed.energy());
  EXPECT_EQ(straight.time(), resumed.time());
  EXPECT_GT(straight.n_broken_bonds(), 0u);
  EXPECT_GT(straight.walls()[2].n_contacts, 0u);
}

// A run saved on one thread and resumed on two is the straight two-thread run, bit for bit: the
// state carries nothing that depends on the thread count. (One thread keeps no per-pair moments,
// their arrays stay at the zeros of the last rebuild; two threads store them and read them back
// for the bodies shared between their chunks, a pair that stays apart holding a zero.)
TEST(Checkpoint, ResumedOnAnotherThreadCountIsBitForBitTheStraightRun)
{
  DemSystem straight = deposition(2);
  straight.run_steps(2 * n_half);

  DemSystem first_half = deposition(1);
  first_half.run_steps(n_half);
  DemSystem resumed = deposition(2);
  resumed.restore_state(first_half.export_state());
  resumed.run_steps(n_half);

  expect_same(straight.export_state(), resumed.export_state());
  expect_same_energy(straight.energy(), resumed.energy());
  EXPECT_GT(straight.n_broken_bonds(), 0u);
}

// What is written is what is read, field by field and exactly, including a wall with an unusual
// name and law, a state before the first step (empty contact lists) and special doubles.
TEST(Checkpoint, RoundTripIsExact)
{
  TemporaryDirectory directory;
  const fs::path file = directory.path / "state.h5";
  {
    DemSystem fresh = deposition();
    const DemSystemState before = fresh.export_state();
    write_checkpoint(before, file);
    expect_same(before, read_checkpoint(file));
  }
  DemSystem system = deposition();
  system.run_steps(50);
  DemSystemState state = system.export_state();
  state.walls[1].name = "a \"quoted\" wall; with ümlaut";
  state.walls[1].velocity = Vec2(-1e-300, 0.1 + 0.2);
  state.particles.vx[3] = -0.0;
  state.particles.omega[4] = std::numeric_limits<double>::denorm_min();
  write_checkpoint(state, file);
  const DemSystemState back = read_checkpoint(file);
  expect_same(state, back);
  EXPECT_TRUE(std::signbit(back.particles.vx[3]));
  // Writing again replaces the file.
  state.time = 42.0;
  write_checkpoint(state, file);
  EXPECT_EQ(read_checkpoint(file).time, 42.0);
}

// A command's texts (the input of its run) round-trip exactly and are read without the DEM state;
// a file written without texts (as before they existed) reads with none.
TEST(Checkpoint, CommandTextsRoundTripAndOlderFilesHaveNone)
{
  TemporaryDirectory directory;
  const fs::path file = directory.path / "state.h5";
  DemSystem system = deposition();
  CommandState command;
  command.name = "pullout";
  command.reals["pull"] = {1.0, 2.0};
  command.texts["input"] = "geohybrid numbers 1\nSoil/Particle contact/normal stiffness = 1e7\nTank/length = 0.16\n";
  write_checkpoint(system.export_state(), command, file);
  const CommandState back = read_checkpoint_command(file);
  EXPECT_EQ(back.name, "pullout");
  EXPECT_EQ(back.reals.at("pull"), command.reals.at("pull"));
  ASSERT_EQ(back.texts.size(), 1u);
  EXPECT_EQ(back.texts.at("input"), command.texts.at("input"));
  command.texts.clear();
  write_checkpoint(system.export_state(), command, file);
  EXPECT_TRUE(read_checkpoint_command(file).texts.empty());
  EXPECT_EQ(read_checkpoint_command(file).reals.at("pull"), command.reals.at("pull"));
}

TEST(Checkpoint, MissingFileNamed)
{
  TemporaryDirectory directory;
  const std::string message = runtime_error_of([&] { read_checkpoint(directory.path / "absent.h5"); });
  EXPECT_NE(message.find("absent.h5"), std::string::npos) << message;
}

TEST(Checkpoint, DamagedFileNamed)
{
  TemporaryDirectory directory;
  // Not HDF5 at all.
  const fs::path garbage = directory.path / "garbage.h5";
  std::ofstream(garbage) << "this is not a checkpoint\n";
  std::string message = runtime_error_of([&] { read_checkpoint(garbage); });
  EXPECT_NE(message.find("garbage.h5"), std::string::npos) << message;

  // A real checkpoint cut in half, as a crash in the middle of a copy would leave it.
  DemSystem system = deposition();
  system.run_steps(20);
  const fs::path cut = directory.path / "cut.h5";
  write_checkpoint(system.export_state(), cut);
  fs::resize_file(cut, fs::file_size(cut) / 2);
  message = runtime_error_of([&] { read_checkpoint(cut); });
  EXPECT_NE(message.find("cut.h5"), std::string::npos) << message;

  // An HDF5 file that is not a checkpoint.
  const fs::path other = directory.path / "other.h5";
  H5Fclose(H5Fcreate(other.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  message = runtime_error_of([&] { read_checkpoint(other); });
  EXPECT_NE(message.find("other.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("not a geohybrid DEM checkpoint"), std::string::npos) << message;
}

TEST(Checkpoint, OtherFormatVersionRefused)
{
  TemporaryDirectory directory;
  const fs::path file = directory.path / "future.h5";
  DemSystem system = deposition();
  write_checkpoint(system.export_state(), file);
  {
    const hid_t h5 = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(h5, 0);
    const hid_t attribute = H5Aopen(h5, "format_version", H5P_DEFAULT);
    const std::uint32_t future = checkpoint_format_version + 1;
    H5Awrite(attribute, H5T_NATIVE_UINT32, &future);
    H5Aclose(attribute);
    H5Fclose(h5);
  }
  const std::string message = runtime_error_of([&] { read_checkpoint(file); });
  EXPECT_NE(message.find("future.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("version " + std::to_string(checkpoint_format_version + 1)), std::string::npos)
    << message;
}

// A checkpoint that cannot be written is reported, and the previous one is left as it was.
TEST(Checkpoint, FailedWriteKeepsPreviousCheckpoint)
{
  TemporaryDirectory directory;
  DemSystem system = deposition();
  const std::string message =
    runtime_error_of([&] { write_checkpoint(system.export_state(), directory.path / "no_such_dir" / "c.h5"); });
  EXPECT_NE(message.find("c.h5"), std::string::npos) << message;

  const fs::path file = directory.path / "checkpoint.h5";
  write_checkpoint(system.export_state(), file);
  // A directory squatting on the temporary name makes the next write fail.
  fs::create_directories(directory.path / "checkpoint.h5.tmp" / "x");
  system.run_steps(5);
  EXPECT_NE(runtime_error_of([&] { write_checkpoint(system.export_state(), file); }), "");
  EXPECT_EQ(read_checkpoint(file).step_count, 0u);
}
