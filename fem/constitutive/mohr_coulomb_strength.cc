#include "mohr_coulomb_strength.h"

#include "fem/conventions.h"
#include "parameter_check.h"

#include <cmath>

namespace geohybrid::fem
{
void MohrCoulombStrength::validate(const std::string &where) const
{
  // phi = 0 would be a Tresca material (and make c cot(phi) infinite); phi = 90 degrees an
  // infinitely strong one. Both are outside what this soil model is for.
  require_parameter(friction_angle_deg > 0.0 && friction_angle_deg < 90.0, where,
                    "friction angle", friction_angle_deg, "must lie in (0, 90) [deg]");
  require_parameter(cohesion >= 0.0 && std::isfinite(cohesion), where, "cohesion", cohesion,
                    "must be zero or positive [Pa]");
  // psi > phi would dissipate negative energy in some paths; psi < 0 is contractant flow, which
  // this perfectly plastic model does not represent.
  require_parameter(dilatancy_angle_deg >= 0.0 && dilatancy_angle_deg <= friction_angle_deg, where,
                    "dilatancy angle", dilatancy_angle_deg,
                    "must lie in [0, friction angle] [deg]");
}

double MohrCoulombStrength::passive_coefficient() const
{
  const double s = std::sin(degrees_to_radians(friction_angle_deg));
  return (1.0 + s) / (1.0 - s);
}

double MohrCoulombStrength::dilatancy_coefficient() const
{
  const double s = std::sin(degrees_to_radians(dilatancy_angle_deg));
  return (1.0 + s) / (1.0 - s);
}

double MohrCoulombStrength::compressive_strength() const
{
  const double phi = degrees_to_radians(friction_angle_deg);
  return 2.0 * cohesion * std::cos(phi) / (1.0 - std::sin(phi));
}

double MohrCoulombStrength::apex_stress() const
{
  return cohesion / std::tan(degrees_to_radians(friction_angle_deg));
}

double MohrCoulombStrength::jaky_k0() const
{
  return 1.0 - std::sin(degrees_to_radians(friction_angle_deg));
}
} // namespace geohybrid::fem
