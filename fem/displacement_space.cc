#include "displacement_space.h"

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>

#include <stdexcept>

namespace geohybrid::fem
{
namespace
{
unsigned int checked_degree(unsigned int degree)
{
  if (degree != 1 && degree != 2)
    throw std::invalid_argument("displacement space: parameter 'element degree' = " +
                                std::to_string(degree) + " must be 1 (Q1) or 2 (Q2)");
  return degree;
}
} // namespace

DisplacementSpace::DisplacementSpace(const dealii::parallel::distributed::Triangulation<dim> &mesh,
                                     unsigned int degree)
  : mesh_(mesh)
  , fe_(dealii::FE_Q<dim>(checked_degree(degree)), dim)
  , dof_handler_(mesh)
  , mapping_(degree)
  , cell_quadrature_(degree + 1)
  , face_quadrature_(degree + 1)
{
  dof_handler_.distribute_dofs(fe_);
  locally_owned_dofs_ = dof_handler_.locally_owned_dofs();
  dealii::DoFTools::extract_locally_relevant_dofs(dof_handler_, locally_relevant_dofs_);
}

dealii::AffineConstraints<double> DisplacementSpace::hanging_node_constraints() const
{
  dealii::AffineConstraints<double> constraints(locally_relevant_dofs_);
  dealii::DoFTools::make_hanging_node_constraints(dof_handler_, constraints);
  return constraints;
}
} // namespace geohybrid::fem
