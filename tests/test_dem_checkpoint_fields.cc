// The field lists of a checkpoint (dem/io/checkpoint_fields.h), checked through themselves: every
// field of every state, given a value of its own, is written and read back exactly. The lists
// are walked by two visitors of this file: one that gives each field a value, one that prints
// each field exactly. A field missing from its list is caught at compile time instead (the
// sizeof checks beside the lists).
#include "dem/dem_system.h"
#include "dem/io/checkpoint.h"
#include "dem/io/checkpoint_fields.h"

#include <hdf5.h>

#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

using namespace geohybrid::dem;
using namespace geohybrid::dem::checkpoint_fields;
namespace fs = std::filesystem;

namespace
{
/// Gives every field a value of its own, different in filling 1 and filling 2: numbers from a
/// counter, flags true in filling 1 and false in 2, the other choice of an enum, texts of the
/// counter. Doubles are binary fractions in (0, 1), which the contact and sheet laws accept
/// (mass_scaling, at least 1, gets 1 more). An array keeps its length (1 if it was empty), and
/// index arrays (uint32) keep their values, so that the state stays one the reader accepts; a
/// dropped array would read back empty.
class Filler
{
public:
  explicit Filler(int filling) : filling_(filling) {}

  void attribute(const char *name, double &value, Presence = in_every_file)
  {
    value = fraction() + (std::string(name) == "mass_scaling" ? 1.0 : 0.0);
  }
  void attribute(const char *, std::uint64_t &value, Presence = in_every_file) { value = number(); }
  void attribute(const char *, std::uint32_t &value, Presence = in_every_file)
  {
    value = static_cast<std::uint32_t>(number());
  }
  void flag(const char *, bool &value) { value = filling_ == 1; }
  void flag_as_count(const char *name, bool &value, Presence = in_every_file) { flag(name, value); }
  void text(const char *, std::string &value) { value = "text \"" + std::to_string(number()) + "\" ü"; }
  template <typename Enum, std::size_t n>
  void choice(const char *, Enum &value, const std::array<std::pair<Enum, const char *>, n> &names)
  {
    value = names[static_cast<std::size_t>(filling_) % n].first;
  }
  template <typename T>
  void array(const char *, SoaVector<T> &values)
  {
    if (values.empty())
      values.resize(1);
    const std::uint64_t base = number();
    for (std::size_t k = 0; k < values.size(); ++k)
      if constexpr (std::is_same_v<T, double>)
        values[k] = (base + 0.5) / 8192.0 + k * 0x1p-40;
      else if constexpr (std::is_same_v<T, std::int64_t>)
        values[k] = -static_cast<std::int64_t>(base + k);
      else if constexpr (std::is_same_v<T, std::uint8_t>)
        values[k] = static_cast<std::uint8_t>((filling_ + k) % 2);
  }
  void vec2(const char *, Vec2 &value) { value = Vec2(fraction(), -fraction()); }
  void rows(const char *, std::vector<Vec2> &values)
  {
    for (Vec2 &v : values)
      v = Vec2(fraction(), -fraction());
  }
  void contact_states(SoaVector<ContactState> &states)
  {
    if (states.empty())
      states.resize(1);
    Columns columns{*this, states};
    visit_contact_state_columns(columns);
  }
  template <typename Describe>
  void group(const char *, Describe &&describe)
  {
    describe(*this);
  }
  void contact_law(const char *, LinearContactLaw &law)
  {
    ContactParameters parameters = law.parameters();
    visit_fields(parameters, *this);
    law = LinearContactLaw(parameters);
  }
  template <typename T>
  void numbered_groups(const char *, const char *, std::vector<T> &elements)
  {
    for (T &element : elements)
      visit_fields(element, *this);
  }
  void sheets(const char *, const char *, std::vector<SparSheet> &sheets, std::vector<SheetContacts> &contacts,
              Presence = in_every_file)
  {
    for (std::size_t k = 0; k < sheets.size(); ++k)
      {
        SheetHead head{sheets[k].name(), sheets[k].parameters()};
        visit_fields(head, *this);
        std::vector<Vec2> nodes;
        for (std::size_t i = 0; i < sheets[k].n_nodes(); ++i)
          nodes.push_back(sheets[k].node(i));
        sheets[k] = SparSheet(head.name, nodes, head.parameters);
        visit_fields(sheets[k], *this);
        visit_fields(contacts[k], *this);
      }
  }
  template <typename T>
  void keyed_arrays(const char *, const char *, std::map<std::string, std::vector<T>> &arrays)
  {
    arrays["key " + std::to_string(number())] = {T(number()), T(number())};
  }
  void keyed_texts(const char *, const char *, std::map<std::string, std::string> &texts)
  {
    text("", texts["key " + std::to_string(number())]);
  }

private:
  struct Columns
  {
    Filler &filler;
    SoaVector<ContactState> &states;
    template <typename T>
    void column(const char *name, T ContactState::*member)
    {
      for (ContactState &s : states)
        if constexpr (std::is_same_v<T, bool>)
          filler.flag(name, s.*member);
        else
          filler.attribute(name, s.*member);
    }
  };

  std::uint64_t number() { return 1000 * filling_ + next_++; }
  double fraction() { return (number() + 0.5) / 8192.0; }

  int filling_;
  std::uint64_t next_ = 1;
};

/// Every field as a line "path = value", numbers exactly (doubles in hexadecimal).
class Printer
{
public:
  std::map<std::string, std::string> lines;
  /// The index arrays, which Filler leaves as they are.
  std::vector<std::string> index_arrays;

  template <typename T>
  void attribute(const char *name, const T &value, Presence = in_every_file)
  {
    print(name, value);
  }
  void flag(const char *name, bool value) { print(name, value); }
  void flag_as_count(const char *name, bool value, Presence = in_every_file) { print(name, value); }
  void text(const char *name, const std::string &value) { print(name, '"' + value + '"'); }
  template <typename Enum, std::size_t n>
  void choice(const char *name, Enum value, const std::array<std::pair<Enum, const char *>, n> &)
  {
    print(name, static_cast<int>(value));
  }
  template <typename T, typename Allocator>
  void array(const char *name, const std::vector<T, Allocator> &values)
  {
    std::ostringstream out;
    out << std::hexfloat;
    for (const T &v : values)
      out << +v << ' ';
    lines[path_ + name] = out.str();
    if (std::is_same_v<T, std::uint32_t>)
      index_arrays.push_back(path_ + name);
  }
  void vec2(const char *name, const Vec2 &value) { array(name, std::vector<double>{value.x(), value.y()}); }
  void rows(const char *name, const std::vector<Vec2> &values)
  {
    std::vector<double> flat;
    for (const Vec2 &v : values)
      flat.insert(flat.end(), {v.x(), v.y()});
    array(name, flat);
  }
  void contact_states(const SoaVector<ContactState> &states)
  {
    Columns columns{*this, states};
    visit_contact_state_columns(columns);
  }
  template <typename Describe>
  void group(const char *name, Describe &&describe)
  {
    const std::string outer = path_;
    path_ += std::string(name) + "/";
    describe(*this);
    path_ = outer;
  }
  void contact_law(const char *name, const LinearContactLaw &law)
  {
    group(name, [&](Printer &in) { visit_fields(law.parameters(), in); });
  }
  template <typename T>
  void numbered_groups(const char *name, const char *prefix, const std::vector<T> &elements)
  {
    group(name, [&](Printer &list) {
      list.print("count", elements.size());
      for (std::size_t k = 0; k < elements.size(); ++k)
        list.group(numbered(prefix, k).c_str(), [&](Printer &in) { visit_fields(elements[k], in); });
    });
  }
  void sheets(const char *name, const char *prefix, const std::vector<SparSheet> &sheets,
              const std::vector<SheetContacts> &contacts, Presence = in_every_file)
  {
    group(name, [&](Printer &list) {
      list.print("count", sheets.size());
      for (std::size_t k = 0; k < sheets.size(); ++k)
        list.group(numbered(prefix, k).c_str(), [&](Printer &in) {
          const SheetHead head{sheets[k].name(), sheets[k].parameters()};
          visit_fields(head, in);
          visit_fields(sheets[k], in);
          visit_fields(contacts[k], in);
        });
    });
  }
  template <typename T>
  void keyed_arrays(const char *name, const char *, const std::map<std::string, std::vector<T>> &arrays)
  {
    group(name, [&](Printer &in) {
      for (const auto &[key, values] : arrays)
        in.array(key.c_str(), values);
    });
  }
  void keyed_texts(const char *name, const char *, const std::map<std::string, std::string> &texts)
  {
    group(name, [&](Printer &in) {
      for (const auto &[key, value] : texts)
        in.text(key.c_str(), value);
    });
  }

private:
  struct Columns
  {
    Printer &printer;
    const SoaVector<ContactState> &states;
    template <typename T>
    void column(const char *name, T ContactState::*member)
    {
      std::vector<T> values;
      for (const ContactState &s : states)
        values.push_back(s.*member);
      printer.array(name, values);
    }
  };

  template <typename T>
  void print(const char *name, const T &value)
  {
    std::ostringstream out;
    out << std::hexfloat << value;
    lines[path_ + name] = out.str();
  }

  std::string path_ = "/";
};

template <typename State>
Printer printed(const State &state)
{
  Printer printer;
  visit_fields(state, printer);
  return printer;
}

/// The lines of `b` that differ from those of `a`, or are missing from one of them.
std::string differences(const Printer &a, const Printer &b)
{
  std::string text;
  for (const auto &[path, line] : a.lines)
    if (!b.lines.count(path) || b.lines.at(path) != line)
      text += path + ": " + line + " | " + (b.lines.count(path) ? b.lines.at(path) : "(missing)") + "\n";
  for (const auto &[path, line] : b.lines)
    if (!a.lines.count(path))
      text += path + ": (missing) | " + line + "\n";
  return text;
}

ContactParameters law(double friction_deg)
{
  ContactParameters c;
  c.normal_stiffness = 1.0e6;
  c.shear_stiffness = 0.5e6;
  c.friction_angle_deg = friction_deg;
  c.restitution = 0.5;
  return c;
}

/// A few steps of discs in a box of four walls (the roof a servo) with a sheet across it: a
/// state in which every list of the file has entries (pairs, wall contacts, sheet contacts).
DemSystemState state_with_everything()
{
  constexpr double r = 0.005, pitch = 2.05 * r, width = 6 * pitch, height = 5 * pitch;
  ParticleSet p;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 6; ++i)
      if ((i + j) % 4 == 0)
        p.add_two_disc_cluster(Vec2((i + 0.5) * pitch, (j + 0.5) * pitch), 0.6 * r, 0.54 * r, 0.5 * r, 0.3, 2650.0);
      else
        p.add_disc(Vec2((i + 0.5) * pitch, (j + 0.5) * pitch), r, 2650.0);
  DemSettings settings;
  settings.local_damping = 0.7;
  DemSystem system(std::move(p), LinearContactLaw(law(20.0)), settings);
  const LinearContactLaw wall_law(law(10.0));
  system.add_wall(Wall("floor", Vec2(0.0, 0.0), Vec2(width, 0.0), wall_law));
  system.add_wall(Wall("right", Vec2(width, 0.0), Vec2(width, height), wall_law));
  Wall roof("roof", Vec2(width, height), Vec2(0.0, height), wall_law);
  roof.control = WallControl::servo_stress;
  roof.servo.target_stress = 1.0e3;
  system.add_wall(roof);
  system.add_wall(Wall("left", Vec2(0.0, height), Vec2(0.0, 0.0), wall_law));
  SheetParameters sheet;
  sheet.thickness = 1.0e-4;
  sheet.mass_scaling = 100.0;
  sheet.interface = law(15.0);
  system.add_sheet(SparSheet("sheet", subdivide_polyline({Vec2(0.2 * r, 2 * pitch), Vec2(width - 0.2 * r, 2 * pitch)}, r),
                             sheet));
  system.run_steps(200);
  return system.export_state();
}

/// That state with the values of `filling` in every field.
DemSystemState filled(int filling)
{
  DemSystemState state = state_with_everything();
  Filler filler(filling);
  visit_fields(state, filler);
  return state;
}
} // namespace

// Two fillings that differ in every field, each written and read back: every line is the same. A
// field that were not written, or read back at its default, could not match both fillings.
TEST(CheckpointFields, EveryFieldOfTheSystemStateRoundTrips)
{
  geohybrid::testing::TemporaryDirectory directory("test_dem_checkpoint_fields");
  const Printer first = printed(filled(1)), second = printed(filled(2));
  for (const auto &[path, line] : first.lines)
    {
      const bool kept = std::find(first.index_arrays.begin(), first.index_arrays.end(), path) != first.index_arrays.end();
      ASSERT_TRUE(second.lines.count(path)) << path;
      if (!kept && path.find("/count") == std::string::npos)
        {
          EXPECT_NE(line, second.lines.at(path)) << path << " has the same value in both fillings";
        }
    }
  // What the lists reach: all of DemSystemState's parts, a sheet and its node-wall contacts.
  EXPECT_TRUE(first.lines.count("/sheets/sheet_000000/interface/restitution"));
  EXPECT_TRUE(first.lines.count("/sheets/sheet_000000/wall_contacts/wall_000003/dashpot_force"));
  EXPECT_TRUE(first.lines.count("/walls/wall_000002/law/bond_new_contacts"));

  for (int filling : {1, 2})
    {
      const DemSystemState state = filled(filling);
      const fs::path file = directory.path / ("filling_" + std::to_string(filling) + ".h5");
      write_checkpoint(state, file);
      EXPECT_EQ(differences(printed(state), printed(read_checkpoint(file))), "") << "filling " << filling;
    }
}

TEST(CheckpointFields, EveryFieldOfTheCommandStateRoundTrips)
{
  geohybrid::testing::TemporaryDirectory directory("test_dem_checkpoint_fields");
  const DemSystemState state = state_with_everything();
  for (int filling : {1, 2})
    {
      CommandState command;
      Filler filler(filling);
      visit_fields(command, filler);
      ASSERT_FALSE(command.name.empty());
      ASSERT_EQ(command.reals.size(), 1u);
      ASSERT_EQ(command.counts.size(), 1u);
      ASSERT_EQ(command.texts.size(), 1u);
      const fs::path file = directory.path / ("filling_" + std::to_string(filling) + ".h5");
      write_checkpoint(state, command, file);
      EXPECT_EQ(differences(printed(command), printed(read_checkpoint_command(file))), "");
      CommandState both;
      read_checkpoint(file, both);
      EXPECT_EQ(differences(printed(command), printed(both)), "");
    }
}

// Fields added to the files later: a file without them reads with their defaults (every wall
// touched sheets; no texts); a file without a field every version has is refused, naming the
// file and the field.
TEST(CheckpointFields, OlderFilesReadWithDefaultsAndMissingFieldsNamed)
{
  geohybrid::testing::TemporaryDirectory directory("test_dem_checkpoint_fields");
  const fs::path file = directory.path / "older.h5";
  DemSystemState state = state_with_everything();
  for (Wall &wall : state.walls)
    wall.touches_sheets = false;
  CommandState command;
  command.name = "pullout";
  command.reals["pull"] = {1.0};
  command.texts["input"] = "an input";
  write_checkpoint(state, command, file);
  {
    const hid_t h5 = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(h5, 0);
    EXPECT_GE(H5Adelete_by_name(h5, "walls/wall_000001", "touches_sheets", H5P_DEFAULT), 0);
    EXPECT_GE(H5Adelete_by_name(h5, "command", "text_keys", H5P_DEFAULT), 0);
    H5Fclose(h5);
  }
  CommandState back;
  const DemSystemState read = read_checkpoint(file, back);
  EXPECT_FALSE(read.walls[0].touches_sheets);
  EXPECT_TRUE(read.walls[1].touches_sheets);
  EXPECT_TRUE(back.texts.empty());
  EXPECT_EQ(back.reals.at("pull"), command.reals.at("pull"));

  {
    const hid_t h5 = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(h5, 0);
    EXPECT_GE(H5Adelete_by_name(h5, "walls/wall_000002", "servo_integral", H5P_DEFAULT), 0);
    H5Fclose(h5);
  }
  std::string message;
  try
    {
      read_checkpoint(file);
    }
  catch (const std::runtime_error &e)
    {
      message = e.what();
    }
  EXPECT_NE(message.find("older.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("servo_integral"), std::string::npos) << message;
}
