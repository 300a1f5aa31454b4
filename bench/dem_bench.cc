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
#include "dem/dem_system.h"

#include <omp.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace geohybrid::dem;

namespace
{
// ---- the benchmark's fixed setup -------------------------------------------------------------
constexpr double r_min       = 1.5e-3;  // [m]
constexpr double r_max       = 2.5e-3;  // [m]
constexpr double density     = 2650.0;  // [kg/m^3]
constexpr double box_width   = 1.0;     // [m]
constexpr double wall_height = 3.0;     // side walls reach well above the packing [m]
constexpr double kn          = 7.0e7;   // [N/m/m]
constexpr double friction_deg = 10.0;
constexpr double gravity     = 9.81;
// dt = 0.5 sqrt(m_min / kn), the step of every measurement in bench/RESULTS.md: the critical step
// of discs with ks = kn / 2 is sqrt(m / kn) / sqrt(3) (a dense-packing bound), so 0.866 of it.
constexpr double dt_safety   = 0.5 * 1.7320508075688772;
constexpr int packing_version = 2;      // bump when the deposition procedure changes

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

// ---- command line ----------------------------------------------------------------------------
struct Args
{
  std::map<std::string, std::string> values;
  std::string get(const std::string &key, const std::string &fallback = "") const
  {
    auto it = values.find(key);
    if (it != values.end())
      return it->second;
    if (fallback.empty())
      throw std::invalid_argument("missing option --" + key);
    return fallback;
  }
  bool flag(const std::string &key) const { return values.count(key) > 0; }
};

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

// ---- packing file ----------------------------------------------------------------------------
struct Packing
{
  std::vector<double> x, y, r;
  std::map<std::string, std::string> info; // header key=value pairs
};

void write_packing(const std::string &path, const Packing &p)
{
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out)
      throw std::runtime_error("cannot write " + tmp);
    out << "# geohybrid dem_bench packing";
    for (const auto &[k, v] : p.info)
      out << ' ' << k << '=' << v;
    out << "\n# radius x y [m]\n";
    char line[128];
    for (std::size_t i = 0; i < p.r.size(); ++i)
      {
        std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.r[i], p.x[i], p.y[i]);
        out << line;
      }
    if (!out)
      throw std::runtime_error("error writing " + tmp);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename " + tmp + " to " + path);
}

bool read_packing(const std::string &path, Packing &p)
{
  std::ifstream in(path);
  if (!in)
    return false;
  std::string line;
  while (std::getline(in, line))
    {
      if (line.empty())
        continue;
      if (line[0] == '#')
        {
          std::istringstream s(line.substr(1));
          std::string word;
          while (s >> word)
            {
              const auto eq = word.find('=');
              if (eq != std::string::npos)
                p.info[word.substr(0, eq)] = word.substr(eq + 1);
            }
          continue;
        }
      std::istringstream s(line);
      double r, x, y;
      if (!(s >> r >> x >> y))
        throw std::runtime_error("bad line in " + path + ": " + line);
      p.r.push_back(r);
      p.x.push_back(x);
      p.y.push_back(y);
    }
  return true;
}

ParticleSet to_particles(const Packing &p)
{
  ParticleSet set;
  set.reserve(p.r.size(), p.r.size());
  for (std::size_t i = 0; i < p.r.size(); ++i)
    set.add_disc(Vec2(p.x[i], p.y[i]), p.r[i], density, static_cast<std::int64_t>(i + 1));
  return set;
}

/// Throws if two discs overlap (cell grid).
void check_no_overlap(const Packing &p)
{
  const std::size_t n = p.r.size();
  const double cell = 2.0 * r_max;
  double ymax = 0.0;
  for (double v : p.y)
    ymax = std::max(ymax, v);
  const std::size_t ncx = static_cast<std::size_t>(box_width / cell) + 1;
  const std::size_t ncy = static_cast<std::size_t>(ymax / cell) + 1;
  std::vector<std::vector<std::size_t>> cells(ncx * ncy);
  for (std::size_t i = 0; i < n; ++i)
    cells[static_cast<std::size_t>(p.y[i] / cell) * ncx + static_cast<std::size_t>(p.x[i] / cell)].push_back(i);
  for (std::size_t i = 0; i < n; ++i)
    {
      const long cx = static_cast<long>(p.x[i] / cell), cy = static_cast<long>(p.y[i] / cell);
      for (long oy = -1; oy <= 1; ++oy)
        for (long ox = -1; ox <= 1; ++ox)
          {
            if (cx + ox < 0 || cy + oy < 0 || cx + ox >= long(ncx) || cy + oy >= long(ncy))
              continue;
            for (std::size_t j : cells[(cy + oy) * ncx + (cx + ox)])
              if (j > i && std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]) < p.r[i] + p.r[j])
                throw std::logic_error("initial arrangement: discs overlap");
          }
    }
}

// ---- initial arrangement: geometric "drop and roll" (Visscher & Bolsterli 1972) -------------
// Each disc falls at a random x until it meets the floor or a disc, then rolls down over that
// disc until a second support (disc, floor or wall) holds it, falling again when it rolls off.
// Supports are kept `gap` apart, so the discs start a few microns apart in a nearly stable,
// dense arrangement: gravity only has to close the gaps and load the contacts.
class DropAndRoll
{
public:
  DropAndRoll(Packing &p, double gap) : p_(p), gap_(gap), cell_(2.0 * r_max + 2.0 * gap), ncx_(std::size_t(box_width / cell_) + 1) {}

  /// Drops a disc of radius r at x0; false if it found no stable place (then nothing is added).
  bool drop(double r, double x0)
  {
    double x = std::clamp(x0, r + gap_, box_width - r - gap_);
    double y = std::numeric_limits<double>::max();
    for (int iteration = 0; iteration < 200; ++iteration)
      {
        long support;
        y = fall(r, x, y, support);
        if (support < 0)
          return place(r, x, y); // on the floor
        // Roll over disc a, away from its centre.
        long a = support;
        for (int roll = 0; roll < 50; ++roll)
          {
            const double xa = p_.x[a], ya = p_.y[a], R = r + p_.r[a] + gap_;
            double theta0 = std::atan2(y - ya, x - xa);
            if (theta0 <= 0.0 || theta0 >= pi)
              break; // below the support's centre: fall from here
            const bool right = x > xa || (x == xa && (a % 2 == 0));
            const double theta_end = right ? 0.0 : pi;
            double theta_hit = theta_end;
            long hit = -3; // -3: none, -2: wall, -1: floor, >= 0: disc
            const auto consider = [&](double theta, long what) {
              if (right ? (theta < theta0 - 1e-12 && theta > theta_hit) : (theta > theta0 + 1e-12 && theta < theta_hit))
                {
                  theta_hit = theta;
                  hit = what;
                }
            };
            // Floor: ya + R sin(theta) = r + gap.
            const double sf = (r + gap_ - ya) / R;
            if (std::abs(sf) <= 1.0)
              consider(right ? std::asin(sf) : pi - std::asin(sf), -1);
            // Walls: xa + R cos(theta) = r + gap or = width - r - gap (upper half circle).
            for (double xw : {r + gap_, box_width - r - gap_})
              {
                const double cw = (xw - xa) / R;
                if (std::abs(cw) <= 1.0)
                  consider(std::acos(cw), -2);
              }
            // Discs near a.
            for_near(xa, ya, R + r + r_max + 2.0 * gap_, [&](std::size_t k) {
              if (long(k) == a)
                return;
              const double dx = p_.x[k] - xa, dy = p_.y[k] - ya, d = std::hypot(dx, dy);
              const double Rk = r + p_.r[k] + gap_;
              if (d >= R + Rk || d <= std::abs(R - Rk) || d == 0.0)
                return;
              const double phi = std::atan2(dy, dx);
              const double alpha = std::acos(std::clamp((R * R + d * d - Rk * Rk) / (2.0 * R * d), -1.0, 1.0));
              for (double t : {phi + alpha, phi - alpha})
                {
                  while (t > pi) t -= 2.0 * pi;
                  while (t <= -pi) t += 2.0 * pi;
                  consider(t, long(k));
                }
            });
            x = xa + R * std::cos(theta_hit);
            y = ya + R * std::sin(theta_hit);
            if (hit == -3)
              break; // rolled off a: fall again
            if (hit == -1 || hit == -2)
              return place(r, x, y);
            // Held by a and disc `hit`: stable if they are on either side of the centre.
            const bool other_side = right ? p_.x[hit] > x : p_.x[hit] < x;
            if (other_side)
              return place(r, x, y);
            a = hit; // both supports on one side: roll on over the outer one
          }
      }
    return false;
  }

private:
  template <class F> void for_near(double x, double y, double reach, F &&f) const
  {
    const long cx0 = std::max(0L, long((x - reach) / cell_)), cx1 = std::min(long(ncx_) - 1, long((x + reach) / cell_));
    const long cy0 = std::max(0L, long((y - reach) / cell_)), cy1 = std::min(long(rows_()) - 1, long((y + reach) / cell_));
    for (long cy = cy0; cy <= cy1; ++cy)
      for (long cx = cx0; cx <= cx1; ++cx)
        for (std::size_t k : cells_[cy * ncx_ + cx])
          f(k);
  }
  std::size_t rows_() const { return cells_.size() / ncx_; }

  /// Highest y <= y_from where a disc of radius r at x rests on the floor or a disc.
  double fall(double r, double x, double y_from, long &support) const
  {
    double best = r + gap_;
    support = -1;
    const double reach = r + r_max + gap_;
    const long cx0 = std::max(0L, long((x - reach) / cell_)), cx1 = std::min(long(ncx_) - 1, long((x + reach) / cell_));
    long top = long(rows_()) - 1;
    if (y_from < 1e300)
      top = std::min(top, long(y_from / cell_) + 1);
    for (long cy = top; cy >= 0; --cy)
      {
        if ((cy + 1) * cell_ + reach < best)
          break;
        for (long cx = cx0; cx <= cx1; ++cx)
          for (std::size_t k : cells_[cy * ncx_ + cx])
            {
              const double dx = x - p_.x[k], Rk = r + p_.r[k] + gap_;
              if (std::abs(dx) >= Rk)
                continue;
              const double yc = p_.y[k] + std::sqrt(Rk * Rk - dx * dx);
              if (yc <= y_from + 1e-12 && yc > best)
                {
                  best = yc;
                  support = long(k);
                }
            }
      }
    return best;
  }

  bool place(double r, double x, double y)
  {
    // Refuse a place that overlaps (a corner case of the geometry).
    bool clear = y >= r && x >= r && x <= box_width - r;
    if (rows_() > 0)
      for_near(x, y, r + r_max + gap_, [&](std::size_t k) {
        if (std::hypot(p_.x[k] - x, p_.y[k] - y) < r + p_.r[k] + 0.5 * gap_)
          clear = false;
      });
    if (!clear)
      return false;
    const std::size_t cy = std::size_t(y / cell_), cx = std::min(ncx_ - 1, std::size_t(x / cell_));
    if (cy >= rows_())
      cells_.resize((cy + 1) * ncx_);
    cells_[cy * ncx_ + cx].push_back(p_.r.size());
    p_.r.push_back(r);
    p_.x.push_back(x);
    p_.y.push_back(y);
    return true;
  }

  Packing &p_;
  double gap_, cell_;
  std::size_t ncx_;
  std::vector<std::vector<std::size_t>> cells_;
};

Packing drop_and_roll(std::size_t n, unsigned seed)
{
  const double gap = 1e-5; // [m]
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> radius(r_min, r_max), unit(0.0, 1.0);
  Packing p;
  DropAndRoll generator(p, gap);
  std::size_t failures = 0;
  while (p.r.size() < n)
    {
      const double r = radius(rng);
      while (!generator.drop(r, unit(rng) * box_width))
        if (++failures > n)
          throw std::runtime_error("drop and roll: too many discs found no place");
    }
  // Number the discs row by row (bands one large diameter high, then x), as a lattice would.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  const auto band = [&](std::size_t k) { return long(p.y[k] / (2.0 * r_max)); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return band(a) != band(b) ? band(a) < band(b) : p.x[a] < p.x[b];
  });
  Packing sorted;
  for (std::size_t k : order)
    {
      sorted.r.push_back(p.r[k]);
      sorted.x.push_back(p.x[k]);
      sorted.y.push_back(p.y[k]);
    }
  check_no_overlap(sorted);
  std::cerr << "drop and roll: " << failures << " drops retried\n";
  return sorted;
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

/// Loads the packing into a fresh system configured for the timed phase.
DemSystem timed_system(const Packing &packing, int threads, bool track_energy, bool shuffle, bool sort)
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

int write_lammps(const Args &a)
{
  Packing packing;
  if (!read_packing(a.get("packing"), packing))
    throw std::runtime_error("cannot read packing " + a.get("packing"));
  const std::string dir = a.get("dir");
  const std::uint64_t steps = std::stoull(a.get("steps", "2000"));
  const DemSystem system = timed_system(packing, 1, false, false, false);
  const ParticleSet &p = system.particles();
  const std::size_t n = p.n_bodies();
  double ymax = 0.0, rmin = 1e9, total_mass = 0.0;
  for (std::size_t b = 0; b < n; ++b)
    {
      ymax = std::max(ymax, p.y[b] + p.disc_radius[b]);
      rmin = std::min(rmin, p.disc_radius[b]);
      total_mass += p.mass[b];
    }
  char line[256];
  {
    std::ofstream out(dir + "/packing.data");
    out << "geohybrid dem_bench packing (2D discs, z = 0)\n\n" << n << " atoms\n1 atom types\n\n";
    std::snprintf(line, sizeof line, "0 %.17g xlo xhi\n0 %.17g ylo yhi\n-0.5 0.5 zlo zhi\n\n",
                  box_width, 1.5 * ymax);
    out << line << "Atoms # sphere\n\n";
    // atom_style sphere: id type diameter density x y z. This LAMMPS (29 Sep 2021) turns the
    // density into a mass with the sphere volume 4/3 pi r^3 even in 2D, so the density written is
    // the one that gives our disc mass per metre, m = rho pi r^2: rho' = 3 rho / (4 r).
    for (std::size_t b = 0; b < n; ++b)
      {
        const double r = p.disc_radius[b];
        const double rho = p.mass[b] / (4.0 / 3.0 * pi * r * r * r);
        std::snprintf(line, sizeof line, "%zu 1 %.17g %.17g %.17g %.17g 0\n", b + 1, 2.0 * r, rho,
                      p.x[b], p.y[b]);
        out << line;
      }
  }
  const LinearContactLaw &law = system.particle_law();
  const double skin = 0.4 * rmin;
  std::ofstream in(dir + "/in.bench");
  in << "# Generated by dem_bench: the timed phase of geohybrid's DEM benchmark, for LAMMPS.\n"
        "units           si\n"
        "dimension       2\n"
        "boundary        f fm p\n"
        "atom_style      sphere\n"
        "atom_modify     map array\n"
        "comm_modify     vel yes\n"
        "newton          on\n"
        "read_data       packing.data\n";
  std::snprintf(line, sizeof line, "neighbor        %.17g bin\n", skin);
  in << line << "neigh_modify    delay 0 every 1 check yes\n";
  char law_args[200];
  std::snprintf(law_args, sizeof law_args, "%.17g %.17g 0 0 %.17g 0", law.normal_stiffness(),
                law.shear_stiffness(), law.friction_coefficient());
  in << "pair_style      gran/hooke/history " << law_args << "\npair_coeff      * *\n";
  in << "fix             integrate all nve/sphere disc\n";
  std::snprintf(line, sizeof line, "fix             gravity all gravity %.17g vector 0 -1 0\n", gravity);
  in << line;
  in << "fix             floor all wall/gran hooke/history " << law_args << " yplane 0 NULL\n";
  std::snprintf(line, sizeof line, "fix             sides all wall/gran hooke/history %s xplane 0 %.17g\n",
                law_args, box_width);
  in << line << "fix             twod all enforce2d\n";
  std::snprintf(line, sizeof line, "timestep        %.17g\n", system.time_step());
  in << line;
  in << "compute         pa all property/atom radius omegaz\n"
        "variable        m atom mass\n"
        "variable        speed atom sqrt(vx*vx+vy*vy)\n"
        "variable        ek atom 0.5*mass*(vx*vx+vy*vy)+0.25*mass*c_pa[1]*c_pa[1]*c_pa[2]*c_pa[2]\n"
        "compute         mtot all reduce sum v_m\n"
        "compute         ke all reduce sum v_ek\n"
        "compute         vmax all reduce max v_speed\n"
        "thermo_style    custom step c_mtot c_ke c_vmax\n"
        "thermo_modify   norm no\n";
  std::snprintf(line, sizeof line, "thermo          %llu\n", static_cast<unsigned long long>(steps));
  in << line;
  std::snprintf(line, sizeof line, "print           \"BENCH expected_total_mass=%.17g\"\n", total_mass);
  in << line;
  in << "# One untimed step (lists, forces at t = 0), as dem_bench does before timing.\n"
        "run             1\n";
  std::snprintf(line, sizeof line, "run             %llu\n", static_cast<unsigned long long>(steps));
  in << line;
  in << "print           \"BENCH lammps_total_mass=$(c_mtot:%.17g) final_kinetic_energy=$(c_ke:%.6g) "
        "final_max_speed=$(c_vmax:%.6g)\"\n"
        "write_dump      all custom final.dump id x y vx vy c_pa[2] modify sort id format float %.17g\n";
  std::cout << "lammps_dir=" << dir << "\nlammps_skin=" << skin << "\ndt=" << system.time_step() << '\n';
  return 0;
}

/// Reads "id x y vx vy omega" rows (lines starting with '#' or non-numeric headers are skipped).
std::map<long long, std::vector<double>> read_state(const std::string &path, bool lammps_dump)
{
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("cannot read " + path);
  std::map<long long, std::vector<double>> rows;
  std::string line;
  bool in_atoms = !lammps_dump;
  while (std::getline(in, line))
    {
      if (lammps_dump && line.rfind("ITEM: ATOMS", 0) == 0)
        {
          in_atoms = true;
          continue;
        }
      if (!in_atoms || line.empty() || line[0] == '#')
        continue;
      std::istringstream s(line);
      long long id;
      std::vector<double> v(5);
      if (s >> id >> v[0] >> v[1] >> v[2] >> v[3] >> v[4])
        rows[id] = v;
    }
  return rows;
}

int compare(const Args &a)
{
  const auto ours = read_state(a.get("ours"), false);
  const auto lmp = read_state(a.get("lammps"), true);
  if (ours.size() != lmp.size() || ours.empty())
    throw std::runtime_error("compare: different particle counts");
  double max_dpos = 0.0, max_dvel = 0.0, sum_dpos = 0.0;
  for (const auto &[id, v] : ours)
    {
      const auto it = lmp.find(id);
      if (it == lmp.end())
        throw std::runtime_error("compare: id missing in LAMMPS dump");
      const auto &w = it->second;
      const double dp = std::hypot(v[0] - w[0], v[1] - w[1]);
      max_dpos = std::max(max_dpos, dp);
      sum_dpos += dp;
      max_dvel = std::max(max_dvel, std::hypot(v[2] - w[2], v[3] - w[3]));
    }
  std::printf("max_position_difference=%.6g\nmean_position_difference=%.6g\nmax_velocity_difference=%.6g\n",
              max_dpos, sum_dpos / double(ours.size()), max_dvel);
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
