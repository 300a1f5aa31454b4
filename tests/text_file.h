#pragma once
// Output files the tests read back: the whole text, its lines, or a CSV's numbers; empty if the file
// cannot be read.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace geohybrid::testing
{
inline std::string read_text(const std::filesystem::path &file)
{
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<std::string> lines_of(const std::filesystem::path &file)
{
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

/// The rows of a CSV file of numbers, its header line skipped.
inline std::vector<std::vector<double>> numbers_of(const std::filesystem::path &file)
{
  std::vector<std::vector<double>> rows;
  const std::vector<std::string> lines = lines_of(file);
  for (std::size_t k = 1; k < lines.size(); ++k)
    {
      std::vector<double> row;
      std::istringstream in(lines[k]);
      for (std::string field; std::getline(in, field, ',');)
        row.push_back(std::stod(field));
      rows.push_back(row);
    }
  return rows;
}
} // namespace geohybrid::testing
