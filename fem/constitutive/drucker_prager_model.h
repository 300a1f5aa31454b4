#pragma once
// Elastic-perfectly plastic Drucker-Prager soil matched to Mohr-Coulomb in plane strain, with
// non-associated flow: a smooth cone that is cheaper than Mohr-Coulomb and has no edges.
//
//   f = sqrt(J2) + alpha I1 - kappa,   g = sqrt(J2) + alpha_bar I1   (tension positive, I1 = tr sigma)
//
// The plane-strain match: once plastic flow is steady, plane strain forces the out-of-plane
// plastic strain rate to zero, dg/dsigma_zz = 0. Then the in-plane Mohr circle of the cone's
// stresses touches the Mohr-Coulomb line t = c cos(phi) - s sin(phi), and the in-plane dilatancy
// equals sin(psi), when
//   alpha_bar = sin(psi) / sqrt(9 + 3 sin^2 psi),
//   alpha     = sin(phi) / (3 (sqrt(1 - 3 alpha_bar^2) + alpha_bar sin(phi))),
//   kappa     = c cos(phi) / (sqrt(1 - 3 alpha_bar^2) + alpha_bar sin(phi)),
// which reduce to the classical alpha = tan(phi)/sqrt(9 + 12 tan^2 phi), kappa = 3 c / sqrt(9 + 12
// tan^2 phi) for psi = phi (de Souza Neto, Peric & Owen 2008, section 6.4.1), and keep the apex at
// c cot(phi). Before the flow is steady (at first yield), sigma_zz is still adjusting and the
// in-plane strength differs from Mohr-Coulomb's.
//
// The return mapping is the closed-form one of de Souza Neto et al. (Box 8.9): along the cone's
// corrector, or to the apex when that would reverse the deviator.
#include "isotropic_elasticity.h"
#include "mohr_coulomb_strength.h"
#include "stress_update.h"

#include <string>

namespace geohybrid::fem
{
class DruckerPragerModel
{
public:
  /// Throws std::invalid_argument naming `where` if a strength parameter is out of range.
  DruckerPragerModel(const IsotropicElasticity &elasticity, const MohrCoulombStrength &strength,
                     const std::string &where = "Drucker-Prager soil");

  StressUpdate update(const StressTensor &stress, const StrainTensor &strain_increment) const;
  /// update() without its tangent (computed and dropped: no explicit run uses this model's speed).
  StressOnlyUpdate update_stress(const StressTensor &stress, const StrainTensor &strain_increment) const
  {
    const StressUpdate full = update(stress, strain_increment);
    return {full.stress, full.plastic_strain_increment, full.region};
  }

  /// f = sqrt(J2) + alpha I1 - kappa [Pa]: <= 0 inside the cone.
  double yield_function(const StressTensor &stress) const;

  bool has_symmetric_tangent() const { return alpha_ == alpha_bar_; }
  const IsotropicElasticity &elasticity() const { return elasticity_; }
  const MohrCoulombStrength &strength() const { return strength_; }

  double friction_coefficient() const { return alpha_; }    ///< alpha [-]
  double dilatancy_coefficient() const { return alpha_bar_; } ///< alpha_bar [-]
  double cohesion_coefficient() const { return kappa_; }    ///< kappa [Pa]

private:
  IsotropicElasticity elasticity_;
  MohrCoulombStrength strength_;
  double alpha_;
  double alpha_bar_;
  double kappa_;
};
} // namespace geohybrid::fem
