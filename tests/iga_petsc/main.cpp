// The iga_petsc tests run under `mpiexec -n 2` (tests/CMakeLists.txt): one PETSc session per process around
// the whole suite, as MPI starts once per process.
#include <gtest/gtest.h>

#include "trivar/iga_petsc/petsc_session.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  trivar::PetscSession session;
  return RUN_ALL_TESTS();
}
