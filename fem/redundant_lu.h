#pragma once
// A sparse direct solve that gives the same bits on every run: the distributed matrix gathered
// whole onto every rank (PETSc's PCREDUNDANT), each rank factorising its copy with MUMPS alone,
// and each keeping its own rows of the solution.
//
// Why not MUMPS distributed over the ranks (deal.II's SparseDirectMUMPS on the communicator):
// its factorisation is asynchronous, each rank assembling the contribution blocks it receives in
// the order they arrive, so the sums, and the last bits of the solution, vary from run to run.
// Measured on the 2-rank implicit pull-out: the same matrix and right-hand side solved again gave
// a correction that differed by up to 1e-16 of its size in 55 of 87 solves; on one rank, 0 of 87.
// Newton carries those bits on, and T_max differed in its last digit between two runs. MUMPS's
// own switches do not help: with ICNTL(13) = 1 (no ScaLAPACK root) and ICNTL(28) = 1 (sequential
// analysis), 37 of 87 still differed.
//
// The cost: every rank factorises the whole matrix (the wall time of one rank's factorisation,
// the memory of the whole factor per rank); the assembly stays distributed. A 2D tank's tangent
// (tens of thousands of DoFs) factorises in well under a second.
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

namespace geohybrid::fem
{
/// Solves A x = b by LU (MUMPS) on a whole copy of A on each rank. Collective. Throws
/// std::runtime_error if the factorisation fails (a zero pivot: a singular matrix).
void solve_redundant_lu(const dealii::PETScWrappers::MPI::SparseMatrix &A, dealii::PETScWrappers::MPI::Vector &x,
                        const dealii::PETScWrappers::MPI::Vector &b);
} // namespace geohybrid::fem
