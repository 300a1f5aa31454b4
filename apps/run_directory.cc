#include "run_directory.h"

#include "output_guard.h"

#include "dem/io/checked_output.h"

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cctype>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <locale>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace geohybrid::apps
{
std::string number(double value, int digits)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << std::setprecision(digits) << value;
  return s.str();
}

namespace
{
/// The text of a parameter file whose 'include FILE' lines name FILE as an absolute path: a
/// relative FILE is looked for beside the including file first (so that an input and the soil
/// fragment it includes can be run from any directory), then in the working directory (deal.II's
/// own rule, kept for inputs written for it). One line for one line: error messages keep their
/// line numbers.
std::string with_includes_resolved(const std::filesystem::path &file)
{
  std::ifstream in(file);
  std::ostringstream text;
  for (std::string line; std::getline(in, line);)
    {
      const auto first = line.find_first_not_of(" \t");
      if (first != std::string::npos && (line.compare(first, 8, "include ") == 0 || line.compare(first, 8, "INCLUDE ") == 0))
        {
          std::string name = line.substr(first + 8);
          name = name.substr(0, name.find('#'));
          name.erase(0, name.find_first_not_of(" \t"));
          name.erase(name.find_last_not_of(" \t\r") + 1);
          const std::filesystem::path beside = file.parent_path() / name;
          if (!name.empty() && std::filesystem::path(name).is_relative() && std::filesystem::is_regular_file(beside))
            line = line.substr(0, first) + "include " + std::filesystem::absolute(beside).lexically_normal().string();
        }
      text << line << '\n';
    }
  return text.str();
}
} // namespace

namespace
{
/// Refuses a file that is not a parameter file before deal.II reads it: deal.II would run an
/// empty one with every default (a 20,000-particle tank), and quote a binary one's bytes.
void check_input_text(const std::string &input_file)
{
  std::ifstream in(input_file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.eof() && in.fail())
    throw std::runtime_error("input file '" + input_file + "' cannot be read");
  for (std::size_t k = 0; k < text.size(); ++k)
    {
      const auto c = static_cast<unsigned char>(text[k]);
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f') || c == 0x7f)
        throw std::runtime_error("input file '" + input_file + "' is not a text file (a control byte at offset " +
                                 std::to_string(k) + "): give a parameter file (.prm or .json)");
    }
  // Empty: nothing but blanks and comments ('#' to the end of the line; a .json file's '{}').
  bool comment = false, empty = true;
  for (const char c : text)
    {
      if (c == '\n')
        comment = false;
      else if (c == '#')
        comment = true;
      else if (!comment && c != '{' && c != '}' && !std::isspace(static_cast<unsigned char>(c)))
        empty = false;
    }
  if (empty)
    throw std::runtime_error("input file '" + input_file +
                             "' is empty: it sets no parameter (a run of every default is not what it meant); "
                             "--print-parameters lists every parameter");
}
} // namespace

void parse_input_file(dealii::ParameterHandler &prm, const std::string &input_file)
{
  if (!std::filesystem::is_regular_file(input_file))
    throw std::runtime_error("input file '" + input_file + "' does not exist");
  check_input_text(input_file);
  try
    {
      if (std::filesystem::path(input_file).extension() == ".prm")
        {
          std::istringstream text(with_includes_resolved(input_file));
          prm.parse_input(text, input_file);
        }
      else
        prm.parse_input(input_file);
    }
  catch (const dealii::ExceptionBase &e)
    {
      std::ostringstream info;
      e.print_info(info);
      std::string text = info.str(), line;
      std::istringstream lines(text);
      std::string message;
      while (std::getline(lines, line))
        {
          const auto first = line.find_first_not_of(" \t");
          if (first != std::string::npos)
            message += (message.empty() ? "" : " ") + line.substr(first);
        }
      throw std::runtime_error("input file '" + input_file + "': " + message);
    }
}

namespace
{
/// "Subsection/.../entry" split at its slashes.
std::vector<std::string> path_parts(const std::string &path)
{
  std::vector<std::string> parts;
  for (std::size_t start = 0;;)
    {
      const std::size_t slash = path.find('/', start);
      parts.push_back(path.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
      if (slash == std::string::npos)
        break;
      start = slash + 1;
    }
  return parts;
}
} // namespace

void set_parameter(dealii::ParameterHandler &prm, const std::string &path, const std::string &value)
{
  const std::vector<std::string> parts = path_parts(path);
  for (std::size_t k = 0; k + 1 < parts.size(); ++k)
    prm.enter_subsection(parts[k]);
  prm.set(parts.back(), value);
  for (std::size_t k = 0; k + 1 < parts.size(); ++k)
    prm.leave_subsection();
}

std::string get_parameter(const dealii::ParameterHandler &prm, const std::string &path)
{
  const std::vector<std::string> parts = path_parts(path);
  std::vector<std::string> subsections(parts.begin(), parts.end() - 1);
  return prm.get(subsections, parts.back());
}

std::filesystem::path prepare_output_directory(const std::string &directory, bool resume)
{
  if (directory.empty())
    throw std::invalid_argument("parameter 'output directory' is empty");
  const std::filesystem::path path(directory);
  claim_output_directory(path, resume);
  std::error_code error;
  std::filesystem::create_directories(path, error);
  if (error)
    throw std::runtime_error("cannot create output directory '" + directory + "': " + error.message());
  std::filesystem::remove(path / "summary.json", error);
  return path;
}

void write_resolved_parameters(const dealii::ParameterHandler &prm, const std::filesystem::path &directory)
{
  std::ofstream out(directory / "parameters.prm");
  prm.print_parameters(out, dealii::ParameterHandler::OutputStyle::PRM);
  dem::close_checked(out, directory / "parameters.prm");
}

namespace
{
std::size_t count_fields(const std::string &line) { return 1 + std::count(line.begin(), line.end(), ','); }

/// The time in the first field of a row, if it is a number.
std::optional<double> row_time(const std::string &line)
{
  std::istringstream field(line.substr(0, line.find(',')));
  field.imbue(std::locale::classic());
  double time;
  if (!(field >> time) || !(field >> std::ws).eof())
    return std::nullopt;
  return time;
}
} // namespace

std::ofstream open_csv_rows(const std::filesystem::path &file, const std::string &header,
                            std::optional<double> keep_until_time)
{
  const auto fail = [&](const std::string &what) -> void {
    throw std::runtime_error("CSV file '" + file.string() + "': " + what);
  };
  if (keep_until_time && std::filesystem::exists(file))
    {
      std::ifstream in(file, std::ios::binary);
      if (!in)
        fail("cannot be read to continue the run");
      std::string line, kept;
      if (!std::getline(in, line) || line != header)
        fail("its columns differ from those of this run, so it cannot be continued; move it away to "
             "start a new one");
      kept = line + '\n';
      const std::size_t n_fields = count_fields(header);
      while (std::getline(in, line) && !in.eof()) // eof after getline: the line had no final newline
        {
          const std::optional<double> time = row_time(line);
          if (count_fields(line) != n_fields || !time || !(*time <= *keep_until_time))
            break;
          kept += line + '\n';
        }
      in.close();
      const std::filesystem::path temporary = file.string() + ".tmp";
      {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << kept;
        dem::close_checked(out, temporary);
      }
      std::error_code error;
      std::filesystem::rename(temporary, file, error);
      if (error)
        fail("cannot replace it with '" + temporary.string() + "': " + error.message());
      std::ofstream out(file, std::ios::app);
      if (!out)
        fail("cannot be opened for appending");
      return out;
    }
  std::ofstream out(file, std::ios::trunc);
  out << header << '\n';
  dem::flush_checked(out, file); // the header on the disk, not only in the buffer
  return out;
}

WallClockInterval::WallClockInterval(double seconds)
  : interval_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(std::clamp(seconds, 0.0, 1e9)))),
    last_(std::chrono::steady_clock::now()), enabled_(seconds > 0.0)
{}

bool WallClockInterval::due()
{
  if (!enabled_)
    return false;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < interval_)
    return false;
  last_ = now;
  return true;
}

ProgressReport::ProgressReport(std::string label, double end)
  : label_(std::move(label)), end_(end), terminal_(isatty(fileno(stderr)) != 0),
    start_(std::chrono::steady_clock::now()), last_print_(start_)
{}

void ProgressReport::update(double now)
{
  const int percent = end_ > 0.0 ? static_cast<int>(100.0 * now / end_) : 100;
  const auto clock = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(clock - start_).count();
  const double eta = now > 0.0 ? elapsed * (end_ - now) / now : 0.0;
  if (terminal_)
    {
      if (percent == last_percent_ && std::chrono::duration<double>(clock - last_print_).count() < 0.5)
        return;
      const int width = 40, filled = std::min(width, percent * width / 100);
      std::fprintf(stderr, "\r%s [%s%s] %3d%%  elapsed %.0f s  ETA %.0f s ", label_.c_str(),
                   std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), percent,
                   elapsed, eta);
    }
  else
    {
      // Plain lines for logs: one every 10 %, and at least one a minute (a phase whose fraction
      // moves slowly, such as a layer of the tank's filling settling, still shows it is alive).
      if (percent / 10 == last_percent_ / 10 && std::chrono::duration<double>(clock - last_print_).count() < 60.0)
        return;
      std::fprintf(stderr, "%s: %d%% (elapsed %.0f s, ETA %.0f s)\n", label_.c_str(), percent, elapsed, eta);
    }
  last_percent_ = percent;
  last_print_ = clock;
}

void ProgressReport::finish()
{
  update(end_);
  if (terminal_)
    std::fprintf(stderr, "\n");
}

void ProgressReport::stop()
{
  if (terminal_ && last_percent_ >= 0)
    std::fprintf(stderr, "\n");
}
} // namespace geohybrid::apps
