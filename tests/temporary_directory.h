#pragma once
// Test support: a fresh directory under the system's temporary directory, removed with
// everything in it when the object goes out of scope.
#include <chrono>
#include <filesystem>
#include <random>
#include <string>
#include <system_error>

namespace geohybrid::testing
{
struct TemporaryDirectory
{
  std::filesystem::path path;
  explicit TemporaryDirectory(const std::string &prefix)
  {
    std::random_device device;
    const auto tick = std::chrono::steady_clock::now().time_since_epoch().count();
    path = std::filesystem::temp_directory_path() /
           ("geohybrid_" + prefix + "_" + std::to_string(device()) + "_" + std::to_string(tick));
    std::filesystem::create_directories(path);
  }
  ~TemporaryDirectory()
  {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory &) = delete;
  TemporaryDirectory &operator=(const TemporaryDirectory &) = delete;
};
} // namespace geohybrid::testing
