#pragma once
// Plane-strain bookkeeping shared by the soil models: moving between the in-plane 2x2 tensors the
// finite elements see and the 3x3 tensors the constitutive laws need, and the spectral
// decomposition of a plane-strain stress. In plane strain z is always a principal direction, so
// the decomposition is the closed-form one of the in-plane 2x2 block plus sigma_zz.
#include "fem/conventions.h"

#include <deal.II/base/tensor.h>

#include <array>
#include <cmath>

namespace geohybrid::fem
{
// The small helpers are inline: the explicit solver calls them at every point every step, and a
// call into another file (no link-time optimisation) cost more than their few copies. They build
// their tensors from all the components at once (SymmetricTensor's independent components: the
// diagonal, then xy, xz, yz), not by zeroing one and writing three entries into it, which made
// the next read of the tensor wait for those writes.

/// The in-plane strain as a 3D strain with eps_zz = eps_xz = eps_yz = 0.
inline dealii::SymmetricTensor<2, 3> embed_in_3d(const StrainTensor &in_plane)
{
  const double components[6] = {in_plane[0][0], in_plane[1][1], 0.0, in_plane[0][1], 0.0, 0.0};
  return dealii::SymmetricTensor<2, 3>(components);
}

/// The xx, yy, xy block of a 3D symmetric tensor.
inline dealii::SymmetricTensor<2, 2> in_plane_part(const dealii::SymmetricTensor<2, 3> &tensor)
{
  const double components[3] = {tensor[0][0], tensor[1][1], tensor[0][1]};
  return dealii::SymmetricTensor<2, 2>(components);
}

/// The in-plane block C_ijkl, i, j, k, l in {x, y}, of a 3D stiffness: the plane-strain tangent.
TangentTensor in_plane_part(const dealii::SymmetricTensor<4, 3> &stiffness);

/// Principal values and directions of a plane-strain stress. Slots 0 and 1 are the in-plane
/// principal directions a and b (value_a >= value_b), slot 2 is z.
struct PlaneStrainPrincipalFrame
{
  std::array<double, 3> values;     ///< (sigma_a, sigma_b, sigma_zz)
  dealii::Tensor<1, 2> direction_a; ///< unit vector of sigma_a
  dealii::Tensor<1, 2> direction_b; ///< unit vector of sigma_b, direction_a rotated by +90 degrees
};

PlaneStrainPrincipalFrame principal_frame(const StressTensor &stress);
/// principal_frame(stress).values without the directions (no atan2, sin, cos: the elastic check
/// of a stress update needs only these).
inline std::array<double, 3> principal_values(const StressTensor &stress)
{
  // Mohr's circle of the in-plane block: centre and radius.
  const double centre = 0.5 * (stress[0][0] + stress[1][1]);
  const double half_difference = 0.5 * (stress[0][0] - stress[1][1]);
  // sqrt, not hypot: stresses are far from overflow (|sigma| < 1e150 Pa), and glibc's hypot was
  // a tenth of a hybrid pull-out's time (perf), the explicit solver calling this at every point
  // every step.
  const double radius = std::sqrt(half_difference * half_difference + stress[0][1] * stress[0][1]);
  return {{centre + radius, centre - radius, stress[2][2]}};
}

/// The stress with the frame's directions and the given principal values (slots as in the frame).
StressTensor stress_from_principal(const PlaneStrainPrincipalFrame &frame,
                                   const std::array<double, 3> &values);

/// The in-plane consistent tangent of an isotropic stress update sigma = F(sigma_trial),
/// sigma_trial = sigma_n + C : delta eps, from its derivative in principal space (de Souza Neto,
/// Peric & Owen, Computational Methods for Plasticity, 2008, appendix A; Clausen, Damkilde &
/// Andersen, Comput. Struct. 84, 2006):
///   C_ep = sum_ab D_ab E_a (x) E_b + 2 c_s M (x) M,   E_a = n_a (x) n_a,  M = sym(n_a (x) n_b),
/// where D_ab = d(sigma_a)/d(eps_trial_b) (slots of the frame) and the in-plane shear coefficient
/// c_s = 2 G (sigma_a - sigma_b) / (sigma_trial_a - sigma_trial_b) accounts for the rotation of
/// the principal axes; when the two trial values coincide it takes its limit D_aa - D_ab.
TangentTensor tangent_from_principal(const PlaneStrainPrincipalFrame &trial_frame,
                                     const std::array<double, 3> &returned_values,
                                     const dealii::Tensor<2, 3> &principal_tangent,
                                     double shear_modulus);
} // namespace geohybrid::fem
