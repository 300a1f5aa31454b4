#include "reference_runs.h"

#include "apps/run_directory.h"
#include "apps/summary.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
namespace fs = std::filesystem;

/// k of "seed<k>" or "seed_<k>", or nothing.
std::optional<unsigned long> seed_number(const std::string &name)
{
  std::size_t start = name.rfind("seed_", 0) == 0 ? 5 : name.rfind("seed", 0) == 0 ? 4 : std::string::npos;
  if (start == std::string::npos || start == name.size() || name.find_first_not_of("0123456789", start) != std::string::npos)
    return std::nullopt;
  return std::stoul(name.substr(start));
}
} // namespace

ReferenceRuns read_reference_runs(const fs::path &directory, const std::string &where)
{
  std::error_code error;
  if (!fs::is_directory(directory, error))
    throw std::invalid_argument(where + ": the directory '" + directory.string() +
                                "' does not exist (relative to the working directory)");
  std::vector<std::pair<unsigned long, fs::path>> found;
  for (const fs::directory_entry &entry : fs::directory_iterator(directory))
    if (const auto k = seed_number(entry.path().filename().string()); k && entry.is_directory())
      found.emplace_back(*k, entry.path());
  if (found.empty())
    throw std::invalid_argument(where + ": '" + directory.string() +
                                "' holds no finished runs (subdirectories seed1, seed2, ... or seed_1, ...)");
  std::sort(found.begin(), found.end());

  ReferenceRuns runs;
  runs.directory = directory;
  try
    {
      for (const auto &[k, path] : found)
        runs.seeds.push_back(read_pullout_run(path));
    }
  catch (const std::runtime_error &e)
    {
      throw std::invalid_argument(where + ": " + e.what());
    }
  std::vector<double> T_max;
  for (const PulloutRunRecord &run : runs.seeds)
    T_max.push_back(run.max_head_tension_kN);
  runs.T_max = spread_of(T_max);

  // The curves, row by row: each run records at the first step past the same displacements.
  const std::vector<std::array<double, 2>> &first = runs.seeds.front().curve;
  const double tolerance = first.size() > 1 ? 0.5 * (first[1][0] - first[0][0]) : 0.0;
  for (const PulloutRunRecord &run : runs.seeds)
    {
      if (run.curve.size() != first.size())
        throw std::invalid_argument(where + ": " + (run.directory / "pullout_curve.csv").string() + " has " +
                                    std::to_string(run.curve.size()) + " rows, " +
                                    (runs.seeds.front().directory / "pullout_curve.csv").string() + " " +
                                    std::to_string(first.size()) + ": not the same pull");
      for (std::size_t r = 0; r < first.size(); ++r)
        if (std::abs(run.curve[r][0] - first[r][0]) > tolerance)
          throw std::invalid_argument(where + ": row " + std::to_string(r + 1) + " of " +
                                      (run.directory / "pullout_curve.csv").string() + " is at " +
                                      number(run.curve[r][0]) + " m, of the first seed's at " + number(first[r][0]) +
                                      " m: not the same pull");
    }
  for (std::size_t r = 0; r < first.size(); ++r)
    {
      std::array<double, 2> mean{{0.0, 0.0}};
      for (const PulloutRunRecord &run : runs.seeds)
        for (int c = 0; c < 2; ++c)
          mean[c] += run.curve[r][c] / static_cast<double>(runs.seeds.size());
      runs.mean_curve.push_back(mean);
      runs.T_max_of_mean_curve = std::max(runs.T_max_of_mean_curve, mean[1]);
    }
  const nlohmann::json summary = read_summary(runs.seeds.front().directory / "summary.json");
  if (const auto n = summary.find("n_particles"); n != summary.end() && n->is_number())
    runs.clusters = n->get<double>();
  return runs;
}

std::string experiment_text(const CurveReferences &references)
{
  return references.experimental_T_max ? "; experiment " + number(*references.experimental_T_max / 1e3, 4) + " kN/m"
                                       : std::string();
}

std::string demonstration_lines(const CurveReferences &references)
{
  std::string text;
  if (!references.demonstration.empty())
    text += "geohybrid pullout: a DEMONSTRATION of the workflow, not a result: " + references.demonstration + "\n";
  if (const auto &f = references.full_size)
    text += "geohybrid pullout: the same case at full size (" + f->directory.string() + ", " +
            std::to_string(f->seeds.size()) + " seed(s)" +
            (f->clusters > 0.0 ? ", " + number(f->clusters, 6) + " clusters" : std::string()) + "): T_max " +
            number(f->T_max.mean, 4) + " kN/m, the mean of the seeds' (" + number(f->T_max_of_mean_curve, 4) +
            " on their mean curve)\n";
  return text;
}
} // namespace geohybrid::apps
