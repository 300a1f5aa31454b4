#include "band_points.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <sstream>
#include <stdexcept>

namespace geohybrid::coupling
{
BandPoints::BandPoints(const fem::DisplacementSpace &space, const Vector &layout, const std::vector<dem::Vec2> &points)
  : space_(space), layout_(layout)
{
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
          std::ostringstream message;
          message << "band points: the particle at (" << point[0] << ", " << point[1]
                  << ") m lies outside the continuum's mesh: the overlap band must lie inside the mesh";
          throw std::invalid_argument(message.str());
        }
      found.first->get_dof_indices(dof_indices);
      // Snap the reference point into the unit cell (round-off on a cell's edge).
      dealii::Point<fem::dim> reference = dealii::GeometryInfo<fem::dim>::project_to_unit_cell(found.second);
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
