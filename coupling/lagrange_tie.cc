#include "lagrange_tie.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace geohybrid::coupling
{
LagrangeTie::LagrangeTie(const BandParticles &band, const dem::ParticleSet &particles,
                         const fem::ExplicitSolver &continuum)
  : band_(&band)
{
  const std::size_t n = band.size();
  const unsigned int n_nodes = band.points.nodes_per_point();
  const auto &mass = continuum.lumped_mass();
  for (unsigned int c = 0; c < 2; ++c)
    {
      // Per DoF, the band points it interpolates to, then A = D + N M^-1 N^T.
      std::vector<std::vector<std::pair<std::size_t, double>>> by_dof(mass.locally_owned_size());
      for (std::size_t p = 0; p < n; ++p)
        for (unsigned int k = 0; k < n_nodes; ++k)
          {
            const unsigned int dof = c == 0 ? band.points.x_dof(p, k) : band.points.y_dof(p, k);
            if (band.points.shape_value(p, k) != 0.0)
              by_dof[dof].emplace_back(p, band.points.shape_value(p, k));
          }
      std::vector<Eigen::Triplet<double>> entries;
      for (std::size_t p = 0; p < n; ++p)
        entries.emplace_back(p, p, particles.inverse_mass[band.body[p]]);
      for (unsigned int dof = 0; dof < by_dof.size(); ++dof)
        if (!by_dof[dof].empty() && !continuum.is_constrained(dof))
          {
            const double inverse_mass = 1.0 / mass.local_element(dof);
            for (const auto &[p, Np] : by_dof[dof])
              for (const auto &[q, Nq] : by_dof[dof])
                entries.emplace_back(p, q, Np * Nq * inverse_mass);
          }
      matrix_[c].resize(n, n);
      matrix_[c].setFromTriplets(entries.begin(), entries.end());
      factor_[c] = std::make_unique<Factor>(matrix_[c]);
      if (factor_[c]->info() != Eigen::Success)
        throw std::invalid_argument("Lagrange multiplier coupling: the constraint matrix is not positive definite "
                                    "(a band particle without mass?)");
    }
  for (unsigned int c = 0; c < 2; ++c)
    {
      gap_[c].resize(n);
      multiplier_[c].resize(n);
      work_[c].resize(n);
    }
  n_threads_ = static_cast<int>(std::max(1u, continuum.settings().n_threads));
  node_predictor_.assign(mass.locally_owned_size(), 0.0);
  // Each DoF the band's points interpolate from, once (a node is shared by the points round it).
  for (std::size_t p = 0; p < n; ++p)
    for (unsigned int k = 0; k < n_nodes; ++k)
      band_dofs_.insert(band_dofs_.end(), {band.points.x_dof(p, k), band.points.y_dof(p, k)});
  std::sort(band_dofs_.begin(), band_dofs_.end());
  band_dofs_.erase(std::unique(band_dofs_.begin(), band_dofs_.end()), band_dofs_.end());
}

void LagrangeTie::predict_nodes(const fem::ExplicitSolver &continuum, double tau)
{
  const auto &velocity = continuum.velocity();
  const auto &mass = continuum.lumped_mass();
  const auto &f_ext = continuum.external_force(), &f_int = continuum.internal_force();
  for (const unsigned int dof : band_dofs_)
    node_predictor_[dof] = velocity.local_element(dof) +
                           (continuum.is_constrained(dof)
                              ? 0.0
                              : tau * (f_ext.local_element(dof) - f_int.local_element(dof)) / mass.local_element(dof));
}

void LagrangeTie::solve(unsigned int component, const Eigen::VectorXd &b, Eigen::VectorXd &x)
{
  const Factor &f = *factor_[component];
  Eigen::VectorXd &work = work_[component];
  const auto &P = f.permutationP().indices();
  const auto &Pinv = f.permutationPinv().indices();
  for (Eigen::Index i = 0; i < b.size(); ++i)
    work[P[i]] = b[i];
  f.matrixL().solveInPlace(work);
  work.array() /= f.vectorD().array();
  f.matrixU().solveInPlace(work);
  for (Eigen::Index i = 0; i < b.size(); ++i)
    x[Pinv[i]] = work[i];
}

void LagrangeTie::add_to_nodes(fem::ExplicitSolver &continuum, std::size_t p, unsigned int component, double force,
                               CouplingForceSums &sums) const
{
  const BandPoints &points = band_->points;
  for (unsigned int k = 0; k < points.nodes_per_point(); ++k)
    {
      const double N = points.shape_value(p, k);
      continuum.add_external_force(component == 0 ? points.x_dof(p, k) : points.y_dof(p, k), N * force);
      sums.on_continuum[component] += N * force;
    }
}

void LagrangeTie::solve_and_apply(dem::ParticleSet &particles, fem::ExplicitSolver &continuum, double tau,
                                  double continuum_share, CouplingForceSums &sums)
{
#pragma omp parallel for num_threads(2) schedule(static, 1) if (n_threads_ > 1)
  for (int c = 0; c < 2; ++c)
    solve_component(static_cast<unsigned int>(c), particles, tau);
  last_solve_tau_ = tau;
  // On one thread: a node's x and y forces share a cache line, as do the sums' components.
  const BandParticles &band = *band_;
  for (unsigned int c = 0; c < 2; ++c)
    {
      double *const force = c == 0 ? particles.fx.data() : particles.fy.data();
      for (std::size_t p = 0; p < band.size(); ++p)
        {
          const double lambda = multiplier_[c][p];
          force[band.body[p]] -= lambda;
          sums.on_particles[c] -= lambda;
          add_to_nodes(continuum, p, c, lambda * continuum_share, sums);
        }
    }
}

double LagrangeTie::largest_velocity_gap() const
{
  double largest_gap = 0.0;
  for (unsigned int c = 0; last_solve_tau_ > 0.0 && c < 2; ++c)
    {
      const Eigen::VectorXd check = matrix_[c] * multiplier_[c];
      for (Eigen::Index p = 0; p < check.size(); ++p)
        largest_gap = std::max(largest_gap, last_solve_tau_ * std::abs(check[p] - gap_[c][p]));
    }
  return largest_gap;
}

void LagrangeTie::solve_component(unsigned int c, const dem::ParticleSet &particles, double tau)
{
  const BandParticles &band = *band_;
  const unsigned int n_nodes = band.points.nodes_per_point();
  const std::size_t n = band.size();
  Eigen::VectorXd &gap = gap_[c], &multiplier = multiplier_[c];
  const double *const v = c == 0 ? particles.vx.data() : particles.vy.data();
  const double *const force = c == 0 ? particles.fx.data() : particles.fy.data();
  for (std::size_t p = 0; p < n; ++p)
    {
      const std::uint32_t b = band.body[p];
      double interpolated = 0.0;
      for (unsigned int k = 0; k < n_nodes; ++k)
        interpolated += band.points.shape_value(p, k) *
                        node_predictor_[c == 0 ? band.points.x_dof(p, k) : band.points.y_dof(p, k)];
      gap[p] = (v[b] + tau * force[b] * particles.inverse_mass[b] - interpolated) / tau;
    }
  solve(c, gap, multiplier);
}

void LagrangeTie::apply(dem::ParticleSet &particles, fem::ExplicitSolver &continuum, const TieTiming &timing,
                        CouplingForceSums &sums)
{
  const double tau = timing.impulse_time;
  if (!(tau > 0.0))
    throw std::invalid_argument("Lagrange multiplier coupling: the time step must be positive");
  // The continuum's predictors at the band's nodes (a prescribed DoF keeps its velocity).
  predict_nodes(continuum, tau);
  solve_and_apply(particles, continuum, tau, 1.0, sums);
}

void LagrangeTie::apply_window_start(dem::ParticleSet &particles, fem::ExplicitSolver &continuum,
                                     double particle_impulse_time, double continuum_impulse_time,
                                     double particle_step, unsigned int ratio, CouplingForceSums &sums)
{
  const BandParticles &band = *band_;
  const double tau = particle_impulse_time, tau_c = continuum_impulse_time;
  if (!(tau > 0.0 && tau_c > 0.0 && particle_step > 0.0))
    throw std::invalid_argument("Lagrange multiplier coupling: the time steps must be positive");
  // The tied particles' forces now, over the rest of the window, go to the continuum first: its
  // predictors, and so the multipliers, see them.
  const double ahead = (ratio - 1) * particle_step / tau_c;
  for (unsigned int c = 0; c < 2; ++c)
    {
      const double *const force = c == 0 ? particles.fx.data() : particles.fy.data();
      for (std::size_t p = 0; p < band.size(); ++p)
        add_to_nodes(continuum, p, c, ahead * force[band.body[p]], sums);
    }
  predict_nodes(continuum, tau_c);
  // The multiplier acts on the particle over tau and on the nodes over tau_c: the same impulse.
  solve_and_apply(particles, continuum, tau, tau / tau_c, sums);
}

void LagrangeTie::apply_within_window(dem::ParticleSet &particles, const fem::ExplicitSolver &continuum,
                                      double particle_step, CouplingForceSums &sums)
{
  const BandParticles &band = *band_;
  const auto &velocity = continuum.velocity(); // the window's half-step velocity
  last_solve_tau_ = 0.0; // each particle's multiplier closes its gap exactly
  for (unsigned int c = 0; c < 2; ++c)
    {
      const double *const v = c == 0 ? particles.vx.data() : particles.vy.data();
      double *const force = c == 0 ? particles.fx.data() : particles.fy.data();
      for (std::size_t p = 0; p < band.size(); ++p)
        {
          const std::uint32_t b = band.body[p];
          double target = 0.0;
          for (unsigned int k = 0; k < band.points.nodes_per_point(); ++k)
            target += band.points.shape_value(p, k) *
                      velocity.local_element(c == 0 ? band.points.x_dof(p, k) : band.points.y_dof(p, k));
          const double inverse_mass = particles.inverse_mass[b];
          const double multiplier = (v[b] + particle_step * force[b] * inverse_mass - target) /
                                    (particle_step * inverse_mass);
          force[b] -= multiplier;
          sums.on_particles[c] -= multiplier;
        }
    }
}

} // namespace geohybrid::coupling
