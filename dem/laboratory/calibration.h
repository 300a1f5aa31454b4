#pragma once
// Calibration of contact micro-parameters against macroscopic targets (issue 3, the paper's
// section 4.2): the inter-particle friction angle, the normal stiffness kn and the stiffness
// ratio ks/kn are adjusted by repeated biaxial tests until the sample's peak friction angle,
// Young modulus and (optionally) Poisson ratio meet their targets.
//
// This file holds only the iteration logic: how the next guess follows from what was measured.
// The biaxial test itself is a callable, so the logic can be checked against a cheap analytic
// model as well as driven by real DEM runs (apps/calibrate_command.cc).
//
// What each update assumes (each one is a 1D problem with one dominant parameter):
//  - phi_peak increases monotonically with the contact friction: bracketed secant on the friction
//    angle, between 0 and a maximum (89 degrees); a target above what the maximum gives (or below
//    what frictionless contacts give) is out of reach.
//  - E is about proportional to kn at a fixed ks/kn (linear contacts, stiff grains), with the
//    ks/kn dependence of a regular hexagonal packing, E = 2 sqrt(3) kn (kn + ks) / (3 kn + ks).
//  - nu decreases with ks/kn, shaped as for the hexagonal packing, nu = (kn - ks) / (3 kn + ks),
//    plus an offset measured on the sample; bracketed secant on ks/kn once two runs are known.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace geohybrid::dem
{
/// What is adjusted.
struct MicroParameters
{
  double friction_angle_deg = 10.0; ///< contact friction angle delta [deg]
  double normal_stiffness = 7e7;    ///< kn [N/m/m]
  double stiffness_ratio = 0.5;     ///< ks / kn [-]
};

/// What a biaxial campaign measures.
struct MacroResponse
{
  double friction_angle_deg = 0.0; ///< peak friction angle phi' [deg]
  double young_modulus = 0.0;      ///< E [Pa]
  double poisson_ratio = 0.0;      ///< nu [-]
};

struct CalibrationTargets
{
  double friction_angle_deg = 0.0;           ///< phi' [deg], in (0, 90)
  double young_modulus = 0.0;                ///< E [Pa], positive
  std::optional<double> poisson_ratio;       ///< nu [-]; empty = not targeted (ks/kn held)
  double friction_angle_tolerance_deg = 0.5; ///< |phi - target| accepted [deg]
  double young_modulus_tolerance = 0.05;     ///< |E - target| / target accepted [-]
  double poisson_ratio_tolerance = 0.02;     ///< |nu - target| accepted [-]
  std::size_t max_iterations = 12;           ///< biaxial campaigns at most
  double min_friction_angle_deg = 0.0;       ///< search range of the contact friction [deg]
  double max_friction_angle_deg = 89.0;
  double min_stiffness_ratio = 0.05;         ///< search range of ks/kn [-]
  double max_stiffness_ratio = 1.0;

  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// One biaxial campaign of the calibration and how far it is from the targets.
struct CalibrationIteration
{
  std::size_t index = 0; ///< 1 for the starting guess
  MicroParameters micro;
  MacroResponse macro;
  double friction_angle_error_deg = 0.0; ///< phi - target [deg]
  double young_modulus_error = 0.0;      ///< (E - target) / target [-]
  double poisson_ratio_error = 0.0;      ///< nu - target [-]; 0 when nu is not targeted
  bool converged = false;                ///< every targeted value within its tolerance
};

struct CalibrationResult
{
  bool converged = false;
  /// Why it stopped without converging: a target out of reach (naming the parameter and what
  /// its bound gives) or the iteration limit. Empty when converged.
  std::string failure;
  std::vector<CalibrationIteration> iterations; ///< in order; the last is the result
};

/// Runs a biaxial campaign with the given micro-parameters and reports the macro response.
using BiaxialModel = std::function<MacroResponse(const MicroParameters &)>;

/// Young modulus of a regular hexagonal packing of equal discs, E = 2 sqrt(3) kn (1 + r) / (3 + r)
/// with r = ks/kn (per metre of thickness) [Pa].
double hexagonal_young_modulus(double normal_stiffness, double stiffness_ratio);
/// Poisson ratio of the same packing, nu = (1 - r) / (3 + r) [-].
double hexagonal_poisson_ratio(double stiffness_ratio);
/// The inverse of hexagonal_poisson_ratio: r = (1 - 3 nu) / (1 + nu), for nu > -1.
double hexagonal_stiffness_ratio(double poisson_ratio);

/// Calibrates from `start`, calling `model` once per iteration and `on_iteration` (optional)
/// after each. Stops at the first iteration meeting every target, at a target out of reach, or
/// after targets.max_iterations. Exceptions from `model` propagate. Deterministic: the same
/// model gives the same sequence.
CalibrationResult calibrate_micro_parameters(const MicroParameters &start, const CalibrationTargets &targets,
                                             const BiaxialModel &model,
                                             const std::function<void(const CalibrationIteration &)> &on_iteration = {});
} // namespace geohybrid::dem
