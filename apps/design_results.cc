#include "design_results.h"

#include "plot.h"
#include "run_directory.h"
#include "summary.h"
#include "sweep_results.h"

#include "dem/io/checked_output.h"

#include <algorithm>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace geohybrid::apps
{
bool meets_criterion(const DesignDefinition &design, const DesignStep &step)
{
  return step.complete() && step.criterion_kN(design.margin_factor) >= design.target_kN;
}

std::vector<std::string> monotonicity_warnings(const DesignDefinition &design, const std::vector<DesignStep> &steps)
{
  std::vector<const DesignStep *> sorted;
  for (const DesignStep &s : steps)
    if (s.complete())
      sorted.push_back(&s);
  std::sort(sorted.begin(), sorted.end(), [](const DesignStep *a, const DesignStep *b) { return a->value < b->value; });
  std::vector<std::string> warnings;
  for (std::size_t k = 1; k < sorted.size(); ++k)
    {
      const Spread low = sorted[k - 1]->spread(), high = sorted[k]->spread();
      if (high.mean < low.mean)
        warnings.push_back("T_max falls from " + number(low.mean, 4) + " kN/m (std " + number(low.std, 3) + ") at " +
                           design.entry_name + " = " + sorted[k - 1]->text + " m to " + number(high.mean, 4) +
                           " kN/m (std " + number(high.std, 3) + ") at " + design.entry_name + " = " + sorted[k]->text +
                           " m: the design assumes it rises with " + design.entry_name +
                           ", so the answer may not be the smallest value that meets the target");
    }
  return warnings;
}

void write_design_table(const DesignDefinition &design, const std::vector<DesignStep> &steps,
                        const std::filesystem::path &csv)
{
  std::ofstream out(csv);
  out << "step," << design.entry_name << "_m,T_max_kN_per_m,T_max_std_kN_per_m,T_max_min_kN_per_m,T_max_max_kN_per_m,"
      << "n_runs,criterion_kN_per_m,target_kN_per_m,met,directory,message\n";
  for (std::size_t k = 0; k < steps.size(); ++k)
    {
      const DesignStep &s = steps[k];
      out << k + 1 << ',' << s.text << ',';
      if (s.T_max_kN.empty())
        out << ",,,,";
      else
        {
          const Spread spread = s.spread();
          out << number(spread.mean) << ',' << number(spread.std) << ',' << number(spread.min) << ','
              << number(spread.max) << ',';
        }
      out << s.T_max_kN.size() << ',' << (s.complete() ? number(s.criterion_kN(design.margin_factor)) : "") << ','
          << number(design.target_kN) << ',' << (s.complete() ? (meets_criterion(design, s) ? "yes" : "no") : "")
          << ',' << csv_field(s.directory) << ',' << csv_field(s.message) << '\n';
    }
  dem::close_checked(out, csv);
}

bool plot_design(const DesignDefinition &design, const DesignAnswer &answer, bool with_seeds,
                 const std::filesystem::path &csv, const std::filesystem::path &png)
{
  const std::string target = number(design.target_kN);
  std::string settings = "set termoption noenhanced\nset key outside bottom center horizontal\n"
                         "set offsets graph 0.05, graph 0.05, graph 0.1, graph 0.1\n"
                         "set arrow from graph 0, first " + target + " to graph 1, first " + target +
                         " nohead lw 2 lc rgb 'red' dt 2\n"
                         "set label 'target " + number(design.target_kN, 4) + " kN/m' at graph 0.02, first " + target +
                         " offset 0, 0.8 tc rgb 'red'\n";
  if (answer.answer)
    settings += "set arrow from first " + number(*answer.answer) + ", graph 0 to first " + number(*answer.answer) +
                ", graph 1 nohead lw 1.5 lc rgb 'dark-green' dt 3\n"
                "set label '" + design.entry_name + "* = " + number(*answer.answer, 4) + " m' at first " +
                number(*answer.answer) + ", graph 0.95 offset 0.5, 0 tc rgb 'dark-green'\n";
  PlotPanel panel{design.entry + " [m]", "T_max [kN/m]", {}, settings};
  const std::string mean_label = with_seeds ? "mean over the seeds" : "T_max (one run per value)";
  panel.series.push_back({csv, 2, 3, mean_label, 1.0, 1.0, "lines lw 2 lc 1 smooth unique"});
  panel.series.push_back({csv, 2, 3, "", 1.0, 1.0, "points pt 7 ps 1.2 lc 1"});
  if (with_seeds)
    {
      panel.series.push_back({csv, 2, 3, "min - max", 1.0, 1.0, "yerrorbars lw 1.5 ps 0 lc 1", {5, 6}});
      panel.series.push_back({csv, 2, 8, "mean - " + number(design.margin_factor, 4) + " std", 1.0, 1.0,
                              "points pt 9 ps 1.4 lc rgb 'dark-orange'"});
    }
  return plot_png(png, "geohybrid design: " + design.entry + " for a maximum head tension of " + number(design.target_kN, 4) + " kN/m" +
                         (with_seeds && design.margin_factor > 0.0 ? " (mean - " + number(design.margin_factor, 4) + " std)" : ""),
                  {panel});
}

void write_design_summary(const DesignDefinition &design, const std::vector<DesignStep> &steps,
                          const DesignAnswer &answer, double seconds, const std::filesystem::path &file)
{
  Summary summary;
  const double none = std::numeric_limits<double>::quiet_NaN(); // written as null
  summary.set("entry", design.entry);
  summary.set("mode", design.mode);
  summary.set("outcome", answer.outcome);
  summary.set("message", answer.message);
  summary.set("answer_m", answer.answer ? *answer.answer : none);
  summary.set("highest_failing_m", answer.highest_failing ? *answer.highest_failing : none);
  summary.set("criterion", "mean - k std of T_max over the seeds >= target");
  summary.set("target_T_max_kN_per_m", design.target_kN);
  summary.set("margin_factor", design.margin_factor);
  summary.set("tolerance_m", design.tolerance);
  summary.set("bracket_m", std::vector<double>{design.minimum, design.maximum});
  summary.set("seeds", design.seeds);
  summary.set("base_input", design.base_input);
  summary.set("wall_time_s", seconds);
  std::vector<std::string> warnings = design.notes;
  warnings.insert(warnings.end(), answer.warnings.begin(), answer.warnings.end());
  summary.set("warnings", warnings);
  nlohmann::json runs = nlohmann::json::array();
  std::size_t n_runs = 0;
  for (const DesignStep &s : steps)
    {
      nlohmann::json run = {{"value_m", s.value}, {"directory", s.directory}, {"T_max_kN_per_m", s.T_max_kN},
                            {"met", meets_criterion(design, s)}};
      if (!s.T_max_kN.empty())
        {
          const Spread spread = s.spread();
          run["mean_kN_per_m"] = spread.mean;
          run["std_kN_per_m"] = spread.std;
          run["criterion_kN_per_m"] = s.criterion_kN(design.margin_factor);
        }
      if (!s.message.empty())
        run["message"] = s.message;
      runs.push_back(run);
      n_runs += s.n_runs;
    }
  summary.set_json("values_tried", runs);
  summary.set("n_values_tried", static_cast<double>(steps.size()));
  summary.set("n_runs", static_cast<double>(n_runs));
  summary.write(file);
}
} // namespace geohybrid::apps
