#include "checked_output.h"

#include <stdexcept>
#include <system_error>

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

void write_whole_file(const std::filesystem::path &file, const std::string &contents)
{
  const std::filesystem::path temporary = file.string() + ".tmp";
  std::error_code error;
  {
    std::ofstream out(temporary);
    out << contents;
    out.close();
    if (!out)
      {
        std::filesystem::remove(temporary, error);
        throw std::runtime_error(write_failure_message(file)); // the file the user knows
      }
  }
  std::filesystem::rename(temporary, file, error);
  if (error)
    {
      const std::string why = error.message();
      std::filesystem::remove(temporary, error);
      throw std::runtime_error("cannot rename " + temporary.string() + " to " + file.string() + ": " + why);
    }
}
} // namespace geohybrid::dem
