#pragma once
// The tiny DEM pull-out input of the app tests (--seeds, resume, the ensemble over ranks): shared so
// that the serial and the MPI tests run the same tank.
#include <filesystem>
#include <fstream>
#include <string>

namespace geohybrid::testing
{
/// A tiny run for --seeds: a 0.16 m x 0.1 m tank, 400 clusters, the sheet 0.1 m long at 0.05 m,
/// soft contacts (kn = 1e7 N/m/m, as in test_dem_pullout.cc), a 5 kPa growth stress, settled loosely, pulled 1 mm at 10 mm/s. Each
/// seed fills and pulls in about 3 s of CPU.
inline std::string write_tiny_pullout_input(const std::filesystem::path &directory)
{
  const std::filesystem::path file = directory / "tiny.prm";
  std::ofstream(file) << "set output directory = " << (directory / "out").string() << "\n"
                      << "set threads = 1\nset mode = dem\n"
                      << "subsection Tank\n  set length = 0.16\n  set fill height = 0.1\n  set clamp offset = 0.01\nend\n"
                      << "subsection Anchorage\n  set H = 0.05\n  set L = 0.1\nend\n"
                      << "subsection Sheet\n  subsection Interface\n    set normal stiffness = 1e7\n"
                      << "    set shear stiffness = 5e6\n  end\nend\n"
                      << "subsection Soil\n  subsection Particle contact\n    set normal stiffness = 1e7\n"
                      << "    set shear stiffness = 5e6\n  end\nend\n"
                      << "subsection Filling\n  set number of particles = 400\n  set number of layers = 2\n"
                      << "  set size ratio = 0.8\n  set target porosity = 0.25\n  set growth stress = 5e3\n"
                      << "  set equilibrium unbalanced ratio = 1e-2\n  set seed = 3\nend\n"
                      << "subsection Pull\n  set rate = 0.01\n  set final displacement = 0.001\n"
                      << "  set record interval = 0.00025\n  set tension profiles at = 0.001\nend\n";
  return file.string();
}
} // namespace geohybrid::testing
