#include "band_points.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geohybrid::coupling
{
BandPoints::BandPoints(const fem::DisplacementSpace &space, const Vector &layout, const std::vector<dem::Vec2> &points,
                       double extrapolation_distance)
  : space_(space), layout_(layout), extrapolation_distance_(extrapolation_distance)
{
  if (!(extrapolation_distance >= 0.0))
    throw std::invalid_argument("band points: the extrapolation distance must not be negative");
  if (dealii::Utilities::MPI::n_mpi_processes(space.communicator()) != 1)
    throw std::invalid_argument("band points: the coupling runs on one MPI rank only (for now)");
  locate(points);
}

void BandPoints::locate(const std::vector<dem::Vec2> &points)
{
  const auto &fe = space_.fe();
  const unsigned int n_dofs = fe.n_dofs_per_cell();
  nodes_per_point_ = fe.base_element(0).n_dofs_per_cell();
  n_points_ = points.size();
  x_dof_.assign(n_points_ * nodes_per_point_, 0);
  y_dof_.assign(n_points_ * nodes_per_point_, 0);
  shape_value_.assign(n_points_ * nodes_per_point_, 0.0);
  const auto &partitioner = *layout_.get_partitioner();
  std::vector<dealii::types::global_dof_index> dof_indices(n_dofs);
  for (std::size_t p = 0; p < n_points_; ++p)
    {
      const dealii::Point<fem::dim> point(points[p].x(), points[p].y());
      std::pair<dealii::DoFHandler<fem::dim>::active_cell_iterator, dealii::Point<fem::dim>> found;
      try
        {
          found = dealii::GridTools::find_active_cell_around_point(space_.mapping(), space_.dof_handler(), point);
        }
      catch (...)
        {
          found.first = space_.dof_handler().end();
        }
      if (found.first == space_.dof_handler().end() || found.first->state() != dealii::IteratorState::valid)
        {
          // Outside the mesh: the nearest cell (by the distance to its bounding box), if near enough.
          double nearest = std::numeric_limits<double>::max();
          for (const auto &cell : space_.dof_handler().active_cell_iterators())
            {
              const auto box = cell->bounding_box();
              double distance2 = 0.0;
              for (unsigned int c = 0; c < fem::dim; ++c)
                {
                  const double outside = std::max({box.lower_bound(c) - point[c], point[c] - box.upper_bound(c), 0.0});
                  distance2 += outside * outside;
                }
              if (distance2 < nearest)
                {
                  nearest = distance2;
                  found.first = cell;
                }
            }
          if (std::sqrt(nearest) <= extrapolation_distance_)
            found.second = space_.mapping().transform_real_to_unit_cell(found.first, point);
          else
            found.first = space_.dof_handler().end();
        }
      const bool inside = found.first != space_.dof_handler().end();
      if (!inside)
        {
          std::ostringstream message;
          message << "band points: the particle at (" << point[0] << ", " << point[1]
                  << ") m lies outside the continuum's mesh: the overlap band must lie inside the mesh";
          throw std::invalid_argument(message.str());
        }
      found.first->get_dof_indices(dof_indices);
      // Inside, snap the reference point into the unit cell (round-off on a cell's edge); outside,
      // extrapolate.
      const bool in_cell = dealii::GeometryInfo<fem::dim>::is_inside_unit_cell(found.second, 1e-10);
      const dealii::Point<fem::dim> reference =
        in_cell ? dealii::GeometryInfo<fem::dim>::project_to_unit_cell(found.second) : found.second;
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          const auto [component, scalar] = fe.system_to_component_index(i);
          const std::size_t k = p * nodes_per_point_ + scalar;
          const unsigned int local = partitioner.global_to_local(dof_indices[i]);
          if (component == 0)
            {
              x_dof_[k] = local;
              shape_value_[k] = fe.shape_value_component(i, reference, 0);
            }
          else
            y_dof_[k] = local;
        }
    }
}
} // namespace geohybrid::coupling
