#pragma once
// The small hybrid pull-out input of the app tests (test_app_pullout_hybrid.cc, the signals of
// test_app_interrupt.cc): the tank of test_coupling_hybrid_pullout.cc (0.4 m x 0.2 m, 4,000
// grains for the whole tank, about 1,500 in the box, an elastic continuum elsewhere).
#include <filesystem>
#include <fstream>
#include <string>

namespace geohybrid::testing
{
/// The library test's tank and grains (soft contacts, kn = 1e7 N/m/m), the sheet 0.25 m long
/// under 0.1 m, a 0.05 m margin; the continuum linear elastic (E = 5 MPa, nu = 0.3) with the
/// library's damping (0.7); pulled 1 mm at 5 mm/s, a point every 0.2 mm.
inline std::string write_small_hybrid_pullout_input(const std::filesystem::path &directory,
                                                   const std::string &extra = "")
{
  const std::filesystem::path file = directory / "pullout.prm";
  std::ofstream(file) << "set output directory = " << (directory / "out").string() << "\n"
                      << "set threads = 1\nset mode = hybrid\n"
                      << "subsection Tank\n  set length = 0.4\n  set fill height = 0.2\n  set clamp offset = 0.01\nend\n"
                      << "subsection Anchorage\n  set H = 0.1\n  set L = 0.25\nend\n"
                      << "subsection Sheet\n  set segment length = 0.01\n  subsection Interface\n"
                      << "    set normal stiffness = 1e7\n    set shear stiffness = 5e6\n  end\nend\n"
                      << "subsection Soil\n  subsection Particle contact\n    set normal stiffness = 1e7\n"
                      << "    set shear stiffness = 5e6\n  end\nend\n"
                      << "subsection Filling\n  set number of particles = 4000\n  set number of layers = 2\n"
                      << "  set size ratio = 0.8\n  set target porosity = 0.25\n  set growth stress = 5e3\n"
                      << "  set equilibrium unbalanced ratio = 1e-3\n  set seed = 3\nend\n"
                      << "subsection Pull\n  set rate = 0.005\n  set final displacement = 0.001\n"
                      << "  set record interval = 0.0002\n  set tension profiles at = 0.0005, 0.001\nend\n"
                      << "subsection Output\n  set experimental T_max = 0.5\nend\n"
                      << "subsection Continuum\n  set soil model = linear elastic\n  set Young modulus = 5e6\n"
                      << "  set Poisson ratio = 0.3\n  set local damping = 0.7\nend\n"
                      << "subsection Hybrid\n  set DEM region margin = 0.05\n  set lift thickness = 0.05\nend\n"
                      << extra;
  return file.string();
}
} // namespace geohybrid::testing
