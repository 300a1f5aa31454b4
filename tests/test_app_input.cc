// Input files: an 'include' names its file relative to the including file, so that an input and
// the soil fragment beside it (examples/soil/sand1.prm) run from any working directory.
#include "apps/run_directory.h"
#include "temporary_directory.h"

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace
{
void declare(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Soil");
  prm.enter_subsection("Particle contact");
  prm.declare_entry("friction angle", "10", dealii::Patterns::Double());
  prm.leave_subsection();
  prm.leave_subsection();
}
double friction_angle(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Soil");
  prm.enter_subsection("Particle contact");
  const double value = prm.get_double("friction angle");
  prm.leave_subsection();
  prm.leave_subsection();
  return value;
}
} // namespace

TEST(InputFile, IncludeIsFoundBesideTheIncludingFile)
{
  const fs::path d = geohybrid::testing::fresh_directory("test_app_input");
  fs::create_directories(d / "examples" / "soil");
  std::ofstream(d / "examples" / "soil" / "sand.prm") << "subsection Particle contact\n  set friction angle = 30.5\nend\n";
  std::ofstream(d / "examples" / "case.prm") << "# a case\nsubsection Soil\n  include soil/sand.prm   # the soil\nend\n";
  // The working directory (the build's tests folder) holds no soil/sand.prm: only the rule
  // "beside the including file" finds it.
  ASSERT_FALSE(fs::exists("soil/sand.prm"));
  dealii::ParameterHandler prm;
  declare(prm);
  geohybrid::apps::parse_input_file(prm, (d / "examples" / "case.prm").string());
  EXPECT_EQ(friction_angle(prm), 30.5);

  // A file that is nowhere: the error names the input file and the line.
  std::ofstream(d / "examples" / "missing.prm") << "subsection Soil\n  include soil/none.prm\nend\n";
  dealii::ParameterHandler other;
  declare(other);
  try
    {
      geohybrid::apps::parse_input_file(other, (d / "examples" / "missing.prm").string());
      FAIL() << "a missing include was accepted";
    }
  catch (const std::exception &e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("missing.prm"), std::string::npos) << what;
      EXPECT_NE(what.find("none.prm"), std::string::npos) << what;
      EXPECT_NE(what.find('2'), std::string::npos) << what; // the line of the include
    }
  fs::remove_all(d);
}
