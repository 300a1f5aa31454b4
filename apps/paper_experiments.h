#pragma once
// The maximum head tensions of the reference paper's wrap-around anchorages, the one copy of them
// in the code: Lajevardi, Briançon, Dias et al., "Experimental and numerical studies for
// geosynthetics anchorage with wrap around" (../shared/reference/ beside the repository, text of the paper; the
// same values as validation/paper/pullout_experiments.csv, which bench/validation_report reads):
//
//   Table 3: INSA tank, sand 1, experiments (b = 0.5 m), kN/m;
//   Table 4: INSA tank, gravel, experiments (b = 0.5 m), kN/m;
//   Table 6: the paper's own PFC2D model, GT230, sand 1, H = 0.40 m, D1 = D2 = 0.20 m, given in kN
//            for the 0.5 m wide sheet and converted here to kN/m (x 2).
//
// `geohybrid report` finds a run's case from its resolved input (parameters.prm): a wrap-around,
// the sheet by its stiffness J (Table 2: GT230 2104 kN/m, GT75 687 kN/m, within 1 %), the soil by
// its unit weight (Table 1: sand 1 15.2 kN/m3, gravel 19.5 kN/m3, within 1 %; nothing else in an
// input names the soil), D1, H and B within 1 mm and D2 = H - D1.
#include <string>
#include <vector>

namespace dealii
{
class ParameterHandler;
}

namespace geohybrid::apps
{
struct PaperValue
{
  std::string table;        ///< "Table 3", "Table 4" or "Table 6"
  std::string kind;         ///< "experiment" or "the paper's PFC2D"
  std::string soil;         ///< "sand 1" or "gravel"
  std::string geosynthetic; ///< "GT230" or "GT75"
  double D1, H, B;          ///< [m]
  double T_max_kN_per_m;
};

/// Every row of Tables 3, 4 and 6.
const std::vector<PaperValue> &paper_wraparound_values();

/// The rows of the paper for the case of a pull-out input (declare_pullout_parameters, resolved),
/// as above; none if the input is not one of the paper's cases.
std::vector<PaperValue> paper_values_for(const dealii::ParameterHandler &pullout_input);

/// The case in words: "GT230 wrap-around in sand 1, D1 = 0.2 m, H = 0.4 m, B = 0.25 m".
std::string paper_case_name(const PaperValue &value);
} // namespace geohybrid::apps
