#include "checked_output.h"

#include <stdexcept>

namespace geohybrid::dem
{
std::string write_failure_message(const std::filesystem::path &file)
{
  return "cannot write " + file.string() + " (is the disk full, or the directory not writable?)";
}

void flush_checked(std::ostream &out, const std::filesystem::path &file)
{
  if (!out.flush())
    throw std::runtime_error(write_failure_message(file));
}

void close_checked(std::ofstream &out, const std::filesystem::path &file)
{
  // close() flushes the buffer and sets failbit if that or close(2) fails; an earlier failed
  // write left badbit, which close() keeps.
  out.close();
  if (!out)
    throw std::runtime_error(write_failure_message(file));
}
} // namespace geohybrid::dem
