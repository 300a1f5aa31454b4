#pragma once
// What a soil model returns for one material point and one strain increment: the new stress, the
// consistent tangent (the exact derivative of the new stress with respect to the strain increment,
// which gives Newton's method its quadratic convergence), and what happened.
#include "fem/conventions.h"

namespace geohybrid::fem
{
/// Where the return mapping ended, for the tangent, the tests and the output.
enum class ReturnRegion : unsigned char
{
  elastic,                   ///< the trial stress was admissible
  surface,                   ///< a smooth part of the yield surface (Mohr-Coulomb plane, Drucker-Prager cone)
  edge_triaxial_compression, ///< Mohr-Coulomb edge sigma_1 = sigma_2 (two least compressive equal)
  edge_triaxial_extension,   ///< Mohr-Coulomb edge sigma_2 = sigma_3 (two most compressive equal)
  apex                       ///< the tip of the yield surface: hydrostatic tension c cot(phi)
};

const char *to_string(ReturnRegion region);

struct StressUpdate
{
  StressTensor stress;                                 ///< sigma_{n+1}, with sigma_zz [Pa]
  TangentTensor tangent;                               ///< d(sigma_{n+1})/d(delta eps), in plane [Pa]
  dealii::SymmetricTensor<2, 3> plastic_strain_increment; ///< delta eps^p, with its zz part [-]
  ReturnRegion region = ReturnRegion::elastic;
};

/// A stress update without the tangent: what the explicit solver needs (it assembles no
/// stiffness). Its stress, plastic strain increment and region are those of the full update to
/// the last bit (the same arithmetic, the tangent's left out).
struct StressOnlyUpdate
{
  StressTensor stress;                                    ///< sigma_{n+1}, with sigma_zz [Pa]
  dealii::SymmetricTensor<2, 3> plastic_strain_increment; ///< delta eps^p, with its zz part [-]
  ReturnRegion region = ReturnRegion::elastic;
};

inline const char *to_string(ReturnRegion region)
{
  switch (region)
    {
      case ReturnRegion::elastic: return "elastic";
      case ReturnRegion::surface: return "surface";
      case ReturnRegion::edge_triaxial_compression: return "edge (triaxial compression)";
      case ReturnRegion::edge_triaxial_extension: return "edge (triaxial extension)";
      case ReturnRegion::apex: return "apex";
    }
  return "unknown";
}
} // namespace geohybrid::fem
