// DEM performance benchmark: geohybrid's DemSystem against LAMMPS (GRANULAR package) on the same
// settled packing of 2D discs. This is a benchmark, not a test; bench/run_dem_bench drives it.
//
// Sub-commands (all write key=value lines on stdout that run_dem_bench parses):
//
//   dem_bench prepare --packing FILE [--n 40000] [--seed 1] [--threads 2] [--ke-tol 1e-4]
//                     [--max-steps 400000]
//       Builds the packing if FILE is missing or was made with other parameters: discs with radii
//       uniform in [1.5, 2.5] mm, density 2650 kg/m^3, in a 1 m wide box (floor + two side walls),
//       placed by a geometric drop-and-roll a few microns apart, then deposited under gravity with
//       local damping 0.7 and restitution 0.5 until the coordination number is >= 3 and the
//       kinetic energy is below ke-tol x sum(m g d) (checked every 1000 steps).
//   dem_bench time --packing FILE --threads N [--steps 2000] [--final FILE] [--track-energy]
//                  [--shuffle] [--sort]   (--sort: renumber in Morton order, dem::spatially_sorted)
//       Loads the settled packing (velocities zero, no contact history), and times `steps` steps
//       (after one untimed step that builds the lists and the initial forces) with gravity, no
//       local damping and no dashpot (restitution 1), dt = 0.5 sqrt(m_min / kn) (0.866 x critical_time_step()).
//   dem_bench lammps --packing FILE --dir DIR [--steps 2000]
//       Writes DIR/packing.data and DIR/in.bench: the same packing, law, walls, time step and
//       number of steps for LAMMPS (pair gran/hooke/history, fix wall/gran, nve/sphere disc).
//   dem_bench compare --ours FILE --lammps FILE
//       Compares two final states (ours, and LAMMPS's `write_dump ... modify sort id`).
//
// Parts: dem_bench.h; the packing file and the initial arrangement in dem_bench_packing.cc, the
// LAMMPS input and the comparison in dem_bench_lammps.cc.
#include "dem_bench.h"

#include <omp.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace geohybrid::dem;
using namespace dem_bench;

namespace
{
using Clock = std::chrono::steady_clock;
/// CPU time of the whole process (all threads) [s].
double process_cpu_seconds()
{
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
double seconds_since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

ContactParameters contact_parameters(double restitution)
{
  ContactParameters c;
  c.normal_stiffness   = kn;
  c.shear_stiffness    = 0.5 * kn;
  c.friction_angle_deg = friction_deg;
  c.shear_strength     = 0.0;
  c.tensile_strength   = 0.0;
  c.restitution        = restitution;
  c.bond_new_contacts  = false;
  return c;
}

void add_box_walls(DemSystem &system, const LinearContactLaw &law)
{
  // Active side on the left of start -> end (conventions in wall.h).
  system.add_wall(Wall("floor", Vec2(0.0, 0.0), Vec2(box_width, 0.0), law));
  system.add_wall(Wall("left", Vec2(0.0, wall_height), Vec2(0.0, 0.0), law));
  system.add_wall(Wall("right", Vec2(box_width, 0.0), Vec2(box_width, wall_height), law));
}

Args parse(int argc, char **argv, int first)
{
  Args a;
  for (int k = first; k < argc; ++k)
    {
      std::string s = argv[k];
      if (s.rfind("--", 0) != 0)
        throw std::invalid_argument("unexpected argument " + s);
      s = s.substr(2);
      if (k + 1 < argc && std::string(argv[k + 1]).rfind("--", 0) != 0)
        a.values[s] = argv[++k];
      else
        a.values[s] = "1";
    }
  return a;
}

// ---- statistics ------------------------------------------------------------------------------
struct State
{
  double kinetic = 0.0, max_speed = 0.0, coordination = 0.0, height = 0.0, weight_scale = 0.0;
};

State measure(const DemSystem &s)
{
  const ParticleSet &p = s.particles();
  State st;
  double weight_d = 0.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      st.kinetic += 0.5 * p.mass[b] * (p.vx[b] * p.vx[b] + p.vy[b] * p.vy[b]) +
                    0.5 * p.inertia[b] * p.omega[b] * p.omega[b];
      st.max_speed = std::max(st.max_speed, std::hypot(p.vx[b], p.vy[b]));
      st.height = std::max(st.height, p.y[b] + p.disc_radius[p.first_disc[b]]);
      weight_d += p.mass[b] * gravity * 2.0 * p.disc_radius[p.first_disc[b]];
    }
  st.weight_scale = weight_d; // sum of m g d: the energy scale of moving every disc by a diameter
  st.coordination = (2.0 * s.n_touching_pairs() + s.n_touching_wall_contacts()) / double(p.n_bodies());
  return st;
}

// ---- sub-commands ----------------------------------------------------------------------------
int prepare(const Args &a)
{
  const std::string path = a.get("packing");
  const std::size_t n = std::stoul(a.get("n", "40000"));
  const unsigned seed = static_cast<unsigned>(std::stoul(a.get("seed", "1")));
  const int threads = std::stoi(a.get("threads", "2"));
  const double ke_tolerance = std::stod(a.get("ke-tol", "1e-4")); // kinetic energy / sum(m g d)
  const std::uint64_t max_steps = std::stoull(a.get("max-steps", "400000"));

  Packing cached;
  if (read_packing(path, cached) && cached.info["version"] == std::to_string(packing_version) &&
      cached.info["n"] == std::to_string(n) && cached.info["seed"] == std::to_string(seed) &&
      cached.r.size() == n)
    {
      std::cout << "packing_cached=1\n";
      for (const auto &[k, v] : cached.info)
        std::cout << "packing_" << k << '=' << v << '\n';
      return 0;
    }

  omp_set_num_threads(threads);
  const auto t0 = Clock::now();
  Packing initial = drop_and_roll(n, seed);
  double h0 = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    h0 = std::max(h0, initial.y[i] + initial.r[i]);
  std::cerr << "prepare: " << n << " discs dropped and rolled into place up to " << h0 << " m; depositing on "
            << threads << " threads\n";

  const LinearContactLaw law(contact_parameters(0.5));
  DemSettings settings;
  settings.gravity       = Vec2(0.0, -gravity);
  settings.local_damping = 0.7;
  settings.n_threads     = threads;
  settings.track_energy  = false;
  DemSystem system(to_particles(initial), law, settings);
  add_box_walls(system, law);
  system.set_time_step(dt_safety * system.critical_time_step());

  const std::uint64_t check_every = 1000;
  State st;
  bool settled = false;
  while (system.step_count() < max_steps)
    {
      system.run_steps(check_every);
      st = measure(system);
      const double ke_ratio = st.kinetic / st.weight_scale;
      if (system.step_count() % 5000 == 0)
        std::cerr << "  step " << system.step_count() << " t=" << system.time() << " s  height="
                  << st.height << " m  CN=" << st.coordination << "  KE/(sum m g d)=" << ke_ratio
                  << "  vmax=" << st.max_speed << " m/s  (" << seconds_since(t0) << " s)\n";
      if (st.coordination >= 3.0 && ke_ratio < ke_tolerance)
        {
          settled = true;
          break;
        }
    }
  const double wall_seconds = seconds_since(t0);
  if (!settled)
    {
      std::cerr << "prepare: not settled after " << system.step_count() << " steps (CN "
                << st.coordination << ", KE ratio " << st.kinetic / st.weight_scale << ")\n";
      return 2;
    }

  Packing out;
  const ParticleSet &p = system.particles();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      out.r.push_back(p.disc_radius[p.first_disc[b]]);
      out.x.push_back(p.x[b]);
      out.y.push_back(p.y[b]);
    }
  char buf[64];
  out.info["version"] = std::to_string(packing_version);
  out.info["n"] = std::to_string(n);
  out.info["seed"] = std::to_string(seed);
  out.info["settle_steps"] = std::to_string(system.step_count());
  std::snprintf(buf, sizeof buf, "%.6g", system.time());
  out.info["settle_sim_time_s"] = buf;
  std::snprintf(buf, sizeof buf, "%.1f", wall_seconds);
  out.info["settle_wall_s"] = buf;
  out.info["settle_threads"] = std::to_string(threads);
  std::snprintf(buf, sizeof buf, "%.4f", st.coordination);
  out.info["settle_coordination"] = buf;
  std::snprintf(buf, sizeof buf, "%.3g", st.kinetic / st.weight_scale);
  out.info["settle_ke_ratio"] = buf;
  std::snprintf(buf, sizeof buf, "%.4g", st.max_speed);
  out.info["settle_vmax"] = buf;
  std::snprintf(buf, sizeof buf, "%.4f", st.height);
  out.info["settle_height_m"] = buf;
  std::snprintf(buf, sizeof buf, "%.4f", h0);
  out.info["initial_height_m"] = buf;
  write_packing(path, out);
  std::cout << "packing_cached=0\n";
  for (const auto &[k, v] : out.info)
    std::cout << "packing_" << k << '=' << v << '\n';
  return 0;
}
} // namespace

/// Loads the packing into a fresh system configured for the timed phase.
DemSystem dem_bench::timed_system(const Packing &packing, int threads, bool track_energy, bool shuffle, bool sort)
{
  Packing p = packing;
  if (shuffle)
    {
      std::vector<std::size_t> order(p.r.size());
      std::iota(order.begin(), order.end(), 0);
      std::shuffle(order.begin(), order.end(), std::mt19937_64(12345));
      Packing q;
      for (std::size_t k : order)
        {
          q.r.push_back(p.r[k]);
          q.x.push_back(p.x[k]);
          q.y.push_back(p.y[k]);
        }
      p = q;
    }
  const LinearContactLaw law(contact_parameters(1.0)); // no dashpot: LAMMPS gamma_n = 0
  DemSettings settings;
  settings.gravity       = Vec2(0.0, -gravity);
  settings.local_damping = 0.0;
  settings.n_threads     = threads;
  settings.track_energy  = track_energy;
  ParticleSet particles = to_particles(p);
  if (sort) // Morton order of cells one largest diameter wide
    particles = spatially_sorted(particles, 2.0 * *std::max_element(p.r.begin(), p.r.end()));
  DemSystem system(std::move(particles), law, settings);
  add_box_walls(system, law);
  system.set_time_step(dt_safety * system.critical_time_step());
  return system;
}

namespace
{
int time_run(const Args &a)
{
  Packing packing;
  if (!read_packing(a.get("packing"), packing))
    throw std::runtime_error("cannot read packing " + a.get("packing"));
  const int threads = std::stoi(a.get("threads"));
  const std::uint64_t steps = std::stoull(a.get("steps", "2000"));
  const bool track_energy = a.flag("track-energy");
  const bool shuffle = a.flag("shuffle");
  const bool sort = a.flag("sort");
  // DemSystem passes num_threads to its own loops, but ParticleSet::update_disc_positions uses
  // the default team: set it too so that "1 thread" means one thread everywhere.
  omp_set_num_threads(threads);

  DemSystem system = timed_system(packing, threads, track_energy, shuffle, sort);
  const std::size_t n = system.particles().n_bodies();
  system.step(); // lists and forces at t = 0 plus one step: LAMMPS's "run 1"
  const std::uint64_t rebuilds0 = system.n_neighbour_rebuilds();
  const double cpu0 = process_cpu_seconds();
  const auto t0 = Clock::now();
  system.run_steps(steps);
  const double seconds = seconds_since(t0);
  const double cpu_seconds = process_cpu_seconds() - cpu0;
  const State st = measure(system);

  std::printf("threads=%d\nsteps=%llu\nparticles=%zu\ndt=%.17g\nseconds=%.6f\n", threads,
              static_cast<unsigned long long>(steps), n, system.time_step(), seconds);
  std::printf("cpu_seconds=%.6f\n", cpu_seconds);
  std::printf("particle_steps_per_s=%.6g\n", double(n) * double(steps) / seconds);
  // Per CPU second (all threads): a load-independent figure when other processes share the machine.
  std::printf("particle_steps_per_cpu_s=%.6g\n", double(n) * double(steps) / cpu_seconds);
  std::printf("neighbour_rebuilds=%llu\npair_candidates=%zu\ntouching_pairs=%zu\n",
              static_cast<unsigned long long>(system.n_neighbour_rebuilds() - rebuilds0),
              system.pair_contacts().size(), system.n_touching_pairs());
  std::printf("final_kinetic_energy=%.6g\nfinal_max_speed=%.6g\nfinal_coordination=%.4f\n",
              st.kinetic, st.max_speed, st.coordination);
  {
    // How much of the pair loop checks body ownership (PairContacts: the first pairs of each
    // chunk after the first), and how many bodies are completed after the chunks.
    const PairContacts &c = system.pair_contacts();
    std::size_t checked = 0;
    for (std::size_t k = 0; k < c.n_chunks; ++k)
      checked += c.chunk_checked_end[k] - c.chunk_begin(k);
    std::printf("pair_chunks=%zu\npairs_checked_for_ownership=%zu\nshared_bodies=%zu\n", c.n_chunks, checked,
                c.shared_body.size());
  }

  if (a.values.count("final"))
    {
      std::ofstream out(a.get("final"));
      out << "# id x y vx vy omega (id = line of the packing file, 1-based)\n";
      const ParticleSet &p = system.particles();
      char line[256];
      std::vector<std::size_t> by_id(n);
      for (std::size_t b = 0; b < n; ++b)
        by_id[static_cast<std::size_t>(p.body_id[b] - 1)] = b;
      for (std::size_t k = 0; k < n; ++k)
        {
          const std::size_t b = by_id[k];
          std::snprintf(line, sizeof line, "%lld %.17g %.17g %.17g %.17g %.17g\n",
                        static_cast<long long>(p.body_id[b]), p.x[b], p.y[b], p.vx[b], p.vy[b], p.omega[b]);
          out << line;
        }
    }
  return 0;
}
} // namespace

int main(int argc, char **argv)
{
  try
    {
      if (argc < 2)
        throw std::invalid_argument("usage: dem_bench prepare|time|lammps|compare [options]");
      const std::string command = argv[1];
      const Args a = parse(argc, argv, 2);
      if (command == "prepare")
        return prepare(a);
      if (command == "time")
        return time_run(a);
      if (command == "lammps")
        return write_lammps(a);
      if (command == "compare")
        return compare(a);
      throw std::invalid_argument("unknown command " + command);
    }
  catch (const std::exception &e)
    {
      std::cerr << "dem_bench: " << e.what() << '\n';
      return 1;
    }
}
