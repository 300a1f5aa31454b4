#include "calibration.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
double hexagonal_young_modulus(double normal_stiffness, double stiffness_ratio)
{
  return 2.0 * std::sqrt(3.0) * normal_stiffness * (1.0 + stiffness_ratio) / (3.0 + stiffness_ratio);
}

double hexagonal_poisson_ratio(double stiffness_ratio) { return (1.0 - stiffness_ratio) / (3.0 + stiffness_ratio); }

double hexagonal_stiffness_ratio(double poisson_ratio) { return (1.0 - 3.0 * poisson_ratio) / (1.0 + poisson_ratio); }

void CalibrationTargets::validate() const
{
  const auto require = [](bool ok, const std::string &what) {
    if (!ok)
      throw std::invalid_argument("calibration: " + what);
  };
  require(friction_angle_deg > 0.0 && friction_angle_deg < 90.0, "the target friction angle must lie in (0, 90) deg");
  require(young_modulus > 0.0 && std::isfinite(young_modulus), "the target Young modulus must be positive");
  require(!poisson_ratio || (*poisson_ratio > -1.0 && *poisson_ratio < 1.0),
          "the target Poisson ratio of a 2D medium must lie in (-1, 1)");
  require(friction_angle_tolerance_deg > 0.0, "the friction angle tolerance must be positive");
  require(young_modulus_tolerance > 0.0, "the Young modulus tolerance must be positive");
  require(poisson_ratio_tolerance > 0.0, "the Poisson ratio tolerance must be positive");
  require(max_iterations >= 1, "at least one iteration is needed");
  require(min_friction_angle_deg >= 0.0 && min_friction_angle_deg < max_friction_angle_deg &&
            max_friction_angle_deg < 90.0,
          "the contact friction range must satisfy 0 <= min < max < 90 deg");
  require(min_stiffness_ratio > 0.0 && min_stiffness_ratio < max_stiffness_ratio,
          "the ks/kn range must satisfy 0 < min < max");
}

namespace
{
/// The root of a monotone function of one variable known only through (costly, slightly noisy)
/// measurements, searched within [x_min, x_max]. Once the root is bracketed, regula falsi kept
/// away from the bracket's ends (so the bracket shrinks by at least a tenth per measurement);
/// before, a secant through the last two measurements, or the caller's model guess when there is
/// no usable secant. Steps are capped so that one poor slope estimate cannot throw the search to a
/// bound.
class MonotoneSearch
{
public:
  /// `increasing`: whether the measured value grows with x. `min_width`: two x closer than this
  /// carry no slope information (measurement noise dominates).
  MonotoneSearch(double x_min, double x_max, double target, bool increasing, double max_step, double min_width)
    : x_min_(x_min), x_max_(x_max), target_(target), sign_(increasing ? 1.0 : -1.0), max_step_(max_step),
      min_width_(min_width)
  {}

  void record(double x, double value)
  {
    const Point p{x, sign_ * (value - target_), true}; // the residual g increases with x
    previous_ = latest_;
    latest_ = p;
    if (p.g < 0.0)
      {
        below_ = p;
        // A bracket contradicted by the new point (the response moved as the other parameters
        // changed, or noise) or too narrow to improve on: keep only the side just measured.
        if (above_.known && (above_.x <= p.x || above_.x - p.x < min_width_))
          above_ = Point{};
      }
    else
      {
        above_ = p;
        if (below_.known && (below_.x >= p.x || p.x - below_.x < min_width_))
          below_ = Point{};
      }
  }

  /// The value measured at the bound on the wrong side, when the target is out of reach.
  std::optional<double> out_of_reach_bound() const
  {
    if (latest_.known && latest_.g < 0.0 && latest_.x >= x_max_ - 1e-12 * std::max(1.0, std::abs(x_max_)))
      return x_max_;
    if (latest_.known && latest_.g > 0.0 && latest_.x <= x_min_ + 1e-12 * std::max(1.0, std::abs(x_min_)))
      return x_min_;
    return std::nullopt;
  }

  /// The next x to measure. `model_guess` is used while there is neither a bracket nor a secant.
  double next(double model_guess) const
  {
    if (below_.known && above_.known)
      {
        const double width = above_.x - below_.x;
        const double x = below_.x - below_.g * width / (above_.g - below_.g);
        return std::clamp(x, below_.x + 0.1 * width, above_.x - 0.1 * width);
      }
    const Point &p = latest_;
    double guess = model_guess;
    if (previous_.known && std::abs(p.x - previous_.x) > min_width_)
      {
        const double slope = (p.g - previous_.g) / (p.x - previous_.x);
        if (slope > 0.0)
          guess = p.x - p.g / slope;
      }
    double step = guess - p.x;
    // Go the way the residual says (a model guess or a noisy secant may point back).
    if ((p.g < 0.0) != (step > 0.0))
      step = (p.g < 0.0 ? 0.25 : -0.25) * max_step_;
    step = std::clamp(step, -max_step_, max_step_);
    return std::clamp(p.x + step, x_min_, x_max_);
  }

private:
  struct Point
  {
    double x = 0.0, g = 0.0; ///< where, and the residual there
    bool known = false;
  };
  double x_min_, x_max_, target_, sign_, max_step_, min_width_;
  Point latest_, previous_, below_, above_; ///< below/above: the bracket's ends
};

std::string number(double value, int digits = 4)
{
  std::ostringstream s;
  s.precision(digits);
  s << value;
  return s.str();
}
} // namespace

CalibrationResult calibrate_micro_parameters(const MicroParameters &start, const CalibrationTargets &targets,
                                             const BiaxialModel &model,
                                             const std::function<void(const CalibrationIteration &)> &on_iteration)
{
  targets.validate();
  if (!(start.normal_stiffness > 0.0) || !(start.stiffness_ratio >= 0.0) ||
      !(start.friction_angle_deg >= 0.0 && start.friction_angle_deg < 90.0))
    throw std::invalid_argument("calibration: the starting guess needs kn > 0, ks/kn >= 0 and a friction angle in "
                                "[0, 90) deg");

  // The three parameters are updated together after every campaign, each from the value it
  // mostly controls: friction from phi, ks/kn from nu, kn from E. Not nested: one campaign
  // measures all three values at once, and the couplings are weak (kn and ks/kn barely move phi;
  // ks/kn moves E in a known way, compensated below; friction moves E and nu a little, corrected
  // at the next campaign), so the joint iteration takes about as many campaigns as the slowest of
  // the three 1D problems, where a nested search would repeat the inner searches for every
  // friction. A parameter whose value is within tolerance is held, so that the noise of a met
  // target does not disturb the others.
  //
  // Friction: 20 degrees at most per step; with no slope known yet, one degree of phi per degree
  // of friction (the order of magnitude of 2D cluster samples at low friction).
  MonotoneSearch friction(targets.min_friction_angle_deg, targets.max_friction_angle_deg, targets.friction_angle_deg,
                          true, 20.0, 0.05);
  std::optional<MonotoneSearch> ratio;
  if (targets.poisson_ratio)
    ratio.emplace(targets.min_stiffness_ratio, targets.max_stiffness_ratio, *targets.poisson_ratio, false, 0.5, 0.005);

  CalibrationResult result;
  MicroParameters micro = start;
  for (std::size_t k = 1;; ++k)
    {
      CalibrationIteration it;
      it.index = k;
      it.micro = micro;
      it.macro = model(micro);
      const MacroResponse &m = it.macro;
      if (!std::isfinite(m.friction_angle_deg) || !std::isfinite(m.young_modulus) || !std::isfinite(m.poisson_ratio) ||
          !(m.young_modulus > 0.0))
        {
          result.iterations.push_back(it);
          if (on_iteration)
            on_iteration(it);
          result.failure = "iteration " + std::to_string(k) + " measured phi = " + number(m.friction_angle_deg) +
                           " deg, E = " + number(m.young_modulus) + " Pa, nu = " + number(m.poisson_ratio) +
                           ": the biaxial test gave no usable elastic response";
          return result;
        }
      it.friction_angle_error_deg = m.friction_angle_deg - targets.friction_angle_deg;
      it.young_modulus_error = (m.young_modulus - targets.young_modulus) / targets.young_modulus;
      it.poisson_ratio_error = targets.poisson_ratio ? m.poisson_ratio - *targets.poisson_ratio : 0.0;
      const bool friction_met = std::abs(it.friction_angle_error_deg) <= targets.friction_angle_tolerance_deg;
      const bool modulus_met = std::abs(it.young_modulus_error) <= targets.young_modulus_tolerance;
      const bool poisson_met = !targets.poisson_ratio || std::abs(it.poisson_ratio_error) <= targets.poisson_ratio_tolerance;
      it.converged = friction_met && modulus_met && poisson_met;
      result.iterations.push_back(it);
      if (on_iteration)
        on_iteration(it);
      if (it.converged)
        {
          result.converged = true;
          return result;
        }

      friction.record(micro.friction_angle_deg, m.friction_angle_deg);
      if (ratio)
        ratio->record(micro.stiffness_ratio, m.poisson_ratio);
      if (!friction_met)
        if (const auto bound = friction.out_of_reach_bound())
          {
            result.failure = "the target friction angle " + number(targets.friction_angle_deg) +
                             " deg is out of reach: a contact friction angle of " + number(*bound) +
                             " deg gives a peak friction angle of " + number(m.friction_angle_deg) + " deg";
            return result;
          }
      if (!poisson_met)
        if (const auto bound = ratio->out_of_reach_bound())
          {
            result.failure = "the target Poisson ratio " + number(*targets.poisson_ratio) +
                             " is out of reach: ks/kn = " + number(*bound) + " gives nu = " + number(m.poisson_ratio);
            return result;
          }
      if (k >= targets.max_iterations)
        {
          result.failure = "not converged after " + std::to_string(k) +
                           " iterations (last: phi error " + number(it.friction_angle_error_deg) +
                           " deg, E error " + number(100.0 * it.young_modulus_error) + " %" +
                           (targets.poisson_ratio ? ", nu error " + number(it.poisson_ratio_error) : std::string()) +
                           "); raise the maximum number of iterations or loosen the tolerances";
          return result;
        }

      MicroParameters next = micro;
      if (!poisson_met)
        {
          // Model guess: the hexagonal nu(ks/kn) shifted by the offset measured on this sample.
          const double offset = m.poisson_ratio - hexagonal_poisson_ratio(micro.stiffness_ratio);
          const double hexagonal_target = std::max(*targets.poisson_ratio - offset, -0.9);
          next.stiffness_ratio = ratio->next(hexagonal_stiffness_ratio(hexagonal_target));
        }
      if (!friction_met)
        next.friction_angle_deg = friction.next(micro.friction_angle_deg - it.friction_angle_error_deg);
      // E proportional to kn at fixed ks/kn, times the hexagonal dependence on ks/kn, so that a
      // change of ks/kn does not by itself move E. The factor is capped: one bad measurement of E
      // must not move kn by orders of magnitude.
      const double modulus_factor = modulus_met ? 1.0 : std::clamp(targets.young_modulus / m.young_modulus, 0.1, 10.0);
      next.normal_stiffness = micro.normal_stiffness * modulus_factor *
                              hexagonal_young_modulus(1.0, micro.stiffness_ratio) /
                              hexagonal_young_modulus(1.0, next.stiffness_ratio);
      micro = next;
    }
}
} // namespace geohybrid::dem
