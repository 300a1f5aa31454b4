#pragma once
// The whole text of a file (an output the tests read back), empty if it cannot be read.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace geohybrid::testing
{
inline std::string read_text(const std::filesystem::path &file)
{
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}
} // namespace geohybrid::testing
