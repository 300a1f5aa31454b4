// The DEM's HDF5 files on a full disk (issue 24): a snapshot or checkpoint whose writes fail stops
// with a message naming the file, keeps what was complete before, and leaves no HDF5 file
// identifier open. An identifier left open by a failed H5Fclose is what HDF5 1.10 closes again
// at its shutdown (inside MPI_Finalize for geohybrid, at exit for this test), reading a freed
// file: the segmentation fault, rc 139, this guards against.
//
// The disk is "full" through a file-size limit on this process (file_size_limit.h): the writes
// fail with EFBIG instead of ENOSPC, through the same write(2) and the same HDF5 error path.
// The DEM's text files (a particle CSV) are checked as every command's (dem/io/checked_output.h).
#include "dem/dem_system.h"
#include "dem/io/checkpoint.h"
#include "dem/io/particle_csv.h"
#include "dem/io/snapshot_writer.h"
#include "dem/laboratory/packing.h"

#include <hdf5.h>

#include "file_size_limit.h"
#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace geohybrid::dem;
using geohybrid::testing::FileSizeLimit;
namespace fs = std::filesystem;

namespace
{
struct TemporaryDirectory : geohybrid::testing::TemporaryDirectory
{
  TemporaryDirectory() : geohybrid::testing::TemporaryDirectory("test_dem_full_disk") {}
};

/// 2,000 discs on a loose lattice above a floor: a snapshot of them is about 0.2 MB, a
/// checkpoint about as much.
DemSystem loose_discs()
{
  LooseLatticeSpec lattice;
  lattice.n_particles = 2000;
  lattice.x_max = 0.3;
  ContactParameters law;
  law.normal_stiffness = 1e6;
  law.shear_stiffness = 0.5e6;
  law.friction_angle_deg = 20.0;
  DemSettings settings;
  settings.gravity = Vec2(0.0, -9.81);
  DemSystem system(make_loose_lattice(lattice), LinearContactLaw(law), settings);
  system.add_wall(Wall("floor", Vec2(0.0, 0.0), Vec2(0.3, 0.0), LinearContactLaw(law)));
  return system;
}

std::string text_of(const fs::path &file)
{
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Open HDF5 identifiers of every kind, files included: 0 once everything is closed.
ssize_t open_hdf5_objects() { return H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL); }
} // namespace

// The second snapshot does not fit: the message names particles.h5 and the system's error, the
// .xdmf still lists the first snapshot only, and the first snapshot still reads back.
TEST(FullDisk, SnapshotNamesTheFileAndKeepsTheEarlierSnapshots)
{
  TemporaryDirectory directory;
  DemSystem system = loose_discs();
  SnapshotWriter writer(directory.path);
  writer.write(system);
  const std::string listed_before = text_of(writer.xdmf_path());
  const auto size_before = fs::file_size(writer.h5_path());
  ASSERT_GT(size_before, 100'000u); // a second snapshot needs as much again
  system.run_steps(10);

  std::string message;
  {
    const FileSizeLimit limit(size_before + 4096);
    try
      {
        writer.write(system);
      }
    catch (const std::runtime_error &e)
      {
        message = e.what();
      }
  }
  EXPECT_NE(message.find("DEM snapshot file '" + writer.h5_path().string() + "'"), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message; // the system's word for the failed write
  EXPECT_EQ(open_hdf5_objects(), 0);
  EXPECT_EQ(writer.n_snapshots(), 1u);
  EXPECT_EQ(text_of(writer.xdmf_path()), listed_before);

  const hid_t file = H5Fopen(writer.h5_path().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group = H5Gopen2(file, "snapshot_000000", H5P_DEFAULT);
  ASSERT_GE(group, 0);
  std::uint64_t n_discs = 0;
  const hid_t attribute = H5Aopen(group, "n_discs", H5P_DEFAULT);
  ASSERT_GE(attribute, 0);
  EXPECT_GE(H5Aread(attribute, H5T_NATIVE_UINT64, &n_discs), 0);
  EXPECT_EQ(n_discs, 2000u);
  H5Aclose(attribute);
  H5Gclose(group);
  H5Fclose(file);
  EXPECT_EQ(open_hdf5_objects(), 0);
}

// A checkpoint that does not fit: the message names checkpoint.h5, no temporary file is left
// beside it, and the previous checkpoint is the one that reads back.
TEST(FullDisk, CheckpointNamesTheFileAndKeepsThePreviousOne)
{
  TemporaryDirectory directory;
  DemSystem system = loose_discs();
  const fs::path file = directory.path / "checkpoint.h5";
  write_checkpoint(system.export_state(), file);
  const auto size = fs::file_size(file);
  system.run_steps(10);

  std::string message;
  {
    const FileSizeLimit limit(size / 2);
    try
      {
        write_checkpoint(system.export_state(), file);
      }
    catch (const std::runtime_error &e)
      {
        message = e.what();
      }
  }
  EXPECT_NE(message.find("DEM checkpoint '" + file.string() + "'"), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_EQ(open_hdf5_objects(), 0);
  EXPECT_FALSE(fs::exists(directory.path / "checkpoint.h5.tmp"));
  EXPECT_EQ(read_checkpoint(file).step_count, 0u);
}

// A file that fails only when its buffers reach the disk (small writes HDF5 keeps in memory
// until the flush): the same message and nothing left open.
TEST(FullDisk, FailureAtTheFlushIsReportedAndLeavesNothingOpen)
{
  TemporaryDirectory directory;
  DemSystem system = loose_discs();
  SnapshotWriter writer(directory.path);
  const auto size_empty = fs::file_size(writer.h5_path());
  std::string message;
  {
    const FileSizeLimit limit(size_empty + 512);
    try
      {
        writer.write(system);
      }
    catch (const std::runtime_error &e)
      {
        message = e.what();
      }
  }
  EXPECT_NE(message.find("particles.h5"), std::string::npos) << message;
  EXPECT_EQ(open_hdf5_objects(), 0);
  EXPECT_EQ(writer.n_snapshots(), 0u);
}

// A particle CSV (dem::write_particle_csv, final_particles.csv of `geohybrid dem`) on a full
// disk (/dev/full: every write fails with ENOSPC). Three discs fit in the stream's buffer, whose
// failure comes only at the close: the close is checked (dem/io/checked_output.h), not left to the
// destructor, which would say nothing.
TEST(FullDisk, ParticleCsvNamesTheFile)
{
  if (!fs::exists("/dev/full"))
    GTEST_SKIP() << "no /dev/full on this system";
  TemporaryDirectory directory;
  LooseLatticeSpec lattice;
  lattice.n_particles = 3;
  const fs::path file = directory.path / "final_particles.csv";
  fs::create_symlink("/dev/full", file);
  std::string message;
  try
    {
      write_particle_csv(make_loose_lattice(lattice), file);
    }
  catch (const std::runtime_error &e)
    {
      message = e.what();
    }
  EXPECT_NE(message.find("cannot write " + file.string() + " (is the disk full"), std::string::npos) << message;
}
