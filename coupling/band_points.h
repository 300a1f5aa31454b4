#pragma once
// Where the particles of the overlap band sit in the continuum's mesh: for each point, the cell
// holding it and the values there of the cell's scalar shape functions, with the local indices of
// the x and y DoFs they weigh. The bridging operators then read a short flat list per step (the
// interpolated displacement or velocity at a particle, and the spreading of a particle's force
// to the nodes, N_I(X_p) f_p) without searching the mesh or allocating.
//
// A point a little outside the mesh (within `extrapolation_distance` of its nearest cell) is
// tied to that cell's shape functions extrapolated: the particles just outside the band's
// particle-side edge, whose contacts reach into the band, must be tied too (see band_particles.h).
//
// Points are located once, in the reference configuration: the bridging domain method ties a
// particle to the continuum's field at its material point (small strain in the band), so the
// interpolation does not change during a run. locate() may be called again (it allocates) if the
// band's particles ever change.
//
// One MPI rank only for now: the local indices are those of the rank's ghosted vectors, and a
// particle near a partition boundary would need its cell's owner to add its forces.
#include "dem/conventions.h"
#include "fem/displacement_space.h"

#include <deal.II/lac/la_parallel_vector.h>

#include <vector>

namespace geohybrid::coupling
{
class BandPoints
{
public:
  using Vector = dealii::LinearAlgebra::distributed::Vector<double>;

  /// Locates `points` [m] in `space`'s mesh; `layout` is a vector of the solver (its partitioner
  /// gives the local indices). Throws std::invalid_argument naming the point if one lies farther
  /// than `extrapolation_distance` [m] outside the mesh (the band must lie inside the continuum),
  /// or if the space is distributed over more than one MPI rank.
  BandPoints(const fem::DisplacementSpace &space, const Vector &layout, const std::vector<dem::Vec2> &points,
             double extrapolation_distance = 0.0);
  void locate(const std::vector<dem::Vec2> &points);

  std::size_t size() const { return n_points_; }
  unsigned int nodes_per_point() const { return nodes_per_point_; }

  /// The field `u` (x or y component) interpolated at point p: sum_k N_k(X_p) u_k.
  dem::Vec2 interpolate(const Vector &u, std::size_t p) const
  {
    dem::Vec2 value(0.0, 0.0);
    const std::size_t begin = p * nodes_per_point_;
    for (std::size_t k = begin; k < begin + nodes_per_point_; ++k)
      {
        value.x() += shape_value_[k] * u.local_element(x_dof_[k]);
        value.y() += shape_value_[k] * u.local_element(y_dof_[k]);
      }
    return value;
  }
  /// Entry k of point p (k < nodes_per_point()): local indices of the node's x and y DoFs and N_k(X_p).
  unsigned int x_dof(std::size_t p, unsigned int k) const { return x_dof_[p * nodes_per_point_ + k]; }
  unsigned int y_dof(std::size_t p, unsigned int k) const { return y_dof_[p * nodes_per_point_ + k]; }
  double shape_value(std::size_t p, unsigned int k) const { return shape_value_[p * nodes_per_point_ + k]; }

private:
  const fem::DisplacementSpace &space_;
  const Vector &layout_;
  double extrapolation_distance_ = 0.0;
  std::size_t n_points_ = 0;
  unsigned int nodes_per_point_ = 0;
  std::vector<unsigned int> x_dof_, y_dof_;
  std::vector<double> shape_value_;
};
} // namespace geohybrid::coupling
