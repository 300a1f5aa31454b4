#include "plane_strain_tensors.h"

#include <cmath>

namespace geohybrid::fem
{
TangentTensor in_plane_part(const dealii::SymmetricTensor<4, 3> &stiffness)
{
  TangentTensor part;
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = i; j < 2; ++j)
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int l = k; l < 2; ++l)
          part[i][j][k][l] = stiffness[i][j][k][l];
  return part;
}

PlaneStrainPrincipalFrame principal_frame(const StressTensor &stress)
{
  // The values as principal_values; the angle of the major direction on Mohr's circle.
  const double half_difference = 0.5 * (stress[0][0] - stress[1][1]);
  const double angle = 0.5 * std::atan2(stress[0][1], half_difference);
  PlaneStrainPrincipalFrame frame;
  frame.values = principal_values(stress);
  frame.direction_a[0] = std::cos(angle);
  frame.direction_a[1] = std::sin(angle);
  frame.direction_b[0] = -frame.direction_a[1];
  frame.direction_b[1] = frame.direction_a[0];
  return frame;
}

StressTensor stress_from_principal(const PlaneStrainPrincipalFrame &frame,
                                   const std::array<double, 3> &values)
{
  StressTensor stress;
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = i; j < 2; ++j)
      stress[i][j] = values[0] * frame.direction_a[i] * frame.direction_a[j] +
                     values[1] * frame.direction_b[i] * frame.direction_b[j];
  stress[2][2] = values[2];
  return stress;
}

TangentTensor tangent_from_principal(const PlaneStrainPrincipalFrame &trial_frame,
                                     const std::array<double, 3> &returned_values,
                                     const dealii::Tensor<2, 3> &principal_tangent,
                                     double shear_modulus)
{
  const auto &na = trial_frame.direction_a;
  const auto &nb = trial_frame.direction_b;
  dealii::SymmetricTensor<2, 2> projector[2], shear;
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = i; j < 2; ++j)
      {
        projector[0][i][j] = na[i] * na[j];
        projector[1][i][j] = nb[i] * nb[j];
        shear[i][j] = 0.5 * (na[i] * nb[j] + nb[i] * na[j]);
      }

  // Below this relative gap the trial values are treated as equal: the quotient would lose
  // more digits to cancellation than the limit loses to the approximation.
  const double trial_gap = trial_frame.values[0] - trial_frame.values[1];
  const double scale = std::abs(trial_frame.values[0]) + std::abs(trial_frame.values[1]) +
                       shear_modulus * 1e-12;
  const double shear_coefficient =
    std::abs(trial_gap) > 1e-9 * scale ?
      2.0 * shear_modulus * (returned_values[0] - returned_values[1]) / trial_gap :
      principal_tangent[0][0] - principal_tangent[0][1];

  TangentTensor tangent = 2.0 * shear_coefficient * dealii::outer_product(shear, shear);
  for (unsigned int a = 0; a < 2; ++a)
    for (unsigned int b = 0; b < 2; ++b)
      tangent += principal_tangent[a][b] * dealii::outer_product(projector[a], projector[b]);
  return tangent;
}
} // namespace geohybrid::fem
