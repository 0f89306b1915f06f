#include "iga_petsc/collective_failure.hpp"

#include <petscmat.h>

#include "trivar/iga_petsc/petsc_system.hpp"

int fail_inside_a_collective_call() {
  using trivar::petsc_check;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  const PetscInt local = 2, first = local * rank;
  Mat A;
  petsc_check(MatCreateAIJ(PETSC_COMM_WORLD, local, local, PETSC_DETERMINE, PETSC_DETERMINE, 1, nullptr, 0, nullptr, &A),
              "MatCreateAIJ");
  petsc_check(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  for (PetscInt i = first; i < first + local; ++i) petsc_check(MatSetValue(A, i, i, 1.0, ADD_VALUES), "MatSetValue");
  // Row 0 (the first rank's), column of the last rank's block: not preallocated there.
  if (rank == ranks - 1 && ranks > 1) petsc_check(MatSetValue(A, 0, first, 1.0, ADD_VALUES), "MatSetValue");
  petsc_check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  petsc_check(MatDestroy(&A), "MatDestroy");
  return 0;
}
