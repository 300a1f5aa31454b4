// The hybrid pull-out against the pure DEM pull-out of the same tank (issue 6: "T_max of the
// hybrid within 5 % of pure DEM, with the wall time of both; how T_max and cost change with the
// size of the DEM region"). A benchmark, not a test: bench/run_hybrid_bench drives it and writes
// the table of bench/RESULTS.md.
//
//   hybrid_bench --mode dem|hybrid [--margin M] [--seed S] [--particles N] [--displacement D]
//                [--rate R] [--threads T] [--young E] [--scale-inertia 0|1] [--driven W]
//                [--mohr-coulomb 0|1] [--dem-length L] [--interface-friction DEG] [--overburden 0|1]
//                [--poisson NU] [--phi DEG] [--probe-x X]
//
// The tank: 0.8 m x 0.3 m, a simple run-out L = 0.5 m at H = 0.15 m, grains of about 4 mm
// (N = 12,000 two-disc clusters for the whole tank), the soft contacts of the DEM pull-out tests,
// GT230's interface; the hybrid's continuum linear elastic, E = 5 MPa (--young), nu = 0.3
// (--poisson), or Mohr-Coulomb (--mohr-coulomb 1) with phi = 30 deg (--phi), psi = 0, c = 0. This
// DEM soil's own (`geohybrid biaxial` at 1.5 and 3 kPa, porosity 0.22; bench/RESULTS.md):
// E = 0.39 MPa, nu = 0.44, phi = 18 deg, psi = 0.
// Prints key=value lines (curve = head displacement, head tension and the tension where the sheet
// crosses into the continuum, or at --probe-x (tank frame, default 0.527 m) in the particles): the wall times of the set-up (fill, and for the hybrid the coupling and
// settling) and of the pull, T_max and where, the sizes. Run it with OMP_WAIT_POLICY=PASSIVE on a
// shared host: with 2 threads and the default (spinning) policy, a loaded host made the coupled
// pull's many short parallel regions about 10 x slower (measured).
#include "coupling/hybrid_pullout.h"
#include "dem/laboratory/pullout_tank.h"
#include "dem/measurements.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
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

/// The mean normal stress on the sheet's two faces over the segments whose middle lies in
/// [x_min, x_max) (the tank's frame; `x_offset` takes the system's frame there) [Pa, compression
/// positive]: against gamma H, the overburden the sheet should carry there. Zeros if no segment.
dem::SheetFaceStresses sheet_faces(const dem::DemSystem &system, double x_offset, double x_min, double x_max)
{
  const dem::SparSheet &sheet = system.sheets().at(0);
  std::size_t first = sheet.n_nodes(), last = 0;
  for (std::size_t k = 0; k + 1 < sheet.n_nodes(); ++k)
    {
      const double x = 0.5 * (sheet.x[k] + sheet.x[k + 1]) + x_offset;
      if (x >= x_min && x < x_max)
        {
          first = std::min(first, k);
          last = std::max(last, k + 1);
        }
    }
  return first < last ? dem::sheet_face_stresses(system, 0, first, last) : dem::SheetFaceStresses{};
}

void report_sheet_faces(const dem::DemSystem &system, double x_offset, double x_min, double x_max, const std::string &label)
{
  const dem::SheetFaceStresses faces = sheet_faces(system, x_offset, x_min, x_max);
  std::cout << label << "_sheet_top_sigma_n_Pa=" << faces.normal_left << "\n"
            << label << "_sheet_bottom_sigma_n_Pa=" << faces.normal_right << "\n";
}

/// The continuum's vertical stress at a level (the box's frame), in 0.05 m bins of x (the tank's
/// frame): the mean -sigma_yy over the quadrature points of the cells the level crosses [Pa].
void report_continuum_stress_at(const coupling::HybridPullOut &hybrid, double level, const std::string &label)
{
  const double x0 = hybrid.box().x0, bin = 0.05;
  std::map<long, std::pair<double, int>> bins;
  const fem::MaterialPointHistory &points = hybrid.continuum().material_points();
  for (const auto &cell : hybrid.continuum().space().mesh().active_cell_iterators())
    {
      if (!cell->is_locally_owned())
        continue;
      double y_min = cell->vertex(0)[1], y_max = y_min;
      for (unsigned int v = 1; v < 4; ++v)
        {
          y_min = std::min(y_min, cell->vertex(v)[1]);
          y_max = std::max(y_max, cell->vertex(v)[1]);
        }
      if (level < y_min || level >= y_max)
        continue;
      auto &sum = bins[std::lround(std::floor((cell->center()[0] + x0) / bin))];
      for (const auto &point : points.at(cell))
        {
          sum.first -= point->stress[1][1];
          ++sum.second;
        }
    }
  std::cout << label << "_continuum_sigma_yy_Pa=";
  for (const auto &[k, sum] : bins)
    std::cout << (static_cast<double>(k) + 0.5) * bin << ":" << std::lround(sum.first / sum.second) << " ";
  std::cout << "\n";
}

/// The tension of the DEM sheet's segment that spans x (the tank's frame) [N/m]; 0 if none does.
double tension_at(const dem::DemSystem &system, double x_offset, double x)
{
  const dem::SparSheet &sheet = system.sheets().at(0);
  for (std::size_t k = 0; k + 1 < sheet.n_nodes(); ++k)
    if ((sheet.x[k] + x_offset - x) * (sheet.x[k + 1] + x_offset - x) <= 0.0)
      return sheet.tension[k];
  return 0.0;
}

/// x [m] and sigma_nn [Pa] at each node of the sheet's part in the continuum (the tank's frame).
void report_continuum_sheet(const fem::EmbeddedSheet &sheet, double x_offset, const std::string &label)
{
  std::cout << label << "_continuum_sheet_sigma_nn_Pa=";
  for (std::size_t k = 0; k < sheet.sheet().n_nodes(); ++k)
    std::cout << sheet.node_position(k)[0] + x_offset << ":" << std::lround(sheet.interface_normal_stress(k)) << " ";
  std::cout << "\n";
}

void report_curve(const std::vector<dem::PullPoint> &curve, const std::vector<double> &probe)
{
  double T_max = 0.0, u_at = 0.0;
  for (const dem::PullPoint &p : curve)
    if (p.head_tension > T_max)
      {
        T_max = p.head_tension;
        u_at = p.head_displacement;
      }
  std::cout << "T_max_N_per_m=" << T_max << "\nu_at_T_max_m=" << u_at << "\n";
  for (std::size_t k = 0; k < curve.size(); ++k)
    std::cout << "curve=" << curve[k].head_displacement << "," << curve[k].head_tension << ","
              << (k < probe.size() ? probe[k] : 0.0) << "\n";
}
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::string mode = "hybrid";
  double poisson = 0.3, phi = 30.0, probe_x = 0.527, margin = 0.05, dem_length = 0.0, interface_friction = 0.0, displacement = 0.005, rate = 0.02, young = 5e6, driven_below_weight = 0.1;
  bool scale_inertia = true, mohr_coulomb = false, overburden = true;
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
      else if (key == "--probe-x")
        probe_x = std::stod(value);
      else if (key == "--overburden")
        overburden = value != "0";
      else if (key == "--mohr-coulomb")
        mohr_coulomb = value != "0";
      else if (key == "--driven")
        driven_below_weight = std::stod(value);
      else if (key == "--young")
        young = std::stod(value);
      else if (key == "--poisson")
        poisson = std::stod(value);
      else if (key == "--phi")
        phi = std::stod(value);
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
      report_sheet_faces(filled.tank.system, 0.0, 0.0, 0.5, "settled_back");
      report_sheet_faces(filled.tank.system, 0.0, 0.5, 0.8, "settled_front");
      std::cout << "n_particles=" << filled.tank.system.particles().n_bodies() << "\nsetup_wall_s=" << setup
                << "\ntime_step_s=" << filled.tank.system.time_step() << std::endl;
      const auto pull_start = std::chrono::steady_clock::now();
      std::vector<double> probe;
      const std::vector<dem::PullPoint> curve =
        dem::pull_out(filled.tank.system, pull, [&](const dem::PullPoint &, const dem::DemSystem &system) {
          probe.push_back(tension_at(system, 0.0, probe_x));
          const dem::SheetFaceStresses back = sheet_faces(system, 0.0, 0.0, probe_x);
          const dem::SheetFaceStresses front = sheet_faces(system, 0.0, probe_x, 1.0);
          std::cout << "faces=" << back.normal_left << "," << back.normal_right << "," << front.normal_left << ","
                    << front.normal_right << "\n";
        });
      std::cout << "pull_wall_s=" << seconds_since(pull_start) << "\ntotal_wall_s=" << seconds_since(start) << "\n";
      report_curve(curve, probe);
      return 0;
    }
  coupling::HybridPullOutSpec spec;
  spec.tank = tank;
  spec.region.margin = margin;
  spec.region.lift_thickness = 0.05;
  spec.region.scale_band_inertia = scale_inertia;
  spec.region.driven_below_weight = driven_below_weight;
  spec.region.dem_region_length = dem_length;
  spec.region.fill_under_overburden = overburden;
  spec.continuum.sheet_interface.friction_angle_deg =
    interface_friction > 0.0 ? interface_friction : tank.sheet.interface.friction_angle_deg;
  // Linear elastic, or (--mohr-coulomb 1) Mohr-Coulomb phi = 30 deg, psi = 0, c = 0 (the
  // pull-out inputs' kind, whose stress update costs more per point).
  spec.continuum.soil.kind = mohr_coulomb ? fem::SoilModelKind::mohr_coulomb : fem::SoilModelKind::linear_elastic;
  spec.continuum.soil.strength.friction_angle_deg = phi;
  spec.continuum.soil.strength.dilatancy_angle_deg = 0.0;
  spec.continuum.soil.strength.cohesion = 0.0;
  spec.continuum.soil.young_modulus = young;
  spec.continuum.soil.poisson_ratio = poisson;
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
            << "\ncrossing_x_m=" << s.crossing_x << "\noverburden_Pa=" << s.overburden
            << "\noverburden_reached_Pa=" << s.overburden_reached << "\nbox_settling_steps=" << s.box_settling_steps
            << "\nsetup_wall_s=" << setup << std::endl;
  const double sheet_level_in_box = tank.geometry.sheet_level() - box.y0;
  report_sheet_faces(hybrid.particles().tank.system, box.x0, 0.5, 0.8, "settled_front");
  report_continuum_stress_at(hybrid, sheet_level_in_box, "settled");
  if (const fem::EmbeddedSheet *fe = hybrid.continuum().sheet())
    {
      double sum = 0.0;
      for (std::size_t k = 0; k < fe->sheet().n_nodes(); ++k)
        sum += fe->interface_normal_stress(k);
      std::cout << "settled_continuum_sheet_mean_sigma_nn_Pa=" << sum / fe->sheet().n_nodes() << "\n";
      report_continuum_sheet(*fe, box.x0, "settled");
    }
  std::cout << "gamma_H_Pa=" << tank.unit_weight * tank.geometry.cover << std::endl;
  const auto pull_start = std::chrono::steady_clock::now();
  std::vector<double> probe;
  const std::vector<dem::PullPoint> curve = hybrid.pull(pull, [&](const dem::PullPoint &) {
    const coupling::SheetCrossing *crossing = hybrid.stepper().sheet_crossing();
    probe.push_back(crossing ? crossing->tension() : tension_at(hybrid.particles().tank.system, box.x0, probe_x));
    // The back part: the continuum's nodes outside the box, or the particles' segments.
    dem::SheetFaceStresses back = sheet_faces(hybrid.particles().tank.system, box.x0, 0.0, probe_x);
    if (const fem::EmbeddedSheet *fe = hybrid.continuum().sheet())
      {
        double sum = 0.0;
        int n = 0;
        for (std::size_t k = 0; k < fe->sheet().n_nodes(); ++k)
          if (fe->node_position(k)[0] < 0.0)
            {
              sum -= fe->interface_normal_stress(k);
              ++n;
            }
        back.normal_left = back.normal_right = n > 0 ? sum / n : 0.0;
      }
    const dem::SheetFaceStresses front = sheet_faces(hybrid.particles().tank.system, box.x0, probe_x, 1.0);
    std::cout << "faces=" << back.normal_left << "," << back.normal_right << "," << front.normal_left << ","
              << front.normal_right << "\n";
  });
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
  if (const fem::EmbeddedSheet *fe = hybrid.continuum().sheet())
    {
      report_continuum_sheet(*fe, box.x0, "pulled");
      report_continuum_stress_at(hybrid, sheet_level_in_box, "pulled");
    }
  report_curve(curve, probe);
  return 0;
}
