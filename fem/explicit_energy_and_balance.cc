// What a run reads of the explicit solver between steps (explicit_solver.h): the kinetic energy,
// the energy ledger (its terms are booked by each step, ExplicitSolver::take_step), the
// out-of-balance ratio and the boundary reactions. Each sums the ranks.
#include "explicit_solver.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>

#include <cmath>

namespace geohybrid::fem
{
double ExplicitSolver::kinetic_energy() const
{
  double energy = 0.0;
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    energy += 0.5 * mass_.local_element(i) * velocity_.local_element(i) * velocity_.local_element(i);
  return dealii::Utilities::MPI::sum(energy, space_.communicator());
}

ExplicitEnergyLedger ExplicitSolver::energy_ledger() const
{
  double kinetic = 0.0;
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    if (!constrained_[i])
      kinetic += 0.5 * mass_.local_element(i) * velocity_.local_element(i) * velocity_.local_element(i);
  const MPI_Comm comm = space_.communicator();
  ExplicitEnergyLedger sum;
  sum.kinetic = dealii::Utilities::MPI::sum(kinetic, comm);
  if (n_steps_ == 0)
    {
      sum.initial_kinetic = sum.kinetic;
      return sum;
    }
  sum.initial_kinetic = dealii::Utilities::MPI::sum(ledger_.initial_kinetic, comm);
  sum.internal_work = dealii::Utilities::MPI::sum(ledger_.internal_work, comm);
  sum.damping_work = dealii::Utilities::MPI::sum(ledger_.damping_work, comm);
  sum.gravity_work = dealii::Utilities::MPI::sum(ledger_.gravity_work, comm);
  sum.load_work = dealii::Utilities::MPI::sum(ledger_.load_work, comm);
  sum.added_force_work = dealii::Utilities::MPI::sum(ledger_.added_force_work, comm);
  return sum;
}

double ExplicitSolver::out_of_balance_ratio() const
{
  double residual = 0.0, internal = 0.0, external = 0.0;
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    {
      const double fi = internal_force_.local_element(i), fe = external_force_.local_element(i);
      internal += fi * fi;
      external += fe * fe;
      if (!constrained_[i])
        residual += (fe - fi) * (fe - fi);
    }
  const MPI_Comm comm = space_.communicator();
  residual = std::sqrt(dealii::Utilities::MPI::sum(residual, comm));
  const double scale = std::sqrt(dealii::Utilities::MPI::sum(internal, comm)) +
                       std::sqrt(dealii::Utilities::MPI::sum(external, comm));
  return scale > 0.0 ? residual / scale : residual;
}

dealii::Tensor<1, dim> ExplicitSolver::boundary_reaction(dealii::types::boundary_id boundary_id) const
{
  const dealii::IndexSet boundary_dofs =
    dealii::DoFTools::extract_boundary_dofs(space_.dof_handler(), dealii::ComponentMask(), {boundary_id});
  const auto &owned = space_.locally_owned_dofs();
  dealii::Tensor<1, dim> reaction;
  for (const auto dof : boundary_dofs)
    if (owned.is_element(dof))
      {
        const unsigned int i = owned.index_within_set(dof);
        reaction[x_component_[i] ? 0 : 1] += internal_force_.local_element(i) - external_force_.local_element(i);
      }
  return dealii::Utilities::MPI::sum(reaction, space_.communicator());
}
} // namespace geohybrid::fem
