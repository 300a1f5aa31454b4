#pragma once
// The visitor that reads the field lists of checkpoint_fields.h from an HDF5 group of a file of a
// given format version. A field the file lacks by its Presence keeps the value the state starts
// with; any other missing field, a dataset of another type or shape, or a flag other than 0 or 1
// throws std::runtime_error beginning with `where` (the file).
//
// Include only from .cc files: hdf5.h (the OpenMPI flavour) pulls in mpi.h.
#include "checkpoint_fields.h"
#include "hdf5_handles.h"
#include "hdf5_types.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace geohybrid::dem::checkpoint_fields
{
class Reader
{
public:
  /// Reads from `group`, at `path` in the file (for messages), of format version `version`.
  Reader(hid_t group, std::uint32_t version, std::string where, std::string path = "")
    : group_(group), version_(version), where_(std::move(where)), path_(std::move(path))
  {}

  void attribute(const char *name, double &value, Presence = in_every_file);
  void attribute(const char *name, std::uint64_t &value, Presence = in_every_file);
  void attribute(const char *name, std::uint32_t &value, Presence = in_every_file);
  void flag(const char *name, bool &value);
  void flag_as_count(const char *name, bool &value, Presence = in_every_file);
  void text(const char *name, std::string &value);

  template <typename Enum, std::size_t n>
  void choice(const char *name, Enum &value, const std::array<std::pair<Enum, const char *>, n> &names)
  {
    std::string stored;
    text(name, stored);
    for (const auto &[choice, choice_name] : names)
      if (stored == choice_name)
        {
          value = choice;
          return;
        }
    fail("attribute '" + std::string(name) + "' has an unknown value '" + stored + "'");
  }

  template <typename T>
  void array(const char *name, SoaVector<T> &values)
  {
    values = read_array<T>(name, 1);
  }
  void vec2(const char *name, Vec2 &value);
  void rows(const char *name, std::vector<Vec2> &values);
  void contact_states(SoaVector<ContactState> &states);

  template <typename Describe>
  void group(const char *name, Describe &&describe)
  {
    hdf5::Handle g = hdf5::open_group(group_, name, where_);
    Reader in(g.get(), version_, where_, path_ + "/" + name);
    describe(in);
  }
  /// Refuses parameters the law refuses, naming the group.
  void contact_law(const char *name, LinearContactLaw &law);

  template <typename T>
  void numbered_groups(const char *name, const char *prefix, std::vector<T> &elements)
  {
    group(name, [&](Reader &list) {
      const std::size_t count = list.count();
      elements.clear();
      elements.reserve(count);
      for (std::size_t k = 0; k < count; ++k)
        {
          T element = blank<T>();
          list.group(numbered(prefix, k).c_str(), [&](Reader &in) { visit_fields(element, in); });
          elements.push_back(std::move(element));
        }
    });
  }
  /// Each sheet built from its SheetHead (refused, naming it, if the sheet refuses its
  /// parameters), then its arrays replaced by the stored ones.
  void sheets(const char *name, const char *prefix, std::vector<SparSheet> &sheets,
              std::vector<SheetContacts> &contacts, Presence = in_every_file);

  template <typename T>
  void keyed_arrays(const char *name, const char *keys_name, std::map<std::string, std::vector<T>> &arrays)
  {
    std::string keys;
    text(keys_name, keys);
    group(name, [&](Reader &in) {
      for (const std::string &key : split_keys(keys))
        {
          const SoaVector<T> values = in.read_array<T>(key.c_str(), 1);
          arrays[key].assign(values.begin(), values.end());
        }
    });
  }
  /// None when the file has no keys (written before texts existed, or with none).
  void keyed_texts(const char *name, const char *keys_name, std::map<std::string, std::string> &texts);

  /// The keys joined by Writer::joined_keys().
  static std::vector<std::string> split_keys(const std::string &text);

  /// The attribute "count" of a numbered list, refused if implausible.
  std::size_t count();

  /// A dataset of any number of rows and `columns` columns (one dimension if columns == 1) whose
  /// stored type is of the class and size of T.
  template <typename T>
  SoaVector<T> read_array(const char *name, std::size_t columns)
  {
    const std::string what = std::string("dataset '") + name + "'";
    hdf5::Handle set(H5Dopen2(group_, name, H5P_DEFAULT), H5Dclose, where_, "opening " + what);
    hdf5::Handle type(H5Dget_type(set.get()), H5Tclose, where_, "reading the type of " + what);
    if (H5Tget_class(type.get()) != hdf5::Type<T>::type_class || H5Tget_size(type.get()) != sizeof(T))
      hdf5::fail(where_, what + " has an unexpected type");
    const std::vector<hsize_t> dims = hdf5::dataset_shape(set.get(), where_, what);
    if (dims.size() != (columns > 1 ? 2u : 1u) || (columns > 1 && dims[1] != columns))
      hdf5::fail(where_, what + " has an unexpected shape");
    SoaVector<T> values(static_cast<std::size_t>(dims[0]) * columns);
    if (!values.empty())
      hdf5::check(H5Dread(set.get(), hdf5::Type<T>::memory(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
                  where_, "reading " + what);
    return values;
  }

private:
  /// Whether the file holds a field of this presence (an attribute, or a group or dataset).
  bool holds(const char *name, Presence presence, bool is_attribute) const;
  template <typename T>
  T read_attribute(const char *name)
  {
    T value{};
    hdf5::read_attribute(group_, name, hdf5::Type<T>::memory(), &value, where_);
    return value;
  }
  bool read_flag(const char *name, std::uint64_t stored);
  [[noreturn]] void fail(const std::string &what) const;

  hid_t group_;
  std::uint32_t version_;
  std::string where_, path_;
};
} // namespace geohybrid::dem::checkpoint_fields
