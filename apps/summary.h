#pragma once
// summary.json, a run's results written last (a directory with it is a finished run), through
// nlohmann-json: numbers kept to the digits that read back to the same double, a non-finite
// number as null, and values that nest (the list of "warnings"). Written with sorted keys and an
// indent of 2, so each top-level scalar stays one `"key": value` line, which the shell readers of
// the validation campaign (bench/validation_campaign.sh's summary_value) rely on.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
class Summary
{
public:
  /// A non-finite value is written as null; an integral value below 2^53 as an integer (counts
  /// read as "3667", as the hand-made writer wrote them).
  void set(const std::string &key, double value);
  void set(const std::string &key, const std::string &value);
  void set(const std::string &key, const char *value) { set(key, std::string(value)); }
  void set(const std::string &key, const std::vector<double> &values);
  void set(const std::string &key, const std::vector<std::string> &values);
  /// A value that nests (a list of objects: a design's runs).
  void set_json(const std::string &key, nlohmann::json value) { json_[key] = std::move(value); }
  /// Writes through FILE.tmp and a rename (dem::write_whole_file): a summary.json is whole. Throws
  /// std::runtime_error naming the file on failure, leaving neither it nor the temporary.
  void write(const std::filesystem::path &file) const;
  const nlohmann::json &json() const { return json_; }

private:
  nlohmann::json json_ = nlohmann::json::object();
};

/// The JSON of `file`. Throws std::runtime_error naming the file if it is missing or not JSON.
nlohmann::json read_summary(const std::filesystem::path &file);
} // namespace geohybrid::apps
