#include "redundant_lu.h"

#include <petscksp.h>

#include <stdexcept>
#include <string>

namespace geohybrid::fem
{
namespace
{
void lu_check(PetscErrorCode error, const char *call)
{
  if (error != 0)
    throw std::runtime_error(std::string("redundant LU: PETSc's ") + call + " failed (error " +
                             std::to_string(static_cast<int>(error)) + ")");
}

/// A KSP destroyed however the solve ends.
struct Ksp
{
  KSP ksp = nullptr;
  ~Ksp() { KSPDestroy(&ksp); }
};
} // namespace

void solve_redundant_lu(const dealii::PETScWrappers::MPI::SparseMatrix &A, dealii::PETScWrappers::MPI::Vector &x,
                        const dealii::PETScWrappers::MPI::Vector &b)
{
  const MPI_Comm comm = A.get_mpi_communicator();
  int n_ranks = 1;
  MPI_Comm_size(comm, &n_ranks);
  Ksp solver;
  lu_check(KSPCreate(comm, &solver.ksp), "KSPCreate");
  lu_check(KSPSetOperators(solver.ksp, A, A), "KSPSetOperators");
  lu_check(KSPSetType(solver.ksp, KSPPREONLY), "KSPSetType");
  PC pc;
  lu_check(KSPGetPC(solver.ksp, &pc), "KSPGetPC");
  lu_check(PCSetType(pc, PCREDUNDANT), "PCSetType");
  // One copy per rank: each sub-communicator holds one rank, so MUMPS runs sequentially.
  lu_check(PCRedundantSetNumber(pc, n_ranks), "PCRedundantSetNumber");
  KSP inner;
  lu_check(PCRedundantGetKSP(pc, &inner), "PCRedundantGetKSP");
  lu_check(KSPSetType(inner, KSPPREONLY), "KSPSetType (inner)");
  PC inner_pc;
  lu_check(KSPGetPC(inner, &inner_pc), "KSPGetPC (inner)");
  lu_check(PCSetType(inner_pc, PCLU), "PCSetType (inner)");
  lu_check(PCFactorSetMatSolverType(inner_pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  lu_check(KSPSolve(solver.ksp, b, x), "KSPSolve");
  KSPConvergedReason reason;
  lu_check(KSPGetConvergedReason(solver.ksp, &reason), "KSPGetConvergedReason");
  // A failed factorisation (a zero pivot) is not an error to PETSc: the solve says it diverged.
  if (reason < 0)
    throw std::runtime_error("the factorisation failed, a singular matrix (zero pivot; PETSc's KSP reason " +
                             std::to_string(static_cast<int>(reason)) + ")");
}
} // namespace geohybrid::fem
