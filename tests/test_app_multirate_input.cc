// Multi-rate stepping's entries (issue 26): `pullout` (Hybrid/continuum step ratio) and
// `coupling-test` (Multi-rate/continuum step ratios) refuse what multi-rate cannot do, naming the
// entry, before any run; and accept what it can.
#include "apps/coupling_test_command.h"
#include "apps/pullout_command.h"
#include "small_hybrid_pullout_input.h"
#include "temporary_directory.h"

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace
{
std::string refusal_of(const std::function<void()> &run)
{
  try
    {
      run();
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}

std::string hybrid_refusal(const geohybrid::testing::TemporaryDirectory &d, const std::string &hybrid_entries)
{
  const std::string file = geohybrid::testing::write_small_hybrid_pullout_input(
    d.path, "subsection Hybrid\n" + hybrid_entries + "end\n");
  return refusal_of([&] { geohybrid::apps::check_pullout_input(file); });
}

geohybrid::apps::CouplingTestInput coupling_test_input(const std::string &entries)
{
  dealii::ParameterHandler prm;
  geohybrid::apps::declare_coupling_test_parameters(prm);
  prm.parse_input_from_string(entries);
  return geohybrid::apps::parse_coupling_test(prm, "the test's input");
}
} // namespace

TEST(MultiRateInput, HybridRatioNeedsTheMultipliersAndNoCrossing)
{
  const geohybrid::testing::TemporaryDirectory d("multirate_input");
  EXPECT_EQ(hybrid_refusal(d, "  set continuum step ratio = 0\n"), "");
  EXPECT_EQ(hybrid_refusal(d, "  set continuum step ratio = 3\n"), "");
  const std::string penalty = hybrid_refusal(d, "  set continuum step ratio = 3\n  set coupling method = penalty\n");
  EXPECT_NE(penalty.find("'Hybrid/continuum step ratio' = 3 needs 'Hybrid/coupling method' = multipliers"),
            std::string::npos)
    << penalty;
  const std::string crossing = hybrid_refusal(d, "  set continuum step ratio = 0\n  set DEM region length = 0.05\n");
  EXPECT_NE(crossing.find("'Hybrid/continuum step ratio' = 0 cannot be combined with 'Hybrid/DEM region length'"),
            std::string::npos)
    << crossing;
  EXPECT_NE(hybrid_refusal(d, "  set continuum step ratio = -1\n").find("continuum step ratio"), std::string::npos);
}

TEST(MultiRateInput, CouplingTestRatiosAreDivisorsOfTenWithTheMultipliers)
{
  EXPECT_EQ(coupling_test_input("subsection Multi-rate\n  set continuum step ratios = 2, 5\nend\n").continuum_step_ratios,
            (std::vector<unsigned int>{2, 5}));
  EXPECT_TRUE(coupling_test_input("").continuum_step_ratios.empty());
  const std::string three =
    refusal_of([] { coupling_test_input("subsection Multi-rate\n  set continuum step ratios = 3\nend\n"); });
  EXPECT_NE(three.find("'Multi-rate/continuum step ratios' holds 3"), std::string::npos) << three;
  const std::string penalty = refusal_of([] {
    coupling_test_input("set method = penalty\nsubsection Multi-rate\n  set continuum step ratios = 2\nend\n");
  });
  EXPECT_NE(penalty.find("needs 'method' = multipliers"), std::string::npos) << penalty;
}
