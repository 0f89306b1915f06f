#pragma once
// Sum factorisation on tensor-product elements: every tensor contraction is done one direction at a time, so
// moving between the (p+1)^D coefficients of an element and its q^D quadrature points costs O(p q^D) instead
// of O(p^D q^D), and an element matrix costs O(p^{2D} q) instead of O(p^{2D} q^D).
#include <array>
#include <vector>

#include "trivar/core/box.hpp"

namespace trivar {

// out[o][r][i] = sum_s M(r, s) in[o][s][i] for o < outer, i < inner: M(r, s) = m[r * row_stride + s * col_stride],
// r < rows, s < cols. Contracts the middle index of a 3-index array; a D-index array is contracted along
// direction k with inner = product of the sizes before k, outer = product after k.
void contract(const double* in, int inner, int cols, int outer, const double* m, int rows, int row_stride,
              int col_stride, double* out);

// Element matrices A(I, J) = sum_q sum_(a,b) C_ab(q) F^a_I(q) F^b_J(q) of tensor bases, where F^0 is the basis
// function and F^(1+k) its derivative in direction k, each a product of 1-D factors (value or derivative per
// direction). The quadrature points of direction k are contracted in turn; after direction k the pairs (a, b)
// whose remaining 1-D factors coincide are summed, so the last, most expensive contraction runs at most four
// times (value/derivative on either side) whatever the number of pairs.
template <int D>
class ElementMatrixKernel {
public:
  static constexpr int kPairs = (D + 1) * (D + 1);

  // val[k], der[k]: (n[k] x nq[k]) tables, entry [i * nq[k] + q]. pairs: indices a * (D + 1) + b of the
  // coefficient arrays given, coef: pairs.size() arrays of prod(nq) values (q_0 fastest), one per pair.
  // Returns the matrix in the layout [ij_0][ij_1]...[ij_{D-1}] with ij_k = i_k + n[k] * j_k (row index
  // i_k, column index j_k in direction k); valid until the next call. symmetric (C_ab = C_ba for every pair,
  // so A is symmetric): only the entries with i_{D-1} <= j_{D-1} are computed, the others are left zero and
  // must be read as A(J, I).
  const double* compute(const std::array<const double*, D>& val, const std::array<const double*, D>& der,
                        const Ints<D>& n, const Ints<D>& nq, const std::vector<int>& pairs, const double* coef,
                        bool symmetric);

private:
  std::array<std::vector<double>, kPairs> buf_[2];
  std::array<bool, kPairs> live_[2]{};
};

extern template class ElementMatrixKernel<2>;
extern template class ElementMatrixKernel<3>;

}  // namespace trivar
