#include "checkpoint_writer.h"

#include <type_traits>

namespace geohybrid::dem::checkpoint_fields
{
namespace
{
template <typename T>
void write_attribute(hid_t group, const char *name, T value, const std::string &where)
{
  hdf5::write_attribute(group, name, hdf5::Type<T>::file(), hdf5::Type<T>::memory(), &value, where);
}

/// One contact's history, gathered member by member into a dataset each.
class ContactStateColumns
{
public:
  ContactStateColumns(Writer &out, const SoaVector<ContactState> &states) : out_(out), states_(states) {}

  template <typename T>
  void column(const char *name, T ContactState::*member)
  {
    // Booleans as bytes, 0 or 1.
    using Stored = std::conditional_t<std::is_same_v<T, bool>, std::uint8_t, T>;
    std::vector<Stored> values(states_.size());
    for (std::size_t q = 0; q < states_.size(); ++q)
      values[q] = static_cast<Stored>(states_[q].*member);
    out_.array(name, values);
  }

private:
  Writer &out_;
  const SoaVector<ContactState> &states_;
};
} // namespace

void Writer::attribute(const char *name, double value, Presence) { write_attribute(group_, name, value, where_); }

void Writer::attribute(const char *name, std::uint64_t value, Presence)
{
  write_attribute(group_, name, value, where_);
}

void Writer::attribute(const char *name, std::uint32_t value, Presence)
{
  write_attribute(group_, name, value, where_);
}

void Writer::flag(const char *name, bool value) { write_attribute<std::uint8_t>(group_, name, value ? 1 : 0, where_); }

void Writer::flag_as_count(const char *name, bool value, Presence)
{
  write_attribute<std::uint64_t>(group_, name, value ? 1 : 0, where_);
}

void Writer::text(const char *name, const std::string &value)
{
  hdf5::write_string_attribute(group_, name, value, where_);
}

void Writer::vec2(const char *name, const Vec2 &value)
{
  const double xy[2] = {value.x(), value.y()};
  dataset(name, hdf5::Type<double>::file(), hdf5::Type<double>::memory(), 2, 1, xy);
}

void Writer::rows(const char *name, const std::vector<Vec2> &values)
{
  std::vector<double> flat;
  flat.reserve(2 * values.size());
  for (const Vec2 &v : values)
    flat.insert(flat.end(), {v.x(), v.y()});
  dataset(name, hdf5::Type<double>::file(), hdf5::Type<double>::memory(), values.size(), 2, flat.data());
}

void Writer::contact_states(const SoaVector<ContactState> &states)
{
  ContactStateColumns columns(*this, states);
  visit_contact_state_columns(columns);
}

void Writer::contact_law(const char *name, const LinearContactLaw &law)
{
  group(name, [&](Writer &in) { visit_fields(law.parameters(), in); });
}

void Writer::sheets(const char *name, const char *prefix, const std::vector<SparSheet> &sheets,
                    const std::vector<SheetContacts> &contacts, Presence)
{
  group(name, [&](Writer &list) {
    list.attribute("count", std::uint64_t(sheets.size()));
    for (std::size_t k = 0; k < sheets.size(); ++k)
      list.group(numbered(prefix, k).c_str(), [&](Writer &in) {
        const SheetHead head{sheets[k].name(), sheets[k].parameters()};
        visit_fields(head, in);
        visit_fields(sheets[k], in);
        visit_fields(contacts[k], in);
      });
  });
}

void Writer::keyed_texts(const char *name, const char *keys_name, const std::map<std::string, std::string> &texts)
{
  if (texts.empty())
    return;
  std::vector<std::string> keys;
  group(name, [&](Writer &in) {
    for (const auto &[key, value] : texts)
      {
        in.text(key.c_str(), value);
        keys.push_back(key);
      }
  });
  text(keys_name, joined_keys(keys));
}

std::string Writer::joined_keys(const std::vector<std::string> &keys)
{
  std::string text;
  for (const std::string &k : keys)
    text += k + "\n";
  return text;
}

void Writer::dataset(const char *name, hid_t file_type, hid_t memory_type, std::size_t rows, std::size_t columns,
                     const void *data)
{
  std::vector<hsize_t> dims{rows};
  if (columns > 1)
    dims.push_back(columns);
  hdf5::write_dataset(group_, name, file_type, memory_type, dims, data, where_);
}
} // namespace geohybrid::dem::checkpoint_fields
