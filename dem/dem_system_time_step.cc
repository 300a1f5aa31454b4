// The stable time step: the critical step of the system as it is (particles, walls, sheets,
// energy weights), and the step set from it or checked against it.
#include "dem_system.h"

#include "dem_system_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
void DemSystem::update_time_step()
{
  // One definition: the automatic step is the safety factor times the critical step of the
  // system as it is now (walls, sheets, weights included), never of an earlier one; a step fixed
  // when the particles alone were known and kept while it stayed below the new limit gave 0.84 of
  // the critical step for the 0.5 asked on a scene of stiffer walls.
  set_time_step(settings_.time_step > 0.0 ? time_step_ : settings_.time_step_safety * critical_time_step());
}

double DemSystem::critical_time_step() const
{
  // The stiffest law any contact of the system can have.
  double kn_max = particle_law_.normal_stiffness(), ks_max = particle_law_.shear_stiffness();
  for (const Wall &w : walls_)
    {
      kn_max = std::max(kn_max, w.law.normal_stiffness());
      ks_max = std::max(ks_max, w.law.shear_stiffness());
    }
  for (const SparSheet &sheet : sheets_)
    {
      const LinearContactLaw &law = sheet.interface_law();
      kn_max = std::max(kn_max, law.normal_stiffness());
      ks_max = std::max(ks_max, law.shear_stiffness());
    }
  const ParticleSet &p = particles_;
  const bool with_weights = weighted();
  const double largest_radius = with_weights ? detail::largest_disc_radius(p) : 0.0;
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      if (p.inverse_mass[b] == 0.0)
        continue;
      const double n_contacts = max_contacts_per_disc * p.n_discs[b];
      // Rotational stiffness of the contacts about the centre of mass, for contacts spread evenly
      // round each disc (d: the disc's offset from the centre of mass, r its radius): the shear
      // spring acts at a lever r + d cos(theta), the normal spring at d sin(theta), whose squares
      // average to r^2 + d^2 / 2 and d^2 / 2.
      double rotational_stiffness = 0.0;
      for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
        {
          const double offset2 = p.disc_offset_x[d] * p.disc_offset_x[d] + p.disc_offset_y[d] * p.disc_offset_y[d];
          const double radius2 = p.disc_radius[d] * p.disc_radius[d];
          rotational_stiffness +=
            max_contacts_per_disc * (ks_max * (radius2 + 0.5 * offset2) + kn_max * 0.5 * offset2);
        }
      // With energy weights the mass is already weighted (and perhaps scaled:
      // CouplingAttachment::scale_band_inertia); the contacts' springs by at most
      // largest_contact_weight.
      const double stiffness_weight = with_weights ? coupling_->largest_contact_weight(p, b, largest_radius) : 1.0;
      const double omega2_translation = stiffness_weight * n_contacts * (kn_max + ks_max) * p.inverse_mass[b];
      const double omega2_rotation = stiffness_weight * 2.0 * rotational_stiffness * p.inverse_inertia[b];
      dt = std::min(dt, 2.0 / std::sqrt(std::max(omega2_translation, omega2_rotation)));
    }
  if (!sheets_.empty())
    {
      const double contact_stiffness = sheet_contact_stiffness();
      for (const SparSheet &sheet : sheets_)
        dt = std::min(dt, sheet.critical_time_step(contact_stiffness));
    }
  return dt;
}

void DemSystem::set_time_step(double dt)
{
  const double dt_crit = critical_time_step();
  if (!(dt > 0.0) || dt > dt_crit)
    {
      std::ostringstream message;
      message << "time step " << dt << " s is above the stable limit " << dt_crit
              << " s (the bound for a dense packing of these particles and stiffnesses, see "
                 "DemSystem::critical_time_step"
              << (sheets_.empty() ? "" : ", and sqrt(m_node / (2 J / l0 + k)) for the sheet nodes: "
                                         "raise the sheet's mass scaling")
              << "); lower 'time step' or leave it 0 for automatic";
      throw std::invalid_argument(message.str());
    }
  time_step_ = dt;
}
} // namespace geohybrid::dem
