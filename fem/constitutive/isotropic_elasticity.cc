#include "isotropic_elasticity.h"

#include "parameter_check.h"

#include <cmath>

namespace geohybrid::fem
{
IsotropicElasticity::IsotropicElasticity(double young_modulus, double poisson_ratio,
                                         const std::string &where)
  : young_modulus_(young_modulus)
  , poisson_ratio_(poisson_ratio)
{
  require_parameter(young_modulus > 0.0 && std::isfinite(young_modulus), where, "Young's modulus",
                    young_modulus, "must be positive [Pa]");
  // nu = 0.5 is incompressible: lambda is infinite and displacement elements lock.
  require_parameter(poisson_ratio > -1.0 && poisson_ratio < 0.5, where, "Poisson's ratio",
                    poisson_ratio, "must lie in (-1, 0.5) [-]");
  shear_modulus_ = young_modulus / (2.0 * (1.0 + poisson_ratio));
  lame_lambda_   = young_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  plane_strain_stiffness_ = lame_lambda_ * dealii::outer_product(dealii::unit_symmetric_tensor<2>(),
                                                                 dealii::unit_symmetric_tensor<2>()) +
                            2.0 * shear_modulus_ * dealii::identity_tensor<2>();
}
} // namespace geohybrid::fem
