#include "trivar/iga_petsc/petsc_system.hpp"

#include <algorithm>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/iga_petsc/petsc_session.hpp"

namespace trivar {

void petsc_check(PetscErrorCode code, const char* what) {
  if (code != 0) petsc_failure(code, what);
}

DofLayout dof_layout(const SparseMatrix& local, int num_basis, int components) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  DofLayout L;
  L.num_basis = num_basis;
  L.components = components;
  // The owner of a function: the lowest rank that assembled a row of it.
  std::vector<int> owner(static_cast<std::size_t>(num_basis));
  const int* outer = local.outerIndexPtr();
  for (int G = 0; G < num_basis; ++G) owner[static_cast<std::size_t>(G)] = outer[G + 1] > outer[G] ? rank : ranks;
  MPI_Allreduce(MPI_IN_PLACE, owner.data(), num_basis, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  std::vector<PetscInt> count(static_cast<std::size_t>(ranks) + 1, 0);
  for (int o : owner) {
    require(o < ranks, "petsc: a basis function has no element in its support");
    ++count[static_cast<std::size_t>(o) + 1];
  }
  for (int r = 0; r < ranks; ++r) count[static_cast<std::size_t>(r) + 1] += count[static_cast<std::size_t>(r)];
  L.begin = components * count[static_cast<std::size_t>(rank)];
  L.end = components * count[static_cast<std::size_t>(rank) + 1];
  L.size = components * count.back();
  L.block.resize(static_cast<std::size_t>(num_basis));
  std::vector<PetscInt> next(count.begin(), count.end() - 1);
  for (int G = 0; G < num_basis; ++G) L.block[static_cast<std::size_t>(G)] = next[static_cast<std::size_t>(owner[static_cast<std::size_t>(G)])]++;
  return L;
}

namespace {

Mat empty_matrix(const DofLayout& L, MatType type) {
  Mat A;
  petsc_check(MatCreate(PETSC_COMM_WORLD, &A), "MatCreate");
  petsc_check(MatSetSizes(A, L.local_rows(), L.local_rows(), L.size, L.size), "MatSetSizes");
  petsc_check(MatSetType(A, type), "MatSetType");
  petsc_check(MatSetBlockSize(A, L.components), "MatSetBlockSize");
  return A;
}

// Adds every non-empty row of `local` to A (values, or zeros for the preallocator). Rows owned by another rank
// travel to it: of those only the entries this rank's elements made (the rest of the pattern is zero here).
void add_rows(Mat A, const SparseMatrix& local, const DofLayout& L, bool values) {
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> vals;
  for (Eigen::Index r = 0; r < local.outerSize(); ++r) {
    const int b = local.outerIndexPtr()[r], e = local.outerIndexPtr()[r + 1];
    if (b == e) continue;
    const PetscInt row = L.row(static_cast<int>(r));
    const bool ghost = values && (row < L.begin || row >= L.end);
    cols.clear();
    vals.clear();
    for (int k = b; k < e; ++k) {
      const double v = values ? local.valuePtr()[k] : 0.0;
      if (ghost && v == 0.0) continue;
      cols.push_back(L.row(local.innerIndexPtr()[k]));
      vals.push_back(v);
    }
    petsc_check(MatSetValues(A, 1, &row, static_cast<PetscInt>(cols.size()), cols.data(), vals.data(), ADD_VALUES),
                "MatSetValues");
  }
  petsc_check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

}  // namespace

Mat distributed_matrix(SparseMatrix& local, const DofLayout& L, bool rows_complete) {
  Mat A = empty_matrix(L, MATAIJ);
  if (rows_complete) {
    // Counted directly: columns owned by this rank (diagonal block) and the others, per owned row.
    std::vector<PetscInt> diagonal(static_cast<std::size_t>(L.local_rows()), 0), off(diagonal.size(), 0);
    for (Eigen::Index r = 0; r < local.outerSize(); ++r) {
      const PetscInt row = L.row(static_cast<int>(r));
      if (row < L.begin || row >= L.end) continue;
      for (int k = local.outerIndexPtr()[r]; k < local.outerIndexPtr()[r + 1]; ++k) {
        const PetscInt col = L.row(local.innerIndexPtr()[k]);
        ++(col >= L.begin && col < L.end ? diagonal : off)[static_cast<std::size_t>(row - L.begin)];
      }
    }
    petsc_check(MatSeqAIJSetPreallocation(A, 0, diagonal.data()), "MatSeqAIJSetPreallocation");
    petsc_check(MatMPIAIJSetPreallocation(A, 0, diagonal.data(), 0, off.data()), "MatMPIAIJSetPreallocation");
  } else {
    Mat pre = empty_matrix(L, MATPREALLOCATOR);
    petsc_check(MatSetUp(pre), "MatSetUp");
    add_rows(pre, local, L, false);
    petsc_check(MatPreallocatorPreallocate(pre, PETSC_TRUE, A), "MatPreallocatorPreallocate");
    petsc_check(MatDestroy(&pre), "MatDestroy");
  }
  // Every entry was preallocated: a new one would mean a pattern bug, not a slow insertion.
  petsc_check(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  add_rows(A, local, L, true);
  local = SparseMatrix();
  return A;
}

Vec distributed_vector(const Eigen::VectorXd& local, const DofLayout& L) {
  Vec b;
  petsc_check(VecCreateMPI(PETSC_COMM_WORLD, L.local_rows(), L.size, &b), "VecCreateMPI");
  petsc_check(VecSetBlockSize(b, L.components), "VecSetBlockSize");
  petsc_check(VecSet(b, 0.0), "VecSet");
  for (Eigen::Index i = 0; i < local.size(); ++i)
    if (local[i] != 0.0) {
      const PetscInt row = L.row(static_cast<int>(i));
      petsc_check(VecSetValues(b, 1, &row, &local[i], ADD_VALUES), "VecSetValues");
    }
  petsc_check(VecAssemblyBegin(b), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(b), "VecAssemblyEnd");
  return b;
}

void apply_dirichlet(Mat A, Vec b, const FixedDofs& fixed, const DofLayout& L) {
  std::vector<PetscInt> rows;
  Vec x;
  petsc_check(VecDuplicate(b, &x), "VecDuplicate");
  petsc_check(VecSet(x, 0.0), "VecSet");
  for (std::size_t i = 0; i < fixed.fixed.size(); ++i) {
    if (!fixed.fixed[i]) continue;
    const PetscInt row = L.row(static_cast<int>(i));
    if (row < L.begin || row >= L.end) continue;
    rows.push_back(row);
    petsc_check(VecSetValue(x, row, fixed.values[static_cast<Eigen::Index>(i)], INSERT_VALUES), "VecSetValue");
  }
  petsc_check(VecAssemblyBegin(x), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(x), "VecAssemblyEnd");
  petsc_check(MatZeroRowsColumns(A, static_cast<PetscInt>(rows.size()), rows.data(), 1.0, x, b), "MatZeroRowsColumns");
  petsc_check(VecDestroy(&x), "VecDestroy");
}

Eigen::VectorXd gather(Vec x, const DofLayout& L) {
  VecScatter scatter;
  Vec all;
  petsc_check(VecScatterCreateToAll(x, &scatter, &all), "VecScatterCreateToAll");
  petsc_check(VecScatterBegin(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  petsc_check(VecScatterEnd(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* v = nullptr;
  petsc_check(VecGetArrayRead(all, &v), "VecGetArrayRead");
  Eigen::VectorXd out(static_cast<Eigen::Index>(L.num_basis) * L.components);
  for (Eigen::Index i = 0; i < out.size(); ++i) out[i] = v[L.row(static_cast<int>(i))];
  petsc_check(VecRestoreArrayRead(all, &v), "VecRestoreArrayRead");
  petsc_check(VecScatterDestroy(&scatter), "VecScatterDestroy");
  petsc_check(VecDestroy(&all), "VecDestroy");
  return out;
}

}  // namespace trivar
