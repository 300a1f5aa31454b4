// What a coupling to a continuum changes in a particle system: the bridging domain's energy
// weights, the band's scaled inertia and the bodies whose translation a constraint sets. An
// uncoupled system never meets these.
#include "coupling_attachment.h"

#include "dem_system_detail.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geohybrid::dem
{
void CouplingAttachment::refuse_when_attached(const char *what) const
{
  if (attached_)
    throw std::logic_error(std::string("DEM: ") + what +
                           " after the coupling is attached: they change the masses its time step was set for");
}

void CouplingAttachment::set_energy_weights(ParticleSet &p, EnergyWeights weights)
{
  refuse_when_attached("energy weights set");
  const std::string where = "DEM energy weights: ";
  if (weighted_)
    throw std::invalid_argument(where + "the weights are already set");
  if (!(weights.band_width > 0.0) || !std::isfinite(weights.band_width))
    throw std::invalid_argument(where + "parameter 'band width' = " + std::to_string(weights.band_width) +
                                " m must be positive");
  if (weights.body_band_coordinate.size() != p.n_bodies())
    throw std::invalid_argument(where + std::to_string(weights.body_band_coordinate.size()) +
                                " band coordinates for " + std::to_string(p.n_bodies()) + " bodies");
  // A body in the continuum-only region has no mass left; it may only be a fixed body (one the
  // coupling moves with the continuum, whose contacts with the band's bodies still carry weight).
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (!(weights.body_weight(b) > 0.0) && p.inverse_mass[b] != 0.0)
      throw std::invalid_argument(where + "body " + std::to_string(p.body_id[b]) +
                                  " lies in the continuum-only region (band coordinate " +
                                  std::to_string(weights.body_band_coordinate[b]) + " m >= band width " +
                                  std::to_string(weights.band_width) + " m) and is free: it has no energy to carry");
  // The particles' share of the kinetic energy (and of gravity, which acts on the mass).
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      const double weight = weights.body_weight(b);
      p.mass[b] *= weight;
      p.inertia[b] *= weight;
      if (p.inverse_mass[b] != 0.0)
        {
          p.inverse_mass[b] /= weight;
          p.inverse_inertia[b] /= weight;
        }
    }
  energy_weights_ = std::move(weights);
  weighted_ = true;
}

double CouplingAttachment::largest_contact_weight(const ParticleSet &p, std::size_t b, double largest_radius) const
{
  // The weight at the far end of the longest branch: twice the largest disc radius beyond the
  // body's farthest disc.
  double reach = 0.0;
  for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
    reach = std::max(reach, std::hypot(p.disc_offset_x[d], p.disc_offset_y[d]) + 2.0 * largest_radius);
  return energy_weights_.largest_contact_weight(b, reach);
}

double CouplingAttachment::scale_band_inertia(ParticleSet &p)
{
  refuse_when_attached("the band's inertia scaled");
  if (!weighted_)
    throw std::logic_error("DEM: scale_band_inertia needs the energy weights (set_energy_weights)");
  if (!inertia_scale_.empty())
    throw std::logic_error("DEM: the band's inertia is already scaled");
  inertia_scale_.assign(p.n_bodies(), 1.0);
  const double largest_radius = detail::largest_disc_radius(p);
  double largest = 1.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (p.inverse_mass[b] != 0.0)
      {
        const double factor = std::max(1.0, largest_contact_weight(p, b, largest_radius) / energy_weights_.body_weight(b));
        inertia_scale_[b] = factor;
        p.inverse_mass[b] /= factor;
        p.inverse_inertia[b] /= factor;
        largest = std::max(largest, factor);
      }
  return largest;
}

void CouplingAttachment::scale_inertia(ParticleSet &p, const std::vector<std::uint32_t> &bodies, double factor)
{
  refuse_when_attached("the tied bodies' inertia scaled");
  if (!(factor >= 1.0 && std::isfinite(factor)))
    throw std::invalid_argument("DEM: an inertia factor must be at least 1, not " + std::to_string(factor));
  if (inertia_scale_.empty())
    inertia_scale_.assign(p.n_bodies(), 1.0);
  for (const std::uint32_t b : bodies)
    {
      if (b >= p.n_bodies() || p.inverse_mass[b] == 0.0)
        throw std::invalid_argument("DEM: body index " + std::to_string(b) + " is out of range or fixed");
      inertia_scale_[b] *= factor;
      p.inverse_mass[b] /= factor;
      p.inverse_inertia[b] /= factor;
    }
}

void CouplingAttachment::set_constrained_bodies(const ParticleSet &p, const std::vector<std::uint32_t> &bodies)
{
  const std::size_t nb = p.n_bodies();
  if (bodies.empty())
    damping_scale_ = SoaVector<double>();
  else
    {
      SoaVector<double> scale;
      scale.assign(nb, 1.0);
      for (const std::uint32_t b : bodies)
        {
          if (b >= nb)
            throw std::invalid_argument("DEM: constrained body index " + std::to_string(b) + " is out of range (" +
                                        std::to_string(nb) + " bodies)");
          if (p.inverse_mass[b] == 0.0)
            throw std::invalid_argument("DEM: constrained body " + std::to_string(p.body_id[b]) + " is fixed");
          scale[b] = 0.0;
        }
      damping_scale_ = std::move(scale);
    }
}
} // namespace geohybrid::dem
