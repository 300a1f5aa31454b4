#pragma once
// Test support: a fresh directory under the system's temporary directory, removed with
// everything in it when the object goes out of scope.
#include <chrono>
#include <filesystem>
#include <random>
#include <string>
#include <system_error>

#include <unistd.h>

namespace geohybrid::testing
{
/// geohybrid_<name>_<id> under the system's temporary directory (TMPDIR), emptied and made anew.
/// `id` is this process's pid (rank 0's under mpirun), so that two test runs at once, of two
/// checkouts or two ctest, never share a directory; a test removes it once it passed.
inline std::filesystem::path scratch_path(const std::string &name, long id = static_cast<long>(::getpid()))
{
  return std::filesystem::temp_directory_path() / ("geohybrid_" + name + "_" + std::to_string(id));
}

inline std::filesystem::path fresh_directory(const std::string &name, long id = static_cast<long>(::getpid()))
{
  const std::filesystem::path d = scratch_path(name, id);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

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
