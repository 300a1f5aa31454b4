#pragma once
// The one description of what a checkpoint stores: for each state, the list of its fields with
// their names in the file (the layout of checkpoint.h). The writer (checkpoint_writer.h) and the
// reader (checkpoint_reader.h) both walk these lists, so a field is named once and cannot be
// written under one name and read under another, or written and never read.
//
// A list is a function template visit_fields(state, visitor) that calls one visitor member per
// field; the member says how the field is stored:
//
//   attribute(name, value, presence)     a scalar attribute (double, uint32, uint64)
//   flag(name, value)                    a bool as a uint8 attribute, 0 or 1
//   flag_as_count(name, value, presence) a bool as a uint64 attribute, 0 or 1
//   text(name, value)                    a std::string as a fixed-length string attribute
//   choice(name, value, names)           an enum as a string attribute, from a table of names
//   array(name, values)                  a SoaVector as a one-dimensional dataset
//   vec2(name, value)                    a Vec2 as a dataset of 2 doubles
//   rows(name, values)                   a std::vector<Vec2> as an n x 2 dataset
//   contact_states(states)               a SoaVector<ContactState>, one dataset per member
//                                        (visit_contact_state_columns)
//   group(name, fn)                      a group whose content fn(visitor of the group) describes
//   contact_law(name, law)               a LinearContactLaw as a group of its ContactParameters
//   numbered_groups(name, prefix, list)  a group with attribute count and one group
//                                        PREFIX_NNNNNN per element
//   sheets(name, prefix, sheets, contacts, presence)  as numbered_groups, a group per sheet
//                                        holding its SheetHead, its arrays and its contacts
//   keyed_arrays(name, keys_name, map)   a map of arrays: a group of datasets and the keys
//   keyed_texts(name, keys_name, map)    a map of texts: a group of attributes and the keys;
//                                        no group at all when the map is empty
//
// A state is visited as `State &` by the reader and as `const State &` by the writer, hence the
// template parameter and IfState. Presence says which files hold a field that was added later.
#include "dem/dem_system.h"
#include "checkpoint.h"

#include <array>
#include <cstdio>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

namespace geohybrid::dem::checkpoint_fields
{
/// Which files hold a field: every one (the default); those of format version first_version on
/// (older ones lack it); or any file may lack it (added without raising the version). Where a
/// file lacks it, the reader keeps the value the state starts with (its default).
struct Presence
{
  std::uint32_t first_version = 1;
  bool may_be_missing = false;
};
constexpr Presence in_every_file{};
constexpr Presence from_version(std::uint32_t version) { return Presence{version, false}; }
constexpr Presence maybe_missing{1, true};

/// `State` or `const State`: enables a field list for both the reader and the writer.
template <typename T, typename State>
using IfState = std::enable_if_t<std::is_same_v<std::remove_const_t<T>, State>>;

/// What a SparSheet is built from, stored beside its arrays: its name and parameters are fixed at
/// construction (the interface law follows from them), so the reader builds the sheet from them.
struct SheetHead
{
  std::string name;
  SheetParameters parameters;
};

/// The names under which a wall's control is stored.
constexpr std::array<std::pair<WallControl, const char *>, 2> wall_control_names{
  {{WallControl::prescribed_velocity, "prescribed_velocity"}, {WallControl::servo_stress, "servo_stress"}}};

/// The name of element `index` of a numbered list: PREFIX_NNNNNN.
inline std::string numbered(const char *prefix, std::size_t index)
{
  char name[48];
  std::snprintf(name, sizeof(name), "%s_%06zu", prefix, index);
  return name;
}

/// The value the reader fills in from the file: a default one, or an empty wall (a Wall has no
/// default).
template <typename T>
T blank()
{
  return T{};
}
template <>
inline Wall blank<Wall>()
{
  return Wall("", Vec2::Zero(), Vec2::Zero(), LinearContactLaw());
}

// ---- the fields of each state --------------------------------------------------------------------

/// One contact's history, stored column by column (a dataset per member) beside its contact's
/// arrays.
template <typename Visitor>
void visit_contact_state_columns(Visitor &v)
{
  v.column("tangential_force", &ContactState::tangential_force);
  v.column("bonded", &ContactState::bonded);
  v.column("touching", &ContactState::touching);
  v.column("dashpot_force", &ContactState::dashpot_force);
}

template <typename Parameters, typename Visitor>
IfState<Parameters, ContactParameters> visit_fields(Parameters &c, Visitor &v)
{
  v.attribute("normal_stiffness", c.normal_stiffness);
  v.attribute("shear_stiffness", c.shear_stiffness);
  v.attribute("friction_angle_deg", c.friction_angle_deg);
  v.attribute("shear_strength", c.shear_strength);
  v.attribute("tensile_strength", c.tensile_strength);
  v.attribute("restitution", c.restitution);
  v.flag("bond_new_contacts", c.bond_new_contacts);
}

template <typename Energy, typename Visitor>
IfState<Energy, EnergyBudget> visit_fields(Energy &e, Visitor &v)
{
  v.attribute("kinetic", e.kinetic);
  v.attribute("gravitational", e.gravitational);
  v.attribute("elastic", e.elastic);
  v.attribute("friction_dissipated", e.friction_dissipated);
  v.attribute("viscous_dissipated", e.viscous_dissipated);
  v.attribute("local_damping_dissipated", e.local_damping_dissipated);
  v.attribute("boundary_work", e.boundary_work);
  // Version 1 had no sheets.
  v.attribute("sheet_kinetic", e.sheet_kinetic, from_version(2));
  v.attribute("sheet_elastic", e.sheet_elastic, from_version(2));
  v.attribute("interface_friction_dissipated", e.interface_friction_dissipated, from_version(2));
}

template <typename Particles, typename Visitor>
IfState<Particles, ParticleSet> visit_fields(Particles &p, Visitor &v)
{
  v.array("body_id", p.body_id);
  v.array("x", p.x);
  v.array("y", p.y);
  v.array("rotation", p.rotation);
  v.array("vx", p.vx);
  v.array("vy", p.vy);
  v.array("omega", p.omega);
  v.array("fx", p.fx);
  v.array("fy", p.fy);
  v.array("torque", p.torque);
  v.array("mass", p.mass);
  v.array("inertia", p.inertia);
  v.array("inverse_mass", p.inverse_mass);
  v.array("inverse_inertia", p.inverse_inertia);
  v.array("first_disc", p.first_disc);
  v.array("n_discs", p.n_discs);
  v.array("disc_body", p.disc_body);
  v.array("disc_radius", p.disc_radius);
  v.array("disc_offset_x", p.disc_offset_x);
  v.array("disc_offset_y", p.disc_offset_y);
  v.array("disc_x", p.disc_x);
  v.array("disc_y", p.disc_y);
}

/// The body adjacency and the chunk plan are not stored: they follow from the pairs.
template <typename Pairs, typename Visitor>
IfState<Pairs, PairContacts> visit_fields(Pairs &c, Visitor &v)
{
  v.array("disc_i", c.disc_i);
  v.array("disc_j", c.disc_j);
  v.contact_states(c.state);
  v.array("force_x", c.force_x);
  v.array("force_y", c.force_y);
  v.array("torque_i", c.torque_i);
  v.array("torque_j", c.torque_j);
  v.array("elastic_normal_force", c.elastic_normal_force);
  v.array("friction_work", c.friction_work);
  v.array("viscous_work", c.viscous_work);
}

template <typename Contacts, typename Visitor>
IfState<Contacts, WallContacts> visit_fields(Contacts &c, Visitor &v)
{
  v.array("disc", c.disc);
  v.contact_states(c.state);
  v.array("force_x", c.force_x);
  v.array("force_y", c.force_y);
  v.array("elastic_normal_force", c.elastic_normal_force);
  v.array("friction_work", c.friction_work);
  v.array("viscous_work", c.viscous_work);
}

/// A wall whole (geometry, law, control), so that the saved walls replace those the system was
/// built with.
template <typename WallT, typename Visitor>
IfState<WallT, Wall> visit_fields(WallT &wall, Visitor &v)
{
  v.text("name", wall.name);
  v.choice("control", wall.control, wall_control_names);
  v.attribute("n_contacts", wall.n_contacts);
  v.attribute("servo_target_stress", wall.servo.target_stress);
  v.attribute("servo_relaxation", wall.servo.relaxation);
  v.attribute("servo_max_speed", wall.servo.max_speed);
  v.attribute("servo_integral_gain", wall.servo.integral_gain);
  v.attribute("servo_integral", wall.servo.integral);
  v.vec2("start", wall.start);
  v.vec2("end", wall.end);
  v.vec2("velocity", wall.velocity);
  v.vec2("force_from_particles", wall.force_from_particles);
  v.attribute("loaded_length", wall.loaded_length);
  // Files written before it existed lack it: every wall touched sheets (the default).
  v.flag_as_count("touches_sheets", wall.touches_sheets, maybe_missing);
  v.contact_law("law", wall.law);
}

/// Stored as attributes of the sheet's own group.
template <typename Head, typename Visitor>
IfState<Head, SheetHead> visit_fields(Head &head, Visitor &v)
{
  v.text("name", head.name);
  v.attribute("axial_stiffness", head.parameters.axial_stiffness);
  v.attribute("thickness", head.parameters.thickness);
  v.attribute("areal_mass", head.parameters.areal_mass);
  v.attribute("mass_scaling", head.parameters.mass_scaling);
  v.group("interface", [&](auto &in) { visit_fields(head.parameters.interface, in); });
}

/// The arrays of a sheet; its name and parameters are its SheetHead.
template <typename Sheet, typename Visitor>
IfState<Sheet, SparSheet> visit_fields(Sheet &sheet, Visitor &v)
{
  v.array("x", sheet.x);
  v.array("y", sheet.y);
  v.array("vx", sheet.vx);
  v.array("vy", sheet.vy);
  v.array("fx", sheet.fx);
  v.array("fy", sheet.fy);
  v.array("mass", sheet.mass);
  v.array("inverse_mass", sheet.inverse_mass);
  v.array("gravitational_mass", sheet.gravitational_mass);
  v.array("damping_fx", sheet.damping_fx);
  v.array("damping_fy", sheet.damping_fy);
  v.array("reaction_x", sheet.reaction_x);
  v.array("reaction_y", sheet.reaction_y);
  v.array("load_x", sheet.load_x);
  v.array("load_y", sheet.load_y);
  v.array("rest_length", sheet.rest_length);
  v.array("tension", sheet.tension);
}

template <typename Contacts, typename Visitor>
IfState<Contacts, SheetWallContacts> visit_fields(Contacts &c, Visitor &v)
{
  v.array("node", c.node);
  v.contact_states(c.state);
  v.array("force_x", c.force_x);
  v.array("force_y", c.force_y);
  v.array("elastic_normal_force", c.elastic_normal_force);
  v.array("friction_work", c.friction_work);
  v.array("viscous_work", c.viscous_work);
}

template <typename Contacts, typename Visitor>
IfState<Contacts, SheetContacts> visit_fields(Contacts &c, Visitor &v)
{
  v.group("contacts", [&](auto &in) {
    in.array("disc", c.disc);
    in.array("segment", c.segment);
    in.contact_states(c.state);
    in.array("position", c.position);
    in.array("overlap", c.overlap);
    in.array("counted", c.counted);
    in.array("force_x", c.force_x);
    in.array("force_y", c.force_y);
    in.array("elastic_normal_force", c.elastic_normal_force);
    in.array("friction_work", c.friction_work);
    in.array("viscous_work", c.viscous_work);
    in.array("node_x_at_rebuild", c.node_x_at_rebuild);
    in.array("node_y_at_rebuild", c.node_y_at_rebuild);
  });
  v.numbered_groups("wall_contacts", "wall", c.walls);
}

/// The file's root; its attributes format and format_version are the file's, not the state's
/// (checkpoint.cc).
template <typename State, typename Visitor>
IfState<State, DemSystemState> visit_fields(State &s, Visitor &v)
{
  v.attribute("time", s.time);
  v.attribute("time_step", s.time_step);
  v.attribute("skin", s.skin);
  v.attribute("radius_growth_since_rebuild", s.radius_growth_since_rebuild);
  v.group("particle_law", [&](auto &in) { visit_fields(s.particle_contact, in); });
  v.attribute("step_count", s.step_count);
  v.attribute("n_rebuilds", s.n_rebuilds);
  v.attribute("n_broken_bonds", s.n_broken_bonds);
  v.flag("rebuild_needed", s.rebuild_needed);
  v.group("energy", [&](auto &in) { visit_fields(s.accumulated, in); });
  v.group("particles", [&](auto &in) { visit_fields(s.particles, in); });
  v.group("pairs", [&](auto &in) { visit_fields(s.pairs, in); });
  v.numbered_groups("walls", "wall", s.walls);
  v.numbered_groups("wall_contacts", "wall", s.wall_contacts);
  v.group("verlet", [&](auto &in) {
    in.array("disc_x_at_rebuild", s.disc_x_at_rebuild);
    in.array("disc_y_at_rebuild", s.disc_y_at_rebuild);
    in.rows("wall_start_at_rebuild", s.wall_start_at_rebuild);
  });
  v.rows("wall_force_previous", s.wall_force_previous);
  v.group("damping", [&](auto &in) {
    in.array("fx", s.damping_fx);
    in.array("fy", s.damping_fy);
    in.array("torque", s.damping_torque);
  });
  // Version 1 had no sheets.
  v.sheets("sheets", "sheet", s.sheets, s.sheet_contacts, from_version(2));
}

/// The content of the group /command. Files written before the texts existed have none.
template <typename Command, typename Visitor>
IfState<Command, CommandState> visit_fields(Command &c, Visitor &v)
{
  v.text("name", c.name);
  v.keyed_arrays("reals", "real_keys", c.reals);
  v.keyed_arrays("counts", "count_keys", c.counts);
  v.keyed_texts("texts", "text_keys", c.texts);
}

// A field added to a stored structure must be added to its list above, or a resumed run silently
// differs from the straight one. These sizes (x86-64, libstdc++) make such a change fail to
// compile: add the field to its list (with a Presence if files without it exist, or raising
// checkpoint_format_version), then update the size here.
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(ContactState) == 24, "ContactState changed: update its list");
static_assert(sizeof(ContactParameters) == 56, "ContactParameters changed: update its list");
static_assert(sizeof(WallServo) == 40, "WallServo changed: update the list of Wall");
static_assert(sizeof(Wall) == 272, "Wall changed: update its list");
static_assert(sizeof(ParticleSet) == 22 * sizeof(std::vector<double>), "ParticleSet changed: update its list");
static_assert(sizeof(PairContacts) == 17 * sizeof(std::vector<double>) + sizeof(std::size_t),
              "PairContacts changed: update its list (the adjacency and chunk plan are derived, not stored)");
static_assert(sizeof(WallContacts) == 7 * sizeof(std::vector<double>), "WallContacts changed: update its list");
static_assert(sizeof(EnergyBudget) == 10 * sizeof(double), "EnergyBudget changed: update its list");
static_assert(sizeof(SheetParameters) == 4 * sizeof(double) + sizeof(ContactParameters),
              "SheetParameters changed: update the list of SheetHead");
static_assert(sizeof(SparSheet) == 17 * sizeof(std::vector<double>) + sizeof(std::string) + sizeof(SheetParameters) +
                                     sizeof(LinearContactLaw),
              "SparSheet changed: update its list (or SheetHead's)");
static_assert(sizeof(SheetContacts) == 14 * sizeof(std::vector<double>), "SheetContacts changed: update its list");
static_assert(sizeof(SheetWallContacts) == 7 * sizeof(std::vector<double>),
              "SheetWallContacts changed: update its list");
static_assert(sizeof(DemSystemState) == 1408, "DemSystemState changed: update its list");
static_assert(sizeof(CommandState) == sizeof(std::string) + 2 * sizeof(std::map<std::string, std::vector<double>>) +
                                        sizeof(std::map<std::string, std::string>),
              "CommandState changed: update its list");
#endif
} // namespace geohybrid::dem::checkpoint_fields
