// The iga_petsc tests run under `mpiexec -n 2` (tests/CMakeLists.txt): one PETSc session per process around
// the whole suite, as MPI starts once per process. With --fail-inside-a-collective-call the program runs that
// failure instead (collective_failure.hpp), which ends the job.
#include <gtest/gtest.h>

#include <cstring>

#include "iga_petsc/collective_failure.hpp"
#include "trivar/iga_petsc/petsc_session.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  trivar::PetscSession session;
  if (argc > 1 && std::strcmp(argv[1], "--fail-inside-a-collective-call") == 0) return fail_inside_a_collective_call();
  return RUN_ALL_TESTS();
}
