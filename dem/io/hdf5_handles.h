#pragma once
// Small helpers over the HDF5 C API shared by the DEM's HDF5 files (snapshots, checkpoints):
// identifiers closed by RAII, HDF5's error stack turned into exception text, and the few write
// and read calls these files need. Every failure throws std::runtime_error beginning with
// `where`, a description of the file such as "DEM snapshot file '/out/particles.h5'".
//
// Include only from .cc files: hdf5.h (the OpenMPI flavour) pulls in mpi.h.
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace geohybrid::dem::hdf5
{
/// Turns off HDF5's printing of its error stack for the lifetime of the guard (the message goes
/// into the exception instead) and restores the previous handler afterwards.
class SilenceErrors
{
public:
  SilenceErrors()
  {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~SilenceErrors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  SilenceErrors(const SilenceErrors &) = delete;
  SilenceErrors &operator=(const SilenceErrors &) = delete;

private:
  H5E_auto2_t function_ = nullptr;
  void *data_ = nullptr;
};

namespace detail
{
inline herr_t collect_error(unsigned n, const H5E_error2_t *error, void *client_data)
{
  auto *text = static_cast<std::string *>(client_data);
  if (error->desc && *error->desc)
    {
      if (!text->empty())
        *text += "; ";
      for (const char *c = error->desc; *c; ++c)
        *text += (*c == '\n' ? ' ' : *c);
      if (error->func_name)
        *text += std::string(" (") + error->func_name + ")";
    }
  return n < 1 ? 0 : 1; // the two innermost entries say what went wrong
}
} // namespace detail

/// The innermost messages of the current HDF5 error stack.
inline std::string error_text()
{
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, detail::collect_error, &text);
  return text.empty() ? std::string("unknown HDF5 error") : text;
}

[[noreturn]] inline void fail(const std::string &where, const std::string &what)
{
  throw std::runtime_error(where + ": " + what);
}

inline void check(herr_t status, const std::string &where, const std::string &what)
{
  if (status < 0)
    fail(where, what + " failed: " + error_text());
}

/// An HDF5 identifier that is closed when it goes out of scope.
class Handle
{
public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer, const std::string &where, const std::string &what) : id_(id), closer_(closer)
  {
    if (id_ < 0)
      fail(where, what + " failed: " + error_text());
  }
  ~Handle()
  {
    if (id_ >= 0)
      closer_(id_);
  }
  Handle(Handle &&other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Handle(const Handle &) = delete;
  Handle &operator=(const Handle &) = delete;
  Handle &operator=(Handle &&) = delete;
  hid_t get() const { return id_; }

  /// Closes now, reporting a failure (H5Fclose is where buffered data reach the disk).
  void close(const std::string &where, const std::string &what)
  {
    const hid_t id = id_;
    id_ = -1;
    if (closer_(id) < 0)
      fail(where, what + " failed: " + error_text());
  }

private:
  hid_t id_;
  Closer closer_;
};

/// File access properties: strong close, and no file locking where the library has it, so that a
/// reader holding the file open for a moment does not make a long run fail.
inline Handle file_access(const std::string &where)
{
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, where, "creating file access properties");
  check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), where, "setting the close degree");
#if H5_VERSION_GE(1, 10, 7)
  check(H5Pset_file_locking(fapl.get(), 0, 1), where, "disabling file locking");
#endif
  return fapl;
}

inline Handle create_group(hid_t parent, const std::string &name, const std::string &where)
{
  return Handle(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, where,
                "creating group '" + name + "'");
}

inline Handle open_group(hid_t parent, const std::string &name, const std::string &where)
{
  return Handle(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose, where, "opening group '" + name + "'");
}

/// Writes a dataset of the given shape (a first dimension of 0 gives an empty dataset).
inline void write_dataset(hid_t parent, const char *name, hid_t file_type, hid_t memory_type,
                          const std::vector<hsize_t> &dims, const void *data, const std::string &where)
{
  const std::string what = std::string("dataset '") + name + "'";
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, where,
               "creating the dataspace of " + what);
  Handle set(H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose, where, "creating " + what);
  hsize_t n = 1;
  for (hsize_t d : dims)
    n *= d;
  if (n > 0)
    check(H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), where, "writing " + what);
  // A small dataset's data wait in HDF5's buffer until the dataset is closed: a full disk shows
  // here, and the destructor would not say so.
  set.close(where, "writing " + what);
}

/// Writes a scalar attribute.
inline void write_attribute(hid_t parent, const char *name, hid_t file_type, hid_t memory_type, const void *value,
                            const std::string &where)
{
  const std::string what = std::string("attribute '") + name + "'";
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, where, "creating the dataspace of " + what);
  Handle attribute(H5Acreate2(parent, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, where,
                   "creating " + what);
  check(H5Awrite(attribute.get(), memory_type, value), where, "writing " + what);
}

/// Reads a scalar attribute, converting to `memory_type`; a missing attribute is an error.
inline void read_attribute(hid_t parent, const char *name, hid_t memory_type, void *value, const std::string &where)
{
  const std::string what = std::string("attribute '") + name + "'";
  Handle attribute(H5Aopen(parent, name, H5P_DEFAULT), H5Aclose, where, "opening " + what);
  Handle space(H5Aget_space(attribute.get()), H5Sclose, where, "reading the dataspace of " + what);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    fail(where, what + " is not a scalar");
  check(H5Aread(attribute.get(), memory_type, value), where, "reading " + what);
}

/// Writes a scalar attribute holding a fixed-length string (its bytes exactly).
inline void write_string_attribute(hid_t parent, const char *name, const std::string &value, const std::string &where)
{
  const std::string what = std::string("attribute '") + name + "'";
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, where, "creating the string type of " + what);
  check(H5Tset_size(type.get(), value.size() + 1), where, "sizing the string type of " + what);
  check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), where, "setting the padding of " + what);
  write_attribute(parent, name, type.get(), type.get(), value.c_str(), where);
}

/// Reads a fixed-length string attribute written by write_string_attribute().
inline std::string read_string_attribute(hid_t parent, const char *name, const std::string &where)
{
  const std::string what = std::string("attribute '") + name + "'";
  Handle attribute(H5Aopen(parent, name, H5P_DEFAULT), H5Aclose, where, "opening " + what);
  Handle file_type(H5Aget_type(attribute.get()), H5Tclose, where, "reading the type of " + what);
  if (H5Tget_class(file_type.get()) != H5T_STRING || H5Tis_variable_str(file_type.get()) != 0)
    fail(where, what + " is not a fixed-length string");
  const std::size_t size = H5Tget_size(file_type.get());
  if (size == 0)
    fail(where, what + " has no size");
  Handle memory_type(H5Tcopy(H5T_C_S1), H5Tclose, where, "creating the string type of " + what);
  check(H5Tset_size(memory_type.get(), size), where, "sizing the string type of " + what);
  check(H5Tset_strpad(memory_type.get(), H5T_STR_NULLTERM), where, "setting the padding of " + what);
  std::string buffer(size, '\0');
  check(H5Aread(attribute.get(), memory_type.get(), buffer.data()), where, "reading " + what);
  buffer.resize(size - 1); // the terminating NUL
  return buffer;
}

/// Shape of a dataset.
inline std::vector<hsize_t> dataset_shape(hid_t set, const std::string &where, const std::string &what)
{
  Handle space(H5Dget_space(set), H5Sclose, where, "reading the dataspace of " + what);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0)
    fail(where, "reading the rank of " + what + " failed: " + error_text());
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0)
    check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), where, "reading the shape of " + what);
  return dims;
}
} // namespace geohybrid::dem::hdf5
