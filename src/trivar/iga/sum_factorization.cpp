#include "trivar/iga/sum_factorization.hpp"

#include <algorithm>

namespace trivar {

void contract(const double* in, int inner, int cols, int outer, const double* m, int rows, int row_stride,
              int col_stride, double* out) {
  if (inner == 1) {
    // Small matrix times vectors: the first direction of a grid, where the generic loop would run length-1
    // inner loops.
    for (int o = 0; o < outer; ++o) {
      const double* src = in + static_cast<std::ptrdiff_t>(o) * cols;
      double* dst = out + static_cast<std::ptrdiff_t>(o) * rows;
      for (int r = 0; r < rows; ++r) {
        const double* mr = m + r * row_stride;
        double acc = 0;
        for (int s = 0; s < cols; ++s) acc += mr[s * col_stride] * src[s];
        dst[r] = acc;
      }
    }
    return;
  }
  for (int o = 0; o < outer; ++o) {
    const double* src = in + static_cast<std::ptrdiff_t>(o) * cols * inner;
    double* dst = out + static_cast<std::ptrdiff_t>(o) * rows * inner;
    for (int r = 0; r < rows; ++r) {
      double* d = dst + static_cast<std::ptrdiff_t>(r) * inner;
      std::fill(d, d + inner, 0.0);
      for (int s = 0; s < cols; ++s) {
        const double w = m[r * row_stride + s * col_stride];
        const double* x = src + static_cast<std::ptrdiff_t>(s) * inner;
        for (int i = 0; i < inner; ++i) d[i] += w * x[i];
      }
    }
  }
}

template <int D>
const double* ElementMatrixKernel<D>::compute(const std::array<const double*, D>& val,
                                              const std::array<const double*, D>& der, const Ints<D>& n,
                                              const Ints<D>& nq, const std::vector<int>& pairs, const double* coef,
                                              bool symmetric) {
  constexpr int K = D + 1;
  int from = 0;
  // Level 0 reads the coefficient arrays in place; later levels read the buffers written before.
  std::array<const double*, kPairs> input{};
  std::array<bool, kPairs> in_live{};
  int points = 1;
  for (int k = 0; k < D; ++k) points *= nq[k];
  for (std::size_t t = 0; t < pairs.size(); ++t) {
    input[static_cast<std::size_t>(pairs[t])] = coef + t * static_cast<std::size_t>(points);
    in_live[static_cast<std::size_t>(pairs[t])] = true;
  }
  int P = 1;        // product of n_l^2 over the contracted directions
  int R = points;   // product of nq_l over the directions not yet contracted (this one included)
  double w[64];
  for (int k = 0; k < D; ++k) {
    const int nk = n[k], qk = nq[k];
    R /= qk;
    const int to = 1 - from;
    live_[to].fill(false);
    const std::size_t out_size = static_cast<std::size_t>(P) * nk * nk * R;
    for (int key = 0; key < kPairs; ++key) {
      if (!in_live[static_cast<std::size_t>(key)]) continue;
      const int ca = key / K, cb = key % K;
      const double* Fa = ca == k + 1 ? der[k] : val[k];
      const double* Fb = cb == k + 1 ? der[k] : val[k];
      // A derivative factor in a later direction keeps the pair apart; otherwise only values remain.
      const int okey = (ca > k + 1 ? ca : 0) * K + (cb > k + 1 ? cb : 0);
      auto& out = buf_[to][static_cast<std::size_t>(okey)];
      if (!live_[to][static_cast<std::size_t>(okey)]) {
        out.assign(out_size, 0.0);
        live_[to][static_cast<std::size_t>(okey)] = true;
      }
      const double* in = input[static_cast<std::size_t>(key)];
      const bool last = k == D - 1;
      for (int j = 0; j < nk; ++j)
        for (int i = 0; i < (symmetric && last ? j + 1 : nk); ++i) {
          for (int q = 0; q < qk; ++q) w[q] = Fa[i * qk + q] * Fb[j * qk + q];
          for (int r = 0; r < R; ++r) {
            double* o = out.data() + static_cast<std::ptrdiff_t>(P) * ((i + nk * j) + nk * nk * r);
            for (int q = 0; q < qk; ++q) {
              const double* src = in + static_cast<std::ptrdiff_t>(P) * (q + qk * r);
              const double wq = w[q];
              for (int p = 0; p < P; ++p) o[p] += wq * src[p];
            }
          }
        }
    }
    for (int key = 0; key < kPairs; ++key) {
      in_live[static_cast<std::size_t>(key)] = live_[to][static_cast<std::size_t>(key)];
      input[static_cast<std::size_t>(key)] = buf_[to][static_cast<std::size_t>(key)].data();
    }
    P *= nk * nk;
    from = to;
  }
  // After the last direction every factor has been used: only the pair (value, value) key 0 remains.
  return buf_[from][0].data();
}

template class ElementMatrixKernel<2>;
template class ElementMatrixKernel<3>;

}  // namespace trivar
