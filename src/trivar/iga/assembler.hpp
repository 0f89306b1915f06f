#pragma once
// Assembly of symmetric bilinear forms and load vectors on a tensor patch: one loop over the Bezier elements
// (the knot spans), Gauss quadrature, sum factorisation, threads.
//
// Cost. The sparsity pattern is the tensor product of the 1-D patterns, so it is built directly in compressed
// form (no triplets) and the position of an entry in its row is computed, not searched. Element matrices come
// from ElementMatrixKernel (O(p^{2D} q) per element). Elements are processed in slabs of p + 1 layers along
// the last direction: slabs of one parity touch disjoint rows, so they run in parallel without locks, and as
// the slabs do not depend on the thread count the sums are bit-identical for 1 or N threads.
#include <functional>

#include <Eigen/Core>

#include "trivar/iga/element_partition.hpp"
#include "trivar/iga/sparse_matrix.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

// a(u, v) = integral of sum_(c,d) sum_(a,b) P^{cd}_{ab}(x) D_a v_c D_b u_d for unknowns with `components`
// components, where D_0 is the value and D_{1+k} the physical derivative d/dx_k.
template <int D>
struct BilinearForm {
  int components = 1;
  bool value_terms = false;    // P^{cd}_{00} may be non-zero
  bool gradient_terms = true;  // P^{cd}_{ab}, a, b >= 1, may be non-zero (no mixed value-gradient terms)
  // Fills P: block (c, d) at offset (c * components + d) * (D + 1)^2, entry a * (D + 1) + b. Must be
  // symmetric (P^{cd}_{ab} = P^{dc}_{ba}) and thread-safe.
  std::function<void(const double* x, double* P)> coefficients;
};

// The matrix of the form on the space's basis (dofs numbered component-major, see tensor_space.hpp). With a
// part of the elements (element_partition.hpp), only they are summed and only the rows of their functions
// hold a pattern (each such row its whole pattern, the entries of other parts' elements zero).
template <int D>
SparseMatrix assemble_matrix(const TensorSpace<D>& space, const BilinearForm<D>& form, int threads = 0,
                             const ElementPartition& part = {});

// b = integral of f . v: f(x, out) writes `components` values.
template <int D>
Eigen::VectorXd assemble_load(const TensorSpace<D>& space, int components,
                              const std::function<void(const double* x, double* f)>& f, int threads = 0,
                              const ElementPartition& part = {});

}  // namespace trivar
