#pragma once
// The coupling methods the input chooses among (issue 6), as plain parameter types in one
// std::variant: the coupled stepper visits it once per step, never per particle. Each type's
// `name` is the one spelling of that method, in every command's input, pattern, message and
// summary (issue 25); `has_band` is the one place that says method 3 has no overlap band.
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

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>

namespace geohybrid::coupling
{
struct LagrangeMultiplierCoupling
{
  static constexpr std::string_view name = "multipliers";
  static constexpr bool has_band = true;
};

struct PenaltyCoupling
{
  static constexpr std::string_view name = "penalty";
  static constexpr bool has_band = true;

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
  static constexpr std::string_view name = "interface";
  /// No band, no weights, no tied or driven particles: the discs touch the continuum's edges.
  static constexpr bool has_band = false;

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

namespace detail
{
template <typename Variant>
struct MethodNames;
template <typename... Method>
struct MethodNames<std::variant<Method...>>
{
  static constexpr std::array<std::string_view, sizeof...(Method)> value{{Method::name...}};
};
} // namespace detail

/// Every method's name, in the variant's order: read off the types, so a new method cannot be
/// left out.
inline constexpr auto coupling_method_names = detail::MethodNames<CouplingMethod>::value;

/// An earlier spelling still accepted as input (coupling-test's before issue 25), and the name it
/// stands for.
struct CouplingMethodAlias
{
  std::string_view alias, name;
};
inline constexpr std::array<CouplingMethodAlias, 2> coupling_method_aliases{{
  {"Lagrange multipliers", LagrangeMultiplierCoupling::name},
  {"non-overlapping interface", InterfaceCoupling::name},
}};

/// The names joined by '|', for dealii::Patterns::Selection; `with_aliases` appends the aliases
/// (a command that accepted them before).
std::string coupling_method_selection(bool with_aliases = false);

/// The method named `name` (or an alias of it), with its default parameters. Throws
/// std::invalid_argument naming `where`, `entry` and the value, and listing the names.
CouplingMethod parse_coupling_method_name(std::string_view name, const std::string &where = "coupling method",
                                          const std::string &entry = "coupling method");

/// The method's name, as the input spells it and summary.json writes it.
std::string_view name_of(const CouplingMethod &method);

/// False for the non-overlapping interface (method 3), true for the band's methods (1 and 2).
bool has_band(const CouplingMethod &method);
} // namespace geohybrid::coupling
