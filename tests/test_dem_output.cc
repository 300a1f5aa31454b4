// The DEM snapshot writer: the HDF5 file read back with the HDF5 C API holds what the system held
// when each snapshot was written, and the XDMF file is well-formed and lists every snapshot.
#include "dem/dem_system.h"
#include "dem/io/snapshot_writer.h"

#include <hdf5.h>

#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace geohybrid::dem;
namespace fs = std::filesystem;

namespace
{
struct TemporaryDirectory : geohybrid::testing::TemporaryDirectory
{
  TemporaryDirectory() : geohybrid::testing::TemporaryDirectory("test_dem_output") {}
};

// ---- reading HDF5 back ---------------------------------------------------------------------------

struct H5File
{
  hid_t id;
  explicit H5File(const fs::path &p) : id(H5Fopen(p.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~H5File()
  {
    if (id >= 0)
      H5Fclose(id);
  }
};

std::vector<hsize_t> dataset_shape(hid_t file, const std::string &name)
{
  const hid_t set = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(set, 0) << name;
  if (set < 0)
    return {};
  const hid_t space = H5Dget_space(set);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(set);
  return dims;
}

template <typename T>
std::vector<T> read_dataset(hid_t file, const std::string &name, hid_t memory_type)
{
  std::size_t n = 1;
  for (hsize_t d : dataset_shape(file, name))
    n *= d;
  std::vector<T> values(n);
  const hid_t set = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  if (set < 0)
    return {};
  if (n > 0)
    {
      EXPECT_GE(H5Dread(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0) << name;
    }
  H5Dclose(set);
  return values;
}
std::vector<double> read_doubles(hid_t file, const std::string &name)
{
  return read_dataset<double>(file, name, H5T_NATIVE_DOUBLE);
}
std::vector<std::int64_t> read_int64s(hid_t file, const std::string &name)
{
  return read_dataset<std::int64_t>(file, name, H5T_NATIVE_INT64);
}

double read_time(hid_t file, const std::string &group)
{
  double time = -1.0;
  const hid_t attribute = H5Aopen_by_name(file, group.c_str(), "time", H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(attribute, 0) << group;
  if (attribute >= 0)
    {
      EXPECT_GE(H5Aread(attribute, H5T_NATIVE_DOUBLE, &time), 0);
      H5Aclose(attribute);
    }
  return time;
}

// ---- what the system held when a snapshot was written ----------------------------------------------

struct Expected
{
  double time;
  std::vector<double> x, y, radius, vx, vy, rotation;
  std::vector<std::int64_t> cluster_id;
  std::vector<double> line_points; // 2m x 3
  std::vector<double> normal_force, tangential_force, force_magnitude;
  std::size_t n_touching_pairs, n_touching_wall_contacts;
};

Expected record(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  Expected e;
  e.time = system.time();
  e.x.assign(p.disc_x.begin(), p.disc_x.end());
  e.y.assign(p.disc_y.begin(), p.disc_y.end());
  e.radius.assign(p.disc_radius.begin(), p.disc_radius.end());
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    {
      const std::uint32_t b = p.disc_body[d];
      // omega x r with r the lever from the body's centre of mass to the disc centre.
      e.vx.push_back(p.vx[b] - p.omega[b] * (p.disc_y[d] - p.y[b]));
      e.vy.push_back(p.vy[b] + p.omega[b] * (p.disc_x[d] - p.x[b]));
      e.rotation.push_back(p.rotation[b]);
      e.cluster_id.push_back(p.body_id[b]);
    }
  const PairContacts &c = system.pair_contacts();
  for (std::size_t q = 0; q < c.size(); ++q)
    if (c.state[q].touching)
      {
        const std::uint32_t i = c.disc_i[q], j = c.disc_j[q];
        e.line_points.insert(e.line_points.end(), {p.disc_x[i], p.disc_y[i], 0.0, p.disc_x[j], p.disc_y[j], 0.0});
        e.normal_force.push_back(c.elastic_normal_force[q]);
        e.tangential_force.push_back(c.state[q].tangential_force);
        e.force_magnitude.push_back(std::hypot(c.force_x[q], c.force_y[q]));
      }
  e.n_touching_pairs = system.n_touching_pairs();
  e.n_touching_wall_contacts = system.n_touching_wall_contacts();
  return e;
}

void expect_snapshot(hid_t file, const std::string &group, const Expected &e)
{
  SCOPED_TRACE(group);
  const std::size_t n = e.x.size();
  EXPECT_DOUBLE_EQ(read_time(file, group), e.time);

  const std::string particles = group + "/particles/";
  EXPECT_EQ(dataset_shape(file, particles + "position"), (std::vector<hsize_t>{n, 3}));
  EXPECT_EQ(dataset_shape(file, particles + "velocity"), (std::vector<hsize_t>{n, 3}));
  EXPECT_EQ(dataset_shape(file, particles + "radius"), (std::vector<hsize_t>{n}));
  EXPECT_EQ(dataset_shape(file, particles + "cluster_id"), (std::vector<hsize_t>{n}));
  EXPECT_EQ(dataset_shape(file, particles + "rotation"), (std::vector<hsize_t>{n}));
  const std::vector<double> position = read_doubles(file, particles + "position");
  const std::vector<double> velocity = read_doubles(file, particles + "velocity");
  ASSERT_EQ(position.size(), 3 * n);
  ASSERT_EQ(velocity.size(), 3 * n);
  for (std::size_t d = 0; d < n; ++d)
    {
      EXPECT_EQ(position[3 * d], e.x[d]);
      EXPECT_EQ(position[3 * d + 1], e.y[d]);
      EXPECT_EQ(position[3 * d + 2], 0.0);
      EXPECT_NEAR(velocity[3 * d], e.vx[d], 1e-12);
      EXPECT_NEAR(velocity[3 * d + 1], e.vy[d], 1e-12);
      EXPECT_EQ(velocity[3 * d + 2], 0.0);
    }
  EXPECT_EQ(read_doubles(file, particles + "radius"), e.radius);
  EXPECT_EQ(read_doubles(file, particles + "rotation"), e.rotation);
  EXPECT_EQ(read_int64s(file, particles + "cluster_id"), e.cluster_id);

  const std::string contacts = group + "/contacts/";
  const std::size_t m = e.n_touching_pairs;
  EXPECT_EQ(dataset_shape(file, contacts + "points"), (std::vector<hsize_t>{2 * m, 3}));
  EXPECT_EQ(dataset_shape(file, contacts + "connectivity"), (std::vector<hsize_t>{m, 2}));
  EXPECT_EQ(dataset_shape(file, contacts + "normal_force"), (std::vector<hsize_t>{m}));
  EXPECT_EQ(read_doubles(file, contacts + "points"), e.line_points);
  EXPECT_EQ(read_doubles(file, contacts + "normal_force"), e.normal_force);
  EXPECT_EQ(read_doubles(file, contacts + "tangential_force"), e.tangential_force);
  EXPECT_EQ(read_doubles(file, contacts + "force_magnitude"), e.force_magnitude);
  const std::vector<std::int64_t> connectivity = read_int64s(file, contacts + "connectivity");
  ASSERT_EQ(connectivity.size(), 2 * m);
  for (std::size_t k = 0; k < 2 * m; ++k)
    EXPECT_EQ(connectivity[k], static_cast<std::int64_t>(k));

  EXPECT_EQ(dataset_shape(file, group + "/wall_contacts/points"),
            (std::vector<hsize_t>{2 * e.n_touching_wall_contacts, 3}));
}

// ---- XDMF --------------------------------------------------------------------------------------

std::string read_text(const fs::path &p)
{
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string &text, const std::string &what)
{
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size()))
    ++n;
  return n;
}

/// NumberOfElements of the topology of each grid called `name`, in order.
std::vector<std::size_t> grid_sizes(const std::string &xdmf, const std::string &name)
{
  std::vector<std::size_t> sizes;
  const std::string grid = "<Grid Name=\"" + name + "\"", key = "NumberOfElements=\"";
  for (std::size_t at = xdmf.find(grid); at != std::string::npos; at = xdmf.find(grid, at + 1))
    {
      const std::size_t topology = xdmf.find("<Topology ", at);
      const std::size_t value = xdmf.find(key, topology) + key.size();
      sizes.push_back(std::stoul(xdmf.substr(value, xdmf.find('"', value) - value)));
    }
  return sizes;
}

/// Minimal well-formedness check: every element is closed, in order, and there is one root.
bool well_formed_xml(const std::string &text)
{
  std::vector<std::string> open;
  std::size_t roots = 0;
  for (std::size_t at = text.find('<'); at != std::string::npos; at = text.find('<', at + 1))
    {
      const std::size_t end = text.find('>', at);
      if (end == std::string::npos)
        return false;
      const std::string tag = text.substr(at + 1, end - at - 1);
      if (tag.empty())
        return false;
      if (tag[0] == '?' || tag[0] == '!')
        continue;
      if (tag[0] == '/')
        {
          if (open.empty() || open.back() != tag.substr(1))
            return false;
          open.pop_back();
          continue;
        }
      const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
      if (open.empty())
        ++roots;
      if (tag.back() != '/')
        open.push_back(name);
      else if (open.empty())
        continue;
    }
  return open.empty() && roots == 1;
}

ContactParameters soft_law()
{
  ContactParameters c;
  c.normal_stiffness = 1.0e6;
  c.shear_stiffness = 0.5e6;
  c.friction_angle_deg = 20.0;
  return c;
}

DemSettings quiet_settings()
{
  DemSettings s;
  s.gravity = Vec2(0.0, -9.81);
  s.local_damping = 0.0;
  s.time_step_safety = 0.05;
  return s;
}
} // namespace

// Two single discs and a two-disc cluster, overlapping each other and a floor; two snapshots.
TEST(SnapshotWriter, WritesAndReadsBack)
{
  constexpr double density = 2650.0, r = 0.01;
  ParticleSet p;
  p.add_disc(Vec2(0.0, 0.0), r, density, 7);
  p.add_disc(Vec2(0.019, 0.0), r, density, 8);
  p.add_two_disc_cluster(Vec2(0.0095, 0.0165), r, 0.8 * r, 0.012, 0.1, density, 42);
  p.add_disc(Vec2(0.041, 0.0), r, density, 9); // within the Verlet skin of disc 8, not touching
  p.vx[0] = 0.05;
  p.omega[2] = 3.0; // the cluster spins: the disc velocities carry omega x lever
  DemSystem system(p, LinearContactLaw(soft_law()), quiet_settings());
  system.add_wall(Wall("floor", Vec2(-1.0, -0.0095), Vec2(1.0, -0.0095), LinearContactLaw(soft_law())));

  TemporaryDirectory directory;
  SnapshotWriter writer(directory.path, "grains");
  EXPECT_EQ(writer.n_snapshots(), 0u);
  ASSERT_TRUE(fs::exists(directory.path / "grains.h5"));
  ASSERT_TRUE(fs::exists(directory.path / "grains.xdmf"));

  std::vector<Expected> expected;
  system.step();
  ASSERT_GT(system.n_touching_pairs(), 0u);
  ASSERT_GT(system.n_touching_wall_contacts(), 0u);
  ASSERT_GT(system.pair_contacts().size(), system.n_touching_pairs()); // some candidates do not touch
  writer.write(system);
  expected.push_back(record(system));
  system.run_steps(5);
  writer.write(system);
  expected.push_back(record(system));
  EXPECT_EQ(writer.n_snapshots(), 2u);
  EXPECT_GT(expected[1].time, expected[0].time);
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0); // the writer left no HDF5 object open

  // The two discs of the cluster carry its id.
  EXPECT_EQ(expected[0].cluster_id, (std::vector<std::int64_t>{7, 8, 42, 42, 9}));

  {
    H5File file(directory.path / "grains.h5");
    ASSERT_GE(file.id, 0);
    H5G_info_t root;
    ASSERT_GE(H5Gget_info(file.id, &root), 0);
    EXPECT_EQ(root.nlinks, 2u);
    expect_snapshot(file.id, "/snapshot_000000", expected[0]);
    expect_snapshot(file.id, "/snapshot_000001", expected[1]);
  }

  const std::string xdmf = read_text(directory.path / "grains.xdmf");
  EXPECT_TRUE(well_formed_xml(xdmf)) << xdmf;
  EXPECT_NE(xdmf.find("<Xdmf Version=\"3.0\""), std::string::npos);
  EXPECT_NE(xdmf.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_EQ(count(xdmf, "<Time "), 2u);
  EXPECT_EQ(count(xdmf, "<Grid Name=\"particles\""), 2u);
  EXPECT_EQ(count(xdmf, "<Grid Name=\"contacts\""), 2u);
  EXPECT_EQ(count(xdmf, "TopologyType=\"Polyvertex\""), 2u);
  EXPECT_EQ(grid_sizes(xdmf, "contacts"),
            (std::vector<std::size_t>{expected[0].n_touching_pairs, expected[1].n_touching_pairs}));
  EXPECT_EQ(grid_sizes(xdmf, "wall_contacts"),
            (std::vector<std::size_t>{expected[0].n_touching_wall_contacts, expected[1].n_touching_wall_contacts}));
  EXPECT_EQ(grid_sizes(xdmf, "particles"), (std::vector<std::size_t>{5, 5}));
  EXPECT_NE(xdmf.find("grains.h5:/snapshot_000001/particles/position"), std::string::npos);
  EXPECT_FALSE(fs::exists(directory.path / "grains.xdmf.tmp"));
}

// No contact touches: the contact datasets are empty and the XDMF leaves the contacts grid out.
TEST(SnapshotWriter, NoContacts)
{
  ParticleSet p;
  p.add_disc(Vec2(0.0, 0.0), 0.01, 2650.0);
  p.add_disc(Vec2(0.05, 0.0), 0.01, 2650.0);
  DemSystem system(p, LinearContactLaw(soft_law()), quiet_settings());
  TemporaryDirectory directory;
  SnapshotWriter writer(directory.path / "nested" / "out"); // created on demand
  std::vector<Expected> expected;
  writer.write(system); // before any step: no contact list yet
  expected.push_back(record(system));
  system.step();
  writer.write(system);
  expected.push_back(record(system));
  ASSERT_EQ(system.n_touching_pairs(), 0u);
  EXPECT_EQ(writer.n_snapshots(), 2u);
  {
    H5File file(directory.path / "nested" / "out" / "particles.h5");
    ASSERT_GE(file.id, 0);
    for (std::size_t k = 0; k < 2; ++k)
      {
        const std::string group = "/snapshot_00000" + std::to_string(k);
        expect_snapshot(file.id, group, expected[k]);
        EXPECT_EQ(dataset_shape(file.id, group + "/contacts/connectivity"), (std::vector<hsize_t>{0, 2}));
      }
  }
  const std::string xdmf = read_text(writer.xdmf_path());
  EXPECT_TRUE(well_formed_xml(xdmf)) << xdmf;
  EXPECT_EQ(count(xdmf, "<Time "), 2u);
  EXPECT_EQ(count(xdmf, "<Grid Name=\"particles\""), 2u);
  EXPECT_EQ(count(xdmf, "<Grid Name=\"contacts\""), 0u);
}

// A file that cannot be created gives a std::runtime_error naming it.
TEST(SnapshotWriter, ErrorNamesTheFile)
{
  TemporaryDirectory directory;
  const fs::path blocker = directory.path / "not_a_directory";
  std::ofstream(blocker) << "x";
  try
    {
      SnapshotWriter writer(blocker, "particles");
      FAIL() << "no exception";
    }
  catch (const std::runtime_error &e)
    {
      EXPECT_NE(std::string(e.what()).find("particles.h5"), std::string::npos) << e.what();
    }
  // A directory in the place of the .h5 file: HDF5 itself fails.
  fs::create_directories(directory.path / "out" / "particles.h5");
  try
    {
      SnapshotWriter writer(directory.path / "out");
      FAIL() << "no exception";
    }
  catch (const std::runtime_error &e)
    {
      EXPECT_NE(std::string(e.what()).find("particles.h5"), std::string::npos) << e.what();
    }
}

// Continuing the files of an earlier run: the snapshots up to the given time stay, later ones go,
// the .xdmf is the one the earlier run wrote for the kept ones, and new snapshots follow them.
TEST(SnapshotWriter, ResumeKeepsEarlierSnapshots)
{
  ParticleSet p;
  p.add_disc(Vec2(0.0, 0.0), 0.01, 2650.0);
  p.add_disc(Vec2(0.0199, 0.0), 0.01, 2650.0);
  DemSystem system(p, LinearContactLaw(soft_law()), quiet_settings());
  TemporaryDirectory directory;
  std::vector<Expected> expected;
  std::string xdmf_after_two;
  {
    SnapshotWriter writer(directory.path);
    for (int k = 0; k < 4; ++k)
      {
        system.step();
        writer.write(system);
        expected.push_back(record(system));
        if (k == 1)
          xdmf_after_two = read_text(writer.xdmf_path());
      }
  }
  SnapshotWriter resumed = SnapshotWriter::resume(directory.path, "particles", expected[1].time);
  EXPECT_EQ(resumed.n_snapshots(), 2u);
  EXPECT_EQ(read_text(resumed.xdmf_path()), xdmf_after_two);
  system.run_steps(3);
  resumed.write(system);
  expected[2] = record(system);
  EXPECT_EQ(resumed.n_snapshots(), 3u);
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);
  {
    H5File file(resumed.h5_path());
    ASSERT_GE(file.id, 0);
    H5G_info_t root;
    ASSERT_GE(H5Gget_info(file.id, &root), 0);
    EXPECT_EQ(root.nlinks, 3u);
    for (std::size_t k = 0; k < 3; ++k)
      expect_snapshot(file.id, "/snapshot_00000" + std::to_string(k), expected[k]);
  }
  const std::string xdmf = read_text(resumed.xdmf_path());
  EXPECT_TRUE(well_formed_xml(xdmf)) << xdmf;
  EXPECT_EQ(count(xdmf, "<Time "), 3u);

  // A missing file starts anew; a damaged one is refused with its name.
  SnapshotWriter fresh = SnapshotWriter::resume(directory.path / "elsewhere", "particles", 1.0);
  EXPECT_EQ(fresh.n_snapshots(), 0u);
  EXPECT_TRUE(fs::exists(fresh.h5_path()));
  std::ofstream(directory.path / "broken.h5") << "not HDF5";
  try
    {
      SnapshotWriter::resume(directory.path, "broken", 1.0);
      FAIL() << "no exception";
    }
  catch (const std::runtime_error &e)
    {
      EXPECT_NE(std::string(e.what()).find("broken.h5"), std::string::npos) << e.what();
    }
}
