#include "summary.h"

#include "dem/io/checked_output.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
nlohmann::json number_json(double value)
{
  if (!std::isfinite(value))
    return nullptr;
  // A count stored as a double (n_particles) is written as the integer it is; 2^53 is where
  // doubles stop holding every integer.
  if (value == std::floor(value) && std::abs(value) < 9007199254740992.0)
    return static_cast<std::int64_t>(value);
  return value;
}
} // namespace

void Summary::set(const std::string &key, double value) { json_[key] = number_json(value); }

void Summary::set(const std::string &key, const std::string &value) { json_[key] = value; }

void Summary::set(const std::string &key, const std::vector<double> &values)
{
  nlohmann::json list = nlohmann::json::array();
  for (const double v : values)
    list.push_back(number_json(v));
  json_[key] = std::move(list);
}

void Summary::set(const std::string &key, const std::vector<std::string> &values) { json_[key] = values; }

void Summary::write(const std::filesystem::path &file) const
{
  // Bytes that are not UTF-8 (a path in another encoding) are replaced rather than refused:
  // the summary of a finished run must not fail on its output directory's name.
  dem::write_whole_file(file, json_.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + '\n');
}

nlohmann::json read_summary(const std::filesystem::path &file)
{
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error("cannot read " + file.string());
  try
    {
      return nlohmann::json::parse(in);
    }
  catch (const nlohmann::json::exception &e)
    {
      throw std::runtime_error(file.string() + " is not valid JSON: " + e.what());
    }
}
} // namespace geohybrid::apps
