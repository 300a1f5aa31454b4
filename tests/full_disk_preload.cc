// Test support, loaded into the geohybrid program by LD_PRELOAD (geohybrid_child.h): a disk that
// is full for the files named in GEOHYBRID_TEST_FULL_FILES (base names, separated by commas). Such
// a file opened for writing is created, as on a full disk, but its descriptor is then /dev/full's,
// so every write to it fails with ENOSPC; every other file is left alone.
//
// Why, beside the file-size limit (file_size_limit.h): that limit stops the first file to outgrow
// it, so it cannot stop a run's small files (summary.json, a calibration's fragment) while the
// larger ones written before them (parameters.prm) get through.
#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace
{
bool named_full(const char *path)
{
  const char *names = std::getenv("GEOHYBRID_TEST_FULL_FILES");
  if (names == nullptr || path == nullptr)
    return false;
  const char *slash = std::strrchr(path, '/');
  const char *base = slash != nullptr ? slash + 1 : path;
  const std::size_t n = std::strlen(base);
  for (const char *p = names;;)
    {
      const char *end = std::strchr(p, ',');
      const std::size_t length = end != nullptr ? static_cast<std::size_t>(end - p) : std::strlen(p);
      if (length == n && std::strncmp(p, base, n) == 0)
        return true;
      if (end == nullptr)
        return false;
      p = end + 1;
    }
}

template <typename F>
F next(const char *symbol)
{
  return reinterpret_cast<F>(dlsym(RTLD_NEXT, symbol));
}

using OpenFunction = int (*)(const char *, int, ...);
using OpenAtFunction = int (*)(int, const char *, int, ...);
using FopenFunction = FILE *(*)(const char *, const char *);

/// `fd`, a file just created or truncated, now writing to /dev/full.
int fill(int fd)
{
  static const OpenFunction real_open = next<OpenFunction>("open");
  if (fd < 0)
    return fd;
  const int full = real_open("/dev/full", O_WRONLY);
  if (full >= 0)
    {
      dup2(full, fd);
      close(full);
    }
  return fd;
}

bool writes(int flags) { return (flags & O_ACCMODE) != O_RDONLY; }
bool writes(const char *mode) { return mode != nullptr && (mode[0] == 'w' || mode[0] == 'a' || std::strchr(mode, '+')); }

mode_t mode_of(int flags, va_list arguments)
{
  return (flags & (O_CREAT | O_TMPFILE)) != 0 ? static_cast<mode_t>(va_arg(arguments, int)) : 0;
}
} // namespace

extern "C"
{
int open(const char *path, int flags, ...)
{
  static const OpenFunction real = next<OpenFunction>("open");
  va_list arguments;
  va_start(arguments, flags);
  const mode_t mode = mode_of(flags, arguments);
  va_end(arguments);
  const int fd = real(path, flags, mode);
  return named_full(path) && writes(flags) ? fill(fd) : fd;
}

int open64(const char *path, int flags, ...)
{
  static const OpenFunction real = next<OpenFunction>("open64");
  va_list arguments;
  va_start(arguments, flags);
  const mode_t mode = mode_of(flags, arguments);
  va_end(arguments);
  const int fd = real(path, flags, mode);
  return named_full(path) && writes(flags) ? fill(fd) : fd;
}

int openat(int directory, const char *path, int flags, ...)
{
  static const OpenAtFunction real = next<OpenAtFunction>("openat");
  va_list arguments;
  va_start(arguments, flags);
  const mode_t mode = mode_of(flags, arguments);
  va_end(arguments);
  const int fd = real(directory, path, flags, mode);
  return named_full(path) && writes(flags) ? fill(fd) : fd;
}

FILE *fopen(const char *path, const char *mode)
{
  static const FopenFunction real = next<FopenFunction>("fopen");
  FILE *f = real(path, mode);
  if (f != nullptr && named_full(path) && writes(mode))
    fill(fileno(f));
  return f;
}

FILE *fopen64(const char *path, const char *mode)
{
  static const FopenFunction real = next<FopenFunction>("fopen64");
  FILE *f = real(path, mode);
  if (f != nullptr && named_full(path) && writes(mode))
    fill(fileno(f));
  return f;
}
}
