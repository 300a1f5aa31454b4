#pragma once
// Mean, extremes and sample standard deviation of a few values (the T_max of the seeds of an
// ensemble, `pullout --seeds`, or of a sweep's value, `sweep`).
#include <algorithm>
#include <cmath>
#include <vector>

namespace geohybrid::apps
{
struct Spread
{
  double mean = 0.0, min = 0.0, max = 0.0;
  double std = 0.0; ///< sample standard deviation (n - 1); 0 for one value
};

/// The spread of `v`, which must not be empty.
inline Spread spread_of(const std::vector<double> &v)
{
  Spread s;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  for (const double x : v)
    s.mean += x / static_cast<double>(v.size());
  if (v.size() > 1)
    {
      double squares = 0.0;
      for (const double x : v)
        squares += (x - s.mean) * (x - s.mean);
      s.std = std::sqrt(squares / static_cast<double>(v.size() - 1));
    }
  return s;
}
} // namespace geohybrid::apps
