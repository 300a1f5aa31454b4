#pragma once
// The at-rest (geostatic) stress of a horizontally layered soil under its own weight, used as the
// initial stress so that the analysis starts in equilibrium with gravity without displacing:
//   sigma_yy = -(q + gamma (y_surface - y)),   sigma_xx = sigma_zz = K0 sigma_yy,   sigma_xy = 0,
// with K0 = 1 - sin(phi) by default (Jaky 1944). Tension is positive (fem/conventions.h). In
// equilibrium with the body force rho g as long as the lateral boundaries are rollers.
#include "fem/conventions.h"

#include <deal.II/base/point.h>

#include <string>

namespace geohybrid::fem
{
struct GeostaticStress
{
  double surface_elevation = 0.0; ///< y of the free surface [m]
  double unit_weight = 0.0;       ///< gamma = rho g >= 0 [N/m^3]
  double k0 = 0.5;                ///< sigma_h / sigma_v, > 0 [-]
  double surcharge = 0.0;         ///< q >= 0, a uniform pressure on the surface [Pa]

  /// Throws std::invalid_argument naming `where` and the parameter.
  void validate(const std::string &where) const;

  /// The stress at `point`; above the surface the soil is unstressed.
  StressTensor stress_at(const dealii::Point<dim> &point) const;
};
} // namespace geohybrid::fem
