// dem_bench's packing (bench/dem_bench.h): the packing file, and the initial arrangement of the
// discs by a geometric "drop and roll", which the deposition (dem_bench prepare) then settles.
#include "dem_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace geohybrid::dem;

namespace dem_bench
{
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

namespace
{
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
} // namespace

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
} // namespace dem_bench
