#pragma once
// The soil's constitutive law, chosen once at set-up among the models of this folder and then
// called per quadrature point without a virtual call (a std::variant and one std::visit).
#include "drucker_prager_model.h"
#include "linear_elastic_model.h"
#include "mohr_coulomb_model.h"

#include <string>
#include <variant>

namespace geohybrid::fem
{
enum class SoilModelKind
{
  linear_elastic,
  mohr_coulomb,
  drucker_prager ///< matched to Mohr-Coulomb in plane strain
};

/// What the user gives (from the biaxial calibration of the DEM soil, or by hand).
struct SoilParameters
{
  SoilModelKind kind = SoilModelKind::mohr_coulomb;
  double young_modulus = 50e6;   ///< E [Pa]
  double poisson_ratio = 0.3;    ///< nu [-]
  MohrCoulombStrength strength;  ///< phi, c, psi (ignored by the linear elastic model)
};

SoilModelKind soil_model_kind_from_string(const std::string &name); ///< "linear elastic", "Mohr-Coulomb", "Drucker-Prager"
const char *to_string(SoilModelKind kind);

class SoilModel
{
public:
  using Law = std::variant<LinearElasticModel, MohrCoulombModel, DruckerPragerModel>;

  /// Builds and validates the law; errors name `where` and the parameter.
  explicit SoilModel(const SoilParameters &parameters, const std::string &where = "soil");
  explicit SoilModel(Law law) : law_(std::move(law)) {}

  StressUpdate update(const StressTensor &stress, const StrainTensor &strain_increment) const
  {
    return std::visit([&](const auto &law) { return law.update(stress, strain_increment); }, law_);
  }
  /// update() without the tangent, for the explicit solver: the same stress, bit for bit.
  StressOnlyUpdate update_stress(const StressTensor &stress, const StrainTensor &strain_increment) const
  {
    return std::visit([&](const auto &law) { return law.update_stress(stress, strain_increment); }, law_);
  }
  double yield_function(const StressTensor &stress) const
  {
    return std::visit([&](const auto &law) { return law.yield_function(stress); }, law_);
  }
  bool has_symmetric_tangent() const
  {
    return std::visit([](const auto &law) { return law.has_symmetric_tangent(); }, law_);
  }
  const IsotropicElasticity &elasticity() const
  {
    return std::visit([](const auto &law) -> const IsotropicElasticity & { return law.elasticity(); }, law_);
  }
  /// K0 = 1 - sin(phi) (Jaky) for the plastic models, nu / (1 - nu) (lateral confinement of an
  /// elastic layer) for the elastic one.
  double default_k0() const;
  SoilModelKind kind() const;
  const Law &law() const { return law_; }

private:
  Law law_;
};
} // namespace geohybrid::fem
