#include "trivar/iga/assembler.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "trivar/core/error.hpp"

#include "trivar/core/parallel.hpp"
#include "trivar/iga/patch_quadrature.hpp"
#include "trivar/iga/sum_factorization.hpp"

namespace trivar {

namespace {

// Per direction and 1-D index i: the first index and the number of 1-D functions whose support shares an
// element with function i.
struct Pattern1D {
  std::vector<int> lo, width;
};

Pattern1D pattern_1d(const DirectionTable& t, int count) {
  Pattern1D p;
  p.lo.assign(static_cast<std::size_t>(count), count);
  std::vector<int> hi(static_cast<std::size_t>(count), -1);
  for (int e = 0; e < t.elements(); ++e) {
    const int f = t.first[static_cast<std::size_t>(e)];
    for (int i = f; i <= f + t.degree; ++i) {
      p.lo[static_cast<std::size_t>(i)] = std::min(p.lo[static_cast<std::size_t>(i)], f);
      hi[static_cast<std::size_t>(i)] = std::max(hi[static_cast<std::size_t>(i)], f + t.degree);
    }
  }
  p.width.resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) p.width[static_cast<std::size_t>(i)] = hi[static_cast<std::size_t>(i)] - p.lo[static_cast<std::size_t>(i)] + 1;
  return p;
}

// Runs body(e) for every element of the part, slab by slab (see assembler.hpp): two passes over the slabs of
// p + 1 layers in the last direction, even slabs then odd ones, each pass in parallel over slabs.
template <int D, class Body>
void for_each_element_by_slabs(const PatchQuadrature<D>& quad, int threads, const ElementPartition& part,
                               Body&& body) {
  const DirectionTable& last = quad.dir[D - 1];
  const std::pair<int, int> range = part.layers(last.elements());
  const int first = range.first, end_layer = range.second;
  const int per_layer = quad.num_elements() / last.elements();
  const int slab = last.degree + 1;
  const int slabs = (end_layer - first + slab - 1) / slab;
  for (int parity = 0; parity < 2; ++parity) {
    const int count = (slabs - parity + 1) / 2;
    parallel_for(count, threads, [&](std::ptrdiff_t s) {
      const int b = 2 * static_cast<int>(s) + parity;
      const int begin = (first + b * slab) * per_layer, end = std::min(end_layer, first + (b + 1) * slab) * per_layer;
      for (int e = begin; e < end; ++e) body(e);
    });
  }
}

template <int D>
struct Pattern {
  std::array<Pattern1D, D> dir;
  int components = 1;
  int num_basis = 0;
  // Rows whose index along the last direction lies in [rows_lo, rows_hi] (the functions of the assembled
  // part's elements) get their pattern; the others stay empty.
  int rows_lo = 0, rows_hi = std::numeric_limits<int>::max();
};

// Compressed rows with the column indices filled in and zero values.
template <int D>
SparseMatrix make_matrix(const TensorSpace<D>& space, const Pattern<D>& pat, int threads) {
  const TensorSpline<D>& g = space.geometry;
  const int N = pat.num_basis, m = pat.components, rows = N * m;
  auto width = [&](int I) {
    const int last = I / (N / g.count(D - 1));
    if (last < pat.rows_lo || last > pat.rows_hi) return 0L;
    long w = 1;
    for (int k = 0; k < D; ++k) {
      w *= pat.dir[k].width[static_cast<std::size_t>(I % g.count(k))];
      I /= g.count(k);
    }
    return w * m;
  };
  SparseMatrix A(rows, rows);
  std::vector<long> outer(static_cast<std::size_t>(rows) + 1, 0);
  for (int r = 0; r < rows; ++r) outer[static_cast<std::size_t>(r) + 1] = outer[static_cast<std::size_t>(r)] + width(r % N);
  require(outer.back() <= std::numeric_limits<int>::max(),
          "iga: the system has too many non-zeros (" + std::to_string(outer.back()) + ") for 32-bit indices");
  A.resizeNonZeros(static_cast<Eigen::Index>(outer.back()));
  for (int r = 0; r <= rows; ++r) A.outerIndexPtr()[r] = static_cast<int>(outer[static_cast<std::size_t>(r)]);
  int* inner = A.innerIndexPtr();
  std::fill(A.valuePtr(), A.valuePtr() + outer.back(), 0.0);
  parallel_for(rows, threads, [&](std::ptrdiff_t r) {
    const int I = static_cast<int>(r) % N;
    if (outer[static_cast<std::size_t>(r) + 1] == outer[static_cast<std::size_t>(r)]) return;
    Ints<D> lo, w;
    for (int k = 0, rest = I; k < D; rest /= g.count(k), ++k) {
      lo[k] = pat.dir[k].lo[static_cast<std::size_t>(rest % g.count(k))];
      w[k] = pat.dir[k].width[static_cast<std::size_t>(rest % g.count(k))];
    }
    int per = 1;
    for (int k = 0; k < D; ++k) per *= w[k];
    int* out = inner + outer[static_cast<std::size_t>(r)];
    for (int d = 0; d < m; ++d)
      for (int j = 0; j < per; ++j) {
        int col = 0, stride = 1;
        for (int k = 0, rest = j; k < D; rest /= w[k], ++k) {
          col += (lo[k] + rest % w[k]) * stride;
          stride *= g.count(k);
        }
        *out++ = d * N + col;
      }
  });
  return A;
}

// Coefficient pairs (a, b) that the kernel needs: on NURBS a derivative of R_I involves B_I itself.
template <int D>
std::vector<int> active_pairs(const BilinearForm<D>& form, bool rational) {
  constexpr int K = D + 1;
  std::vector<int> pairs;
  for (int a = 0; a < K; ++a)
    for (int b = 0; b < K; ++b) {
      const bool value = a == 0 && b == 0;
      const bool grad = rational ? true : (a > 0 && b > 0);
      if ((form.value_terms && value) || (form.gradient_terms && grad)) pairs.push_back(a * K + b);
    }
  return pairs;
}

// Adds the element matrix E (layout of ElementMatrixKernel::compute, scaled by the NURBS weights w_I w_J) to
// the rows: rows[I] points at the entry of row I for the first column of the block, off[k][i + n j] is the
// column offset in direction k of local column j in the row of local row i, wid[k][i] that row's width.
// The innermost loop runs along u, where both the columns of a row and E's entries are evenly spaced.
template <int D>
void scatter(const double* E, bool symmetric, const Ints<D>& n, const std::array<std::vector<int>, D>& off,
             const std::array<std::vector<int>, D>& wid, const double* weights, double* const* rows) {
  const int n0 = n[0], S1 = n0 * n0;
  auto add_run = [&](double* r, const double* e, int e_stride, double wI, const double* wj) {
    for (int j0 = 0; j0 < n0; ++j0) r[j0] += e[j0 * e_stride] * wI * wj[j0];
  };
  if constexpr (D == 2) {
    const int n1 = n[1];
    for (int i1 = 0, I = 0; i1 < n1; ++i1)
      for (int i0 = 0; i0 < n0; ++i0, ++I) {
        double* row = rows[I] + off[0][static_cast<std::size_t>(i0)];
        const int w0 = wid[0][static_cast<std::size_t>(i0)];
        for (int j1 = 0; j1 < n1; ++j1) {
          const bool tr = symmetric && i1 > j1;
          const int e1 = (tr ? j1 + n1 * i1 : i1 + n1 * j1) * S1;
          double* r = row + off[1][static_cast<std::size_t>(i1 + n1 * j1)] * w0;
          if (tr)
            add_run(r, E + e1 + n0 * i0, 1, weights[I], weights + n0 * j1);
          else
            add_run(r, E + e1 + i0, n0, weights[I], weights + n0 * j1);
        }
      }
  } else {
    const int n1 = n[1], n2 = n[2], S2 = S1 * n1 * n1;
    for (int i2 = 0, I = 0; i2 < n2; ++i2)
      for (int i1 = 0; i1 < n1; ++i1)
        for (int i0 = 0; i0 < n0; ++i0, ++I) {
          double* row = rows[I] + off[0][static_cast<std::size_t>(i0)];
          const int w0 = wid[0][static_cast<std::size_t>(i0)], w01 = w0 * wid[1][static_cast<std::size_t>(i1)];
          for (int j2 = 0; j2 < n2; ++j2) {
            const bool tr = symmetric && i2 > j2;
            const int e2 = (tr ? j2 + n2 * i2 : i2 + n2 * j2) * S2;
            double* r2 = row + off[2][static_cast<std::size_t>(i2 + n2 * j2)] * w01;
            for (int j1 = 0; j1 < n1; ++j1) {
              const int e1 = e2 + (tr ? j1 + n1 * i1 : i1 + n1 * j1) * S1;
              double* r = r2 + off[1][static_cast<std::size_t>(i1 + n1 * j1)] * w0;
              const double* wj = weights + n0 * (j1 + n1 * j2);
              if (tr)
                add_run(r, E + e1 + n0 * i0, 1, weights[I], wj);
              else
                add_run(r, E + e1 + i0, n0, weights[I], wj);
            }
          }
        }
  }
}

}  // namespace

template <int D>
SparseMatrix assemble_matrix(const TensorSpace<D>& space, const BilinearForm<D>& form, int threads,
                             const ElementPartition& part) {
  require(form.components >= 1 && form.coefficients, "iga: bilinear form without components or coefficients");
  constexpr int K = D + 1;
  const TensorSpline<D>& geo = space.geometry;
  const PatchQuadrature<D> quad = patch_quadrature(space);
  const int m = form.components, N = space.num_basis(), Q = quad.points();
  Pattern<D> pat;
  pat.components = m;
  pat.num_basis = N;
  for (int k = 0; k < D; ++k) pat.dir[k] = pattern_1d(quad.dir[k], geo.count(k));
  if (!part.whole()) {
    const DirectionTable& last = quad.dir[D - 1];
    const auto [first, end] = part.layers(last.elements());
    pat.rows_lo = first < end ? last.first[static_cast<std::size_t>(first)] : 0;
    pat.rows_hi = first < end ? last.first[static_cast<std::size_t>(end - 1)] + last.degree : -1;
  }
  SparseMatrix A = make_matrix(space, pat, threads);
  const std::vector<int> pairs = active_pairs(form, geo.is_rational());
  const int np = static_cast<int>(pairs.size());
  Ints<D> n, nq;
  int nloc = 1;
  for (int k = 0; k < D; ++k) {
    n[k] = quad.dir[k].functions();
    nq[k] = quad.dir[k].points;
    nloc *= n[k];
  }
  const int* outer = A.outerIndexPtr();
  double* values = A.valuePtr();

  for_each_element_by_slabs(quad, threads, part, [&](int el) {
    thread_local GridScratch scratch;
    thread_local GridGeometry<D> g;
    thread_local ElementMatrixKernel<D> kernel;
    thread_local std::vector<double> coef, P, weights;
    thread_local std::vector<int> ids;
    thread_local std::vector<double*> rows;
    const Ints<D> e = quad.element_index(el);
    grid_geometry(space, quad, e, scratch, g);
    coef.resize(static_cast<std::size_t>(m * m * np * Q));
    P.resize(static_cast<std::size_t>(m * m * K * K));
    for (int q = 0; q < Q; ++q) {
      form.coefficients(&g.x[static_cast<std::size_t>(q * D)], P.data());
      // S maps (B, dB/du) of a B-spline to (R, dR/dx) / w_I of its NURBS function: R = w B / W and
      // dR/dx_c = sum_a du_a/dx_c w (dB/du_a / W - B dW/du_a / W^2).
      double S[K][K] = {};
      const double W = g.W[static_cast<std::size_t>(q)];
      S[0][0] = 1.0 / W;
      for (int c = 0; c < D; ++c)
        for (int a = 0; a < D; ++a) {
          const double ji = g.jinv[static_cast<std::size_t>((q * D + a) * D + c)];
          S[c + 1][a + 1] = ji / W;
          S[c + 1][0] -= ji * g.dW[static_cast<std::size_t>(q * D + a)] / (W * W);
        }
      const double dV = g.measure[static_cast<std::size_t>(q)];
      for (int blk = 0; blk < m * m; ++blk) {
        const double* Pb = P.data() + blk * K * K;
        double PS[K][K];
        for (int r = 0; r < K; ++r)
          for (int b = 0; b < K; ++b) {
            double s = 0;
            for (int t = 0; t < K; ++t) s += Pb[r * K + t] * S[t][b];
            PS[r][b] = s;
          }
        for (int t = 0; t < np; ++t) {
          const int a = pairs[static_cast<std::size_t>(t)] / K, b = pairs[static_cast<std::size_t>(t)] % K;
          double s = 0;
          for (int r = 0; r < K; ++r) s += S[r][a] * PS[r][b];
          coef[static_cast<std::size_t>((blk * np + t) * Q + q)] = s * dV;
        }
      }
    }
    std::array<const double*, D> val, der;
    for (int k = 0; k < D; ++k) {
      val[k] = quad.dir[k].values(e[k]);
      der[k] = quad.dir[k].derivatives(e[k]);
    }
    // Per local function: global index, NURBS weight, and per direction its 1-D global index.
    ids.resize(static_cast<std::size_t>(nloc));
    weights.resize(static_cast<std::size_t>(nloc));
    for (int l = 0; l < nloc; ++l) {
      ids[static_cast<std::size_t>(l)] = global_basis(space, quad, e, l);
      weights[static_cast<std::size_t>(l)] = geo.weight(ids[static_cast<std::size_t>(l)]);
    }
    // Column offsets inside a row: (first + j - lo(first + i)) per direction, and the row's widths.
    thread_local std::array<std::vector<int>, D> off;
    thread_local std::array<std::vector<int>, D> wid;
    for (int k = 0; k < D; ++k) {
      const int f = quad.dir[k].first[static_cast<std::size_t>(e[k])];
      off[k].resize(static_cast<std::size_t>(n[k] * n[k]));
      wid[k].resize(static_cast<std::size_t>(n[k]));
      for (int i = 0; i < n[k]; ++i) {
        wid[k][static_cast<std::size_t>(i)] = pat.dir[k].width[static_cast<std::size_t>(f + i)];
        for (int j = 0; j < n[k]; ++j)
          off[k][static_cast<std::size_t>(i + n[k] * j)] = f + j - pat.dir[k].lo[static_cast<std::size_t>(f + i)];
      }
    }
    rows.resize(static_cast<std::size_t>(nloc));
    for (int c = 0; c < m; ++c)
      for (int d = 0; d < m; ++d) {
        // Diagonal blocks of a symmetric form are symmetric: the kernel computes half of them.
        const bool symmetric = c == d;
        const double* E = kernel.compute(val, der, n, nq, pairs,
                                         coef.data() + static_cast<std::size_t>((c * m + d) * np * Q), symmetric);
        for (int I = 0; I < nloc; ++I) {
          int row_width = 1;
          for (int k = 0, r = I; k < D; r /= n[k], ++k) row_width *= wid[k][static_cast<std::size_t>(r % n[k])];
          rows[static_cast<std::size_t>(I)] =
              values + outer[c * N + ids[static_cast<std::size_t>(I)]] + static_cast<std::ptrdiff_t>(d) * row_width;
        }
        scatter<D>(E, symmetric, n, off, wid, weights.data(), rows.data());
      }
  });
  return A;
}

template <int D>
Eigen::VectorXd assemble_load(const TensorSpace<D>& space, int components,
                              const std::function<void(const double* x, double* f)>& f, int threads,
                              const ElementPartition& part) {
  const TensorSpline<D>& geo = space.geometry;
  const PatchQuadrature<D> quad = patch_quadrature(space);
  const int m = components, N = space.num_basis(), Q = quad.points();
  Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N) * m);
  for_each_element_by_slabs(quad, threads, part, [&](int el) {
    thread_local GridScratch scratch;
    thread_local GridGeometry<D> g;
    thread_local std::vector<double> fq, gq, local;
    const Ints<D> e = quad.element_index(el);
    grid_geometry(space, quad, e, scratch, g);
    fq.resize(static_cast<std::size_t>(m * Q));
    for (int q = 0; q < Q; ++q) f(&g.x[static_cast<std::size_t>(q * D)], &fq[static_cast<std::size_t>(q * m)]);
    gq.resize(static_cast<std::size_t>(Q));
    for (int c = 0; c < m; ++c) {
      for (int q = 0; q < Q; ++q)
        gq[static_cast<std::size_t>(q)] = fq[static_cast<std::size_t>(q * m + c)] * g.measure[static_cast<std::size_t>(q)] /
                                          g.W[static_cast<std::size_t>(q)];
      grid_integrate(quad, e, gq.data(), scratch, local);
      for (std::size_t l = 0; l < local.size(); ++l) {
        const int I = global_basis(space, quad, e, static_cast<int>(l));
        b[static_cast<Eigen::Index>(c) * N + I] += local[l] * geo.weight(I);
      }
    }
  });
  return b;
}

#define TRIVAR_INSTANTIATE(D)                                                                                  \
  template SparseMatrix assemble_matrix(const TensorSpace<D>&, const BilinearForm<D>&, int,                    \
                                        const ElementPartition&);                                              \
  template Eigen::VectorXd assemble_load(const TensorSpace<D>&, int,                                          \
                                         const std::function<void(const double*, double*)>&, int,              \
                                         const ElementPartition&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
