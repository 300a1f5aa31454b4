#pragma once
// Method 2, penalty overlap: each band particle p is tied to the continuum by a spring between its
// displacement and the continuum's displacement interpolated at its reference position X_p, both
// counted from the moment they are tied (u_0 the continuum's displacement then),
//   g_p = (x_p - X_p) - sum_I N_I(X_p) (u_I - u_0,I),   energy 1/2 k_p |g_p|^2,
// so the particle feels -k_p g_p and node I feels N_I(X_p) k_p g_p (the forces sum to zero).
// k_p = penalty factor x E x (d_p / w): E the continuum's Young modulus [Pa = N/m/m per metre of
// thickness], d_p the particle's diameter, w the band width. Both sides carry their energy
// weights already, so the springs are not weighted again. Forces at time t_n from the positions at
// t_n: the springs enter both leapfrog integrators like any conservative force.
#include "coupling/band_particles.h"
#include "coupling/coupling_forces.h"
#include "coupling/coupling_method.h"
#include "fem/explicit_solver.h"

#include <string_view>
#include <vector>

namespace geohybrid::coupling
{
/// A coupling tie (coupling_tie.h).
class PenaltyTie
{
public:
  static constexpr std::string_view name = PenaltyCoupling::name;

  /// `band` must outlive the tie: every apply() reads it.
  PenaltyTie(const PenaltyCoupling &parameters, const BandParticles &band, const dem::ParticleSet &particles,
             const fem::ExplicitSolver &continuum, double band_width);

  /// Adds the spring forces of the current positions to both sides (the continuum's through
  /// ExplicitSolver::add_external_force); books the springs' energy. The springs need no timing.
  void apply(dem::ParticleSet &particles, fem::ExplicitSolver &continuum, const TieTiming &timing,
             CouplingForceSums &sums);
  double energy() const { return energy_; } ///< 1/2 sum k_p |g_p|^2 at the last apply() [J/m]

  /// A bound on the squared frequency the springs add (Gershgorin on M^-1 K_penalty, with the
  /// particles' weighted masses and the continuum's lumped masses) [1/s^2].
  double squared_frequency_bound(const dem::ParticleSet &particles, const fem::ExplicitSolver &continuum) const;
  double stiffness(std::size_t p) const { return stiffness_[p]; } ///< k_p [N/m/m]

private:
  const BandParticles *band_;
  std::vector<double> stiffness_;
  std::vector<Vec2> tied_displacement_; ///< the continuum's displacement at X_p when tied [m]
  double energy_ = 0.0;
};
} // namespace geohybrid::coupling
