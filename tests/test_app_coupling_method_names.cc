// The coupling methods' names (issue 25): each is spelled once (coupling/coupling_method.h), parses
// back to its own method, and both commands that choose a method accept it; coupling-test still
// accepts its old spellings; an unknown name is refused with a message that lists the names.
// The multi-rate entries (issue 26) that need one method, the multipliers, are checked here too.
#include "apps/coupling_test_command.h"
#include "apps/pullout_command.h"
#include "coupling/coupling_method.h"
#include "small_hybrid_pullout_input.h"
#include "temporary_directory.h"

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace coupling_method_names_test
{
using geohybrid::coupling::CouplingMethod;
namespace coupling = geohybrid::coupling;

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

/// What coupling-test reads from `entries`.
geohybrid::apps::CouplingTestInput coupling_test_input(const std::string &entries)
{
  dealii::ParameterHandler prm;
  geohybrid::apps::declare_coupling_test_parameters(prm);
  prm.parse_input_from_string(entries);
  return geohybrid::apps::parse_coupling_test(prm, "the test's input");
}

/// The method coupling-test reads from `set method = name`.
CouplingMethod coupling_test_method(const std::string &name)
{
  return coupling_test_input("set method = " + name + "\n").method;
}

/// What `pullout` says of the small hybrid tank with `hybrid_entries` in its subsection Hybrid
/// ("" if it takes the input).
std::string hybrid_refusal(const geohybrid::testing::TemporaryDirectory &d, const std::string &hybrid_entries)
{
  const std::string file =
    geohybrid::testing::write_small_hybrid_pullout_input(d.path, "subsection Hybrid\n" + hybrid_entries + "end\n");
  return refusal_of([&] { geohybrid::apps::check_pullout_input(file); });
}

void expect_lists_the_names(const std::string &message)
{
  for (const std::string_view name : coupling::coupling_method_names)
    EXPECT_NE(message.find(std::string(name)), std::string::npos) << name << ": " << message;
}

TEST(CouplingMethodNames, EachNameParsesBackToItsMethod)
{
  ASSERT_EQ(coupling::coupling_method_names.size(), std::variant_size_v<CouplingMethod>);
  for (std::size_t i = 0; i < coupling::coupling_method_names.size(); ++i)
    {
      const std::string_view name = coupling::coupling_method_names[i];
      const CouplingMethod method = coupling::parse_coupling_method_name(name);
      EXPECT_EQ(method.index(), i) << name;
      EXPECT_EQ(coupling::name_of(method), name);
    }
  EXPECT_EQ(coupling::name_of(coupling::LagrangeMultiplierCoupling{}), "multipliers");
  EXPECT_EQ(coupling::name_of(coupling::PenaltyCoupling{}), "penalty");
  EXPECT_EQ(coupling::name_of(coupling::InterfaceCoupling{}), "interface");
  EXPECT_EQ(coupling::coupling_method_selection(), "multipliers|penalty|interface");
  // The old spellings stand for the same methods.
  for (const coupling::CouplingMethodAlias &alias : coupling::coupling_method_aliases)
    EXPECT_EQ(coupling::name_of(coupling::parse_coupling_method_name(alias.alias)), alias.name);
}

TEST(CouplingMethodNames, AnUnknownNameIsRefusedListingTheNames)
{
  const std::string message =
    refusal_of([] { coupling::parse_coupling_method_name("springs", "input file 'x.prm'", "Hybrid/coupling method"); });
  EXPECT_NE(message.find("input file 'x.prm'"), std::string::npos) << message;
  EXPECT_NE(message.find("'Hybrid/coupling method' = 'springs'"), std::string::npos) << message;
  expect_lists_the_names(message);
  EXPECT_THROW(coupling::parse_coupling_method_name(""), std::invalid_argument);
  EXPECT_THROW(coupling::parse_coupling_method_name("Multipliers"), std::invalid_argument); // spelled exactly
}

TEST(CouplingMethodNames, CouplingTestAcceptsEachNameAndTheOldSpellings)
{
  for (std::size_t i = 0; i < coupling::coupling_method_names.size(); ++i)
    EXPECT_EQ(coupling_test_method(std::string(coupling::coupling_method_names[i])).index(), i);
  for (const coupling::CouplingMethodAlias &alias : coupling::coupling_method_aliases)
    EXPECT_EQ(coupling::name_of(coupling_test_method(std::string(alias.alias))), alias.name);
  // The pattern refuses an unknown name, and its message lists the names.
  const std::string message = refusal_of([] { coupling_test_method("springs"); });
  EXPECT_NE(message.find("springs"), std::string::npos) << message;
  expect_lists_the_names(message);
}

TEST(CouplingMethodNames, HybridPullOutAcceptsEachName)
{
  const geohybrid::testing::TemporaryDirectory d("coupling_method_names");
  for (const std::string_view name : coupling::coupling_method_names)
    {
      const std::string file = geohybrid::testing::write_small_hybrid_pullout_input(
        d.path, "subsection Hybrid\n  set coupling method = " + std::string(name) + "\nend\n");
      EXPECT_EQ(refusal_of([&] { geohybrid::apps::check_pullout_input(file); }), "") << name;
    }
  const std::string file =
    geohybrid::testing::write_small_hybrid_pullout_input(d.path, "subsection Hybrid\n  set coupling method = springs\nend\n");
  const std::string message = refusal_of([&] { geohybrid::apps::check_pullout_input(file); });
  EXPECT_NE(message.find("coupling method"), std::string::npos) << message;
  expect_lists_the_names(message);
}

// Multi-rate stepping's entries (issue 26): `pullout`'s 'Hybrid/continuum step ratio' and
// `coupling-test`'s 'Multi-rate/continuum step ratios' need the multipliers, and refuse, naming
// the entry, what multi-rate cannot do, before any run.
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
} // namespace coupling_method_names_test
