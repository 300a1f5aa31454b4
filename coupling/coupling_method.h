#pragma once
// The coupling methods the input chooses among (issue 6), as plain parameter types in one
// std::variant: the coupled stepper visits it once per step, never per particle.
//
// 1. Bridging domain with Lagrange multipliers (Xiao & Belytschko 2004): each band particle's
//    velocity is constrained to the continuum's velocity interpolated at it, exactly, every step.
// 2. Penalty overlap: each band particle is tied to the continuum's displacement interpolated at
//    it by a spring of stiffness k_p = penalty factor x E x (particle diameter / band width).
// Both use the same energy weights (overlap_band.h).
// 3. Non-overlapping interface (interface_wall.h): no band and no weights; the continuum's
//    boundary edges facing the particles are deformable walls, touched by the discs through the
//    DEM's contact law, and the contact forces go back to the edges' nodes.
#include "dem/contact_law.h"

#include <deal.II/base/types.h>

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

  /// Throws std::invalid_argument naming `where` and the parameter as the input spells it.
  void validate(const std::string &where = "penalty coupling", const std::string &name = "penalty factor") const
  {
    if (!(penalty_factor > 0.0) || !(penalty_factor < 1e12))
      throw std::invalid_argument(where + ": parameter '" + name + "' = " + std::to_string(penalty_factor) +
                                  " must be positive and finite");
  }
};

struct InterfaceCoupling
{
  /// The mesh's boundary id of the edges that face the particles (Q1 cells) [-].
  dealii::types::boundary_id boundary_id = 0;
  /// The disc-edge contact law (the same LinearContactLaw as the DEM's walls): kn, ks [N/m/m],
  /// friction angle [deg], restitution [-]. Frictional only: no bonds across the interface.
  dem::ContactParameters contact;

  void validate() const
  {
    contact.validate("interface coupling");
    if (contact.tensile_strength != 0.0 || contact.shear_strength != 0.0 || contact.bond_new_contacts)
      throw std::invalid_argument("interface coupling: parameters 'tensile strength' and 'shear strength' must be 0 "
                                  "(the interface contacts are frictional, never bonded)");
  }
};

using CouplingMethod = std::variant<LagrangeMultiplierCoupling, PenaltyCoupling, InterfaceCoupling>;
} // namespace geohybrid::coupling
