#include "biaxial_path.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geohybrid::fem
{
namespace
{
/// One increment with eps_xy fixed and, for each of xx and yy, either the strain increment or the
/// final stress prescribed.
struct MixedIncrement
{
  bool stress_controlled[2];
  double target[2]; ///< strain increment, or final stress [Pa]
};

struct MixedResult
{
  StressUpdate update;
  StrainTensor strain_increment;
  unsigned int n_iterations;
};

MixedResult solve_increment(const SoilModel &model, const StressTensor &stress,
                            const MixedIncrement &control, double stress_scale)
{
  MixedResult result;
  for (unsigned int i = 0; i < 2; ++i)
    result.strain_increment[i][i] = control.stress_controlled[i] ? 0.0 : control.target[i];
  const unsigned int max_iterations = 25;
  for (result.n_iterations = 0; result.n_iterations <= max_iterations; ++result.n_iterations)
    {
      result.update = model.update(stress, result.strain_increment);
      double residual[2], jacobian[2][2];
      double residual_norm = 0.0;
      for (unsigned int i = 0; i < 2; ++i)
        {
          if (control.stress_controlled[i])
            {
              residual[i] = result.update.stress[i][i] - control.target[i];
              jacobian[i][0] = result.update.tangent[i][i][0][0];
              jacobian[i][1] = result.update.tangent[i][i][1][1];
              residual_norm += std::abs(residual[i]);
            }
          else
            {
              residual[i] = 0.0;
              jacobian[i][0] = i == 0 ? 1.0 : 0.0;
              jacobian[i][1] = i == 1 ? 1.0 : 0.0;
            }
        }
      if (residual_norm <= 1e-12 * stress_scale)
        return result;
      const double determinant = jacobian[0][0] * jacobian[1][1] - jacobian[0][1] * jacobian[1][0];
      result.strain_increment[0][0] -= (jacobian[1][1] * residual[0] - jacobian[0][1] * residual[1]) / determinant;
      result.strain_increment[1][1] -= (jacobian[0][0] * residual[1] - jacobian[1][0] * residual[0]) / determinant;
    }
  std::ostringstream message;
  message << "plane-strain biaxial path: the mixed-control iterations did not converge in "
          << max_iterations << " iterations at stress (" << stress[0][0] << ", " << stress[1][1]
          << ") Pa";
  throw std::runtime_error(message.str());
}
} // namespace

std::vector<BiaxialPathPoint> run_plane_strain_biaxial(const SoilModel &model, const BiaxialPathSpec &spec)
{
  if (!(spec.confining_pressure > 0.0) || spec.n_confining_increments == 0 || spec.n_axial_increments == 0)
    throw std::invalid_argument("plane-strain biaxial path: the confining pressure and the numbers of "
                                "increments must be positive");
  std::vector<BiaxialPathPoint> path;
  BiaxialPathPoint point{};
  auto advance = [&](const MixedIncrement &control) {
    const MixedResult r = solve_increment(model, point.stress, control, spec.confining_pressure);
    point.lateral_strain += r.strain_increment[0][0];
    point.axial_strain += r.strain_increment[1][1];
    point.volumetric_strain = point.lateral_strain + point.axial_strain;
    point.stress = r.update.stress;
    point.plastic_strain += r.update.plastic_strain_increment;
    point.region = r.update.region;
    point.n_iterations = r.n_iterations;
  };

  for (unsigned int i = 1; i <= spec.n_confining_increments; ++i)
    {
      const double target = -spec.confining_pressure * i / spec.n_confining_increments;
      advance(MixedIncrement{{true, true}, {target, target}});
    }
  path.push_back(point);
  const double axial_increment = spec.final_axial_strain / spec.n_axial_increments;
  for (unsigned int i = 0; i < spec.n_axial_increments; ++i)
    {
      advance(MixedIncrement{{true, false}, {-spec.confining_pressure, axial_increment}});
      path.push_back(point);
    }
  return path;
}
} // namespace geohybrid::fem
