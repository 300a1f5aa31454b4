// REDF sample files: a sample written and read back is the same sample, bit for bit, and shears
// exactly as the one in memory does; a missing, foreign or damaged file is refused with a message
// naming it; two specs are compared on what makes the sample, not on the thread count.
#include "dem/io/checkpoint.h"
#include "dem/laboratory/biaxial_test.h"
#include "dem/laboratory/sample_file.h"

#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <string>

using namespace geohybrid::dem;
namespace fs = std::filesystem;

namespace
{
struct TemporaryDirectory : geohybrid::testing::TemporaryDirectory
{
  TemporaryDirectory() : geohybrid::testing::TemporaryDirectory("test_dem_sample_file") {}
};

/// 150 clusters at porosity 0.22 and 20 kPa: a few seconds.
RedfSpec small_sample()
{
  RedfSpec s;
  s.n_particles = 150;
  s.width = 0.04;
  s.height = 0.06;
  s.target_porosity = 0.22;
  s.porosity_tolerance = 0.01;
  s.target_stress = 20e3;
  s.particle_contact.friction_angle_deg = 20.0;
  s.wall_contact.friction_angle_deg = 0.0;
  s.initial_growth_friction_deg = 10.0;
  s.seed = 7;
  return s;
}

BiaxialCurve shear(RedfSample &sample, const RedfSpec &spec)
{
  BiaxialSpec test;
  test.confining_stress = spec.target_stress;
  test.final_axial_strain = 0.01;
  test.record_interval = 5e-4;
  test.target_inertial_number = 1e-3;
  return run_biaxial_test(sample.system, sample.box, test, 3e-3, spec.density);
}

std::string error_of(const fs::path &file)
{
  try
    {
      read_sample_file(file);
    }
  catch (const std::runtime_error &e)
    {
      return e.what();
    }
  return "";
}
} // namespace

// Written, read back and rebuilt on another number of threads, the sample has the same particles,
// walls and history, and its biaxial curve is the in-memory sample's, bit for bit.
TEST(SampleFile, ReloadedSampleShearsExactlyAsTheOneInMemory)
{
  TemporaryDirectory directory;
  const fs::path file = directory.path / "samples" / "small.h5"; // the directory is created
  const RedfSpec spec = small_sample();
  RedfSample made = make_redf_sample(spec);
  write_sample_file(store_sample(made, spec), file);
  EXPECT_FALSE(fs::exists(file.string() + ".partial"));

  const StoredSample read = read_sample_file(file);
  EXPECT_TRUE(sample_spec_differences(read.spec, spec).empty());
  EXPECT_EQ(read.spec.max_steps, spec.max_steps);
  EXPECT_EQ(read.result.porosity, made.result.porosity);
  EXPECT_EQ(read.result.mean_stress, made.result.mean_stress);
  EXPECT_EQ(read.result.growth_friction_deg, made.result.growth_friction_deg);
  EXPECT_EQ(read.result.size_scale, made.result.size_scale);
  EXPECT_EQ(read.result.n_steps, made.result.n_steps);
  EXPECT_EQ(read.settings.local_damping, made.system.settings().local_damping);
  EXPECT_EQ(read.settings.gravity, made.system.settings().gravity);
  EXPECT_EQ(read.settings.track_energy, made.system.settings().track_energy);
  EXPECT_EQ(read.box.left, made.box.left);
  EXPECT_EQ(read.box.top, made.box.top);

  RedfSample reloaded = restore_sample(read, 2);
  const ParticleSet &a = made.system.particles(), &b = reloaded.system.particles();
  ASSERT_EQ(b.n_bodies(), spec.n_particles);
  ASSERT_EQ(b.n_discs_total(), a.n_discs_total());
  EXPECT_EQ(b.x, a.x);
  EXPECT_EQ(b.y, a.y);
  EXPECT_EQ(b.rotation, a.rotation);
  EXPECT_EQ(b.vx, a.vx);
  EXPECT_EQ(b.omega, a.omega);
  EXPECT_EQ(b.mass, a.mass);
  EXPECT_EQ(b.inertia, a.inertia);
  EXPECT_EQ(b.disc_body, a.disc_body); // the cluster structure
  EXPECT_EQ(b.disc_radius, a.disc_radius);
  EXPECT_EQ(b.disc_offset_x, a.disc_offset_x);
  EXPECT_EQ(b.disc_offset_y, a.disc_offset_y);
  EXPECT_EQ(reloaded.system.time_step(), made.system.time_step());
  EXPECT_EQ(reloaded.system.particle_law().parameters().friction_angle_deg, spec.particle_contact.friction_angle_deg);
  for (std::size_t w = 0; w < 4; ++w)
    {
      EXPECT_EQ(reloaded.system.walls()[w].start, made.system.walls()[w].start);
      EXPECT_EQ(reloaded.system.walls()[w].law.parameters().friction_angle_deg, 0.0);
    }

  const BiaxialCurve expected = shear(made, spec), got = shear(reloaded, spec);
  ASSERT_GE(expected.points.size(), 20u);
  ASSERT_EQ(got.points.size(), expected.points.size());
  for (std::size_t k = 0; k < expected.points.size(); ++k)
    {
      EXPECT_EQ(got.points[k].axial_strain, expected.points[k].axial_strain) << "point " << k;
      EXPECT_EQ(got.points[k].volumetric_strain, expected.points[k].volumetric_strain) << "point " << k;
      EXPECT_EQ(got.points[k].deviatoric_stress, expected.points[k].deviatoric_stress) << "point " << k;
    }
  // A real test, not an empty one: the deviator has grown to several kPa.
  EXPECT_GT(expected.points.back().deviatoric_stress, 0.1 * spec.target_stress);
}

TEST(SampleFile, MissingForeignOrDamagedFileIsNamed)
{
  TemporaryDirectory directory;
  const fs::path missing = directory.path / "none.h5";
  std::string message = error_of(missing);
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;

  // A DEM checkpoint is HDF5 and holds a state, but not a sample's description.
  ParticleSet p;
  p.add_disc(Vec2(0.0, 0.0), 1e-3, 2650.0);
  DemSettings settings;
  const DemSystem system(p, LinearContactLaw{}, settings);
  const fs::path checkpoint = directory.path / "checkpoint.h5";
  write_checkpoint(system.export_state(), checkpoint);
  message = error_of(checkpoint);
  EXPECT_NE(message.find(checkpoint.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not a REDF sample file"), std::string::npos) << message;

  const fs::path text = directory.path / "text.h5";
  std::ofstream(text) << "not HDF5\n";
  message = error_of(text);
  EXPECT_NE(message.find(text.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not a readable HDF5 file"), std::string::npos) << message;
}

TEST(SampleFile, SpecDifferencesNameWhatMakesAnotherSample)
{
  const RedfSpec stored = small_sample();
  RedfSpec wanted = stored;
  wanted.n_threads = 2;       // the same sample on more threads
  wanted.max_steps = 100;     // a limit, not a setting of the sample
  EXPECT_TRUE(sample_spec_differences(stored, wanted).empty());
  wanted.seed = 8;
  wanted.particle_contact.friction_angle_deg = 25.0;
  wanted.shape = ParticleShape::disc;
  const std::vector<std::string> differences = sample_spec_differences(stored, wanted);
  ASSERT_EQ(differences.size(), 3u);
  EXPECT_EQ(differences[0], "seed: 7 stored, 8 wanted");
  EXPECT_EQ(differences[1], "shape: two-disc cluster stored, disc wanted");
  EXPECT_EQ(differences[2], "particle_contact.friction_angle_deg: 20 stored, 25 wanted");
}
