#pragma once
// A single material point taken through the plane-strain biaxial test of the DEM calibration
// (dem/laboratory/biaxial_test.h): in-plane isotropic compression to the confining pressure, then
// axial (y) compression at constant lateral (x) stress, eps_zz = 0 throughout. Mixed stress/strain
// control is solved by Newton iterations with the model's consistent tangent, so the number of
// iterations also tells whether the tangent is right. It lets a FEM soil's parameters be compared
// directly with the DEM curves, and is the material test of fem/'s return mappings.
#include "soil_model.h"

#include <vector>

namespace geohybrid::fem
{
struct BiaxialPathPoint
{
  double axial_strain;        ///< eps_yy, negative in compression [-]
  double lateral_strain;      ///< eps_xx [-]
  double volumetric_strain;   ///< eps_xx + eps_yy (eps_zz = 0), positive in dilation [-]
  StressTensor stress;        ///< sigma (xx lateral, yy axial, zz out of plane) [Pa]
  dealii::SymmetricTensor<2, 3> plastic_strain; ///< accumulated [-]
  ReturnRegion region;        ///< of the last increment
  unsigned int n_iterations;  ///< Newton iterations for the last increment
};

struct BiaxialPathSpec
{
  double confining_pressure = 100e3;    ///< p0 > 0: sigma_xx = sigma_yy = -p0 before shearing [Pa]
  unsigned int n_confining_increments = 4;
  double final_axial_strain = -0.02;    ///< eps_yy at the end, negative in compression [-]
  unsigned int n_axial_increments = 200;
};

/// The path, one point per increment (the confining stage's last point first). Throws
/// std::runtime_error if an increment's Newton iterations do not converge (a wrong tangent, or
/// a confinement the soil cannot carry).
std::vector<BiaxialPathPoint> run_plane_strain_biaxial(const SoilModel &model, const BiaxialPathSpec &spec);
} // namespace geohybrid::fem
