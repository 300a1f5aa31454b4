#include "hdf5_writable_file.h"

#include "hdf5_handles.h"

#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <utility>

namespace geohybrid::dem::hdf5
{
WritableFile::WritableFile(hid_t id, std::string where) : id_(id), where_(std::move(where)) {}

WritableFile WritableFile::create(const std::filesystem::path &file, const std::string &where)
{
  Handle fapl = file_access(where);
  const hid_t id = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (id < 0)
    fail(where, "creating '" + file.string() + "' failed: " + error_text());
  return WritableFile(id, where);
}

WritableFile WritableFile::open(const std::filesystem::path &file, const std::string &where)
{
  Handle fapl = file_access(where);
  const hid_t id = H5Fopen(file.c_str(), H5F_ACC_RDWR, fapl.get());
  if (id < 0)
    fail(where, "opening '" + file.string() + "' to write failed: " + error_text());
  return WritableFile(id, where);
}

WritableFile::WritableFile(WritableFile &&other) noexcept
  : id_(std::exchange(other.id_, H5I_INVALID_HID)), where_(std::move(other.where_))
{}

WritableFile::~WritableFile()
{
  if (id_ >= 0)
    abandon();
}

void WritableFile::close()
{
  if (H5Fflush(id_, H5F_SCOPE_LOCAL) < 0)
    {
      const std::string why = error_text(); // before abandon() resets the error stack
      abandon();
      fail(where_, "writing the file failed: " + why);
    }
  const hid_t id = std::exchange(id_, H5I_INVALID_HID);
  if (H5Fclose(id) < 0)
    fail(where_, "closing the file failed: " + error_text());
}

void WritableFile::abandon() noexcept
{
  // The default (sec2) driver's handle is its POSIX descriptor. dup2 replaces the file behind
  // it atomically; the in-memory file vanishes with the descriptor when HDF5 closes it.
  void *handle = nullptr;
  bool in_memory = false;
  if (H5Fget_vfd_handle(id_, H5P_DEFAULT, &handle) >= 0 && handle != nullptr)
    {
      const int memory = ::memfd_create("geohybrid-abandoned-hdf5", MFD_CLOEXEC);
      if (memory >= 0)
        {
          in_memory = ::dup2(memory, *static_cast<int *>(handle)) >= 0;
          ::close(memory);
        }
    }
  // A file-size limit (ulimit -f) applies to the in-memory file too: its writes land beyond the
  // limit, where the real file's failed. Lifted to the hard limit for the close (these writes
  // reach no disk), then restored. Under a hard limit as low, the close can still fail.
  rlimit limit{};
  const bool limited = in_memory && ::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != limit.rlim_max;
  if (limited)
    {
      rlimit lifted = limit;
      lifted.rlim_cur = limit.rlim_max;
      ::setrlimit(RLIMIT_FSIZE, &lifted);
    }
  H5Fclose(std::exchange(id_, H5I_INVALID_HID));
  if (limited)
    ::setrlimit(RLIMIT_FSIZE, &limit);
}
} // namespace geohybrid::dem::hdf5
