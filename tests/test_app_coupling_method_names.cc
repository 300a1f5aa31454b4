// The coupling methods' names (issue 25): each is spelled once (coupling/coupling_method.h), parses
// back to its own method, and both commands that choose a method accept it; coupling-test still
// accepts its old spellings; an unknown name is refused with a message that lists the names.
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

/// The method coupling-test reads from `set method = name`.
CouplingMethod coupling_test_method(const std::string &name)
{
  dealii::ParameterHandler prm;
  geohybrid::apps::declare_coupling_test_parameters(prm);
  prm.parse_input_from_string("set method = " + name + "\n");
  return geohybrid::apps::parse_coupling_test(prm, "the test's input").method;
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
} // namespace coupling_method_names_test
