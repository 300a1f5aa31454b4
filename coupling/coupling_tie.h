#pragma once
// The interface every coupling method's tie implements, checked at compile time over one
// std::variant (static polymorphism: the stepper visits the variant once per evaluation, and each
// tie's loops over its particles are its own, with no virtual call in them):
//
//   static constexpr std::string_view name;   the method's name (coupling_method.h)
//   void apply(dem::ParticleSet &, fem::ExplicitSolver &, const TieTiming &, CouplingForceSums &);
//                                               the coupling forces on both sides, at t_{n+1}
//   double energy() const;                      what the tie stores and has dissipated [J/m]
//   double squared_frequency_bound(const dem::ParticleSet &, const fem::ExplicitSolver &) const;
//                                               what it adds to the coupled system's omega^2 (Weyl)
//
// What the ties do not share stays with the one that needs it: the multipliers' velocity gap and
// damping exemption (LagrangeTie), the interface's contacts (InterfaceWall). The band (methods 1
// and 2: its weights, its driven particles) is set up by the stepper, which each band tie reads.
#include "coupling/coupling_forces.h"
#include "coupling/coupling_method.h"
#include "coupling/interface_wall.h"
#include "coupling/lagrange_tie.h"
#include "coupling/penalty_tie.h"
#include "dem/particles.h"
#include "fem/explicit_solver.h"

#include <cstddef>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

namespace geohybrid::coupling
{
/// True if `Tie` has the interface above, with those types (a C++17 stand-in for a concept).
template <typename Tie, typename = void>
struct is_coupling_tie : std::false_type
{};

template <typename Tie>
struct is_coupling_tie<
  Tie, std::void_t<decltype(std::declval<Tie &>().apply(std::declval<dem::ParticleSet &>(),
                                                        std::declval<fem::ExplicitSolver &>(),
                                                        std::declval<const TieTiming &>(),
                                                        std::declval<CouplingForceSums &>())),
                   decltype(std::declval<const Tie &>().energy()),
                   decltype(std::declval<const Tie &>().squared_frequency_bound(
                     std::declval<const dem::ParticleSet &>(), std::declval<const fem::ExplicitSolver &>())),
                   decltype(Tie::name)>>
  : std::bool_constant<
      std::is_same_v<decltype(std::declval<const Tie &>().energy()), double> &&
      std::is_same_v<decltype(std::declval<const Tie &>().squared_frequency_bound(
                       std::declval<const dem::ParticleSet &>(), std::declval<const fem::ExplicitSolver &>())),
                     double> &&
      std::is_same_v<std::decay_t<decltype(Tie::name)>, std::string_view>>
{};

template <typename Tie>
inline constexpr bool is_coupling_tie_v = is_coupling_tie<Tie>::value;

/// The ties, in the order of CouplingMethod's alternatives: the tie at index i is method i's.
using CouplingTie = std::variant<LagrangeTie, PenaltyTie, InterfaceWall>;

namespace detail
{
template <std::size_t... I>
constexpr bool ties_match_methods(std::index_sequence<I...>)
{
  return (... && (is_coupling_tie_v<std::variant_alternative_t<I, CouplingTie>> &&
                  std::variant_alternative_t<I, CouplingTie>::name ==
                    std::variant_alternative_t<I, CouplingMethod>::name));
}
} // namespace detail

static_assert(std::variant_size_v<CouplingTie> == std::variant_size_v<CouplingMethod>,
              "every coupling method needs its tie in CouplingTie, in the same order");
static_assert(detail::ties_match_methods(std::make_index_sequence<std::variant_size_v<CouplingTie>>()),
              "each tie must implement the coupling tie interface (is_coupling_tie) and carry its method's name");
} // namespace geohybrid::coupling
