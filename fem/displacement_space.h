#pragma once
// The finite-element space of the soil's displacement on a distributed mesh: vector Q1 or Q2
// elements (FESystem of two FE_Q), an isoparametric mapping of the same degree (so that curved
// boundaries cost Q2 nothing in accuracy), Gauss quadrature exact for the stiffness of affine
// cells, and the DoF index sets of this MPI rank. The implicit solver uses it, and so will the
// explicit one and the sheet's interface elements: they share one DoFHandler and one mesh.
#include "fem/conventions.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>

namespace geohybrid::fem
{
class DisplacementSpace
{
public:
  /// `degree` is 1 or 2. The mesh must outlive this object.
  DisplacementSpace(const dealii::parallel::distributed::Triangulation<dim> &mesh, unsigned int degree);

  unsigned int degree() const { return fe_.degree; }
  const dealii::FESystem<dim> &fe() const { return fe_; }
  const dealii::DoFHandler<dim> &dof_handler() const { return dof_handler_; }
  const dealii::MappingQ<dim> &mapping() const { return mapping_; }
  const dealii::QGauss<dim> &cell_quadrature() const { return cell_quadrature_; }
  const dealii::QGauss<dim - 1> &face_quadrature() const { return face_quadrature_; }
  const dealii::IndexSet &locally_owned_dofs() const { return locally_owned_dofs_; }
  const dealii::IndexSet &locally_relevant_dofs() const { return locally_relevant_dofs_; }
  MPI_Comm communicator() const { return mesh_.get_communicator(); }
  const dealii::parallel::distributed::Triangulation<dim> &mesh() const { return mesh_; }

  /// Hanging-node constraints (none on a mesh without local refinement), on the relevant DoFs.
  dealii::AffineConstraints<double> hanging_node_constraints() const;

private:
  const dealii::parallel::distributed::Triangulation<dim> &mesh_;
  dealii::FESystem<dim> fe_;
  dealii::DoFHandler<dim> dof_handler_;
  dealii::MappingQ<dim> mapping_;
  dealii::QGauss<dim> cell_quadrature_;
  dealii::QGauss<dim - 1> face_quadrature_;
  dealii::IndexSet locally_owned_dofs_;
  dealii::IndexSet locally_relevant_dofs_;
};
} // namespace geohybrid::fem
