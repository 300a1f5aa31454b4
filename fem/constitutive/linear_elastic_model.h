#pragma once
// The linear elastic soil: Hooke's law applied to the strain increment, no yield. Used for the
// closed-form checks (patch test, Lame cylinder) and for stiff regions that never yield.
#include "isotropic_elasticity.h"
#include "plane_strain_tensors.h"
#include "stress_update.h"

namespace geohybrid::fem
{
class LinearElasticModel
{
public:
  explicit LinearElasticModel(const IsotropicElasticity &elasticity) : elasticity_(elasticity) {}

  StressUpdate update(const StressTensor &stress, const StrainTensor &strain_increment) const
  {
    StressUpdate result;
    result.stress = stress + elasticity_.stress(embed_in_3d(strain_increment));
    result.tangent = elasticity_.plane_strain_stiffness();
    return result;
  }
  StressOnlyUpdate update_stress(const StressTensor &stress, const StrainTensor &strain_increment) const
  {
    StressOnlyUpdate result;
    result.stress = stress + elasticity_.stress(embed_in_3d(strain_increment));
    return result;
  }

  /// Never yields: the yield function is -infinity in spirit; -1 keeps arithmetic finite.
  double yield_function(const StressTensor &) const { return -1.0; }
  bool has_symmetric_tangent() const { return true; }
  const IsotropicElasticity &elasticity() const { return elasticity_; }

private:
  IsotropicElasticity elasticity_;
};
} // namespace geohybrid::fem
