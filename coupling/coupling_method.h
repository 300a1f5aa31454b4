#pragma once
// The coupling methods the input chooses among (issue 6), as plain parameter types in one
// std::variant: the coupled stepper visits it once per step, never per particle.
//
// 1. Bridging domain with Lagrange multipliers (Xiao & Belytschko 2004): each band particle's
//    velocity is constrained to the continuum's velocity interpolated at it, exactly, every step.
// 2. Penalty overlap: each band particle is tied to the continuum's displacement interpolated at
//    it by a spring of stiffness k_p = penalty factor x E x (particle diameter / band width).
// Both use the same energy weights (overlap_band.h). The third method of the issue (a
// non-overlapping interface, the FE boundary edges as deformable walls) is not written yet.
#include <stdexcept>
#include <string>
#include <variant>

namespace geohybrid::coupling
{
struct LagrangeMultiplierCoupling
{};

struct PenaltyCoupling
{
  /// k_p / (E d / w): E the continuum's Young modulus, d the particle's diameter, w the band
  /// width; stiffer ties the constraint better and lowers the stable step [-].
  double penalty_factor = 1.0;

  void validate() const
  {
    if (!(penalty_factor > 0.0) || !(penalty_factor < 1e12))
      throw std::invalid_argument("penalty coupling: parameter 'penalty factor' = " + std::to_string(penalty_factor) +
                                  " must be positive and finite");
  }
};

using CouplingMethod = std::variant<LagrangeMultiplierCoupling, PenaltyCoupling>;
} // namespace geohybrid::coupling
