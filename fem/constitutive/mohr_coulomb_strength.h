#pragma once
// The strength of a frictional soil: friction angle phi, cohesion c and dilatancy angle psi, and
// the Mohr-Coulomb constants derived from them. Tension is positive (fem/conventions.h), and with
// sigma_1 >= sigma_2 >= sigma_3 the criterion and the plastic potential read
//   f = k sigma_1 - sigma_3 - sigma_c,  k = (1 + sin phi)/(1 - sin phi),  sigma_c = 2 c sqrt(k),
//   g = m sigma_1 - sigma_3,            m = (1 + sin psi)/(1 - sin psi),
// so that at failure under a lateral compression s_3 = -sigma_1 the axial compression is
// -sigma_3 = k s_3 + sigma_c, i.e. sigma_axial / sigma_lateral = k + sigma_c / s_3.
#include <string>

namespace geohybrid::fem
{
struct MohrCoulombStrength
{
  double friction_angle_deg  = 30.0; ///< phi, in (0, 90) [deg]
  double cohesion            = 0.0;  ///< c >= 0 [Pa]
  double dilatancy_angle_deg = 0.0;  ///< psi, in [0, phi] [deg]

  /// Throws std::invalid_argument naming `where` and the offending parameter.
  void validate(const std::string &where) const;

  double passive_coefficient() const;    ///< k = (1 + sin phi)/(1 - sin phi) [-]
  double dilatancy_coefficient() const;  ///< m = (1 + sin psi)/(1 - sin psi) [-]
  double compressive_strength() const;   ///< sigma_c = 2 c cos(phi)/(1 - sin phi) [Pa]
  double apex_stress() const;            ///< c cot(phi): the hydrostatic tension the soil can carry [Pa]
  double jaky_k0() const;                ///< K0 = 1 - sin phi (Jaky 1944), the at-rest coefficient [-]
};
} // namespace geohybrid::fem
