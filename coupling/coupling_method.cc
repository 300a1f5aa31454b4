#include "coupling_method.h"

#include <type_traits>
#include <utility>

namespace geohybrid::coupling
{
namespace
{
/// The alternative at `index`, default-constructed.
template <std::size_t... I>
CouplingMethod method_at(std::size_t index, std::index_sequence<I...>)
{
  CouplingMethod method;
  ((index == I ? (void)method.emplace<I>() : (void)0), ...);
  return method;
}

std::string listed_names()
{
  std::string names;
  for (const std::string_view name : coupling_method_names)
    names += (names.empty() ? "" : ", ") + std::string(name);
  return names;
}
} // namespace

std::string coupling_method_selection(bool with_aliases)
{
  std::string selection;
  for (const std::string_view name : coupling_method_names)
    selection += (selection.empty() ? "" : "|") + std::string(name);
  if (with_aliases)
    for (const CouplingMethodAlias &alias : coupling_method_aliases)
      selection += "|" + std::string(alias.alias);
  return selection;
}

CouplingMethod parse_coupling_method_name(std::string_view name, const std::string &where, const std::string &entry)
{
  for (const CouplingMethodAlias &alias : coupling_method_aliases)
    if (name == alias.alias)
      name = alias.name;
  for (std::size_t i = 0; i < coupling_method_names.size(); ++i)
    if (name == coupling_method_names[i])
      return method_at(i, std::make_index_sequence<std::variant_size_v<CouplingMethod>>());
  throw std::invalid_argument(where + ": parameter '" + entry + "' = '" + std::string(name) +
                              "' names no coupling method: use one of " + listed_names());
}

std::string_view name_of(const CouplingMethod &method)
{
  return std::visit([](const auto &m) { return std::decay_t<decltype(m)>::name; }, method);
}

bool has_band(const CouplingMethod &method)
{
  return std::visit([](const auto &m) { return std::decay_t<decltype(m)>::has_band; }, method);
}
} // namespace geohybrid::coupling
