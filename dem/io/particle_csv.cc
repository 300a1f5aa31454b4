#include "particle_csv.h"

#include "checked_output.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace geohybrid::dem
{
ParticleSet read_particle_csv(const std::filesystem::path &file, double density, double overlap_tolerance)
{
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error("particle CSV '" + file.string() + "' cannot be opened");
  struct Row
  {
    double x, y, r, vx, vy, omega;
    long long cluster;
    std::size_t line;
  };
  std::vector<Row> rows;
  std::string line;
  std::size_t line_number = 0;
  const auto fail = [&](const std::string &what) {
    throw std::runtime_error("particle CSV '" + file.string() + "', line " + std::to_string(line_number) + ": " + what);
  };
  const auto n_fields = [](std::string text) {
    std::replace(text.begin(), text.end(), ',', ' ');
    std::istringstream words(text);
    std::size_t n = 0;
    for (std::string word; words >> word;)
      ++n;
    return n;
  };
  std::size_t header_fields = 0; // none: no header line
  while (std::getline(in, line))
    {
      ++line_number;
      if (line.empty() || line[0] == '#')
        continue;
      if (line_number == 1 || std::isalpha(static_cast<unsigned char>(line[0])))
        {
          header_fields = n_fields(line); // header
          continue;
        }
      // A row cut short would leave its last columns (a cluster id) silently unset.
      if (const std::size_t n = n_fields(line); n < header_fields)
        fail("has " + std::to_string(n) + " fields, fewer than the " + std::to_string(header_fields) + " of the header");
      std::replace(line.begin(), line.end(), ',', ' ');
      std::istringstream fields(line);
      Row row{0, 0, 0, 0, 0, 0, -1, line_number};
      if (!(fields >> row.x >> row.y >> row.r >> row.vx >> row.vy >> row.omega))
        fail("expected x, y, radius, vx, vy, omega[, cluster_id]");
      long long cluster;
      if (fields >> cluster)
        row.cluster = cluster;
      if (!(row.r > 0.0) || !std::isfinite(row.x) || !std::isfinite(row.y))
        fail("radius must be positive and coordinates finite");
      rows.push_back(row);
    }
  if (rows.empty())
    throw std::runtime_error("particle CSV '" + file.string() + "' holds no particle");

  // Overlap check with a cell grid: O(n).
  double r_max = 0.0, x_min = rows[0].x, y_min = rows[0].y, x_max = x_min, y_max = y_min;
  for (const Row &r : rows)
    {
      r_max = std::max(r_max, r.r);
      x_min = std::min(x_min, r.x);
      x_max = std::max(x_max, r.x);
      y_min = std::min(y_min, r.y);
      y_max = std::max(y_max, r.y);
    }
  const double cell = 2.0 * r_max;
  const std::size_t nx = static_cast<std::size_t>((x_max - x_min) / cell) + 1;
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> cells;
  for (std::size_t k = 0; k < rows.size(); ++k)
    cells[{static_cast<std::size_t>((rows[k].x - x_min) / cell), static_cast<std::size_t>((rows[k].y - y_min) / cell)}]
      .push_back(k);
  (void)nx;
  for (const auto &[key, members] : cells)
    for (std::size_t a : members)
      for (long dx = -1; dx <= 1; ++dx)
        for (long dy = -1; dy <= 1; ++dy)
          {
            const auto it = cells.find({key.first + dx, key.second + dy});
            if (it == cells.end())
              continue;
            for (std::size_t b : it->second)
              {
                if (b <= a || (rows[a].cluster >= 0 && rows[a].cluster == rows[b].cluster))
                  continue;
                const double overlap = rows[a].r + rows[b].r - std::hypot(rows[a].x - rows[b].x, rows[a].y - rows[b].y);
                if (overlap > overlap_tolerance * std::min(rows[a].r, rows[b].r))
                  {
                    line_number = rows[b].line;
                    std::ostringstream what;
                    what << "this particle overlaps the one on line " << rows[a].line << " by " << overlap
                         << " m, more than the tolerance (" << overlap_tolerance
                         << " x the smaller radius); fix the file or raise 'csv overlap tolerance'";
                    fail(what.str());
                  }
              }
          }

  ParticleSet p;
  std::map<long long, std::vector<std::size_t>> clusters;
  std::int64_t next_id = 0;
  for (std::size_t k = 0; k < rows.size(); ++k)
    {
      const Row &r = rows[k];
      if (r.cluster < 0)
        {
          const std::size_t b = p.add_disc(Vec2(r.x, r.y), r.r, density, next_id++);
          p.vx[b] = r.vx;
          p.vy[b] = r.vy;
          p.omega[b] = r.omega;
          continue;
        }
      std::vector<std::size_t> &members = clusters[r.cluster];
      members.push_back(k);
      if (members.size() > 2)
        {
          line_number = r.line;
          fail("cluster " + std::to_string(r.cluster) + " has more than two discs; only two-disc clusters exist");
        }
      if (members.size() < 2)
        continue;
      const Row &a = rows[members[0]], &c = rows[members[1]];
      const Vec2 pa(a.x, a.y), pc(c.x, c.y);
      const double spacing = (pc - pa).norm();
      if (spacing <= 0.0)
        {
          line_number = c.line;
          fail("the two discs of a cluster share one centre");
        }
      const Vec2 axis = (pc - pa) / spacing;
      const TwoDiscGeometry g = two_disc_geometry(a.r, c.r, spacing);
      const Vec2 centre_of_mass = pa + g.centroid_from_large * axis;
      const std::size_t b = p.add_two_disc_cluster(centre_of_mass, a.r, c.r, spacing,
                                                   std::atan2(axis.y(), axis.x()), density, next_id++);
      // The rows hold disc velocities; the body's is that of its centre of mass.
      const Vec2 v_com = Vec2(a.vx, a.vy) + spin_velocity(a.omega, centre_of_mass - pa);
      p.vx[b] = v_com.x();
      p.vy[b] = v_com.y();
      p.omega[b] = a.omega;
    }
  for (const auto &[id, members] : clusters)
    if (members.size() == 1)
      {
        line_number = rows[members[0]].line;
        fail("cluster " + std::to_string(id) + " has a single disc; give it a cluster_id of -1");
      }
  return p;
}

void write_particle_csv(const ParticleSet &p, const std::filesystem::path &file)
{
  std::ofstream out(file);
  out << "x,y,radius,vx,vy,omega,cluster_id\n" << std::setprecision(17);
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    {
      const std::uint32_t b = p.disc_body[d];
      const double lx = p.disc_x[d] - p.x[b], ly = p.disc_y[d] - p.y[b];
      out << p.disc_x[d] << ',' << p.disc_y[d] << ',' << p.disc_radius[d] << ','
          << p.vx[b] - p.omega[b] * ly << ',' << p.vy[b] + p.omega[b] * lx << ',' << p.omega[b] << ','
          << (p.n_discs[b] > 1 ? p.body_id[b] : -1) << '\n';
    }
  close_checked(out, file);
}
} // namespace geohybrid::dem
