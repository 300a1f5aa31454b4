#include "penalty_tie.h"

#include <algorithm>
#include <cmath>

namespace geohybrid::coupling
{
PenaltyTie::PenaltyTie(const PenaltyCoupling &parameters, const BandParticles &band, const dem::ParticleSet &particles,
                       const fem::ExplicitSolver &continuum, double band_width)
  : band_(&band)
{
  parameters.validate();
  const double young_modulus = continuum.soil().elasticity().young_modulus();
  for (std::size_t p = 0; p < band.size(); ++p)
    tied_displacement_.push_back(band.points.interpolate(continuum.displacement(), p));
  stiffness_.resize(band.size());
  for (std::size_t p = 0; p < band.size(); ++p)
    {
      // The body's size: twice the largest distance from its centre to a disc's far edge.
      const std::uint32_t b = band.body[p];
      double extent = 0.0;
      for (std::uint32_t d = particles.first_disc[b]; d < particles.first_disc[b] + particles.n_discs[b]; ++d)
        extent = std::max(extent, std::hypot(particles.disc_offset_x[d], particles.disc_offset_y[d]) +
                                    particles.disc_radius[d]);
      stiffness_[p] = parameters.penalty_factor * young_modulus * 2.0 * extent / band_width;
    }
}

void PenaltyTie::apply(dem::ParticleSet &particles, fem::ExplicitSolver &continuum, const TieTiming & /*timing*/,
                       CouplingForceSums &sums)
{
  const BandParticles &band = *band_;
  energy_ = 0.0;
  const auto &u = continuum.displacement();
  const unsigned int n_nodes = band.points.nodes_per_point();
  for (std::size_t p = 0; p < band.size(); ++p)
    {
      const std::uint32_t b = band.body[p];
      const Vec2 gap = Vec2(particles.x[b], particles.y[b]) - band.reference_position[p] -
                     (band.points.interpolate(u, p) - tied_displacement_[p]);
      const Vec2 force = stiffness_[p] * gap; // on the continuum; the particle gets -force
      energy_ += 0.5 * stiffness_[p] * gap.squaredNorm();
      particles.fx[b] -= force.x();
      particles.fy[b] -= force.y();
      sums.on_particles -= force;
      for (unsigned int k = 0; k < n_nodes; ++k)
        {
          const double N = band.points.shape_value(p, k);
          continuum.add_external_force(band.points.x_dof(p, k), N * force.x());
          continuum.add_external_force(band.points.y_dof(p, k), N * force.y());
          sums.on_continuum += N * force;
        }
    }
}

double PenaltyTie::squared_frequency_bound(const dem::ParticleSet &particles, const fem::ExplicitSolver &continuum) const
{
  const BandParticles &band = *band_;
  // Row sums of |M^-1 K|: a particle's row is k_p (1 + sum_I |N_I|) / m_p, a node's row
  // sum_p |N_I| k_p (1 + sum_J |N_J|) / M_I.
  const unsigned int n_nodes = band.points.nodes_per_point();
  std::vector<double> node_rows(continuum.lumped_mass().locally_owned_size(), 0.0);
  double largest = 0.0;
  for (std::size_t p = 0; p < band.size(); ++p)
    {
      double shape_sum = 0.0;
      for (unsigned int k = 0; k < n_nodes; ++k)
        shape_sum += std::abs(band.points.shape_value(p, k));
      largest = std::max(largest, stiffness_[p] * (1.0 + shape_sum) * particles.inverse_mass[band.body[p]]);
      for (unsigned int k = 0; k < n_nodes; ++k)
        node_rows[band.points.x_dof(p, k)] += std::abs(band.points.shape_value(p, k)) * stiffness_[p] * (1.0 + shape_sum);
    }
  for (unsigned int i = 0; i < node_rows.size(); ++i)
    if (node_rows[i] > 0.0)
      largest = std::max(largest, node_rows[i] / continuum.lumped_mass().local_element(i));
  return largest;
}
} // namespace geohybrid::coupling
