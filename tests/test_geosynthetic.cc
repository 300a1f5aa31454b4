// The geosynthetic's tension-only chain (geosynthetic/tension_only_chain.h) on its own: T against
// J strain, nothing when slack, the energy as the work of T, the two roundings of T agreeing to
// rounding, and the node stiffness of ends and interior nodes.
#include "geosynthetic/tension_only_chain.h"

#include <gtest/gtest.h>

#include <vector>

using geohybrid::geosynthetic::TensionOnlyChain;

namespace
{
const TensionOnlyChain gt230{2.104e6}; // J of GT230 [N/m]
} // namespace

TEST(TensionOnlyChain, TensionIsJTimesTheStrainWhenTautAndNothingWhenSlack)
{
  const double l0 = 5e-3;
  EXPECT_NEAR(gt230.tension(1.01 * l0, l0), 0.01 * 2.104e6, 1e-9 * 2.104e6);
  EXPECT_EQ(gt230.tension(l0, l0), 0.0);
  EXPECT_EQ(gt230.tension(0.5 * l0, l0), 0.0);
  EXPECT_EQ(gt230.tension(0.0, l0), 0.0); // folded onto itself
  EXPECT_FALSE(TensionOnlyChain::is_taut(l0, l0));
  EXPECT_TRUE(TensionOnlyChain::is_taut(1.001 * l0, l0));
}

TEST(TensionOnlyChain, TheContinuumsRoundingAgreesToRounding)
{
  const double l0 = 7e-3;
  for (double factor : {0.9, 1.0, 1.0001, 1.003, 1.05})
    {
      const double l = factor * l0;
      const double by_strain = gt230.tension_at_strain(TensionOnlyChain::strain(l, l0));
      EXPECT_NEAR(by_strain, gt230.tension(l, l0), 1e-12 * gt230.axial_stiffness) << factor;
      EXPECT_GE(by_strain, 0.0) << factor;
    }
}

TEST(TensionOnlyChain, EnergyIsTheWorkOfTheTension)
{
  // dE/dl = T: a centred difference of the energy against T, and E = T^2 l0 / (2 J).
  const double l0 = 1e-2, l = 1.02 * l0, h = 1e-7 * l0;
  const double slope = (gt230.elastic_energy(l + h, l0) - gt230.elastic_energy(l - h, l0)) / (2.0 * h);
  EXPECT_NEAR(slope, gt230.tension(l, l0), 1e-6 * gt230.tension(l, l0));
  const double T = gt230.tension(l, l0);
  EXPECT_NEAR(gt230.elastic_energy(l, l0), T * T * l0 / (2.0 * gt230.axial_stiffness), 1e-12);
  EXPECT_EQ(gt230.elastic_energy(0.99 * l0, l0), 0.0);
}

TEST(TensionOnlyChain, NodeStiffnessCountsTheSegmentsANodeEnds)
{
  const std::vector<double> rest_lengths{0.01, 0.02, 0.04}; // 4 nodes
  const double k = 3e5;                                      // a contact's stiffness
  EXPECT_DOUBLE_EQ(gt230.node_stiffness(rest_lengths.data(), 4, 0, k), k + gt230.axial_stiffness / 0.01);
  EXPECT_DOUBLE_EQ(gt230.node_stiffness(rest_lengths.data(), 4, 1, k),
                   k + gt230.axial_stiffness / 0.01 + gt230.axial_stiffness / 0.02);
  EXPECT_DOUBLE_EQ(gt230.node_stiffness(rest_lengths.data(), 4, 3, 0.0), gt230.spring_stiffness(0.04));
}
