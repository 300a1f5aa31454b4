// The explicit continuum solver's cost per step per cell (bench/run_fem_bench runs it; not a
// test): the INSA tank of examples/pullout_runout_h040.prm (1.5 m x 0.6 m) meshed by
// fem::make_tank_mesh with its sheet's row centred, the soil (sand 1: E = 20 MPa, nu = 0.3,
// 15.2 kN/m3; Mohr-Coulomb phi = 38.4, psi = 8.4 degrees, or elastic) at its geostatic K0 state
// under gravity, smooth walls, local damping 0.3, as in a pull-out. The timed steps follow a few
// untimed ones (caches warm). Runs on the ranks of mpirun.
//
// Usage: fem_bench --degree 1|2 --soil elastic|mohr-coulomb --cell-size H [--steps N] [--threads T]
//                  [--gravity-factor F]
// (--gravity-factor: the solver's gravity is F g while the initial stress is the geostatic one of
// g: F = 0.2 unloads the soil suddenly, its horizontal stress falls below the active one and the
// Mohr-Coulomb points take the plastic returns, surface, edges and, near the free surface, the
// apex: a check of their bits, not a pull-out's cost.)
// Prints one line: key=value pairs (cells, dofs, ranks, threads, steps, seconds,
// ms_per_step, cpu_ms_per_step (rank 0's process, all its threads), us_per_step_per_cell, out_of_balance, plastic_points (on rank 0) and a checksum: the bits of the displacement, the internal
// force and the material points' stresses after the run, hashed, so that a faster solver can be
// checked to give the same numbers to the last bit).
#include "fem/constitutive/soil_model.h"
#include "fem/explicit_solver.h"
#include "fem/tank_mesh.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <string>

using namespace geohybrid::fem;

namespace
{
/// FNV-1a over the bits of the doubles: any change in any bit changes it.
struct BitHash
{
  std::uint64_t value = 14695981039346656037ull;
  void add(double x)
  {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    for (unsigned int k = 0; k < 8; ++k)
      value = (value ^ ((bits >> (8 * k)) & 0xffu)) * 1099511628211ull;
  }
};
/// The CPU time of the process (all its threads) [s]: on a machine shared with other work, the
/// cost of the steps, which the wall time measures only when the cores are free.
double process_cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  unsigned int degree = 1, steps = 200, threads = 1;
  std::string soil_name = "elastic";
  double cell_size = 0.0075, gravity_factor = 1.0;
  for (int k = 1; k + 1 < argc; k += 2)
    {
      const std::string key = argv[k], value = argv[k + 1];
      if (key == "--degree")
        degree = static_cast<unsigned int>(std::stoul(value));
      else if (key == "--soil")
        soil_name = value;
      else if (key == "--cell-size")
        cell_size = std::stod(value);
      else if (key == "--steps")
        steps = static_cast<unsigned int>(std::stoul(value));
      else if (key == "--gravity-factor")
        gravity_factor = std::stod(value);
      else if (key == "--threads")
        threads = static_cast<unsigned int>(std::stoul(value));
      else
        {
          std::cerr << "fem_bench: unknown option " << key << '\n';
          return 2;
        }
    }
  const double length = 1.5, height = 0.6, H = 0.4, gamma = 15.2e3, g = 9.81;
  SoilParameters soil;
  soil.kind = soil_name == "elastic" ? SoilModelKind::linear_elastic : SoilModelKind::mohr_coulomb;
  soil.young_modulus = 20e6;
  soil.poisson_ratio = 0.3;
  soil.strength = {38.4, 0.0, 8.4};
  const SoilModel model(soil, "fem_bench");

  dealii::parallel::distributed::Triangulation<dim> mesh(MPI_COMM_WORLD);
  make_tank_mesh(mesh, length, height, cell_size, {}, {height - H}, "fem_bench");
  BoundaryConditions bc;
  bc.displacements = {{tank_boundary::bottom, true, true, nullptr},
                      {tank_boundary::back_wall, true, false, nullptr},
                      {tank_boundary::front_wall, true, false, nullptr}};
  ExplicitSettings settings;
  settings.element_degree = degree;
  settings.density = gamma / g;
  settings.gravity[1] = -gravity_factor * g;
  settings.damping.local = 0.3;
  settings.n_threads = threads;
  ExplicitSolver solver(mesh, model, bc, settings);
  GeostaticStress geostatic;
  geostatic.surface_elevation = height;
  geostatic.unit_weight = gamma;
  geostatic.k0 = model.default_k0();
  solver.set_initial_stress(geostatic);

  for (unsigned int n = 0; n < 5; ++n)
    solver.step();
  MPI_Barrier(MPI_COMM_WORLD);
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  for (unsigned int n = 0; n < steps; ++n)
    solver.step();
  MPI_Barrier(MPI_COMM_WORLD);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu_seconds = process_cpu_seconds() - cpu_start;
  const unsigned int ranks = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const double out_of_balance = solver.out_of_balance_ratio(); // collective
  BitHash hash;
  unsigned int plastic_points = 0; // whose last step was a return
  for (unsigned int i = 0; i < solver.displacement().locally_owned_size(); ++i)
    {
      hash.add(solver.displacement().local_element(i));
      hash.add(solver.internal_force().local_element(i));
    }
  solver.material_points().for_each_cell([&](const auto &, auto &points) {
    for (const auto &p : points)
      {
        plastic_points += p->region != ReturnRegion::elastic;
        hash.add(static_cast<double>(static_cast<int>(p->region)));
      }
    for (const auto &p : points)
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          {
            hash.add(p->stress[i][j]);
            hash.add(p->plastic_strain[i][j]);
          }
  });
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "degree=Q" << degree << " soil=" << soil_name << " cells=" << mesh.n_global_active_cells()
              << " dofs=" << solver.space().dof_handler().n_dofs() << " ranks=" << ranks << " threads=" << threads
              << " steps=" << steps << " time_step_s=" << solver.time_step() << " seconds=" << seconds
              << " ms_per_step=" << 1e3 * seconds / steps << " cpu_ms_per_step=" << 1e3 * cpu_seconds / steps
              << " us_per_step_per_cell=" << 1e6 * seconds / (steps * mesh.n_global_active_cells())
              << " out_of_balance=" << out_of_balance << " plastic_points=" << plastic_points << " checksum=" << std::hex << hash.value << std::dec
              << std::endl;
  return 0;
}
