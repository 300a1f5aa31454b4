#pragma once
// The search of `geohybrid design`: the smallest value in [minimum, maximum] at which a criterion
// that is false below some value and true above it is met, to within `tolerance`. It knows
// nothing of runs: it names the value to try next and is told whether the criterion was met there.
//
// Both ends are tried first (minimum, then maximum), so that a criterion that is not bracketed
// (met at both ends, met at neither, or met at the minimum and not at the maximum: the wrong way
// round) stops the search with that said, instead of a bisection that would then return an end.
// Then midpoints, rounded to grid() so that a value is short to write and names its directory,
// until the highest value that failed and the lowest that met are within `tolerance`: the answer
// is the latter, a value that was tried, and the criterion failed at a tried value no further
// than `tolerance` below it.
#include <cmath>
#include <stdexcept>
#include <vector>

namespace geohybrid::apps
{
class DesignBisection
{
public:
  enum class Outcome
  {
    running,          ///< next() is the value to try
    found,            ///< answer(): the lowest value met, highest_failing() within the tolerance below
    not_reached,      ///< met at neither end
    met_at_minimum,   ///< met at both ends: the answer is at or below the minimum
    decreasing        ///< met at the minimum but not at the maximum: not the monotone rise assumed
  };

  struct Trial
  {
    double value;
    bool met;
  };

  /// Throws std::invalid_argument unless 0 < tolerance < maximum - minimum.
  DesignBisection(double minimum, double maximum, double tolerance)
    : minimum_(minimum), maximum_(maximum), tolerance_(tolerance), low_(minimum), high_(maximum)
  {
    if (!(tolerance > 0.0 && tolerance < maximum - minimum))
      throw std::invalid_argument("a bisection needs 0 < tolerance < maximum - minimum");
  }

  /// A power of ten a hundred times below the tolerance at least: midpoints are rounded to it,
  /// which moves them by at most a two-hundredth of the tolerance.
  double grid() const { return std::pow(10.0, std::floor(std::log10(tolerance_)) - 2.0); }

  /// The value to try next; only while outcome() is running.
  double next() const
  {
    if (trials_.size() == 0)
      return minimum_;
    if (trials_.size() == 1)
      return maximum_;
    return std::round(0.5 * (low_ + high_) / grid()) * grid();
  }

  /// Records the criterion at next() (the value tried, as it was run: `value` may be next()
  /// read back from its text).
  void record(double value, bool met)
  {
    if (outcome_ != Outcome::running)
      throw std::logic_error("DesignBisection::record after the search ended");
    trials_.push_back({value, met});
    if (trials_.size() == 1)
      return;
    if (trials_.size() == 2)
      {
        const bool at_minimum = trials_[0].met;
        outcome_ = at_minimum ? (met ? Outcome::met_at_minimum : Outcome::decreasing)
                              : (met ? Outcome::running : Outcome::not_reached);
      }
    else
      (met ? high_ : low_) = value;
    // A relative slack of 1e-9: 0.08 - 0.06 is 0.020000000000000004, and a bracket of the tolerance
    // in decimal is within it.
    if (outcome_ == Outcome::running && high_ - low_ <= tolerance_ * (1.0 + 1e-9))
      outcome_ = Outcome::found;
  }

  Outcome outcome() const { return outcome_; }
  double answer() const { return high_; }          ///< the lowest value met (found)
  double highest_failing() const { return low_; }  ///< the highest value not met (found)
  const std::vector<Trial> &trials() const { return trials_; }

private:
  double minimum_, maximum_, tolerance_;
  double low_, high_; ///< criterion not met at low_, met at high_ (once both ends are tried)
  std::vector<Trial> trials_;
  Outcome outcome_ = Outcome::running;
};
} // namespace geohybrid::apps
