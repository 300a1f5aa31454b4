#pragma once
// Elastic-perfectly plastic Mohr-Coulomb soil with non-associated flow (dilatancy angle psi <= phi)
// and its consistent tangent.
//
// The stress update is a backward-Euler return mapping carried out in principal stresses
// (Clausen, Damkilde & Andersen, "Efficient return algorithms for associated plasticity with
// multiple yield planes", IJNME 66, 2006, and their 2007 non-associated sequel; de Souza Neto,
// Peric & Owen 2008, section 8.2). Because the criterion is linear in the sorted principal stresses
// sigma_1 >= sigma_2 >= sigma_3, each return is closed form:
//   - to the main plane f = k sigma_1 - sigma_3 - sigma_c = 0, along the plastic corrector D b,
//     b = dg/dsigma = (m, 0, -1);
//   - to an edge, where two planes are active and the return is a combination of both correctors:
//     sigma_1 = sigma_2 (triaxial compression) or sigma_2 = sigma_3 (triaxial extension);
//   - to the apex sigma_1 = sigma_2 = sigma_3 = c cot(phi).
// The main-plane return is tried first; if it breaks the ordering of the principal stresses, the
// edge it crossed is tried (then the other one), and an edge return with a negative multiplier
// means the apex. Signs: tension positive (fem/conventions.h).
#include "isotropic_elasticity.h"
#include "mohr_coulomb_strength.h"
#include "stress_update.h"

#include <deal.II/base/tensor.h>

#include <array>
#include <string>

namespace geohybrid::fem
{
class MohrCoulombModel
{
public:
  /// Throws std::invalid_argument naming `where` if a strength parameter is out of range.
  MohrCoulombModel(const IsotropicElasticity &elasticity, const MohrCoulombStrength &strength,
                   const std::string &where = "Mohr-Coulomb soil");

  /// Stress after the in-plane strain increment `strain_increment` from the converged `stress`.
  StressUpdate update(const StressTensor &stress, const StrainTensor &strain_increment) const;
  /// The same without the tangent (the explicit solver's, at every point every step): the same
  /// stress, plastic strain and region, bit for bit, for less work on the plastic points (no
  /// tangent in principal space, no rotation of it) and a smaller result on all.
  StressOnlyUpdate update_stress(const StressTensor &stress, const StrainTensor &strain_increment) const
  {
    return update(stress, strain_increment, nullptr);
  }

  /// f = k sigma_1 - sigma_3 - sigma_c [Pa]: <= 0 inside the yield surface.
  double yield_function(const StressTensor &stress) const;

  /// The tangent is symmetric only for associated flow (psi = phi).
  bool has_symmetric_tangent() const { return strength_.dilatancy_angle_deg == strength_.friction_angle_deg; }

  const IsotropicElasticity &elasticity() const { return elasticity_; }
  const MohrCoulombStrength &strength() const { return strength_; }

private:
  using Vector3 = dealii::Tensor<1, 3>;
  using Matrix3 = dealii::Tensor<2, 3>;

  /// Both updates: the tangent goes to `tangent` unless it is nullptr (then it is not computed;
  /// nothing of the stress depends on it).
  StressOnlyUpdate update(const StressTensor &stress, const StrainTensor &strain_increment,
                          TangentTensor *tangent) const;

  /// The return of a trial stress given by its sorted principal values, with d(sigma)/d(eps_trial)
  /// in the same sorted principal space if `with_tangent` (left zero otherwise).
  struct PrincipalReturn
  {
    Vector3 stress;
    Matrix3 tangent;
    ReturnRegion region;
  };
  PrincipalReturn return_in_principal_space(const Vector3 &trial, bool with_tangent) const;
  bool return_to_edge(const Vector3 &trial, ReturnRegion edge, double tolerance, bool with_tangent,
                      PrincipalReturn &result) const;

  IsotropicElasticity elasticity_;
  MohrCoulombStrength strength_;
  double compressive_strength_; ///< sigma_c [Pa]
  double apex_stress_;          ///< c cot(phi) [Pa]
  Matrix3 elastic_principal_;   ///< D = lambda 1 1^T + 2 G I, the elastic law in principal space
  Vector3 main_normal_;         ///< a = (k, 0, -1): gradient of the main plane
  Vector3 main_flow_;           ///< b = (m, 0, -1): gradient of its plastic potential
};
} // namespace geohybrid::fem
