#include "sheet_soil_cells.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <array>
#include <limits>
#include <sstream>

namespace geohybrid::fem
{
std::vector<SheetSoilPoint> locate_sheet_in_soil(const DisplacementSpace &space, const TrussSheet &sheet,
                                                 const std::string &where)
{
  const std::size_t n = sheet.n_nodes();
  std::vector<SheetSoilPoint> soil_points;
  // A node on a cell edge or vertex touches several cells, and the soil stress (sigma_nn) is that
  // of one of them: the one with the smallest CellId, whatever the partition, so that the result
  // does not depend on the number of ranks. A rank that owns one of those cells also sees all the
  // others (owned or ghost), so every such rank picks the same cell; its owner takes the node.
  const MPI_Comm comm = space.communicator();
  const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const auto &fe = space.fe();
  soil_points.resize(n);
  std::vector<unsigned int> owner(n, n_ranks);
  std::vector<dealii::Point<dim>> reference_points(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      std::vector<std::pair<dealii::DoFHandler<dim>::active_cell_iterator, dealii::Point<dim>>> around;
      try
        {
          around = dealii::GridTools::find_all_active_cells_around_point(space.mapping(), space.dof_handler(),
                                                                          sheet.node(k), 1e-10);
        }
      catch (...)
        {
          // Not in a cell this rank knows: another rank's node, or outside the mesh.
        }
      bool touches_own_cell = false;
      for (const auto &c : around)
        touches_own_cell = touches_own_cell || c.first->is_locally_owned();
      if (!touches_own_cell)
        continue;
      const std::pair<dealii::DoFHandler<dim>::active_cell_iterator, dealii::Point<dim>> *chosen = nullptr;
      for (const auto &c : around)
        if (!c.first->is_artificial() && (chosen == nullptr || c.first->id() < chosen->first->id()))
          chosen = &c;
      if (chosen->first->is_locally_owned())
        {
          owner[k] = rank;
          soil_points[k].cell = chosen->first;
          reference_points[k] = dealii::GeometryInfo<dim>::project_to_unit_cell(chosen->second);
        }
    }
  dealii::Utilities::MPI::min(owner, comm, owner);
  for (std::size_t k = 0; k < n; ++k)
    {
      if (owner[k] == n_ranks)
        throw sheet_node_outside_mesh(where, k, sheet.node(k));
      auto &p = soil_points[k];
      p.owned = owner[k] == rank;
      if (!p.owned)
        continue;
      const unsigned int n_dofs = fe.n_dofs_per_cell();
      p.shape_values.resize(n_dofs);
      p.components.resize(n_dofs);
      p.dof_indices.resize(n_dofs);
      p.cell->get_dof_indices(p.dof_indices);
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          p.components[i] = fe.system_to_component_index(i).first;
          p.shape_values[i] = fe.shape_value(i, reference_points[k]);
        }
    }
  return soil_points;
}

double sheet_normal_stress(MaterialPointHistory &material_points, const SheetSoilPoint &point,
                           const dealii::Tensor<1, dim> &normal)
{
  return mean_normal_stress(material_points.at(point.cell), normal);
}

std::invalid_argument sheet_node_outside_mesh(const std::string &where, std::size_t k, const dealii::Point<dim> &node)
{
  std::ostringstream message;
  message << where << ": node " << k << " at (" << node[0] << ", " << node[1] << ") m lies outside the soil mesh";
  return std::invalid_argument(message.str());
}

namespace
{
/// A point within this distance of a unit cell's side, in unit coordinates, is on it (the
/// tolerance of GridTools::find_all_active_cells_around_point in locate_sheet_in_soil).
constexpr double sheet_cell_tolerance = 1e-10;

/// The coordinates of `p` in the unit cell of `cell`: in closed form on a parallelogram (the
/// generated tanks and the structured blocks of meshes/), by the mapping's inverse otherwise.
/// False if the inverse fails (a point far outside a distorted cell).
bool sheet_unit_point(const dealii::Mapping<dim> &mapping, const SheetSoilCell &cell, const dealii::Point<dim> &p,
                      dealii::Point<dim> &unit)
{
  const dealii::Point<dim> v0 = cell->vertex(0);
  const dealii::Tensor<1, dim> a = cell->vertex(1) - v0, b = cell->vertex(2) - v0;
  const dealii::Tensor<1, dim> warp = cell->vertex(3) - cell->vertex(1) - b;
  if (warp.norm() <= 1e-12 * (a.norm() + b.norm()))
    {
      const dealii::Tensor<1, dim> d = p - v0;
      const double det = a[0] * b[1] - a[1] * b[0];
      unit = dealii::Point<dim>((d[0] * b[1] - d[1] * b[0]) / det, (a[0] * d[1] - a[1] * d[0]) / det);
      return true;
    }
  try
    {
      unit = mapping.transform_real_to_unit_cell(cell, p);
      return true;
    }
  catch (...)
    {
      return false;
    }
}

bool sheet_unit_point_inside(const dealii::Point<dim> &unit)
{
  for (unsigned int d = 0; d < dim; ++d)
    if (unit[d] < -sheet_cell_tolerance || unit[d] > 1.0 + sheet_cell_tolerance)
      return false;
  return true;
}

/// The cells around a point on cell edges, with no allocation: at most a handful.
struct SheetCellsAround
{
  std::array<SheetSoilCell, 16> cells;
  std::array<dealii::Point<dim>, 16> units;
  unsigned int n = 0;
  void add(const SheetSoilCell &cell, const dealii::Point<dim> &unit)
  {
    for (unsigned int i = 0; i < n; ++i)
      if (cells[i] == cell)
        return;
    if (n < cells.size())
      cells[n] = cell, units[n++] = unit;
  }
};

/// Adds the active cells of `cell` (itself or its descendants) that hold p.
void add_active_sheet_cells(const dealii::Mapping<dim> &mapping, const SheetSoilCell &cell, const dealii::Point<dim> &p,
                            SheetCellsAround &around)
{
  dealii::Point<dim> unit;
  if (!sheet_unit_point(mapping, cell, p, unit) || !sheet_unit_point_inside(unit))
    return;
  if (cell->is_active())
    around.add(cell, unit);
  else
    for (unsigned int c = 0; c < cell->n_children(); ++c)
      add_active_sheet_cells(mapping, cell->child(c), p, around);
}
} // namespace

bool walk_to_sheet_cell(const dealii::Mapping<dim> &mapping, SheetSoilCell &cell, const dealii::Point<dim> &p,
                        dealii::Point<dim> &unit, unsigned int max_moves)
{
  for (unsigned int move = 0; move <= max_moves; ++move)
    {
      const bool mapped = sheet_unit_point(mapping, cell, p, unit);
      if (mapped && sheet_unit_point_inside(unit))
        {
          if (cell->is_active())
            return true;
          // The child holding p, or else the one whose centre is nearest (the walk goes on from it).
          SheetSoilCell next = cell->child(0);
          double nearest = std::numeric_limits<double>::max();
          for (unsigned int c = 0; c < cell->n_children(); ++c)
            {
              dealii::Point<dim> child_unit;
              if (sheet_unit_point(mapping, cell->child(c), p, child_unit) && sheet_unit_point_inside(child_unit))
                {
                  next = cell->child(c);
                  break;
                }
              const double distance = cell->child(c)->center().distance(p);
              if (distance < nearest)
                {
                  nearest = distance;
                  next = cell->child(c);
                }
            }
          cell = next;
          continue;
        }
      // Across the face p lies farthest beyond (faces 2d and 2d + 1 are unit[d] = 0 and 1), or,
      // without unit coordinates, the face nearest to p.
      unsigned int face = 0;
      if (mapped)
        {
          double beyond = 0.0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              if (-unit[d] > beyond)
                beyond = -unit[d], face = 2 * d;
              if (unit[d] - 1.0 > beyond)
                beyond = unit[d] - 1.0, face = 2 * d + 1;
            }
        }
      else
        {
          double nearest = std::numeric_limits<double>::max();
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->center().distance(p) < nearest)
              nearest = cell->face(f)->center().distance(p), face = f;
        }
      if (cell->at_boundary(face))
        return false;
      cell = cell->neighbor(face);
    }
  return false;
}

SheetSoilCell smallest_id_sheet_cell(const dealii::Mapping<dim> &mapping, const SheetSoilCell &cell,
                                     const dealii::Point<dim> &p, dealii::Point<dim> &unit)
{
  const auto on_side = [](const dealii::Point<dim> &u, unsigned int face) {
    const double coordinate = u[face / 2];
    return face % 2 == 0 ? coordinate <= sheet_cell_tolerance : coordinate >= 1.0 - sheet_cell_tolerance;
  };
  bool on_an_edge = false;
  for (unsigned int f = 0; f < 2 * dim; ++f)
    on_an_edge = on_an_edge || on_side(unit, f);
  if (!on_an_edge)
    return cell;
  SheetCellsAround around;
  around.add(cell, unit);
  for (unsigned int i = 0; i < around.n; ++i)
    for (unsigned int f = 0; f < 2 * dim; ++f)
      if (on_side(around.units[i], f) && !around.cells[i]->at_boundary(f))
        add_active_sheet_cells(mapping, around.cells[i]->neighbor(f), p, around);
  unsigned int chosen = 0;
  for (unsigned int i = 1; i < around.n; ++i)
    if (around.cells[i]->id() < around.cells[chosen]->id())
      chosen = i;
  unit = around.units[chosen];
  return around.cells[chosen];
}

bool find_sheet_cell(const DisplacementSpace &space, const dealii::Point<dim> &p, SheetSoilCell &cell,
                     dealii::Point<dim> &unit)
{
  const auto &dofs = space.dof_handler();
  for (auto coarse = dofs.begin(0); coarse != dofs.end(0); ++coarse)
    {
      if (!sheet_unit_point(space.mapping(), coarse, p, unit) || !sheet_unit_point_inside(unit))
        continue;
      cell = coarse;
      if (walk_to_sheet_cell(space.mapping(), cell, p, unit, 8))
        {
          cell = smallest_id_sheet_cell(space.mapping(), cell, p, unit);
          return true;
        }
    }
  return false;
}
} // namespace geohybrid::fem
