// The hybrid pull-out against the pure DEM pull-out of the same tank (issue 6: "T_max of the
// hybrid within 5 % of pure DEM, with the wall time of both; how T_max and cost change with the
// size of the DEM region"). A benchmark, not a test: bench/run_hybrid_bench drives it and writes
// the table of bench/RESULTS.md.
//
//   hybrid_bench --mode dem|hybrid [--margin M] [--seed S] [--particles N] [--displacement D]
//                [--rate R] [--threads T] [--young E] [--scale-inertia 0|1] [--driven W]
//                [--mohr-coulomb 0|1] [--dem-length L] [--interface-friction DEG]
//
// The tank: 0.8 m x 0.3 m, a simple run-out L = 0.5 m at H = 0.15 m, grains of about 4 mm
// (N = 12,000 two-disc clusters for the whole tank), the soft contacts of the DEM pull-out tests,
// GT230's interface; the hybrid's continuum linear elastic, E = 5 MPa (--young), nu = 0.3.
// Prints key=value lines: the wall times of the set-up (fill, and for the hybrid the coupling and
// settling) and of the pull, T_max and where, the sizes. Run it with OMP_WAIT_POLICY=PASSIVE on a
// shared host: with 2 threads and the default (spinning) policy, a loaded host made the coupled
// pull's many short parallel regions about 10 x slower (measured).
#include "coupling/hybrid_pullout.h"
#include "dem/pullout_tank.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

using namespace geohybrid;

namespace
{
dem::PullOutTankSpec bench_tank(std::size_t n_particles, std::uint64_t seed, int threads)
{
  dem::PullOutTankSpec t;
  t.geometry.tank_length = 0.8;
  t.geometry.fill_height = 0.3;
  t.geometry.cover = 0.15;
  t.geometry.anchorage_length = 0.5;
  t.geometry.clamp_offset = 0.01;
  t.max_segment_length = 0.01;
  t.filling.n_layers = 6;
  t.filling.n_particles = n_particles;
  t.filling.size_distribution = dem::SizeDistribution::uniform(0.8);
  t.filling.target_porosity = 0.25;
  t.filling.growth_stress = 5e3;
  t.filling.equilibrium_unbalanced_ratio = 1e-3;
  t.filling.seed = seed;
  t.filling.n_threads = threads;
  for (dem::ContactParameters *c : {&t.filling.particle_contact, &t.sheet.interface})
    {
      c->normal_stiffness = 1e7;
      c->shear_stiffness = 0.5e7;
    }
  return t;
}

double seconds_since(const std::chrono::steady_clock::time_point &start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void report_curve(const std::vector<dem::PullPoint> &curve)
{
  double T_max = 0.0, u_at = 0.0;
  for (const dem::PullPoint &p : curve)
    if (p.head_tension > T_max)
      {
        T_max = p.head_tension;
        u_at = p.head_displacement;
      }
  std::cout << "T_max_N_per_m=" << T_max << "\nu_at_T_max_m=" << u_at << "\n";
  for (const dem::PullPoint &p : curve)
    std::cout << "curve=" << p.head_displacement << "," << p.head_tension << "\n";
}
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::string mode = "hybrid";
  double margin = 0.05, dem_length = 0.0, interface_friction = 0.0, displacement = 0.005, rate = 0.02, young = 5e6, driven_below_weight = 0.1;
  bool scale_inertia = true, mohr_coulomb = false;
  std::size_t particles = 12000;
  std::uint64_t seed = 1;
  int threads = 2;
  for (int k = 1; k + 1 < argc; k += 2)
    {
      const std::string key = argv[k], value = argv[k + 1];
      if (key == "--mode")
        mode = value;
      else if (key == "--interface-friction")
        interface_friction = std::stod(value);
      else if (key == "--dem-length")
        dem_length = std::stod(value);
      else if (key == "--margin")
        margin = std::stod(value);
      else if (key == "--seed")
        seed = std::stoull(value);
      else if (key == "--particles")
        particles = std::stoull(value);
      else if (key == "--displacement")
        displacement = std::stod(value);
      else if (key == "--rate")
        rate = std::stod(value);
      else if (key == "--threads")
        threads = std::stoi(value);
      else if (key == "--scale-inertia")
        scale_inertia = value != "0";
      else if (key == "--mohr-coulomb")
        mohr_coulomb = value != "0";
      else if (key == "--driven")
        driven_below_weight = std::stod(value);
      else if (key == "--young")
        young = std::stod(value);
      else
        {
          std::cerr << "hybrid_bench: unknown option " << key << "\n";
          return 2;
        }
    }
  if (mode != "dem" && mode != "hybrid")
    {
      std::cerr << "hybrid_bench: --mode must be dem or hybrid\n";
      return 2;
    }
  dem::PullSpec pull;
  pull.rate = rate;
  pull.final_displacement = displacement;
  pull.record_interval = 2.5e-4;
  pull.ramp_displacement = 2.5e-4;
  const dem::PullOutTankSpec tank = bench_tank(particles, seed, threads);
  std::cout << "mode=" << mode << "\nseed=" << seed << "\nthreads=" << threads << "\n";
  const auto start = std::chrono::steady_clock::now();
  if (mode == "dem")
    {
      dem::PullOutTank filled = dem::fill_pull_out_tank(tank);
      const double setup = seconds_since(start);
      std::cout << "n_particles=" << filled.tank.system.particles().n_bodies() << "\nsetup_wall_s=" << setup
                << "\ntime_step_s=" << filled.tank.system.time_step() << std::endl;
      const auto pull_start = std::chrono::steady_clock::now();
      const std::vector<dem::PullPoint> curve = dem::pull_out(filled.tank.system, pull);
      std::cout << "pull_wall_s=" << seconds_since(pull_start) << "\ntotal_wall_s=" << seconds_since(start) << "\n";
      report_curve(curve);
      return 0;
    }
  coupling::HybridPullOutSpec spec;
  spec.tank = tank;
  spec.region.margin = margin;
  spec.region.lift_thickness = 0.05;
  spec.region.scale_band_inertia = scale_inertia;
  spec.region.driven_below_weight = driven_below_weight;
  spec.region.dem_region_length = dem_length;
  spec.continuum.sheet_interface.friction_angle_deg =
    interface_friction > 0.0 ? interface_friction : tank.sheet.interface.friction_angle_deg;
  // Linear elastic, or (--mohr-coulomb 1) Mohr-Coulomb phi = 30 deg, psi = 0, c = 0 (the
  // pull-out inputs' kind, whose stress update costs more per point).
  spec.continuum.soil.kind = mohr_coulomb ? fem::SoilModelKind::mohr_coulomb : fem::SoilModelKind::linear_elastic;
  spec.continuum.soil.strength.friction_angle_deg = 30.0;
  spec.continuum.soil.strength.dilatancy_angle_deg = 0.0;
  spec.continuum.soil.strength.cohesion = 0.0;
  spec.continuum.soil.young_modulus = young;
  spec.continuum.soil.poisson_ratio = 0.3;
  coupling::HybridPullOut hybrid(spec, "hybrid_bench");
  const double setup = seconds_since(start);
  const coupling::HybridSetUp &s = hybrid.set_up();
  const coupling::ParticleBox &box = hybrid.box();
  std::cout << "margin_m=" << margin << "\nscale_inertia=" << scale_inertia << "\ndriven_below_weight=" << driven_below_weight
            << "\ncontinuum_time_step_s=" << hybrid.continuum().critical_time_step() << "\nyoung_Pa=" << young << "\nn_particles=" << s.n_particles << "\nn_cells=" << s.n_cells
            << "\nn_tied=" << s.n_tied << "\nn_driven=" << s.n_driven << "\nbox=" << box.x0 << "," << box.y0 << ","
            << box.x1 << "," << box.y1 << "\nband_width_m=" << s.band_width << "\nsettling_steps=" << s.settling_steps
            << "\ntime_step_s=" << s.time_step << "\nparticle_time_step_s=" << s.particle_time_step
            << "\ndem_region_length_m=" << dem_length << "\nsheet_nodes_continuum=" << s.n_sheet_nodes_continuum
            << "\ncrossing_x_m=" << s.crossing_x << "\nsetup_wall_s=" << setup << std::endl;
  const auto pull_start = std::chrono::steady_clock::now();
  const std::vector<dem::PullPoint> curve = hybrid.pull(pull);
  std::cout << "pull_wall_s=" << seconds_since(pull_start) << "\ntotal_wall_s=" << seconds_since(start) << "\n";
  if (const coupling::SheetCrossing *crossing = hybrid.stepper().sheet_crossing())
    std::cout << "crossing_tension_N_per_m=" << crossing->tension()
              << "\ncontinuum_sheet_interface_x_N_per_m=" << hybrid.continuum().sheet()->interface_resultant()[0]
              << "\ncontinuum_sheet_mean_sigma_nn_Pa=" << [&] {
                   const fem::EmbeddedSheet &fe = *hybrid.continuum().sheet();
                   double sum = 0.0;
                   for (std::size_t k = 0; k < fe.sheet().n_nodes(); ++k)
                     sum += fe.interface_normal_stress(k);
                   return sum / fe.sheet().n_nodes();
                 }()
              << "\n";
  report_curve(curve);
  return 0;
}
