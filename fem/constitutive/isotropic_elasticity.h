#pragma once
// Linear isotropic elasticity (Hooke's law) in the form every soil model of fem/ builds on:
//   sigma = lambda tr(eps) I + 2 G eps,   lambda = E nu / ((1 + nu)(1 - 2 nu)),  G = E / (2 (1 + nu)).
// Plane strain keeps sigma_zz = lambda tr(eps) (eps_zz = 0), so strains are embedded in 3D with a
// zero zz component before Hooke's law is applied. Signs: see fem/conventions.h.
#include "fem/conventions.h"

#include <string>

namespace geohybrid::fem
{
class IsotropicElasticity
{
public:
  /// Throws std::invalid_argument naming `where` unless E > 0 and -1 < nu < 0.5.
  IsotropicElasticity(double young_modulus, double poisson_ratio,
                      const std::string &where = "elastic soil");

  double young_modulus() const { return young_modulus_; }  ///< E [Pa]
  double poisson_ratio() const { return poisson_ratio_; }  ///< nu [-]
  double shear_modulus() const { return shear_modulus_; }  ///< G [Pa]
  double lame_lambda() const { return lame_lambda_; }      ///< lambda [Pa]
  double bulk_modulus() const { return lame_lambda_ + 2.0 * shear_modulus_ / 3.0; } ///< K [Pa]

  /// Hooke's law in 3D.
  StressTensor stress(const dealii::SymmetricTensor<2, 3> &strain) const
  {
    return lame_lambda_ * dealii::trace(strain) * dealii::unit_symmetric_tensor<3>() +
           2.0 * shear_modulus_ * strain;
  }

  /// Its inverse: eps = (1 + nu)/E sigma - nu/E tr(sigma) I.
  dealii::SymmetricTensor<2, 3> strain(const StressTensor &stress) const
  {
    return (1.0 + poisson_ratio_) / young_modulus_ * stress -
           poisson_ratio_ / young_modulus_ * dealii::trace(stress) *
             dealii::unit_symmetric_tensor<3>();
  }

  /// The in-plane block of the elastic stiffness: d(sigma_xx, yy, xy)/d(eps_xx, yy, xy) in plane strain.
  const TangentTensor &plane_strain_stiffness() const { return plane_strain_stiffness_; }

private:
  double young_modulus_;
  double poisson_ratio_;
  double shear_modulus_;
  double lame_lambda_;
  TangentTensor plane_strain_stiffness_;
};
} // namespace geohybrid::fem
