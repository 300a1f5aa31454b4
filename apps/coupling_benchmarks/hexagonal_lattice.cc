#include "hexagonal_lattice.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace geohybrid::coupling
{
HexagonalLatticeModuli hexagonal_lattice_moduli(double kn, double ks)
{
  if (!(kn > 0.0) || !std::isfinite(kn))
    throw std::invalid_argument("hexagonal lattice: parameter 'normal stiffness' = " + std::to_string(kn) +
                                " N/m/m must be positive");
  if (!(ks >= 0.0) || !(ks < 5.0 * kn))
    throw std::invalid_argument("hexagonal lattice: parameter 'shear stiffness' = " + std::to_string(ks) +
                                " N/m/m must lie in [0, 5 kn) (a plane-strain Poisson ratio above -1)");
  HexagonalLatticeModuli m;
  const double root3 = std::sqrt(3.0);
  m.lame_lambda = root3 / 4.0 * (kn - ks);
  m.shear_modulus = root3 / 4.0 * (kn + ks);
  m.poisson_ratio_plane_strain = m.lame_lambda / (2.0 * (m.lame_lambda + m.shear_modulus));
  m.young_modulus_plane_strain = 2.0 * m.shear_modulus * (1.0 + m.poisson_ratio_plane_strain);
  // One disc of area pi r^2 per cell of area sqrt(3)/2 (2r)^2.
  m.density_factor = M_PI / (2.0 * root3);
  return m;
}
} // namespace geohybrid::coupling
