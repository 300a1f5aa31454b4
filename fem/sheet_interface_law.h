#pragma once
// The constitutive law of the zero-thickness interface between one face of the sheet and the soil
// (reference paper, section 4.1: tau_max = a_s + sigma_n tan(delta)), used by both solvers: the
// explicit one (fem/sheet_interface.h) calls it once per step, the implicit one
// (fem/implicit_sheet.h) once per Newton iterate with the slip since the last converged step.
//
// - normal: a penalty spring k_n per face ties the sheet to the soil (soil on both faces, so the
//   sheet cannot open a gap): normal stress k_n g_n per face, g_n the relative displacement
//   sheet - soil along the sheet's normal;
// - shear: an elastic-perfectly-plastic (Coulomb) slider, integrated by backward Euler from the
//   last committed shear stress tau_n: the elastic trial tau_n + k_s ds is returned to the limit
//   c_i + max(0, -sigma_nn) tan(delta) if it exceeds it (a return mapping in one dimension; the
//   consistent tangent dtau/d(ds) is k_s when it sticks and 0 when it slides). sigma_nn is the
//   soil's normal stress on the sheet's plane, tension positive, so -sigma_nn is the confinement.
#include "fem/conventions.h"
#include "fem/truss_sheet.h"

#include <algorithm>
#include <cmath>

namespace geohybrid::fem
{
struct InterfaceShearUpdate
{
  double shear_stress = 0.0; ///< tau per face [Pa]
  double tangent = 0.0;      ///< d tau / d(slip increment): k_s sticking, 0 sliding [Pa/m]
  bool sliding = false;
};

class SheetInterfaceLaw
{
public:
  explicit SheetInterfaceLaw(const SheetInterfaceParameters &parameters)
    : parameters_(parameters), tan_delta_(std::tan(degrees_to_radians(parameters.friction_angle_deg)))
  {}

  double normal_stiffness() const { return parameters_.normal_stiffness; } ///< k_n per face [Pa/m]

  /// c_i + max(0, -sigma_nn) tan(delta) [Pa]
  double shear_limit(double sigma_nn) const { return parameters_.cohesion + std::max(0.0, -sigma_nn) * tan_delta_; }

  /// tau after a tangential slip increment `slip_increment` [m] from the committed `shear_stress`
  /// [Pa], under the normal stress `sigma_nn` [Pa].
  InterfaceShearUpdate shear(double shear_stress, double slip_increment, double sigma_nn) const
  {
    const double limit = shear_limit(sigma_nn);
    const double trial = shear_stress + parameters_.shear_stiffness * slip_increment;
    // Strictly inside: a face with no strength (c_i = 0, no confinement) slides from the start,
    // with tau = 0 and no shear stiffness, rather than sticking at tau = 0.
    if (std::abs(trial) < limit)
      return {trial, parameters_.shear_stiffness, false};
    return {std::clamp(trial, -limit, limit), 0.0, true};
  }

private:
  SheetInterfaceParameters parameters_;
  double tan_delta_;
};
} // namespace geohybrid::fem
