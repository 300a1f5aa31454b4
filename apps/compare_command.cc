#include "compare_command.h"

#include "apps/plot.h"
#include "apps/summary.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
namespace fs = std::filesystem;

const char *const curve_file = "pullout_curve.csv";
const char *const curve_header = "head_displacement_m,head_tension_kN_per_m";
const char *const summary_file = "summary.json";

std::string trimmed(const std::string &s)
{
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
    return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

/// A number from the whole of `text`, or nothing.
bool parse_number(const std::string &text, double &value)
{
  const std::string t = trimmed(text);
  if (t.empty())
    return false;
  char *end = nullptr;
  value = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size();
}

std::vector<std::array<double, 2>> read_curve(const fs::path &directory)
{
  const fs::path file = directory / curve_file;
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error("compare: result directory '" + directory.string() + "' has no " + curve_file +
                             " (not a finished pull-out run?)");
  std::string line;
  std::getline(in, line);
  const std::string header = trimmed(line);
  if (header.rfind(curve_header, 0) != 0 || (header.size() > std::strlen(curve_header) && header[std::strlen(curve_header)] != ','))
    throw std::runtime_error("compare: " + file.string() + " (result directory '" + directory.string() +
                             "') has the columns '" + header + "', expected '" + curve_header + "'");
  std::vector<std::array<double, 2>> rows;
  std::size_t line_number = 1;
  while (std::getline(in, line))
    {
      ++line_number;
      if (trimmed(line).empty())
        continue;
      const auto comma = line.find(',');
      const auto next = comma == std::string::npos ? std::string::npos : line.find(',', comma + 1);
      double x = 0.0, y = 0.0;
      if (comma == std::string::npos || !parse_number(line.substr(0, comma), x) ||
          !parse_number(line.substr(comma + 1, next == std::string::npos ? std::string::npos : next - comma - 1), y))
        throw std::runtime_error("compare: " + file.string() + " (result directory '" + directory.string() +
                                 "'), line " + std::to_string(line_number) + ": expected two numbers, got '" +
                                 trimmed(line) + "'");
      rows.push_back({{x, y}});
    }
  if (rows.empty())
    throw std::runtime_error("compare: " + file.string() + " (result directory '" + directory.string() +
                             "') has a header but no rows");
  return rows;
}

} // namespace

PulloutRunRecord read_pullout_run(const fs::path &directory)
{
  if (!fs::is_directory(directory))
    throw std::runtime_error("compare: result directory '" + directory.string() + "' does not exist");
  PulloutRunRecord record;
  record.directory = directory;
  record.curve = read_curve(directory);
  record.n_points = record.curve.size();

  const fs::path summary = directory / summary_file;
  if (!fs::exists(summary))
    throw std::runtime_error("compare: result directory '" + directory.string() + "' has no " + summary_file +
                             " (an unfinished run?)");
  const std::string where = "compare: " + summary.string() + " (result directory '" + directory.string() + "')";
  nlohmann::json json;
  try
    {
      json = read_summary(summary);
    }
  catch (const std::runtime_error &e)
    {
      throw std::runtime_error(where + ": " + e.what());
    }
  const auto mode = json.is_object() ? json.find("mode") : json.end();
  if (mode == json.end() || !mode->is_string() || mode->get<std::string>().empty())
    throw std::runtime_error(where + " has no \"mode\"");
  record.mode = mode->get<std::string>();
  const auto tension = json.find("T_max_kN_per_m");
  if (tension == json.end() || !tension->is_number())
    throw std::runtime_error(where + " has no number \"T_max_kN_per_m\"");
  record.max_head_tension_kN = tension->get<double>();
  if (const auto warnings = json.find("warnings"); warnings != json.end() && warnings->is_array())
    for (const nlohmann::json &w : *warnings)
      if (w.is_string())
        record.warnings.push_back(w.get<std::string>());
  return record;
}

std::vector<PulloutRunRecord> compare_pullout_runs(const std::vector<fs::path> &directories, const fs::path &png)
{
  if (directories.empty())
    throw std::runtime_error("compare: no result directories given");
  if (png.extension() != ".png")
    throw std::runtime_error("compare: the output '" + png.string() + "' must be a .png file");
  std::vector<PulloutRunRecord> records;
  PlotPanel panel{"head displacement [mm]", "head tension [kN/m]", {}};
  for (const auto &directory : directories)
    {
      records.push_back(read_pullout_run(directory));
      const auto &r = records.back();
      // The directory's own name (not its path) and the mode tell the curves apart.
      std::string name = fs::path(directory).lexically_normal().filename().string();
      if (name.empty())
        name = fs::path(directory).lexically_normal().parent_path().filename().string();
      std::ostringstream label;
      label << name << " (" << r.mode << ", T_max " << std::setprecision(3) << r.max_head_tension_kN << " kN/m)";
      panel.series.push_back({directory / curve_file, 1, 2, label.str(), 1e3, 1.0});
    }
  if (!png.parent_path().empty())
    fs::create_directories(png.parent_path());
  if (!plot_png(png, "pull-out curves", {panel}))
    throw std::runtime_error("compare: could not make " + png.string() + " (gnuplot missing or failed, see above)");
  return records;
}

int run_compare_command(const std::vector<std::string> &arguments)
{
  std::vector<fs::path> directories;
  fs::path png = "pullout_comparison.png";
  for (std::size_t k = 0; k < arguments.size(); ++k)
    {
      if (arguments[k] == "--output")
        {
          if (k + 1 >= arguments.size())
            throw std::runtime_error("compare: --output needs a file name (FILE.png)");
          png = arguments[++k];
        }
      else if (arguments[k].rfind("--", 0) == 0)
        throw std::runtime_error("compare: unexpected option '" + arguments[k] +
                                 "' (usage: geohybrid compare DIR1 DIR2 ... [--output FILE.png])");
      else
        directories.emplace_back(arguments[k]);
    }
  if (directories.empty())
    throw std::runtime_error("compare: no result directories (usage: geohybrid compare DIR1 DIR2 ... "
                             "[--output FILE.png])");
  const auto records = compare_pullout_runs(directories, png);
  for (const auto &r : records)
    std::cout << std::left << std::setw(40) << r.directory.string() << " " << std::setw(7) << r.mode << " T_max "
              << r.max_head_tension_kN << " kN/m, " << r.n_points << " points\n";
  std::cout << "wrote " << png.string() << '\n';
  return 0;
}
} // namespace geohybrid::apps
