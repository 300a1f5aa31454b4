#include "drucker_prager_model.h"

#include "plane_strain_tensors.h"

#include <cmath>

namespace geohybrid::fem
{
DruckerPragerModel::DruckerPragerModel(const IsotropicElasticity &elasticity,
                                       const MohrCoulombStrength &strength, const std::string &where)
  : elasticity_(elasticity)
  , strength_(strength)
{
  strength_.validate(where);
  const double sin_phi = std::sin(degrees_to_radians(strength_.friction_angle_deg));
  const double cos_phi = std::cos(degrees_to_radians(strength_.friction_angle_deg));
  const double sin_psi = std::sin(degrees_to_radians(strength_.dilatancy_angle_deg));
  alpha_bar_ = sin_psi / std::sqrt(9.0 + 3.0 * sin_psi * sin_psi);
  const double match = std::sqrt(1.0 - 3.0 * alpha_bar_ * alpha_bar_) + alpha_bar_ * sin_phi;
  alpha_ = sin_phi / (3.0 * match);
  kappa_ = strength_.cohesion * cos_phi / match;
  // For psi = phi the two coefficients must be the same number, so that the tangent is exactly
  // symmetric and the solver may use CG.
  if (strength_.dilatancy_angle_deg == strength_.friction_angle_deg)
    alpha_bar_ = alpha_;
}

double DruckerPragerModel::yield_function(const StressTensor &stress) const
{
  const auto s = dealii::deviator(stress);
  return std::sqrt(0.5 * s * s) + alpha_ * dealii::trace(stress) - kappa_;
}

StressUpdate DruckerPragerModel::update(const StressTensor &stress,
                                        const StrainTensor &strain_increment) const
{
  const auto strain_3d = embed_in_3d(strain_increment);
  const StressTensor trial = stress + elasticity_.stress(strain_3d);
  const double G = elasticity_.shear_modulus(), K = elasticity_.bulk_modulus();
  const auto deviator_trial = dealii::deviator(trial);
  const double root_J2_trial = std::sqrt(0.5 * deviator_trial * deviator_trial);
  const double I1_trial = dealii::trace(trial);
  const double f_trial = root_J2_trial + alpha_ * I1_trial - kappa_;

  StressUpdate result;
  const double scale = root_J2_trial + std::abs(alpha_ * I1_trial) + kappa_;
  if (f_trial <= 1e-12 * scale)
    {
      result.stress = trial;
      result.tangent = elasticity_.plane_strain_stiffness();
      result.region = ReturnRegion::elastic;
      return result;
    }

  const auto unit = dealii::unit_symmetric_tensor<3>();
  // Return along the cone's corrector: sqrt(J2) drops by G dlambda, I1 by 9 K alpha_bar dlambda.
  const double A = 1.0 / (G + 9.0 * K * alpha_ * alpha_bar_);
  const double multiplier = f_trial * A;
  if (root_J2_trial - G * multiplier >= 0.0)
    {
      const double shrink = 1.0 - G * multiplier / root_J2_trial;
      result.stress = shrink * deviator_trial + (I1_trial - 9.0 * K * alpha_bar_ * multiplier) / 3.0 * unit;
      // Derivative of the two lines above with respect to the strain increment, using
      // d sqrt(J2_trial) = sqrt(2) G n : d eps and dlambda = A (sqrt(2) G n + 3 K alpha 1) : d eps:
      //   D = 2G(1 - G dl/sqrtJ2) I_dev + 2G^2 (dl/sqrtJ2 - A) n n
      //       - 3 sqrt(2) G K A (alpha n 1 + alpha_bar 1 n) + K (1 - 9 K alpha alpha_bar A) 1 1,
      // with n = s_trial / |s_trial|: non-symmetric unless alpha = alpha_bar.
      const auto n = deviator_trial / deviator_trial.norm();
      const dealii::SymmetricTensor<4, 3> tangent =
        2.0 * G * shrink * dealii::deviator_tensor<3>() +
        2.0 * G * G * (multiplier / root_J2_trial - A) * dealii::outer_product(n, n) -
        3.0 * std::sqrt(2.0) * G * K * A *
          (alpha_ * dealii::outer_product(n, unit) + alpha_bar_ * dealii::outer_product(unit, n)) +
        K * (1.0 - 9.0 * K * alpha_ * alpha_bar_ * A) * dealii::outer_product(unit, unit);
      result.tangent = in_plane_part(tangent);
      result.region = ReturnRegion::surface;
    }
  else
    {
      // Beyond the apex: the hydrostatic stress kappa / (3 alpha) = c cot(phi), which perfect
      // plasticity holds whatever the strain.
      result.stress = kappa_ / (3.0 * alpha_) * unit;
      result.tangent = TangentTensor();
      result.region = ReturnRegion::apex;
    }
  result.plastic_strain_increment = strain_3d - elasticity_.strain(result.stress - stress);
  return result;
}
} // namespace geohybrid::fem
