#pragma once
// The visitor that writes the field lists of checkpoint_fields.h into an HDF5 group. Every field
// is written whatever its Presence: the files written now are of the current version.
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
class Writer
{
public:
  /// Writes into `group`; failures throw std::runtime_error beginning with `where`.
  Writer(hid_t group, std::string where) : group_(group), where_(std::move(where)) {}

  void attribute(const char *name, double value, Presence = in_every_file);
  void attribute(const char *name, std::uint64_t value, Presence = in_every_file);
  void attribute(const char *name, std::uint32_t value, Presence = in_every_file);
  void flag(const char *name, bool value);
  void flag_as_count(const char *name, bool value, Presence = in_every_file);
  void text(const char *name, const std::string &value);

  template <typename Enum, std::size_t n>
  void choice(const char *name, Enum value, const std::array<std::pair<Enum, const char *>, n> &names)
  {
    for (const auto &[choice, choice_name] : names)
      if (choice == value)
        return text(name, choice_name);
    hdf5::fail(where_, std::string("attribute '") + name + "': a value without a name");
  }

  template <typename T, typename Allocator>
  void array(const char *name, const std::vector<T, Allocator> &values)
  {
    dataset(name, hdf5::Type<T>::file(), hdf5::Type<T>::memory(), values.size(), 1, values.data());
  }
  void vec2(const char *name, const Vec2 &value);
  void rows(const char *name, const std::vector<Vec2> &values);
  void contact_states(const SoaVector<ContactState> &states);

  template <typename Describe>
  void group(const char *name, Describe &&describe)
  {
    hdf5::Handle g = hdf5::create_group(group_, name, where_);
    Writer in(g.get(), where_);
    describe(in);
  }
  void contact_law(const char *name, const LinearContactLaw &law);

  template <typename T>
  void numbered_groups(const char *name, const char *prefix, const std::vector<T> &elements)
  {
    group(name, [&](Writer &list) {
      list.attribute("count", std::uint64_t(elements.size()));
      for (std::size_t k = 0; k < elements.size(); ++k)
        list.group(numbered(prefix, k).c_str(), [&](Writer &in) { visit_fields(elements[k], in); });
    });
  }
  void sheets(const char *name, const char *prefix, const std::vector<SparSheet> &sheets,
              const std::vector<SheetContacts> &contacts, Presence = in_every_file);

  template <typename T>
  void keyed_arrays(const char *name, const char *keys_name, const std::map<std::string, std::vector<T>> &arrays)
  {
    std::vector<std::string> keys;
    group(name, [&](Writer &in) {
      for (const auto &[key, values] : arrays)
        {
          in.array(key.c_str(), values);
          keys.push_back(key);
        }
    });
    text(keys_name, joined_keys(keys));
  }
  /// No group and no keys when `texts` is empty: the layout of the files written before texts.
  void keyed_texts(const char *name, const char *keys_name, const std::map<std::string, std::string> &texts);

  /// The keys, one a line.
  static std::string joined_keys(const std::vector<std::string> &keys);

private:
  /// A dataset of `rows` rows of `columns` values (one dimension if columns == 1).
  void dataset(const char *name, hid_t file_type, hid_t memory_type, std::size_t rows, std::size_t columns,
               const void *data);

  hid_t group_;
  std::string where_;
};
} // namespace geohybrid::dem::checkpoint_fields
