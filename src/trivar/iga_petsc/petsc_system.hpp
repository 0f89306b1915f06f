#pragma once
// Inside the iga_petsc layer only (PETSc types): a multipatch space's dofs spread over the ranks, and the
// distributed matrices and vectors assembled from each rank's share of the elements.
//
// Ownership. Each rank assembles the elements of its ElementPartition part of every patch (a slab of element
// layers); a scalar basis function belongs to the lowest rank whose elements it is supported on, so every
// rank owns the functions of its slab up to the interface with the previous rank. PETSc needs each rank's rows
// contiguous: the owned functions are renumbered rank by rank, and the m components of a function are
// interleaved (row = m * block + c), so the matrix has PETSc block size m (what GAMG's elasticity set-up uses).
//
// Preallocation comes from the spline supports: the compressed rows a rank assembles hold the whole pattern
// of every row its elements touch. On one patch that is the row's global pattern, so the owner counts its
// rows' diagonal- and off-block entries directly. On several patches a shared function's row also couples to
// the functions of other patches, which another rank may assemble alone: the patterns of all ranks go through
// a MATPREALLOCATOR first (rows owned elsewhere included). Either way the matrix is allocated exactly once,
// before any value arrives.
#include <vector>

#include <petscmat.h>

#include "trivar/iga/dirichlet.hpp"
#include "trivar/iga/sparse_matrix.hpp"

namespace trivar {

// petsc_failure (petsc_session.hpp) for a non-zero PETSc error code: on several ranks the job ends with one error
// line, on one rank trivar::Error naming `what` is thrown.
void petsc_check(PetscErrorCode code, const char* what);

struct DofLayout {
  int num_basis = 0, components = 1;
  std::vector<PetscInt> block;  // per global scalar function: its PETSc block (row m * block + c)
  PetscInt begin = 0, end = 0;  // this rank's rows [begin, end)
  PetscInt size = 0;            // all rows

  PetscInt row(int dof) const { return components * block[static_cast<std::size_t>(dof % num_basis)] + dof / num_basis; }
  PetscInt local_rows() const { return end - begin; }
};

// From the rows this rank assembled (`local`, global component-major numbering, empty rows untouched);
// collective.
DofLayout dof_layout(const SparseMatrix& local, int num_basis, int components);

// A distributed AIJ matrix summed from every rank's `local` rows; collective. `local` is released.
// rows_complete: each of this rank's rows holds its whole global pattern (one patch).
Mat distributed_matrix(SparseMatrix& local, const DofLayout& layout, bool rows_complete);

// A distributed vector summed from every rank's `local` (global component-major numbering); collective.
Vec distributed_vector(const Eigen::VectorXd& local, const DofLayout& layout);

// The symmetric elimination of apply_dirichlet (dirichlet.hpp) on the distributed system: fixed rows and
// columns zeroed, a unit diagonal, b adjusted by the fixed values. Collective.
void apply_dirichlet(Mat A, Vec b, const FixedDofs& fixed, const DofLayout& layout);

// Every dof's value from a distributed vector, on every rank (global component-major numbering); collective.
Eigen::VectorXd gather(Vec x, const DofLayout& layout);

}  // namespace trivar
