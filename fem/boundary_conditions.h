#pragma once
// What holds and loads the soil's boundary, as deal.II Functions of position and pseudo-time t
// (the solver calls Function::set_time on them, so a Function shared with the caller sees the
// solver's time), so that one description serves any loading programme: a prescribed
// displacement on some components, a traction vector, or a pressure normal to the boundary.
// Boundaries are named by the mesh's boundary ids (GridGenerator's colorize, or gmsh physical
// lines).
#include "fem/conventions.h"

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <string>
#include <vector>

namespace geohybrid::fem
{
/// u_i = g_i(x, t) for the constrained components i; g == nullptr means g = 0 (a support).
struct DisplacementBoundary
{
  dealii::types::boundary_id boundary_id;
  bool constrain_x = true;
  bool constrain_y = true;
  std::shared_ptr<dealii::Function<dim>> displacement; ///< 2 components [m], or nullptr for 0
};

/// A traction t(x, t): force per unit area of the (undeformed, small-strain) boundary [Pa].
struct TractionBoundary
{
  dealii::types::boundary_id boundary_id;
  std::shared_ptr<dealii::Function<dim>> traction; ///< 2 components [Pa]
};

/// A pressure p(x, t) pushing on the boundary: traction -p n, n the outward unit normal [Pa].
struct PressureBoundary
{
  dealii::types::boundary_id boundary_id;
  std::shared_ptr<dealii::Function<dim>> pressure; ///< 1 component [Pa]
};

struct BoundaryConditions
{
  std::vector<DisplacementBoundary> displacements;
  std::vector<TractionBoundary> tractions;
  std::vector<PressureBoundary> pressures;

  /// Throws std::invalid_argument naming `where` if a boundary id is not on `mesh`, a function
  /// has the wrong number of components, or a displacement constrains no component.
  void validate(const dealii::Triangulation<dim> &mesh, const std::string &where) const;

  /// Sets the (pseudo-)time of the tractions' and pressures' functions, at which
  /// add_boundary_loads evaluates them.
  void set_load_time(double time);

  /// Adds the work-equivalent nodal forces of the tractions and pressures on the boundary faces
  /// of `cell` to `cell_external` (the loads' functions at the time last set on them).
  /// `face_values` needs values, quadrature points, normal vectors and JxW.
  void add_boundary_loads(const dealii::DoFHandler<dim>::active_cell_iterator &cell,
                          dealii::FEFaceValues<dim> &face_values, dealii::Vector<double> &cell_external) const;
};
} // namespace geohybrid::fem
