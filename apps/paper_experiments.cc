#include "paper_experiments.h"

#include "run_directory.h"

#include <deal.II/base/parameter_handler.h>

#include <cmath>

namespace geohybrid::apps
{
const std::vector<PaperValue> &paper_wraparound_values()
{
  static const std::vector<PaperValue> values{
    // Table 3: sand 1, INSA tank, experiments [kN/m].
    {"Table 3", "experiment", "sand 1", "GT75", 0.2, 0.4, 0.25, 13.0},
    {"Table 3", "experiment", "sand 1", "GT75", 0.2, 0.4, 0.5, 14.0},
    {"Table 3", "experiment", "sand 1", "GT75", 0.3, 0.5, 0.25, 18.1},
    {"Table 3", "experiment", "sand 1", "GT75", 0.3, 0.5, 0.5, 19.4},
    {"Table 3", "experiment", "sand 1", "GT230", 0.2, 0.4, 0.25, 14.2},
    {"Table 3", "experiment", "sand 1", "GT230", 0.2, 0.4, 0.5, 14.8},
    {"Table 3", "experiment", "sand 1", "GT230", 0.3, 0.5, 0.25, 20.6},
    {"Table 3", "experiment", "sand 1", "GT230", 0.3, 0.5, 0.5, 21.2},
    // Table 4: gravel, INSA tank, experiments [kN/m].
    {"Table 4", "experiment", "gravel", "GT75", 0.2, 0.4, 0.25, 26.8},
    {"Table 4", "experiment", "gravel", "GT75", 0.2, 0.4, 0.5, 27.2},
    {"Table 4", "experiment", "gravel", "GT230", 0.2, 0.4, 0.25, 23.4},
    {"Table 4", "experiment", "gravel", "GT230", 0.2, 0.4, 0.5, 23.4},
    {"Table 4", "experiment", "gravel", "GT230", 0.3, 0.5, 0.25, 31.4},
    {"Table 4", "experiment", "gravel", "GT230", 0.3, 0.5, 0.5, 33.8},
    // Table 6: the paper's PFC2D, 7.9, 8.2, 8.35 and 8.5 kN for b = 0.5 m, here per metre.
    {"Table 6", "the paper's PFC2D", "sand 1", "GT230", 0.2, 0.4, 0.125, 15.8},
    {"Table 6", "the paper's PFC2D", "sand 1", "GT230", 0.2, 0.4, 0.25, 16.4},
    {"Table 6", "the paper's PFC2D", "sand 1", "GT230", 0.2, 0.4, 0.5, 16.7},
    {"Table 6", "the paper's PFC2D", "sand 1", "GT230", 0.2, 0.4, 0.75, 17.0},
  };
  return values;
}

namespace
{
bool within(double value, double reference, double relative) { return std::abs(value - reference) <= relative * reference; }
} // namespace

std::vector<PaperValue> paper_values_for(const dealii::ParameterHandler &prm)
{
  std::vector<PaperValue> found;
  if (get_parameter(prm, "Anchorage/type") != "wrap-around")
    return found;
  const auto value = [&](const std::string &path) { return std::stod(get_parameter(prm, path)); };
  const double J = value("Sheet/axial stiffness"), gamma = value("Soil/unit weight");
  const std::string geosynthetic = within(J, 2104e3, 0.01) ? "GT230" : within(J, 687e3, 0.01) ? "GT75" : "";
  const std::string soil = within(gamma, 15.2e3, 0.01) ? "sand 1" : within(gamma, 19.5e3, 0.01) ? "gravel" : "";
  const double D1 = value("Anchorage/D1"), D2 = value("Anchorage/D2"), H = value("Anchorage/H"), B = value("Anchorage/B");
  const double mm = 1e-3;
  if (geosynthetic.empty() || soil.empty() || std::abs(D1 + D2 - H) > mm)
    return found;
  for (const PaperValue &v : paper_wraparound_values())
    if (v.geosynthetic == geosynthetic && v.soil == soil && std::abs(v.D1 - D1) <= mm && std::abs(v.H - H) <= mm &&
        std::abs(v.B - B) <= mm)
      found.push_back(v);
  return found;
}

std::string paper_case_name(const PaperValue &v)
{
  return v.geosynthetic + " wrap-around in " + v.soil + ", D1 = " + number(v.D1) + " m, H = " + number(v.H) +
         " m, B = " + number(v.B) + " m";
}
} // namespace geohybrid::apps
