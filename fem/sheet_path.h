#pragma once
// The reference path of a sheet: the polyline through its nodes as laid, with the arc length s
// from node 0 (the clamp) as coordinate. The explicit solver's interface (sheet_interface.h) keeps
// for each node the point of this path that the node has slid to, so that a node that slides round
// a corner of a wrap-around is compared with the soil of the part it has reached, along that part's
// direction, and not with the soil of its starting point.
//
// Each segment has its own tangent (the direction of increasing s) and normal n = (-t_y, t_x); at
// a vertex the segment a point is on is the one it came from (segment_of keeps the last segment
// while s lies on its closed range), so a node resting on a corner does not flip between two
// frames. Beyond the ends the path goes on straight along its end segments (the clamp, pulled out
// through the front wall, stays on the extension of the first segment).
#include "fem/conventions.h"

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <vector>

namespace geohybrid::fem
{
class SheetPath
{
public:
  using Vector = dealii::Tensor<1, dim>;

  /// The polyline through `vertices` (at least two, consecutive ones distinct: TrussSheet checks).
  explicit SheetPath(const std::vector<dealii::Point<dim>> &vertices) : vertices_(vertices)
  {
    arc_lengths_.push_back(0.0);
    for (std::size_t j = 0; j + 1 < vertices_.size(); ++j)
      {
        const Vector d = vertices_[j + 1] - vertices_[j];
        tangents_.push_back(d / d.norm());
        arc_lengths_.push_back(arc_lengths_.back() + d.norm());
      }
  }

  double switch_tolerance() const { return 1e-9 * length(); } ///< see nearest_point [m]
  unsigned int n_segments() const { return static_cast<unsigned int>(tangents_.size()); }
  double length() const { return arc_lengths_.back(); } ///< [m]
  double vertex_arc_length(std::size_t j) const { return arc_lengths_[j]; } ///< [m]

  /// The segment holding s, searched from `segment` (the one the point was on): it changes only
  /// when s leaves that segment's closed range; s before the start gives segment 0, past the end
  /// the last one.
  unsigned int segment_of(double s, unsigned int segment) const
  {
    while (segment > 0 && s < arc_lengths_[segment])
      --segment;
    while (segment + 1 < n_segments() && s > arc_lengths_[segment + 1])
      ++segment;
    return segment;
  }

  struct Location
  {
    double arc_length = 0.0; ///< s [m]
    unsigned int segment = 0;
  };

  /// The point of the path nearest to `x`, searched from `segment` (where the point was) into
  /// its neighbours for as long as they come nearer. On the inside of a corner, where a point has
  /// a foot on both parts, this takes the part it is nearer to (a node that the tension pulls
  /// round the corner, cutting it, moves to the part it is reaching when it crosses the
  /// bisector); on the outside, the corner itself. Beyond the ends the path goes on straight.
  /// A neighbour must be nearer by `switch_tolerance` (1e-9 of the path's length): a node resting
  /// on a vertex between two segments of different directions would otherwise take one or the
  /// other on the round-off of its displacement, and with it a tangent and normal that differ by
  /// the corner's angle (the 1- and 2-rank runs of an undamped wrap-around parted at once).
  Location nearest_point(const dealii::Point<dim> &x, unsigned int segment) const
  {
    const auto foot = [&](unsigned int j, double &distance) {
      double along = (x - vertices_[j]) * tangents_[j];
      if (j > 0)
        along = std::max(along, 0.0);
      if (j + 1 < n_segments())
        along = std::min(along, arc_lengths_[j + 1] - arc_lengths_[j]);
      distance = (x - (vertices_[j] + along * tangents_[j])).norm();
      return arc_lengths_[j] + along;
    };
    double nearest = 0.0, distance = 0.0;
    Location best{foot(segment, nearest), segment};
    for (unsigned int j = segment; j > 0;)
      {
        const double s = foot(--j, distance);
        if (!(distance < nearest - switch_tolerance()))
          break;
        nearest = distance, best = {s, j};
      }
    if (best.segment == segment)
      for (unsigned int j = segment + 1; j < n_segments(); ++j)
        {
          const double s = foot(j, distance);
          if (!(distance < nearest - switch_tolerance()))
            break;
          nearest = distance, best = {s, j};
        }
    return best;
  }

  /// The point at arc length s on `segment` (straight on beyond the segment's ends) [m].
  dealii::Point<dim> point(double s, unsigned int segment) const
  {
    return vertices_[segment] + (s - arc_lengths_[segment]) * tangents_[segment];
  }
  /// s held to [0, length]: where the soil is, for a point beyond the path's ends [m].
  double clamped(double s) const { return std::clamp(s, 0.0, length()); }

  const Vector &tangent(unsigned int segment) const { return tangents_[segment]; }
  Vector normal(unsigned int segment) const
  {
    const Vector &t = tangents_[segment];
    return Vector({-t[1], t[0]});
  }

private:
  std::vector<dealii::Point<dim>> vertices_;
  std::vector<Vector> tangents_;
  std::vector<double> arc_lengths_;
};
} // namespace geohybrid::fem
