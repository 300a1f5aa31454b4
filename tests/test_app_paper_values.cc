// The paper's Tables 3, 4 and 6 are held twice on purpose: in the code (apps/paper_experiments.h,
// what `geohybrid report` compares a run with) and as data in the repository
// (validation/paper/pullout_experiments.csv, what the campaign's scripts read). The two must agree
// row for row, so that the report and VALIDATION.md never quote different experiments.
#include "apps/paper_experiments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct CsvRow
{
  std::string source, soil, geosynthetic;
  double D1, H, B, T_max;
};

std::vector<CsvRow> read_paper_csv(const std::string &file)
{
  std::ifstream in(file);
  EXPECT_TRUE(in) << file;
  std::vector<CsvRow> rows;
  std::string line;
  bool header_seen = false;
  while (std::getline(in, line))
  {
    if (line.empty() || line[0] == '#')
      continue;
    if (!header_seen)
    {
      EXPECT_EQ(line, "source,soil,geosynthetic,D1_m,H_m,B_m,T_max_kN_per_m") << file;
      header_seen = true;
      continue;
    }
    std::istringstream fields(line);
    CsvRow r;
    std::string cell[7];
    for (std::string &c : cell)
      std::getline(fields, c, ',');
    r.source = cell[0], r.soil = cell[1], r.geosynthetic = cell[2];
    r.D1 = std::stod(cell[3]), r.H = std::stod(cell[4]), r.B = std::stod(cell[5]), r.T_max = std::stod(cell[6]);
    rows.push_back(r);
  }
  return rows;
}

/// "table3" -> "Table 3"; "sand1" -> "sand 1".
std::string table_name(const std::string &source) { return "Table " + source.substr(5); }
std::string soil_name(const std::string &soil) { return soil == "sand1" ? "sand 1" : soil; }
} // namespace

TEST(PaperValues, TheCodeHoldsTheRepositorysCsvRowForRow)
{
  const std::vector<CsvRow> csv = read_paper_csv(GEOHYBRID_SOURCE_DIR "/validation/paper/pullout_experiments.csv");
  const auto &code = geohybrid::apps::paper_wraparound_values();
  ASSERT_EQ(csv.size(), 18u); // Table 3: 8 rows, Table 4: 6, Table 6: 4, as the paper prints them
  ASSERT_EQ(code.size(), csv.size());
  for (const CsvRow &r : csv)
  {
    int matches = 0;
    for (const auto &v : code)
      if (v.table == table_name(r.source) && v.soil == soil_name(r.soil) && v.geosynthetic == r.geosynthetic &&
          std::abs(v.D1 - r.D1) < 1e-9 && std::abs(v.H - r.H) < 1e-9 && std::abs(v.B - r.B) < 1e-9)
      {
        ++matches;
        EXPECT_DOUBLE_EQ(v.T_max_kN_per_m, r.T_max) << r.source << ' ' << r.geosynthetic << " B = " << r.B;
      }
    EXPECT_EQ(matches, 1) << r.source << ' ' << r.geosynthetic << " D1 = " << r.D1 << " B = " << r.B;
  }
}
