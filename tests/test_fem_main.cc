// GoogleTest main for the deal.II continuum tests: MPI and PETSc must be initialised before any
// test and finalised after all of them. Under mpirun only rank 0 prints; the other ranks still
// return a failing exit code if one of their checks fails.
#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#if defined(__SANITIZE_ADDRESS__)
#  include <sanitizer/lsan_interface.h>
#endif

int main(int argc, char **argv)
{
#if defined(__SANITIZE_ADDRESS__)
  // What Open MPI, PMIx, hwloc and PETSc allocate while they start and stop (MPI_Init,
  // PetscInitialize, their finalisations) they keep to the end, part of it in plugins that
  // MPI_Finalize unloads, whose leak reports then have only "<unknown module>" frames that no
  // suppression can name. None of our code runs there: LeakSanitizer ignores those allocations.
  __lsan_disable();
#endif
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
#if defined(__SANITIZE_ADDRESS__)
  __lsan_enable();
#endif
  ::testing::InitGoogleTest(&argc, argv);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    {
      auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
      delete listeners.Release(listeners.default_result_printer());
    }
  const int status = RUN_ALL_TESTS();
#if defined(__SANITIZE_ADDRESS__)
  __lsan_disable(); // for mpi's destructor: MPI_Finalize, PetscFinalize
#endif
  return status;
}
