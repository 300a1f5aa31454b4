#pragma once
// Output files the tests read back: the whole text, or its lines; empty if the file cannot be read.
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
} // namespace geohybrid::testing
