#pragma once
// Contacts of a spar sheet (spar_sheet.h) with discs and with walls.
//
// Disc-segment contacts. A disc of radius r touches segment k (nodes a = k, b = k + 1) as a
// capsule of radius r + t/2: with s the parameter of the point of the segment closest to the
// disc centre c (s in [0, 1]), the overlap is r + t/2 - |c - (a + s (b - a))|. The normal n
// points from the disc centre to that point (the sheet is the "j" side, as a wall:
// conventions.h), and the interface law (a LinearContactLaw: normal spring, shear spring,
// Mohr-Coulomb slider tau <= a_s + sigma_n tan(delta)) gives the force on the disc,
// -Fn n + Ft t. The opposite force acts on the sheet at that point and is shared by the two
// nodes with weights (1 - s, s), which keeps its resultant and its moment about the contact
// point; the disc also gets the moment of the force about its body's centre.
//
// One contact per touching, not two, at a node. A disc near node b sees both segments k and
// k + 1. The node rule counts a contact whose closest point is clamped at a node shared with
// another segment only at a convex vertex (the disc's projection on both segments clamps at
// the shared node), and then only for the lower-index segment; a disc whose projection falls
// inside the adjacent segment is that segment's contact. On a straight or convex chain a disc
// therefore has exactly one contact near a node. On the concave side of a bend a disc can overlap
// both segments with interior projections: at a corner (the segments turn by more than 10 degrees,
// e.g. the inside of a wrap-around) both contacts count, as the disc touches two faces; at a
// nearly straight joint (a sheet kinked slightly by the grains) it presses one face, so only the
// deeper of the two counts and ownership passes where their overlaps are equal (no jump in
// force, no double force while a grain crosses the kink). The free ends of the sheet are the
// capsule's round ends.
//
// Friction across nodes. When a disc moves from segment k to k + 1, the contact on k + 1 starts
// with the tangential force (and bond, dashpot state) of the contact on k that the node rule has
// just switched off, so the interface friction is not reset each time a grain crosses a node.
// A counted contact that is switched off without such a hand-over (rare: the adjacent contact
// already touched) releases its springs' energy, booked as friction work so that the energy
// balance closes (as LinearContactLaw does when a contact opens).
//
// Contacts are candidates found at neighbour-list rebuilds (discs within r + t/2 + skin of the
// segment, through the cell grid of NeighbourSearch), kept sorted by (disc, segment), so a
// disc's candidates are consecutive, history is carried over by a merge, and every loop runs in
// one fixed order: results do not depend on the number of threads.
//
// Node-wall contacts: each node is a disc of radius t/2 against each wall, with the wall's law.
#include "contact_list.h"
#include "spar_sheet.h"
#include "wall.h"

#include <cstdint>
#include <vector>

namespace geohybrid::dem
{
/// Nodes of one sheet near one wall, with their contact history (as WallContacts for discs).
struct SheetWallContacts
{
  SoaVector<std::uint32_t> node;
  SoaVector<ContactState> state;
  SoaVector<double> force_x, force_y;             ///< force on the node [N/m]
  SoaVector<double> elastic_normal_force;         ///< [N/m]
  SoaVector<double> friction_work, viscous_work;  ///< of the last step [J/m]

  std::size_t size() const { return node.size(); }
  void resize_results();
};

/// The contacts of one sheet: candidate disc-segment pairs and node-wall pairs.
struct SheetContacts
{
  SoaVector<std::uint32_t> disc, segment;  ///< sorted by (disc, segment)
  SoaVector<ContactState> state;

  // Results of the last evaluation.
  SoaVector<double> position;              ///< s of the closest point on the segment, in [0, 1]
  SoaVector<double> overlap;               ///< r + t/2 - distance [m]
  SoaVector<std::uint8_t> counted;         ///< 1 if the node rule counts the contact
  SoaVector<double> force_x, force_y;      ///< force on the disc [N/m]
  SoaVector<double> elastic_normal_force;  ///< kn * overlap (0 when apart) [N/m]
  SoaVector<double> friction_work, viscous_work; ///< of the last step [J/m]

  std::vector<SheetWallContacts> walls;    ///< one per wall of the system
  /// Node positions at the last rebuild, to tell when the candidates are stale [m].
  SoaVector<double> node_x_at_rebuild, node_y_at_rebuild;

  std::size_t size() const { return disc.size(); }
  void resize_results();
};

/// Energy and events of one evaluation, for DemSystem's books.
struct SheetContactWork
{
  double friction = 0.0;              ///< slip work and released spring energy [J/m]
  double viscous = 0.0;               ///< dashpot work [J/m]
  std::uint64_t broken_bonds = 0;
};

/// Builds the candidate lists after NeighbourSearch::rebuild_pairs(); owns its scratch arrays so
/// that a rebuild does not allocate once they have grown.
class SheetContactSearch
{
public:
  /// Rebuilds `contacts` for `sheet` (keeping the history of pairs present before): discs within
  /// r + t/2 + skin of a segment, nodes within t/2 + skin of a wall.
  void rebuild(const ParticleSet &particles, const NeighbourSearch &search, const SparSheet &sheet,
               const std::vector<Wall> &walls, double skin, SheetContacts &contacts);

private:
  std::vector<std::uint32_t> near_;
  std::vector<std::uint64_t> keys_;
  SheetContacts previous_;
  SheetWallContacts previous_wall_;
};

/// Largest displacement of a node of `sheet` since the last rebuild of `contacts` [m].
double largest_node_move(const SparSheet &sheet, const SheetContacts &contacts);

/// Evaluates every disc-segment contact of `sheet`: adds the forces and moments to the bodies'
/// fx, fy, torque and the reactions to the nodes' fx, fy, in list order.
SheetContactWork evaluate_sheet_contacts(ParticleSet &particles, SparSheet &sheet, SheetContacts &contacts,
                                         double dt, bool track_energy);

/// Result of the node-wall contacts of one sheet with one wall.
struct SheetWallLoad
{
  Vec2 force_on_wall = Vec2::Zero(); ///< resultant the nodes apply to the wall [N/m]
  std::size_t n_touching = 0;
  SheetContactWork work;
};

/// Evaluates the node-wall contacts of `sheet` with `wall`: adds the forces to the nodes.
SheetWallLoad evaluate_sheet_wall_contacts(SparSheet &sheet, const Wall &wall, SheetWallContacts &contacts,
                                           double dt);

/// The point of segment k of `sheet` at parameter s.
inline Vec2 point_on_segment(const SparSheet &sheet, std::size_t k, double s)
{
  return Vec2((1.0 - s) * sheet.x[k] + s * sheet.x[k + 1], (1.0 - s) * sheet.y[k] + s * sheet.y[k + 1]);
}
} // namespace geohybrid::dem
