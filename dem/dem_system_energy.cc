// The energy budget: the stored terms evaluated now, the booked ones (dissipation, boundary work)
// as accumulated by the step, and the thread-independent sum the booking uses.
#include "dem_system.h"

#include <algorithm>

namespace geohybrid::dem
{
double deterministic_sum(const SoaVector<double> &values, int n_threads)
{
  // At most 64 blocks whose size depends only on the number of values, never on the threads:
  // the partial sums and their order are the same on any number of threads, and the partial
  // sums live on the stack (no allocation in the step loop).
  constexpr std::size_t max_blocks = 64, min_block = 4096;
  const std::size_t n = values.size();
  const std::size_t block = std::max(min_block, (n + max_blocks - 1) / max_blocks);
  const std::size_t n_blocks = (n + block - 1) / block;
  double partial[max_blocks];
#pragma omp parallel for schedule(static) num_threads(n_threads) if (n_blocks > 1)
  for (std::size_t k = 0; k < n_blocks; ++k)
    {
      double s = 0.0;
      const std::size_t end = std::min(n, (k + 1) * block);
      for (std::size_t q = k * block; q < end; ++q)
        s += values[q];
      partial[k] = s;
    }
  double total = 0.0;
  for (std::size_t k = 0; k < n_blocks; ++k)
    total += partial[k];
  return total;
}

EnergyBudget DemSystem::energy() const
{
  const ParticleSet &p = particles_;
  const EnergyWeights *const weights = coupling_ ? coupling_->energy_weights() : nullptr;
  EnergyBudget e = accumulated_;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      if (p.inverse_mass[b] == 0.0)
        continue;
      const double scale = coupling_ ? coupling_->inertia_scale(b) : 1.0;
      e.kinetic += scale * (0.5 * p.mass[b] * (p.vx[b] * p.vx[b] + p.vy[b] * p.vy[b]) +
                            0.5 * p.inertia[b] * p.omega[b] * p.omega[b]);
      e.gravitational -= p.mass[b] * (settings_.gravity.x() * p.x[b] + settings_.gravity.y() * p.y[b]);
    }
  for (std::size_t q = 0; q < pairs_.size(); ++q)
    if (pairs_.state[q].touching)
      {
        const double stored = particle_law_.elastic_energy(pairs_.elastic_normal_force[q], pairs_.state[q].tangential_force);
        e.elastic += weights ? weights->contact_weight(p.disc_body[pairs_.disc_i[q]], p.disc_body[pairs_.disc_j[q]]) * stored
                             : stored;
      }
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (std::size_t q = 0; q < wall_contacts_[w].disc.size(); ++q)
      if (wall_contacts_[w].state[q].touching)
        e.elastic += walls_[w].law.elastic_energy(wall_contacts_[w].elastic_normal_force[q],
                                                  wall_contacts_[w].state[q].tangential_force);
  for (std::size_t s = 0; s < sheets_.size(); ++s)
    {
      const SparSheet &sheet = sheets_[s];
      const SheetContacts &c = sheet_contacts_[s];
      e.sheet_kinetic += sheet.kinetic_energy();
      e.sheet_elastic += sheet.elastic_energy();
      e.gravitational += sheet.gravitational_energy(settings_.gravity);
      for (std::size_t q = 0; q < c.size(); ++q)
        if (c.state[q].touching)
          e.elastic += sheet.interface_law().elastic_energy(c.elastic_normal_force[q], c.state[q].tangential_force);
      for (std::size_t w = 0; w < c.walls.size() && w < walls_.size(); ++w)
        for (std::size_t q = 0; q < c.walls[w].size(); ++q)
          if (c.walls[w].state[q].touching)
            e.elastic += walls_[w].law.elastic_energy(c.walls[w].elastic_normal_force[q],
                                                      c.walls[w].state[q].tangential_force);
    }
  return e;
}
} // namespace geohybrid::dem
