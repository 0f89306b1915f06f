#pragma once
// The matrix type of assembled systems. Row-major so Eigen's sparse matrix * vector product runs on all
// OpenMP threads, which is what conjugate gradients spends its time in.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace trivar {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

}  // namespace trivar
