// The tank meshes of meshes/: they load into the distributed mesh with the walls' boundary ids,
// the tank's area and the sheet's level as a mesh line; the implicit solver carries the soil's
// weight on them; a missing file and an absent boundary id are refused naming the file.
#include "fem/quasi_static_solver.h"
#include "fem/tank_mesh.h"
#include "test_fem_support.h"

#include <deal.II/grid/grid_tools.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <unistd.h>

using namespace geohybrid::fem;
using namespace geohybrid::fem::testing;

namespace
{
const std::string mesh_directory = GEOHYBRID_MESH_DIR;

/// The distinct x of the mesh vertices on the line y = `level`, between x_min and x_max.
std::set<long> vertices_on_level(const Mesh &mesh, double level, double x_min, double x_max)
{
  std::set<long> xs;
  for (const auto &v : mesh.get_vertices())
    if (std::abs(v[1] - level) < 1e-9 && v[0] > x_min - 1e-9 && v[0] < x_max + 1e-9)
      xs.insert(std::lround(v[0] * 1e6));
  return xs;
}
} // namespace

TEST(TankMesh, RunOutTankHasItsWallsAreaAndSheetLevel)
{
  Mesh mesh(MPI_COMM_WORLD);
  read_tank_mesh(mesh, mesh_directory + "/insa_tank_runout.msh");
  EXPECT_EQ(mesh.n_global_active_cells(), 60u * 24u); // 1.5 m x 0.6 m in 25 mm cells
  EXPECT_EQ(mesh.get_boundary_ids(), (std::vector<dealii::types::boundary_id>{1, 2, 3, 4}));
  EXPECT_NEAR(dealii::GridTools::volume(mesh), 1.5 * 0.6, 1e-9); // the .msh keeps ~13 digits
  // The sheet (y = 0.2 m from x = 0.5 m to the front wall) runs along cell edges: 41 vertices.
  EXPECT_EQ(vertices_on_level(mesh, 0.2, 0.5, 1.5).size(), 41u);
}

TEST(TankMesh, WrapAroundTankHasItsWallsAreaAndSheetLines)
{
  Mesh mesh(MPI_COMM_WORLD);
  read_tank_mesh(mesh, mesh_directory + "/insa_tank_wraparound.msh");
  EXPECT_EQ(mesh.get_boundary_ids(), (std::vector<dealii::types::boundary_id>{1, 2, 3, 4}));
  EXPECT_NEAR(dealii::GridTools::volume(mesh), 1.5 * 0.6, 1e-9); // the .msh keeps ~13 digits
  // Lower part y = 0.2 m from x = 0.5 m to 1.5 m, upper part y = 0.4 m from 0.5 m to 0.75 m.
  EXPECT_EQ(vertices_on_level(mesh, 0.2, 0.5, 1.5).size(), 41u);
  EXPECT_EQ(vertices_on_level(mesh, 0.4, 0.5, 0.75).size(), 11u);
}

// Elastic soil under gravity in the run-out tank (rollers on the walls, fixed base): the base
// carries the weight rho g A of the soil.
TEST(TankMesh, ImplicitSolverCarriesTheWeightOnTheTankMesh)
{
  Mesh mesh(MPI_COMM_WORLD);
  read_tank_mesh(mesh, mesh_directory + "/insa_tank_runout.msh");
  BoundaryConditions bc;
  bc.displacements = {{tank_boundary::bottom, true, true, nullptr},
                      {tank_boundary::back_wall, true, false, nullptr},
                      {tank_boundary::front_wall, true, false, nullptr}};
  QuasiStaticSettings settings = exact_settings(1);
  settings.density = 1700.0;
  QuasiStaticSolver solver(mesh, elastic_soil(30e6, 0.3), bc, settings);
  solver.advance_to(1.0);
  EXPECT_NEAR(solver.boundary_reaction(tank_boundary::bottom)[1], 1700.0 * 9.81 * 0.9, 1e-6 * 1700.0 * 9.81 * 0.9);
}

TEST(TankMesh, MissingFileAndUnknownBoundaryIdNameTheFile)
{
  {
    Mesh mesh(MPI_COMM_WORLD);
    try
      {
        read_tank_mesh(mesh, mesh_directory + "/no_such_tank.msh");
        FAIL() << "a missing mesh file was accepted";
      }
    catch (const std::invalid_argument &e)
      {
        EXPECT_NE(std::string(e.what()).find("no_such_tank.msh"), std::string::npos) << e.what();
      }
  }
  {
    Mesh mesh(MPI_COMM_WORLD);
    try
      {
        read_tank_mesh(mesh, mesh_directory + "/insa_tank_runout.msh", {tank_boundary::bottom, 7});
        FAIL() << "an absent boundary id was accepted";
      }
    catch (const std::invalid_argument &e)
      {
        EXPECT_NE(std::string(e.what()).find("insa_tank_runout.msh"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("boundary id 7"), std::string::npos) << e.what();
      }
  }
  {
    // A file that is not a mesh.
    Mesh mesh(MPI_COMM_WORLD);
    EXPECT_THROW(read_tank_mesh(mesh, mesh_directory + "/insa_tank_runout.geo"), std::invalid_argument);
  }
}

// A damaged mesh file (cut short, or bytes that are no mesh) gives one line naming the file, not
// deal.II's report with its source lines and stack trace, and no bytes of the file.
TEST(TankMesh, CorruptFileGivesOneLineNamingTheFile)
{
  std::ifstream whole(mesh_directory + "/insa_tank_runout.msh");
  const std::string text((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
  ASSERT_GT(text.size(), 1000u);
  const std::string cut = text.substr(0, text.find("$Elements") + 30);
  const std::filesystem::path directory = std::filesystem::temp_directory_path();
  int k = 0;
  for (const std::string &bytes : {cut, std::string("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n\x01\xff\x02zz\n")})
    {
      const std::filesystem::path file =
        directory / ("geohybrid_corrupt_" + std::to_string(::getpid()) + "_" + std::to_string(k++) + ".msh");
      std::ofstream(file, std::ios::binary) << bytes;
      Mesh mesh(MPI_COMM_WORLD);
      std::string message;
      try
        {
          read_tank_mesh(mesh, file.string());
        }
      catch (const std::invalid_argument &e)
        {
          message = e.what();
        }
      std::filesystem::remove(file);
      EXPECT_EQ(message.find("tank mesh: cannot read '" + file.string() + "' as a gmsh 2.2 ASCII mesh"), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_EQ(message.find("Stacktrace"), std::string::npos) << message;
      EXPECT_EQ(message.find("An error occurred"), std::string::npos) << message;
      EXPECT_EQ(message.find('\xff'), std::string::npos) << message;
    }
}

// The generated tank (make_tank_mesh) puts a row of cells of exactly the cell size centred on
// each given level, so that a sheet there runs through the middle of its cells; the other rows
// stay between 1/2 and 3/2 of the cell size; a level too close to a side is refused by name.
TEST(TankMesh, GeneratedTankCentresARowOnTheSheet)
{
  const double h = 0.025;
  Mesh mesh(MPI_COMM_WORLD);
  make_tank_mesh(mesh, 1.5, 0.6, h, {}, {0.21}, "generated tank");
  EXPECT_EQ(mesh.get_boundary_ids(), (std::vector<dealii::types::boundary_id>{1, 2, 3, 4}));
  EXPECT_NEAR(dealii::GridTools::volume(mesh), 1.5 * 0.6, 1e-12);
  std::set<long> ys; // the rows' lower and upper edges, in um
  for (const auto &v : mesh.get_vertices())
    ys.insert(std::lround(v[1] * 1e6));
  EXPECT_TRUE(ys.count(std::lround((0.21 - h / 2) * 1e6)) && ys.count(std::lround((0.21 + h / 2) * 1e6)));
  for (auto a = ys.begin(), b = std::next(a); b != ys.end(); ++a, ++b)
    {
      EXPECT_GE(*b - *a, std::lround(0.5e6 * h) - 1);
      EXPECT_LE(*b - *a, std::lround(1.5e6 * h) + 1);
    }
  EXPECT_EQ(mesh.n_global_active_cells() % 60, 0u); // 60 columns of 25 mm
  Mesh refused(MPI_COMM_WORLD);
  try
    {
      make_tank_mesh(refused, 1.5, 0.6, h, {}, {0.006}, "generated tank");
      ADD_FAILURE() << "a level within half a cell of the bottom was accepted";
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("generated tank: parameter 'cell size'"), std::string::npos) << e.what();
    }
}
