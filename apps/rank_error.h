#pragma once
// Under mpirun every rank meets an error of the input at the same point, and main() prints it
// once, from rank 0. An error that one rank meets alone (a seed of an ensemble that failed on it)
// is thrown as RankError: every rank that has one prints it, naming itself. Work that rank 0 does
// alone (preparing an output directory) goes through on_rank_zero, so that its error stops every
// rank instead of leaving the others waiting.
#include <deal.II/base/mpi.h>

#include <stdexcept>
#include <string>

namespace geohybrid::apps
{
class RankError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Runs `f` on rank 0 of `communicator` only; an exception there is thrown on every rank as a
/// std::runtime_error with its message. Every rank must call it. Without MPI, runs `f`.
template <typename F>
void on_rank_zero(MPI_Comm communicator, F &&f)
{
  const bool with_mpi = dealii::Utilities::MPI::job_supports_mpi();
  std::string failure;
  if (!with_mpi || dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
    try
      {
        f();
      }
    catch (const std::exception &e)
      {
        failure = e.what();
        if (failure.empty())
          failure = "rank 0 failed";
      }
  if (with_mpi)
    failure = dealii::Utilities::MPI::broadcast(communicator, failure, 0);
  if (!failure.empty())
    throw std::runtime_error(failure);
}
} // namespace geohybrid::apps
