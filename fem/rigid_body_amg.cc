#include "rigid_body_amg.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/dofs/dof_tools.h>

#include <petscmat.h>
#include <petscpc.h>

#include <map>
#include <stdexcept>
#include <string>

namespace geohybrid::fem
{
namespace
{
void check(PetscErrorCode error, const char *call)
{
  if (error != 0)
    throw std::runtime_error(std::string("RigidBodyAMG: PETSc's ") + call + " failed (error " +
                             std::to_string(static_cast<int>(error)) + ")");
}
} // namespace

std::array<dealii::PETScWrappers::MPI::Vector, 3>
rigid_body_modes(const DisplacementSpace &space, const dealii::IndexSet &owned_dofs,
                 const std::vector<dealii::Point<dim>> &extra_nodes)
{
  const MPI_Comm comm = space.communicator();
  // Every DoF's position: the soil's support points (FE_Q: every DoF has one), then the extra
  // nodes'. The soil's x DoFs (locally owned) from their component; an extra node's DoFs are x, y.
  const dealii::types::global_dof_index n_soil = space.dof_handler().n_dofs();
  std::map<dealii::types::global_dof_index, dealii::Point<dim>> positions;
  dealii::DoFTools::map_dofs_to_support_points(space.mapping(), space.dof_handler(), positions);
  for (std::size_t k = 0; k < extra_nodes.size(); ++k)
    for (unsigned int c = 0; c < dim; ++c)
      positions[n_soil + dim * k + c] = extra_nodes[k];
  const dealii::IndexSet soil_x_dofs =
    dealii::DoFTools::extract_dofs(space.dof_handler(), dealii::ComponentMask(std::vector<bool>{true, false}));
  const auto component_of = [&](dealii::types::global_dof_index index) -> unsigned int {
    if (index >= n_soil)
      return (index - n_soil) % dim;
    return soil_x_dofs.is_element(index) ? 0 : 1;
  };

  // Rotation about the centroid of the DoFs' positions: the modes are then nearly orthogonal
  // before Gram-Schmidt, which keeps it accurate.
  dealii::Point<dim> centroid;
  double n_points = 0.0;
  for (const auto index : owned_dofs)
    {
      centroid += positions.at(index);
      n_points += 1.0;
    }
  n_points = dealii::Utilities::MPI::sum(n_points, comm);
  for (unsigned int d = 0; d < dim; ++d)
    centroid[d] = dealii::Utilities::MPI::sum(centroid[d], comm) / n_points;

  std::array<dealii::PETScWrappers::MPI::Vector, 3> modes;
  for (auto &m : modes)
    m.reinit(owned_dofs, comm);
  for (const auto index : owned_dofs)
    {
      const unsigned int c = component_of(index);
      const dealii::Tensor<1, dim> r = positions.at(index) - centroid;
      modes[c][index] = 1.0;                     // translation along c
      modes[2][index] = c == 0 ? -r[1] : r[0];   // rotation: (-y, x)
    }
  for (auto &m : modes)
    m.compress(dealii::VectorOperation::insert);
  // Modified Gram-Schmidt, as MatNullSpaceCreate asks for orthonormal vectors.
  for (unsigned int i = 0; i < 3; ++i)
    {
      for (unsigned int j = 0; j < i; ++j)
        modes[i].add(-(modes[i] * modes[j]), modes[j]);
      const double norm = modes[i].l2_norm();
      AssertThrow(norm > 0.0, dealii::ExcMessage("RigidBodyAMG: a rigid-body mode vanished (a mesh of one point?)"));
      modes[i] /= norm;
    }
  return modes;
}

RigidBodyAMG::RigidBodyAMG(const dealii::PETScWrappers::MPI::SparseMatrix &A,
                           const std::array<dealii::PETScWrappers::MPI::Vector, 3> &modes, const RigidBodyAMGSettings &settings)
{
  matrix = static_cast<Mat>(A);
  MPI_Comm comm;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(matrix), &comm), "PetscObjectGetComm");
  Vec vectors[3] = {static_cast<Vec>(modes[0]), static_cast<Vec>(modes[1]), static_cast<Vec>(modes[2])};
  MatNullSpace near_null_space;
  check(MatNullSpaceCreate(comm, PETSC_FALSE, 3, vectors, &near_null_space), "MatNullSpaceCreate");
  check(MatSetNearNullSpace(matrix, near_null_space), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&near_null_space), "MatNullSpaceDestroy"); // the matrix keeps a reference

  create_pc();
  check(PCSetType(pc, PCGAMG), "PCSetType(PCGAMG)");
  check(PCGAMGSetType(pc, PCGAMGAGG), "PCGAMGSetType");
  check(PCGAMGSetNSmooths(pc, 1), "PCGAMGSetNSmooths");
  PetscReal thresholds[1] = {settings.threshold};
  check(PCGAMGSetThreshold(pc, thresholds, 1), "PCGAMGSetThreshold");
  check(PCSetFromOptions(pc), "PCSetFromOptions");
  check(PCSetUp(pc), "PCSetUp");
}
} // namespace geohybrid::fem
