// The main job (README.md, scripts/run_main_job.sh: `geohybrid pullout
// examples/pullout_hybrid_wraparound_h040_b025.prm`, the hybrid wrap-around) pinned bit for bit.
// Its box's fill takes minutes, so the box is the one the main job filled (tests/main_job/
// filled_box.h5): the run resumes from it as `--resume` would, repeats the whole coupled set-up
// (the box's settling, the continuum, the tie, the coupled settling) and pulls until its first
// curve points, which must equal those main's code gave (tests/main_job/first_curve_points.txt,
// how they were made is written there) to the last bit. The input is the example's own: only
// run-control entries change (output directory, stop after steps, no full-size curve).
#include "apps/pullout_command.h"
#include "dem/io/checkpoint.h"
#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
const fs::path source_dir = GEOHYBRID_SOURCE_DIR;

/// The reference: one curve point per line, its five numbers as C hexadecimal floats.
std::vector<std::vector<double>> reference_points(const fs::path &file)
{
  std::ifstream in(file);
  std::vector<std::vector<double>> points;
  std::string line;
  while (std::getline(in, line))
    {
      if (line.empty() || line[0] == '#')
        continue;
      std::istringstream words(line);
      std::vector<double> point;
      std::string word;
      while (words >> word)
        point.push_back(std::strtod(word.c_str(), nullptr));
      points.push_back(point);
    }
  return points;
}

std::uint64_t bits(double x)
{
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
} // namespace

// About a minute of CPU: the set-up from the filled box, then 5,000 steps of the pull (1.45 mm).
TEST(MainJob, FirstCurvePointsAreMainsBitForBit)
{
  const std::vector<std::vector<double>> expected = reference_points(source_dir / "tests/main_job/first_curve_points.txt");
  ASSERT_GE(expected.size(), 3u);
  const geohybrid::testing::TemporaryDirectory d("test_main_job");
  const fs::path out = d.path / "out";
  fs::create_directories(out);
  fs::copy_file(source_dir / "tests/main_job/filled_box.h5", out / "filled_box.h5");
  ASSERT_EQ(geohybrid::apps::run_pullout_command(
              (source_dir / "examples/pullout_hybrid_wraparound_h040_b025.prm").string(), true,
              {{"output directory", out.string()}, {"stop after steps", "5000"}, {"Output/full-size runs", ""}}),
            0);
  ASSERT_FALSE(fs::exists(out / "summary.json")); // stopped, as asked
  // The checkpoint holds the points as numbers (the CSV files round them to 10 digits).
  const std::vector<double> points = geohybrid::dem::read_checkpoint_command(out / "checkpoint.h5").real("curve_points");
  ASSERT_EQ(points.size(), 5 * expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k)
    for (std::size_t i = 0; i < 5; ++i)
      EXPECT_EQ(bits(points[5 * k + i]), bits(expected[k][i]))
        << "point " << k << ", column " << i << ": " << std::hexfloat << points[5 * k + i] << " (main's code: "
        << expected[k][i] << ")";
}
