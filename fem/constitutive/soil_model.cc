#include "soil_model.h"

#include <stdexcept>
#include <type_traits>

namespace geohybrid::fem
{
namespace
{
SoilModel::Law make_law(const SoilParameters &p, const std::string &where)
{
  const IsotropicElasticity elasticity(p.young_modulus, p.poisson_ratio, where);
  switch (p.kind)
    {
      case SoilModelKind::linear_elastic: return LinearElasticModel(elasticity);
      case SoilModelKind::mohr_coulomb: return MohrCoulombModel(elasticity, p.strength, where);
      case SoilModelKind::drucker_prager: return DruckerPragerModel(elasticity, p.strength, where);
    }
  throw std::invalid_argument(where + ": unknown soil model kind");
}
} // namespace

SoilModel::SoilModel(const SoilParameters &parameters, const std::string &where)
  : law_(make_law(parameters, where))
{}

SoilModelKind soil_model_kind_from_string(const std::string &name)
{
  if (name == "linear elastic")
    return SoilModelKind::linear_elastic;
  if (name == "Mohr-Coulomb")
    return SoilModelKind::mohr_coulomb;
  if (name == "Drucker-Prager")
    return SoilModelKind::drucker_prager;
  throw std::invalid_argument("soil model '" + name +
                              "' is not one of: linear elastic, Mohr-Coulomb, Drucker-Prager");
}

const char *to_string(SoilModelKind kind)
{
  switch (kind)
    {
      case SoilModelKind::linear_elastic: return "linear elastic";
      case SoilModelKind::mohr_coulomb: return "Mohr-Coulomb";
      case SoilModelKind::drucker_prager: return "Drucker-Prager";
    }
  return "unknown";
}

SoilModelKind SoilModel::kind() const
{
  return std::visit(
    [](const auto &law) {
      using Type = std::decay_t<decltype(law)>;
      if constexpr (std::is_same_v<Type, LinearElasticModel>)
        return SoilModelKind::linear_elastic;
      else if constexpr (std::is_same_v<Type, MohrCoulombModel>)
        return SoilModelKind::mohr_coulomb;
      else
        return SoilModelKind::drucker_prager;
    },
    law_);
}

double SoilModel::default_k0() const
{
  return std::visit(
    [](const auto &law) {
      if constexpr (std::is_same_v<std::decay_t<decltype(law)>, LinearElasticModel>)
        {
          const double nu = law.elasticity().poisson_ratio();
          return nu / (1.0 - nu);
        }
      else
        return law.strength().jaky_k0();
    },
    law_);
}
} // namespace geohybrid::fem
