#include "geostatic_stress.h"

#include "fem/constitutive/parameter_check.h"

#include <algorithm>
#include <cmath>

namespace geohybrid::fem
{
void GeostaticStress::validate(const std::string &where) const
{
  require_parameter(std::isfinite(surface_elevation), where, "surface elevation", surface_elevation,
                    "must be finite [m]");
  require_parameter(unit_weight >= 0.0 && std::isfinite(unit_weight), where, "unit weight", unit_weight,
                    "must be zero or positive [N/m^3]");
  require_parameter(k0 > 0.0 && std::isfinite(k0), where, "K0", k0, "must be positive [-]");
  require_parameter(surcharge >= 0.0 && std::isfinite(surcharge), where, "surcharge", surcharge,
                    "must be zero or positive [Pa]");
}

StressTensor GeostaticStress::stress_at(const dealii::Point<dim> &point) const
{
  const double depth = std::max(0.0, surface_elevation - point[1]);
  const double vertical = -(surcharge + unit_weight * depth);
  StressTensor stress;
  stress[0][0] = k0 * vertical;
  stress[1][1] = vertical;
  stress[2][2] = k0 * vertical;
  return stress;
}
} // namespace geohybrid::fem
