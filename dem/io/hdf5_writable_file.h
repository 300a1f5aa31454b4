#pragma once
// An HDF5 file open for writing whose closing never leaves the library in a state that crashes
// the process later.
//
// Why: HDF5 1.10 (Debian 12 ships 1.10.8) frees a file whose H5Fclose failed to flush its
// buffers (a full disk: ENOSPC, or EFBIG under a file-size limit) but keeps its identifier. At
// library shutdown, which for the OpenMPI flavour runs inside MPI_Finalize, HDF5 closes that
// identifier again and reads the freed file: a segmentation fault (rc 139) after the run's clear
// error message (issue 24). Upstream fixed it in HDF5 1.14 (HDFGroup/hdf5 pull request 2291).
//
// So H5Fclose must never be the call that meets a failed write. close() flushes first
// (H5Fflush writes every buffer, the superblock and the file's length: what reaches the disk
// then is a complete file) and reports a failure, naming the file; after a successful flush the
// close has nothing left to write. A file that failed, or that is dropped without close()
// (an exception during the writing), is abandoned: its descriptor is pointed at an anonymous
// in-memory file before H5Fclose, so that the writes the close still attempts land there and
// cannot fail (a soft file-size limit, ulimit -S -f, is lifted for that close: it applies to
// memory files too; a hard one as low can still make it fail). What the disk holds of an
// abandoned file is unfinished; callers write to a
// temporary name and rename it after close(), or (the append-only snapshot file) list a snapshot
// only once its file closed.
//
// Include only from .cc files: hdf5.h (the OpenMPI flavour) pulls in mpi.h.
#include <hdf5.h>

#include <filesystem>
#include <string>

namespace geohybrid::dem::hdf5
{
class WritableFile
{
public:
  /// H5Fcreate (truncating) or H5Fopen read-write, with hdf5::file_access()'s properties; throws
  /// std::runtime_error beginning with `where` if HDF5 refuses.
  static WritableFile create(const std::filesystem::path &file, const std::string &where);
  static WritableFile open(const std::filesystem::path &file, const std::string &where);

  WritableFile(WritableFile &&other) noexcept;
  WritableFile(const WritableFile &) = delete;
  WritableFile &operator=(const WritableFile &) = delete;
  WritableFile &operator=(WritableFile &&) = delete;
  /// Abandons a file that was not closed (see above).
  ~WritableFile();

  hid_t get() const { return id_; }

  /// Flushes and closes; throws std::runtime_error beginning with `where` (the file abandoned,
  /// its identifier released) if the flush or the close fails.
  void close();

private:
  WritableFile(hid_t id, std::string where);
  /// Points the file's descriptor at an in-memory file, then closes the identifier; never throws.
  void abandon() noexcept;

  hid_t id_;
  std::string where_;
};
} // namespace geohybrid::dem::hdf5
