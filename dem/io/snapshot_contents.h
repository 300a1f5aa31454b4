#pragma once
// What one snapshot holds besides the discs, gathered from a DemSystem before the file is opened
// (snapshot_writer.h gives the layout): the lines of the three contact networks and the sheets'
// nodes and segments. Helpers of SnapshotWriter, not part of its interface.
#include "dem/dem_system.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace geohybrid::dem::snapshot_detail
{
/// Lines of a contact network: two points per line and the values attached to each line.
struct ContactLines
{
  std::vector<double> points;                 // 2m x 3
  std::vector<std::int64_t> connectivity;     // m x 2
  std::vector<double> normal_force, tangential_force, force_magnitude;
  std::vector<std::int32_t> bonded, wall_index;

  std::size_t size() const { return normal_force.size(); }

  void add(const Vec2 &a, const Vec2 &b, double fn, double ft, double fx, double fy, bool is_bonded)
  {
    const auto first = static_cast<std::int64_t>(points.size() / 3);
    points.insert(points.end(), {a.x(), a.y(), 0.0, b.x(), b.y(), 0.0});
    connectivity.insert(connectivity.end(), {first, first + 1});
    normal_force.push_back(fn);
    tangential_force.push_back(ft);
    force_magnitude.push_back(std::hypot(fx, fy));
    bonded.push_back(is_bonded ? 1 : 0);
  }
};

/// Touching pair contacts: lines from disc i to disc j.
ContactLines pair_lines(const DemSystem &system);
/// Touching disc-wall contacts: lines from the disc centre to the closest point of the wall;
/// wall_index holds the wall's index.
ContactLines wall_lines(const DemSystem &system);
/// Disc-sheet contacts: lines from the disc centre to the contact's point on the sheet's centre
/// line; wall_index holds the sheet's index.
ContactLines sheet_contact_lines(const DemSystem &system);

/// Every sheet's nodes and segments, concatenated.
struct SheetGeometry
{
  std::vector<double> position, velocity;     // nodes x 3
  std::vector<std::int32_t> sheet_index;      // per node
  std::vector<std::int64_t> connectivity;     // segments x 2, into the nodes
  std::vector<double> tension, strain;        // per segment

  std::size_t n_nodes() const { return sheet_index.size(); }
  std::size_t n_segments() const { return tension.size(); }
};

/// The system's sheets, in the order of DemSystem::sheets().
SheetGeometry sheet_geometry(const DemSystem &system);
} // namespace geohybrid::dem::snapshot_detail
