#include "contact_list.h"

#include <algorithm>
#include <cmath>
#include <omp.h>
#include <stdexcept>

namespace geohybrid::dem
{
void PairContacts::resize_results()
{
  const std::size_t n = size();
  for (auto *v : {&force_x, &force_y, &torque_i, &torque_j, &elastic_normal_force, &friction_work, &viscous_work})
    v->assign(n, 0.0);
}

void NeighbourSearch::rebuild_pairs(const ParticleSet &p, double skin, int n_threads, PairContacts &pairs,
                                    bool carry_forces)
{
  const std::size_t nd = p.n_discs_total();
  std::swap(previous_.disc_i, pairs.disc_i);
  std::swap(previous_.disc_j, pairs.disc_j);
  std::swap(previous_.state, pairs.state);
  if (carry_forces)
    {
      std::swap(previous_.force_x, pairs.force_x);
      std::swap(previous_.force_y, pairs.force_y);
      std::swap(previous_.elastic_normal_force, pairs.elastic_normal_force);
    }
  pairs.disc_i.clear();
  pairs.disc_j.clear();
  pairs.state.clear();
  grid_ncx_ = grid_ncy_ = 0;

  if (nd > 0)
    {
      // Cells at least as wide as the largest interaction distance.
      double xmin = p.disc_x[0], xmax = xmin, ymin = p.disc_y[0], ymax = ymin, rmax = 0.0;
      for (std::size_t d = 0; d < nd; ++d)
        {
          xmin = std::min(xmin, p.disc_x[d]);
          xmax = std::max(xmax, p.disc_x[d]);
          ymin = std::min(ymin, p.disc_y[d]);
          ymax = std::max(ymax, p.disc_y[d]);
          rmax = std::max(rmax, p.disc_radius[d]);
        }
      double cell = 2.0 * rmax + skin;
      // Never more cells than a few per disc, even if a particle flew far away.
      while (((xmax - xmin) / cell + 1.0) * ((ymax - ymin) / cell + 1.0) > 4.0 * nd + 16.0)
        cell *= 2.0;
      const std::size_t ncx = static_cast<std::size_t>((xmax - xmin) / cell) + 1;
      const std::size_t ncy = static_cast<std::size_t>((ymax - ymin) / cell) + 1;
      const std::size_t nc = ncx * ncy;
      grid_x0_ = xmin;
      grid_y0_ = ymin;
      grid_cell_ = cell;
      grid_ncx_ = ncx;
      grid_ncy_ = ncy;

      // Counting sort of discs into cells (ascending disc index inside each cell).
      disc_cell_.resize(nd);
      cell_start_.assign(nc + 1, 0);
      for (std::size_t d = 0; d < nd; ++d)
        {
          const std::size_t cx = std::min(ncx - 1, static_cast<std::size_t>((p.disc_x[d] - xmin) / cell));
          const std::size_t cy = std::min(ncy - 1, static_cast<std::size_t>((p.disc_y[d] - ymin) / cell));
          disc_cell_[d] = static_cast<std::uint32_t>(cy * ncx + cx);
          ++cell_start_[disc_cell_[d] + 1];
        }
      for (std::size_t c = 0; c < nc; ++c)
        cell_start_[c + 1] += cell_start_[c];
      cell_disc_.resize(nd);
      {
        fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
        for (std::size_t d = 0; d < nd; ++d)
          cell_disc_[fill_[disc_cell_[d]]++] = static_cast<std::uint32_t>(d);
      }

      // Each thread scans a contiguous block of discs i and emits (i, j > i) in ascending order;
      // concatenating the blocks in thread order gives the same sorted list for any thread count.
      const int nt = std::max(1, n_threads);
      if (static_cast<int>(thread_i_.size()) < nt)
        {
          thread_i_.resize(nt);
          thread_j_.resize(nt);
        }
      bool overflow = false;
#pragma omp parallel num_threads(nt) reduction(|| : overflow)
      {
        const int t = omp_get_thread_num();
        std::vector<std::uint32_t> &out_i = thread_i_[t], &out_j = thread_j_[t];
        out_i.clear();
        out_j.clear();
        constexpr std::size_t max_neighbours = 512;
        std::uint32_t neighbours[max_neighbours];
#pragma omp for schedule(static)
        for (std::size_t i = 0; i < nd; ++i)
          {
            const double xi = p.disc_x[i], yi = p.disc_y[i], ri = p.disc_radius[i];
            const std::uint32_t bi = p.disc_body[i];
            const long cx = static_cast<long>(disc_cell_[i] % ncx), cy = static_cast<long>(disc_cell_[i] / ncx);
            std::size_t n_found = 0;
            for (long oy = -1; oy <= 1; ++oy)
              for (long ox = -1; ox <= 1; ++ox)
                {
                  const long nx = cx + ox, ny = cy + oy;
                  if (nx < 0 || ny < 0 || nx >= static_cast<long>(ncx) || ny >= static_cast<long>(ncy))
                    continue;
                  const std::size_t c = static_cast<std::size_t>(ny) * ncx + static_cast<std::size_t>(nx);
                  for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
                    {
                      const std::uint32_t j = cell_disc_[k];
                      if (j <= i || p.disc_body[j] == bi)
                        continue;
                      const double dx = p.disc_x[j] - xi, dy = p.disc_y[j] - yi;
                      const double reach = ri + p.disc_radius[j] + skin;
                      if (dx * dx + dy * dy < reach * reach)
                        {
                          if (n_found == max_neighbours)
                            overflow = true;
                          else
                            neighbours[n_found++] = j;
                        }
                    }
                }
            std::sort(neighbours, neighbours + n_found);
            for (std::size_t k = 0; k < n_found; ++k)
              {
                out_i.push_back(static_cast<std::uint32_t>(i));
                out_j.push_back(neighbours[k]);
              }
          }
      }
      if (overflow)
        throw std::runtime_error("neighbour search: a disc has more than 512 neighbours within the "
                                 "skin; the skin or the size ratio of the discs is far too large");
      for (int t = 0; t < nt; ++t)
        {
          pairs.disc_i.insert(pairs.disc_i.end(), thread_i_[t].begin(), thread_i_[t].end());
          pairs.disc_j.insert(pairs.disc_j.end(), thread_j_[t].begin(), thread_j_[t].end());
        }
    }

  // Carry the history over: both lists are sorted by (i, j).
  const std::size_t n = pairs.disc_i.size();
  pairs.state.assign(n, ContactState{});
  pairs.resize_results();
  std::size_t k = 0;
  for (std::size_t q = 0; q < n && k < previous_.disc_i.size(); ++q)
    {
      const auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
      const std::uint64_t target = key(pairs.disc_i[q], pairs.disc_j[q]);
      while (k < previous_.disc_i.size() && key(previous_.disc_i[k], previous_.disc_j[k]) < target)
        ++k;
      if (k < previous_.disc_i.size() && key(previous_.disc_i[k], previous_.disc_j[k]) == target)
        {
          pairs.state[q] = previous_.state[k];
          if (carry_forces)
            {
              pairs.force_x[q] = previous_.force_x[k];
              pairs.force_y[q] = previous_.force_y[k];
              pairs.elastic_normal_force[q] = previous_.elastic_normal_force[k];
            }
        }
    }

  build_body_adjacency(p, pairs, static_cast<std::size_t>(n_threads));
}

void build_body_adjacency(const ParticleSet &p, PairContacts &pairs, std::size_t n_chunks)
{
  const std::size_t nb = p.n_bodies(), n = pairs.size();
  pairs.body_offset.assign(nb + 1, 0);
  for (std::size_t q = 0; q < n; ++q)
    {
      ++pairs.body_offset[p.disc_body[pairs.disc_i[q]] + 1];
      ++pairs.body_offset[p.disc_body[pairs.disc_j[q]] + 1];
    }
  for (std::size_t b = 0; b < nb; ++b)
    pairs.body_offset[b + 1] += pairs.body_offset[b];
  pairs.body_entry.resize(2 * n);
  // Filling in ascending pair order keeps every body's list in a fixed order.
  SoaVector<std::uint32_t> &next = pairs.adjacency_scratch;
  next.assign(pairs.body_offset.begin(), pairs.body_offset.end() - 1);
  for (std::size_t q = 0; q < n; ++q)
    {
      pairs.body_entry[next[p.disc_body[pairs.disc_i[q]]]++] = static_cast<std::uint32_t>(2 * q);
      pairs.body_entry[next[p.disc_body[pairs.disc_j[q]]]++] = static_cast<std::uint32_t>(2 * q + 1);
    }

  // Ownership by chunks of pairs. A body's entries are in ascending pair order, so its first
  // entry is its lowest pair and its last entry its highest.
  pairs.n_chunks = std::max<std::size_t>(1, n_chunks);
  pairs.body_first_pair.assign(nb, static_cast<std::uint32_t>(n));
  pairs.shared_body.clear();
  pairs.shared_first_entry.clear();
  const auto chunk_of = [&pairs](std::size_t q) {
    std::size_t k = q * pairs.n_chunks / std::max<std::size_t>(1, pairs.size());
    while (k > 0 && q < pairs.chunk_begin(k)) // the integer divisions may land one chunk off
      --k;
    while (k + 1 < pairs.n_chunks && q >= pairs.chunk_begin(k + 1))
      ++k;
    return k;
  };
  for (std::size_t b = 0; b < nb; ++b)
    {
      const std::uint32_t begin = pairs.body_offset[b], end = pairs.body_offset[b + 1];
      if (begin == end)
        continue;
      const std::size_t first = pairs.body_entry[begin] >> 1, last = pairs.body_entry[end - 1] >> 1;
      pairs.body_first_pair[b] = static_cast<std::uint32_t>(first);
      const std::size_t owner_end = pairs.chunk_begin(chunk_of(first) + 1);
      if (last < owner_end)
        continue;
      std::uint32_t e = begin;
      while ((pairs.body_entry[e] >> 1) < owner_end)
        ++e;
      pairs.shared_body.push_back(static_cast<std::uint32_t>(b));
      pairs.shared_first_entry.push_back(e);
    }
  // The entries of a shared body from shared_first_entry on are its pairs in chunks that do not
  // own it: each such chunk must check ownership up to (and including) that pair.
  pairs.chunk_checked_end.resize(pairs.n_chunks);
  for (std::size_t k = 0; k < pairs.n_chunks; ++k)
    pairs.chunk_checked_end[k] = static_cast<std::uint32_t>(pairs.chunk_begin(k));
  for (std::size_t s = 0; s < pairs.shared_body.size(); ++s)
    for (std::uint32_t e = pairs.shared_first_entry[s]; e < pairs.body_offset[pairs.shared_body[s] + 1]; ++e)
      {
        const std::uint32_t q = pairs.body_entry[e] >> 1;
        std::uint32_t &checked_end = pairs.chunk_checked_end[chunk_of(q)];
        checked_end = std::max(checked_end, q + 1);
      }
}

void NeighbourSearch::append_discs_near_box(const Vec2 &lo, const Vec2 &hi, std::vector<std::uint32_t> &discs) const
{
  if (grid_ncx_ == 0 || grid_ncy_ == 0)
    return;
  // Cell index of a coordinate, clamped to the grid (discs beyond the grid's edges were put in
  // its outer cells).
  const auto cell_index = [this](double value, double origin, std::size_t n) {
    const double c = std::floor((value - origin) / grid_cell_);
    return std::isnan(c) ? std::size_t(0) : static_cast<std::size_t>(std::clamp(c, 0.0, static_cast<double>(n - 1)));
  };
  const std::size_t cx0 = cell_index(lo.x(), grid_x0_, grid_ncx_), cx1 = cell_index(hi.x(), grid_x0_, grid_ncx_);
  const std::size_t cy0 = cell_index(lo.y(), grid_y0_, grid_ncy_), cy1 = cell_index(hi.y(), grid_y0_, grid_ncy_);
  for (std::size_t cy = cy0; cy <= cy1; ++cy)
    for (std::size_t cx = cx0; cx <= cx1; ++cx)
      {
        const std::size_t c = cy * grid_ncx_ + cx;
        discs.insert(discs.end(), cell_disc_.begin() + cell_start_[c], cell_disc_.begin() + cell_start_[c + 1]);
      }
}

void NeighbourSearch::rebuild_wall(const ParticleSet &p, const Wall &wall, double skin, WallContacts &contacts)
{
  std::swap(previous_wall_.disc, contacts.disc);
  std::swap(previous_wall_.state, contacts.state);
  contacts.disc.clear();
  contacts.state.clear();
  Vec2 closest;
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    if (closest_point_on_segment(Vec2(p.disc_x[d], p.disc_y[d]), wall.start, wall.end, closest) <
        p.disc_radius[d] + skin)
      contacts.disc.push_back(static_cast<std::uint32_t>(d));
  contacts.state.assign(contacts.disc.size(), ContactState{});
  std::size_t k = 0;
  for (std::size_t q = 0; q < contacts.disc.size(); ++q)
    {
      while (k < previous_wall_.disc.size() && previous_wall_.disc[k] < contacts.disc[q])
        ++k;
      if (k < previous_wall_.disc.size() && previous_wall_.disc[k] == contacts.disc[q])
        contacts.state[q] = previous_wall_.state[k];
    }
  const std::size_t n = contacts.disc.size();
  for (auto *v : {&contacts.force_x, &contacts.force_y, &contacts.elastic_normal_force, &contacts.friction_work, &contacts.viscous_work})
    v->assign(n, 0.0);
  previous_wall_.disc.clear();
}
} // namespace geohybrid::dem
