// The hash of a pull-out's physics (apps/parameters_hash.h, `geohybrid pullout FILE
// --print-parameters-hash`): FNV-1a's published values; one hash for inputs that differ only in
// run-control entries or in how they are written, another for a changed stiffness or seed; the
// input checked as a run checks it, nothing written; and the hash a tiny run's summary.json holds.
#include "apps/parameters_hash.h"
#include "apps/pullout_command.h"
#include "temporary_directory.h"
#include "text_file.h"
#include "tiny_pullout_input.h"

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace parameters_hash_test
{
/// `base` included, then `extra`: an input that says the same as base plus extra.
std::string input_with(const fs::path &directory, const std::string &name, const std::string &base,
                       const std::string &extra)
{
  const fs::path file = directory / (name + ".prm");
  std::ofstream(file) << "# " << name << "\ninclude " << base << "\n" << extra;
  return file.string();
}

/// The string a flat summary.json gives `key`, empty if none.
std::string summary_string(const fs::path &file, const std::string &key)
{
  const std::string text = geohybrid::testing::read_text(file);
  const std::string start = "\"" + key + "\": \"";
  const auto at = text.find(start);
  if (at == std::string::npos)
    return "";
  return text.substr(at + start.size(), text.find('"', at + start.size()) - at - start.size());
}
} // namespace parameters_hash_test

// Fowler, Noll and Vo's test vectors for FNV-1a 64 (the empty string gives the offset basis).
TEST(ParametersHash, Fnv1aGivesThePublishedValues)
{
  using geohybrid::apps::fnv1a_64;
  EXPECT_EQ(fnv1a_64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a_64("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a_64("foobar"), 0x85944171f73967e8ULL);
}

// Run-control entries (and writing the same input another way: through an include, with
// comments) leave the hash as it is; a stiffness or the seed changes it. Nothing is written.
TEST(ParametersHash, RunControlEntriesLeaveItPhysicsChangesIt)
{
  using geohybrid::apps::check_pullout_input;
  using parameters_hash_test::input_with;
  const geohybrid::testing::TemporaryDirectory d("parameters_hash");
  const std::string base = geohybrid::testing::write_tiny_pullout_input(d.path);
  const std::string hash = check_pullout_input(base);
  ASSERT_EQ(hash.size(), 16u);
  EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos) << hash;
  EXPECT_EQ(check_pullout_input(input_with(d.path, "run_control", base,
                                           "set output directory = " + (d.path / "elsewhere").string() +
                                             "\nset threads = 2\nset checkpoint interval = 10 # s\n"
                                             "set stop after steps = 100\n"
                                             "subsection Filling\n  set lift cache directory = " +
                                             (d.path / "lifts").string() + "\nend\n")),
            hash);
  const std::string stiffer = check_pullout_input(input_with(
    d.path, "stiffer", base, "subsection Sheet\n  subsection Interface\n    set normal stiffness = 2e7\n  end\nend\n"));
  const std::string seed_4 =
    check_pullout_input(input_with(d.path, "seed_4", base, "subsection Filling\n  set seed = 4\nend\n"));
  EXPECT_NE(stiffer, hash);
  EXPECT_NE(seed_4, hash);
  EXPECT_NE(seed_4, stiffer);
  // What is hashed: the resolved entries by path, without the run-control ones.
  dealii::ParameterHandler prm;
  geohybrid::apps::declare_pullout_parameters(prm);
  prm.parse_input(base);
  dealii::ParameterHandler defaults;
  geohybrid::apps::declare_pullout_parameters(defaults);
  const std::string canonical =
    geohybrid::apps::canonical_parameters(prm, defaults, geohybrid::apps::pullout_run_control_entries());
  EXPECT_EQ(canonical.rfind(std::string(geohybrid::apps::numbers_version) + "\n", 0), 0u) << canonical;
  EXPECT_NE(canonical.find("\nFilling/seed = 3\n"), std::string::npos) << canonical;
  EXPECT_NE(canonical.find("\nSheet/Interface/normal stiffness = 1e7\n"), std::string::npos) << canonical;
  EXPECT_EQ(canonical.find("threads"), std::string::npos) << canonical;
  EXPECT_EQ(canonical.find("output directory"), std::string::npos) << canonical;
  EXPECT_EQ(geohybrid::apps::pullout_parameters_hash(prm), hash);
  EXPECT_FALSE(fs::exists(d.path / "out"));
  EXPECT_FALSE(fs::exists(d.path / "elsewhere"));
  EXPECT_FALSE(fs::exists(d.path / "lifts"));
}

// Only entries that differ from their defaults are hashed: an entry set to its default, or one
// declared later with a default that keeps the numbers (here a made-up 'Pull/future entry'),
// leaves the hash as it was, so that committed runs stay matched to their inputs.
TEST(ParametersHash, EntriesAtTheirDefaultsLeaveIt)
{
  using geohybrid::apps::check_pullout_input;
  const geohybrid::testing::TemporaryDirectory d("parameters_hash");
  const std::string base = geohybrid::testing::write_tiny_pullout_input(d.path);
  const std::string hash = check_pullout_input(base);
  dealii::ParameterHandler defaults;
  geohybrid::apps::declare_pullout_parameters(defaults);
  const std::string mode_default = defaults.get("mode");
  dealii::ParameterHandler resolved;
  geohybrid::apps::declare_pullout_parameters(resolved);
  resolved.parse_input(base);
  ASSERT_EQ(resolved.get("mode"), mode_default); // the tiny input leaves it
  EXPECT_EQ(check_pullout_input(
              parameters_hash_test::input_with(d.path, "mode_default", base, "set mode = " + mode_default + "\n")),
            hash);
  // 'Hybrid/lift thickness' = 0.05, its default before auto (which gives the same numbers
  // wherever 0.05 gave any), is hashed as auto: parameters.prm files that spell it keep their hash.
  EXPECT_EQ(check_pullout_input(parameters_hash_test::input_with(d.path, "former_lifts", base,
                                                                 "subsection Hybrid\n  set lift thickness = 0.05\nend\n")),
            hash);
  EXPECT_NE(check_pullout_input(parameters_hash_test::input_with(d.path, "other_lifts", base,
                                                                 "subsection Hybrid\n  set lift thickness = 0.1\nend\n")),
            hash);
  // The same input with one more entry in both the declarations and the defaults.
  const auto with_future_entry = [](dealii::ParameterHandler &prm) {
    geohybrid::apps::declare_pullout_parameters(prm);
    prm.enter_subsection("Pull");
    prm.declare_entry("future entry", "0.5", dealii::Patterns::Double());
    prm.leave_subsection();
  };
  dealii::ParameterHandler later, later_defaults;
  with_future_entry(later);
  with_future_entry(later_defaults);
  later.parse_input(base);
  const auto control = geohybrid::apps::pullout_run_control_entries();
  EXPECT_EQ(geohybrid::apps::parameters_hash(later, later_defaults, control), hash);
  later.enter_subsection("Pull");
  later.set("future entry", "0.25");
  later.leave_subsection();
  EXPECT_NE(geohybrid::apps::parameters_hash(later, later_defaults, control), hash);
  // Another value changes it (the tiny input pulls at 0.01 m/s).
  EXPECT_NE(check_pullout_input(
              parameters_hash_test::input_with(d.path, "rate", base, "subsection Pull\n  set rate = 0.0123\nend\n")),
            hash);
}

// The input is refused as the run refuses it, by name, before anything is written.
TEST(ParametersHash, RefusesWhatTheRunRefuses)
{
  const geohybrid::testing::TemporaryDirectory d("parameters_hash");
  const std::string base = geohybrid::testing::write_tiny_pullout_input(d.path);
  for (const auto &[extra, expected] :
       {std::pair<std::string, std::string>{"subsection Anchorage\n  set L = 5\nend\n", "'Anchorage/L'"},
        {"set mode = hybrid\n", "'Hybrid/DEM region margin'"},
        {"subsection Filling\n  set number of layers = 3\nend\n", "'Filling/number of layers'"}})
    {
      std::string message;
      try
        {
          geohybrid::apps::check_pullout_input(parameters_hash_test::input_with(d.path, "bad", base, extra));
        }
      catch (const std::exception &e)
        {
          message = e.what();
        }
      EXPECT_NE(message.find(expected), std::string::npos) << extra << " -> " << message;
      EXPECT_NE(message.find("bad.prm"), std::string::npos) << message;
      EXPECT_FALSE(fs::exists(d.path / "out")) << extra;
    }
}

// A tiny run (about 3 s of CPU) writes the hash of its input into summary.json; its resolved
// parameters.prm, read as an input, gives it again (bench/run_validation resumes a scratch run
// only if so).
TEST(ParametersHash, SummaryHoldsTheHashOfItsInput)
{
  const geohybrid::testing::TemporaryDirectory d("parameters_hash");
  const std::string input = geohybrid::testing::write_tiny_pullout_input(d.path);
  const std::string hash = geohybrid::apps::check_pullout_input(input);
  ASSERT_EQ(geohybrid::apps::run_pullout_command(input, false), 0);
  EXPECT_EQ(parameters_hash_test::summary_string(d.path / "out" / "summary.json", "parameters_hash"), hash);
  EXPECT_EQ(geohybrid::apps::check_pullout_input((d.path / "out" / "parameters.prm").string()), hash);
}
