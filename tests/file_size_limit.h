#pragma once
// A file-size limit on this process (RLIMIT_FSIZE) with SIGXFSZ ignored: a write that would take
// a file beyond the limit fails with EFBIG, as a write to a full disk fails with ENOSPC. The code
// under test meets the same failed write(2) as on a full disk, without root or a mount (CI runs
// in a container). Pipes and terminals are not limited, so the test's own output is not.
#include <sys/resource.h>

#include <csignal>
#include <cstddef>
#include <stdexcept>

namespace geohybrid::testing
{
class FileSizeLimit
{
public:
  explicit FileSizeLimit(std::size_t bytes)
  {
    if (getrlimit(RLIMIT_FSIZE, &previous_) != 0)
      throw std::runtime_error("getrlimit(RLIMIT_FSIZE) failed");
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN); // the default action would kill the process
    rlimit limited = previous_;
    limited.rlim_cur = static_cast<rlim_t>(bytes); // the soft limit only: it can be raised back
    if (setrlimit(RLIMIT_FSIZE, &limited) != 0)
      throw std::runtime_error("setrlimit(RLIMIT_FSIZE) failed");
  }
  ~FileSizeLimit()
  {
    setrlimit(RLIMIT_FSIZE, &previous_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit &) = delete;
  FileSizeLimit &operator=(const FileSizeLimit &) = delete;

private:
  rlimit previous_{};
  void (*previous_handler_)(int) = SIG_DFL;
};
} // namespace geohybrid::testing
