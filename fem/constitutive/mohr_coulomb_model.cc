#include "mohr_coulomb_model.h"

#include "plane_strain_tensors.h"

#include <algorithm>
#include <cmath>

namespace geohybrid::fem
{
namespace
{
/// The permutation that sorts the three principal values in decreasing order.
std::array<unsigned int, 3> decreasing_order(const std::array<double, 3> &values)
{
  // Three compare-and-swaps (a sorting network; equal values keep their order, as the
  // insertion sort std::sort used for three did): this runs at every point every explicit step.
  std::array<unsigned int, 3> order = {{0, 1, 2}};
  const auto sort_pair = [&](unsigned int a, unsigned int b) {
    if (values[order[b]] > values[order[a]])
      std::swap(order[a], order[b]);
  };
  sort_pair(0, 1);
  sort_pair(1, 2);
  sort_pair(0, 1);
  return order;
}
} // namespace

MohrCoulombModel::MohrCoulombModel(const IsotropicElasticity &elasticity,
                                   const MohrCoulombStrength &strength, const std::string &where)
  : elasticity_(elasticity)
  , strength_(strength)
{
  strength_.validate(where);
  compressive_strength_ = strength_.compressive_strength();
  apex_stress_ = strength_.apex_stress();
  const double lambda = elasticity_.lame_lambda(), G = elasticity_.shear_modulus();
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      elastic_principal_[i][j] = lambda + (i == j ? 2.0 * G : 0.0);
  main_normal_ = Vector3({strength_.passive_coefficient(), 0.0, -1.0});
  main_flow_ = Vector3({strength_.dilatancy_coefficient(), 0.0, -1.0});
}

double MohrCoulombModel::yield_function(const StressTensor &stress) const
{
  const auto values = principal_values(stress);
  const double sigma_1 = *std::max_element(values.begin(), values.end());
  const double sigma_3 = *std::min_element(values.begin(), values.end());
  return main_normal_[0] * sigma_1 - sigma_3 - compressive_strength_;
}

StressUpdate MohrCoulombModel::update(const StressTensor &stress,
                                      const StrainTensor &strain_increment) const
{
  StressUpdate result;
  const StressOnlyUpdate update_without_tangent = update(stress, strain_increment, &result.tangent);
  result.stress = update_without_tangent.stress;
  result.plastic_strain_increment = update_without_tangent.plastic_strain_increment;
  result.region = update_without_tangent.region;
  return result;
}

StressOnlyUpdate MohrCoulombModel::update(const StressTensor &stress, const StrainTensor &strain_increment,
                                          TangentTensor *tangent) const
{
  const auto strain_3d = embed_in_3d(strain_increment);
  const StressTensor trial = stress + elasticity_.stress(strain_3d);
  // The principal directions (atan2, sin, cos) only once the point yields: most points of a
  // pull-out stay elastic, and the explicit solver updates each of them every step.
  const std::array<double, 3> values = principal_values(trial);
  const auto order = decreasing_order(values);
  const Vector3 sorted_trial({values[order[0]], values[order[1]], values[order[2]]});

  // The admissibility test is relative to the stress level so that a point that ended the last
  // step exactly on the surface is not returned again for round-off.
  const double scale = std::abs(sorted_trial[0]) + std::abs(sorted_trial[2]) + compressive_strength_;
  const double f_trial = main_normal_ * sorted_trial - compressive_strength_;
  if (f_trial <= 1e-12 * scale)
    {
      if (tangent)
        *tangent = elasticity_.plane_strain_stiffness();
      return {trial, {}, ReturnRegion::elastic};
    }

  StressOnlyUpdate result;

  const PlaneStrainPrincipalFrame frame = principal_frame(trial);
  const PrincipalReturn principal = return_in_principal_space(sorted_trial, tangent != nullptr);
  std::array<double, 3> returned_values;
  for (unsigned int i = 0; i < 3; ++i)
    returned_values[order[i]] = principal.stress[i];
  result.stress = stress_from_principal(frame, returned_values);
  if (tangent)
    {
      dealii::Tensor<2, 3> tangent_in_frame;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          tangent_in_frame[order[i]][order[j]] = principal.tangent[i][j];
      *tangent = tangent_from_principal(frame, returned_values, tangent_in_frame, elasticity_.shear_modulus());
    }
  result.region = principal.region;
  result.plastic_strain_increment = strain_3d - elasticity_.strain(result.stress - stress);
  return result;
}

MohrCoulombModel::PrincipalReturn
MohrCoulombModel::return_in_principal_space(const Vector3 &trial, bool with_tangent) const
{
  const double tolerance =
    1e-12 * (std::abs(trial[0]) + std::abs(trial[2]) + compressive_strength_ + std::abs(apex_stress_));
  const Matrix3 &D = elastic_principal_;

  // Main plane: sigma = sigma_trial - dlambda D b with a . sigma = sigma_c.
  const Vector3 corrector = D * main_flow_;
  const double f_trial = main_normal_ * trial - compressive_strength_;
  const double stiffness = main_normal_ * corrector;
  PrincipalReturn result;
  result.stress = trial - (f_trial / stiffness) * corrector;
  const bool crossed_compression_edge = result.stress[0] < result.stress[1] - tolerance;
  const bool crossed_extension_edge = result.stress[1] < result.stress[2] - tolerance;
  if (!crossed_compression_edge && !crossed_extension_edge)
    {
      if (with_tangent)
        result.tangent = D - dealii::outer_product(corrector, D * main_normal_) / stiffness;
      result.region = ReturnRegion::surface;
      return result;
    }

  // The main-plane return left the sextant sigma_1 >= sigma_2 >= sigma_3: try the edge it
  // crossed first, then the other; if neither is consistent, the trial stress lies beyond the apex.
  const ReturnRegion first = crossed_compression_edge ? ReturnRegion::edge_triaxial_compression :
                                                        ReturnRegion::edge_triaxial_extension;
  const ReturnRegion second = crossed_compression_edge ? ReturnRegion::edge_triaxial_extension :
                                                         ReturnRegion::edge_triaxial_compression;
  if (return_to_edge(trial, first, tolerance, with_tangent, result) ||
      return_to_edge(trial, second, tolerance, with_tangent, result))
    return result;

  result.stress = Vector3({apex_stress_, apex_stress_, apex_stress_});
  result.tangent = Matrix3(); // perfect plasticity: the apex does not move
  result.region = ReturnRegion::apex;
  return result;
}

bool MohrCoulombModel::return_to_edge(const Vector3 &trial, ReturnRegion edge, double tolerance,
                                      bool with_tangent, PrincipalReturn &result) const
{
  const double k = main_normal_[0], m = main_flow_[0];
  // The second active plane and its potential: k sigma_2 - sigma_3 = sigma_c on the compression
  // edge, k sigma_1 - sigma_2 = sigma_c on the extension edge.
  const bool compression = edge == ReturnRegion::edge_triaxial_compression;
  const Vector3 normals[2] = {main_normal_, compression ? Vector3({0.0, k, -1.0}) : Vector3({k, -1.0, 0.0})};
  const Vector3 flows[2] = {main_flow_, compression ? Vector3({0.0, m, -1.0}) : Vector3({m, -1.0, 0.0})};
  const Matrix3 &D = elastic_principal_;
  const Vector3 correctors[2] = {D * flows[0], D * flows[1]};

  // Both planes satisfied: sum_j (a_i . D b_j) dlambda_j = f_i(sigma_trial), a 2x2 system.
  double H[2][2], f[2];
  for (unsigned int i = 0; i < 2; ++i)
    {
      f[i] = normals[i] * trial - compressive_strength_;
      for (unsigned int j = 0; j < 2; ++j)
        H[i][j] = normals[i] * correctors[j];
    }
  const double determinant = H[0][0] * H[1][1] - H[0][1] * H[1][0];
  const double H_inverse[2][2] = {{H[1][1] / determinant, -H[0][1] / determinant},
                                  {-H[1][0] / determinant, H[0][0] / determinant}};
  const double multiplier[2] = {H_inverse[0][0] * f[0] + H_inverse[0][1] * f[1],
                                H_inverse[1][0] * f[0] + H_inverse[1][1] * f[1]};
  // Plastic flow only loads a plane (multiplier >= 0), measured as the stress it removes.
  for (unsigned int i = 0; i < 2; ++i)
    if (multiplier[i] * H[i][i] < -tolerance)
      return false;

  const Vector3 stress = trial - multiplier[0] * correctors[0] - multiplier[1] * correctors[1];
  const bool ordered = compression ? stress[1] >= stress[2] - tolerance : stress[0] >= stress[1] - tolerance;
  if (!ordered)
    return false;

  result.stress = stress;
  result.region = edge;
  if (!with_tangent)
    return true;
  const Vector3 normal_images[2] = {D * normals[0], D * normals[1]};
  result.tangent = D;
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = 0; j < 2; ++j)
      result.tangent -= H_inverse[i][j] * dealii::outer_product(correctors[i], normal_images[j]);
  return true;
}
} // namespace geohybrid::fem
