#pragma once
// Method 1, the bridging domain method with Lagrange multipliers (Xiao & Belytschko 2004, section
// 3): in the band, each particle's velocity equals the continuum's velocity interpolated at it,
//   g_p = v_p - sum_I N_I(X_p) v_I = 0,
// enforced exactly on the half-step velocities that set the displacement increments, so the
// particles and the continuum also move together (and the multipliers do no work: the coupled
// leapfrog conserves its energy).
//
// At time t_n both sides know their forces F_n and their velocities; with no coupling force their
// next half-step velocities would be the predictors v*_p = v_p + tau F_p / m_p and
// v*_I = v_I + tau f_I / M_I (tau: the time the forces act before the next drift, dt, or dt/2 at the
// start). A multiplier lambda_p, applied as -lambda_p to particle p and +N_I(X_p) lambda_p to node I,
// corrects them to v*_p - tau lambda_p / m_p and v*_I + tau sum_p N_I lambda_p / M_I; the constraint
// then reads, per component,
//   A lambda = g* / tau,   A_pq = delta_pq / m_p + sum_I N_I(X_p) N_I(X_q) / M_I,
// with g* the predictors' gap. m_p are the particles' weighted masses and M_I the continuum's
// weighted lumped masses (a node with a prescribed displacement counts as infinitely heavy). A is
// symmetric positive definite and constant (fixed weights, fixed X_p): it is factored once (sparse
// LDL^T, one per component since the constrained DoFs may differ) and each step costs two solves,
// one per thread when there are two (each component sums in its own order: the same bits).
#include "coupling/band_particles.h"
#include "coupling/coupling_forces.h"
#include "coupling/coupling_method.h"
#include "fem/explicit_solver.h"

#include <Eigen/SparseCholesky>

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace geohybrid::coupling
{
/// A coupling tie (coupling_tie.h).
class LagrangeTie
{
public:
  static constexpr std::string_view name = LagrangeMultiplierCoupling::name;

  /// `band` must outlive the tie: every apply() reads it.
  LagrangeTie(const BandParticles &band, const dem::ParticleSet &particles, const fem::ExplicitSolver &continuum);

  /// Solves for the multipliers at the current forces and velocities and applies them to both
  /// sides (the continuum's through ExplicitSolver::add_external_force), for timing.impulse_time.
  void apply(dem::ParticleSet &particles, fem::ExplicitSolver &continuum, const TieTiming &timing,
             CouplingForceSums &sums);
  double energy() const { return 0.0; } ///< a velocity constraint stores no energy

  // Multi-rate stepping (coupled_stepper.h): the continuum takes one step of `ratio` particle
  // steps dt (a window), with one half-step velocity over it, and the tied particles move with it.
  // At a window's start (both sides at T_n) the multipliers are solved as above, in impulses:
  // particle p receives -P_p over its impulse time, the nodes N_I P_p over the continuum's. The
  // continuum also receives, for the window, the tied particles' present forces over its rest,
  // (ratio - 1) dt F_p: the tied particles with the nodes are one body stepped at the window's
  // length, its forces sampled at the window's start as the continuum's are (the particles'
  // forces within the window are not passed on: passing their difference one window late, which
  // conserves momentum, lost a quarter of the energy of an undamped patch in 10,000 steps).
  // Within the window each tied particle keeps the continuum's velocity: its multiplier cancels
  // its net force.

  /// At a window's start: `particle_impulse_time` dt (dt / 2 at the first), `continuum_impulse_time`
  /// ratio times it, `particle_step` dt.
  void apply_window_start(dem::ParticleSet &particles, fem::ExplicitSolver &continuum, double particle_impulse_time,
                          double continuum_impulse_time, double particle_step, unsigned int ratio,
                          CouplingForceSums &sums);
  /// At the particles' steps within a window (the continuum already at its end).
  void apply_within_window(dem::ParticleSet &particles, const fem::ExplicitSolver &continuum, double particle_step,
                           CouplingForceSums &sums);

  /// The largest |tau A lambda - g*| of the last apply(): the velocity gap the correction leaves,
  /// round-off when the solve is right [m/s]. Computed when asked (a product with A per
  /// component), not in every step: only a check needs it.
  double largest_velocity_gap() const;
  double squared_frequency_bound(const dem::ParticleSet &, const fem::ExplicitSolver &) const
  {
    return 0.0; // the constraint adds no stiffness (it only joins masses)
  }

private:
  using Matrix = Eigen::SparseMatrix<double>;
  using Factor = Eigen::SimplicialLDLT<Matrix>;
  /// x = A^-1 b with the stored factor, without allocating: the permutation goes through
  /// work_[component], not the temporary of Eigen's solve().
  void solve(unsigned int component, const Eigen::VectorXd &b, Eigen::VectorXd &x);
  /// node_predictor_ = v_I + tau (f_ext - f_int) / M_I at the band's nodes (prescribed: v_I).
  void predict_nodes(const fem::ExplicitSolver &continuum, double tau);
  /// Solves A lambda = g* / tau from node_predictor_ and the particles' predictors over `tau`,
  /// and applies -lambda to the particles and N lambda continuum_share to the nodes (the share:
  /// tau over the continuum's impulse time, 1 in lockstep).
  void solve_and_apply(dem::ParticleSet &particles, fem::ExplicitSolver &continuum, double tau,
                       double continuum_share, CouplingForceSums &sums);
  /// multiplier_[c] from the predictors' gap in component c (on a thread of its own).
  void solve_component(unsigned int c, const dem::ParticleSet &particles, double tau);
  /// Adds band particle p's `force` (component 0: x, 1: y) to its nodes' external force.
  void add_to_nodes(fem::ExplicitSolver &continuum, std::size_t p, unsigned int component, double force,
                    CouplingForceSums &sums) const;

  const BandParticles *band_;
  std::array<Matrix, 2> matrix_;
  std::array<std::unique_ptr<Factor>, 2> factor_;
  std::array<Eigen::VectorXd, 2> gap_, multiplier_, work_; // per component
  int n_threads_ = 1; ///< the continuum's (its settings): 2 or more solve the components at once
  std::vector<double> node_predictor_; ///< v*_I per local DoF touched by the band
  std::vector<unsigned int> band_dofs_; ///< those DoFs, each once, rising
  /// The impulse time of the last solve; 0 when the last step was within a window (no solve).
  double last_solve_tau_ = 0.0;
};
} // namespace geohybrid::coupling
