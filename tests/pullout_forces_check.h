#pragma once
// pullout_forces.csv of a finished dem or hybrid pull, checked against its pullout_curve.csv.
#include "text_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

namespace geohybrid::testing
{
/// Where the head tension comes from: per row the five parts (each a mean over the steps of the
/// curve's point) sum to its head tension, which is the curve's; the sheet is pressed; no contact
/// carries more than its Coulomb limit; and the clamp's booked work is the curve's integral of
/// T du. Both are taken from the first point on: a point is the mean over equal steps, which is
/// the mean over the displacement only at a constant speed (the first interval holds the ramp).
inline void expect_pullout_forces_add_up(const std::filesystem::path &out)
{
  ASSERT_EQ(lines_of(out / "pullout_forces.csv")[0].substr(0, 62),
            "head_displacement_m,head_tension_kN_per_m,interface_friction_k");
  const std::vector<std::vector<double>> forces = numbers_of(out / "pullout_forces.csv"),
                                         points = numbers_of(out / "pullout_curve.csv");
  ASSERT_EQ(forces.size(), points.size());
  double integral = 0.0;
  for (std::size_t r = 0; r < forces.size(); ++r)
    {
      const std::vector<double> &f = forces[r], &c = points[r];
      ASSERT_EQ(f.size(), 13u);
      EXPECT_NEAR(f[1], c[1], 1e-9 * std::abs(c[1]) + 1e-12) << r;
      EXPECT_NEAR(f[2] + f[3] + f[4] + f[5] + f[6], f[1], 1e-9 * std::abs(f[1]) + 1e-12) << r;
      EXPECT_GT(f[7], 0.0) << r;
      EXPECT_GE(f[8], 0.0);
      EXPECT_LE(f[8], 1.0 + 1e-9) << r;
      if (r > 1)
        integral += 1e3 * c[1] * (c[0] - points[r - 1][0]);
    }
  const double clamp_work = forces.back()[12] - forces[1][12];
  EXPECT_GT(clamp_work, 0.0);
  EXPECT_NEAR(clamp_work, integral, 0.02 * integral);
}
} // namespace geohybrid::testing
