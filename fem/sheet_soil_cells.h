#pragma once
// Where a sheet's nodes are in the soil mesh, for both solvers' interfaces: the active cell that
// holds a point of the sheet, the point's coordinates in it, and the soil's normal stress there.
// A point on a cell edge or vertex touches several cells; the one taken is the one with the
// smallest CellId, whatever the partition, and its owner computes the node's interface, so that
// results do not depend on the number of ranks.
// - Small slip (the implicit solver, implicit_sheet.h): locate_sheet_in_soil, once, by deal.II's
//   search round each node.
// - Large slip (the explicit solver, sheet_interface.h): find_sheet_cell from the coarse cells,
//   which every rank has whole, then walk_to_sheet_cell from the point's last cell to its
//   neighbours as it slides, every step and without allocation.
#include "fem/constitutive/plane_strain_tensors.h"
#include "fem/displacement_space.h"
#include "fem/material_point_history.h"
#include "fem/truss_sheet.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace geohybrid::fem
{
/// Where a sheet node sits in the soil, on the rank that computes its interface: the soil cell,
/// the soil's shape functions there, and the cell's DoFs (small slip: the implicit solver,
/// implicit_sheet.h).
struct SheetSoilPoint
{
  bool owned = false; ///< this rank computes the node's interface
  dealii::DoFHandler<dim>::active_cell_iterator cell;
  std::vector<double> shape_values;                       ///< N_i(X_k) of the cell's DoFs
  std::vector<unsigned int> components;                   ///< the component of each cell DoF
  std::vector<dealii::types::global_dof_index> dof_indices;
};

/// Locates every node of `sheet` in `space`'s mesh: the cell with the smallest CellId round it.
/// Throws std::invalid_argument naming `where` if a node lies outside the mesh. Collective.
std::vector<SheetSoilPoint> locate_sheet_in_soil(const DisplacementSpace &space, const TrussSheet &sheet,
                                                 const std::string &where);

/// The mean of the soil's normal stress n.sigma.n over `points` (pointers to a cell's material
/// points), from their committed stresses (tension positive) [Pa].
template <typename MaterialPoints>
double mean_normal_stress(const MaterialPoints &points, const dealii::Tensor<1, dim> &normal)
{
  double sigma_nn = 0.0;
  for (const auto &point : points)
    sigma_nn += normal * (in_plane_part(point->stress) * normal);
  return sigma_nn / points.size();
}

/// The soil's normal stress n.sigma.n on the sheet's plane at a node: the mean over the committed
/// stresses of the quadrature points of its cell (tension positive) [Pa].
double sheet_normal_stress(MaterialPointHistory &material_points, const SheetSoilPoint &point,
                           const dealii::Tensor<1, dim> &normal);

/// The error for sheet node `k`, at `node`, outside the soil mesh, naming `where`.
std::invalid_argument sheet_node_outside_mesh(const std::string &where, std::size_t k, const dealii::Point<dim> &node);

/// A cell of the soil mesh on any level: a sliding point's walk starts from a coarse cell.
using SheetSoilCell = dealii::DoFHandler<dim>::cell_iterator;

/// From `cell` (any level; a point's last cell, or a coarse cell), the active cell holding `p`,
/// and `unit` its coordinates there: down into the children that hold it, and across the face
/// beyond which it lies. False if the walk leaves the mesh or takes more than `max_moves` cells.
bool walk_to_sheet_cell(const dealii::Mapping<dim> &mapping, SheetSoilCell &cell, const dealii::Point<dim> &p,
                        dealii::Point<dim> &unit, unsigned int max_moves);

/// The active cell that holds p with the smallest CellId, from `cell` which holds it (at `unit`,
/// updated): a point on an edge or a vertex touches several cells, and the choice must not depend
/// on the partition. The cells are found across the faces p lies on, from cell to cell.
SheetSoilCell smallest_id_sheet_cell(const dealii::Mapping<dim> &mapping, const SheetSoilCell &cell,
                                     const dealii::Point<dim> &p, dealii::Point<dim> &unit);

/// The active cell holding p with the smallest CellId, and p's unit coordinates there, searched
/// from the coarse cells (every rank has the whole coarse mesh, so every rank finds the same);
/// false if p is outside the mesh.
bool find_sheet_cell(const DisplacementSpace &space, const dealii::Point<dim> &p, SheetSoilCell &cell,
                     dealii::Point<dim> &unit);
} // namespace geohybrid::fem
