#include "checkpoint_reader.h"

#include <optional>
#include <stdexcept>
#include <type_traits>

namespace geohybrid::dem::checkpoint_fields
{
namespace
{
/// One contact's history, read member by member from a dataset each.
class ContactStateColumns
{
public:
  ContactStateColumns(Reader &in, const std::string &where, SoaVector<ContactState> &states)
    : in_(in), where_(where), states_(states)
  {}

  template <typename T>
  void column(const char *name, T ContactState::*member)
  {
    constexpr bool is_flag = std::is_same_v<T, bool>;
    using Stored = std::conditional_t<is_flag, std::uint8_t, T>;
    const SoaVector<Stored> values = in_.read_array<Stored>(name, 1);
    if (first_)
      states_.assign(values.size(), ContactState{});
    else if (values.size() != states_.size())
      hdf5::fail(where_, "contact states of different lengths");
    first_ = false;
    for (std::size_t q = 0; q < values.size(); ++q)
      {
        if constexpr (is_flag)
          if (values[q] > 1)
            hdf5::fail(where_, "a contact state flag is not 0 or 1");
        states_[q].*member = static_cast<T>(values[q]);
      }
  }

private:
  Reader &in_;
  const std::string &where_;
  SoaVector<ContactState> &states_;
  bool first_ = true;
};
} // namespace

void Reader::attribute(const char *name, double &value, Presence presence)
{
  if (holds(name, presence, true))
    value = read_attribute<double>(name);
}

void Reader::attribute(const char *name, std::uint64_t &value, Presence presence)
{
  if (holds(name, presence, true))
    value = read_attribute<std::uint64_t>(name);
}

void Reader::attribute(const char *name, std::uint32_t &value, Presence presence)
{
  if (holds(name, presence, true))
    value = read_attribute<std::uint32_t>(name);
}

void Reader::flag(const char *name, bool &value) { value = read_flag(name, read_attribute<std::uint8_t>(name)); }

void Reader::flag_as_count(const char *name, bool &value, Presence presence)
{
  if (holds(name, presence, true))
    value = read_flag(name, read_attribute<std::uint64_t>(name));
}

void Reader::text(const char *name, std::string &value) { value = hdf5::read_string_attribute(group_, name, where_); }

void Reader::vec2(const char *name, Vec2 &value)
{
  const SoaVector<double> v = read_array<double>(name, 1);
  if (v.size() != 2)
    hdf5::fail(where_, std::string("dataset '") + name + "' does not hold 2 values");
  value = Vec2(v[0], v[1]);
}

void Reader::rows(const char *name, std::vector<Vec2> &values)
{
  const SoaVector<double> flat = read_array<double>(name, 2);
  values.resize(flat.size() / 2);
  for (std::size_t k = 0; k < values.size(); ++k)
    values[k] = Vec2(flat[2 * k], flat[2 * k + 1]);
}

void Reader::contact_states(SoaVector<ContactState> &states)
{
  ContactStateColumns columns(*this, where_, states);
  visit_contact_state_columns(columns);
}

void Reader::contact_law(const char *name, LinearContactLaw &law)
{
  ContactParameters parameters;
  group(name, [&](Reader &in) { visit_fields(parameters, in); });
  try
    {
      law = LinearContactLaw(parameters);
    }
  catch (const std::invalid_argument &e)
    {
      fail(std::string("group '") + name + "': " + e.what());
    }
}

void Reader::sheets(const char *name, const char *prefix, std::vector<SparSheet> &sheets,
                    std::vector<SheetContacts> &contacts, Presence presence)
{
  if (!holds(name, presence, false))
    return;
  group(name, [&](Reader &list) {
    const std::size_t count = list.count();
    sheets.clear();
    contacts.assign(count, SheetContacts{});
    for (std::size_t k = 0; k < count; ++k)
      list.group(numbered(prefix, k).c_str(), [&](Reader &in) {
        SheetHead head;
        visit_fields(head, in);
        // A chain built to validate the head; its arrays are all replaced by the stored ones.
        std::optional<SparSheet> sheet;
        try
          {
            sheet.emplace(head.name, std::vector<Vec2>{Vec2(0.0, 0.0), Vec2(1.0, 0.0)}, head.parameters);
          }
        catch (const std::invalid_argument &e)
          {
            in.fail(e.what());
          }
        visit_fields(*sheet, in);
        visit_fields(contacts[k], in);
        sheets.push_back(std::move(*sheet));
      });
  });
}

void Reader::keyed_texts(const char *name, const char *keys_name, std::map<std::string, std::string> &texts)
{
  if (H5Aexists(group_, keys_name) <= 0)
    return;
  std::string keys;
  text(keys_name, keys);
  group(name, [&](Reader &in) {
    for (const std::string &key : split_keys(keys))
      in.text(key.c_str(), texts[key]);
  });
}

std::vector<std::string> Reader::split_keys(const std::string &text)
{
  std::vector<std::string> keys;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    keys.push_back(text.substr(start, end - start));
  return keys;
}

std::size_t Reader::count()
{
  const std::uint64_t count = read_attribute<std::uint64_t>("count");
  if (count > 1000000)
    hdf5::fail(where_, "implausible count " + std::to_string(count));
  return static_cast<std::size_t>(count);
}

bool Reader::holds(const char *name, Presence presence, bool is_attribute) const
{
  if (version_ < presence.first_version)
    return false;
  if (!presence.may_be_missing)
    return true;
  return (is_attribute ? H5Aexists(group_, name) : H5Lexists(group_, name, H5P_DEFAULT)) > 0;
}

bool Reader::read_flag(const char *name, std::uint64_t stored)
{
  if (stored > 1)
    hdf5::fail(where_, std::string("attribute '") + name + "' is not 0 or 1");
  return stored == 1;
}

void Reader::fail(const std::string &what) const { hdf5::fail(where_, (path_.empty() ? "/" : path_) + ": " + what); }
} // namespace geohybrid::dem::checkpoint_fields
