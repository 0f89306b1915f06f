#include "trivar/spline/second_derivative_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

// A polynomial on [0, 1]^2 with dim components in scaled Bernstein form: coefficient (i, j) times C(m, i) C(n, j),
// so that products are plain two-dimensional convolutions. Degree -1 in a direction, or zero = true, is the zero
// polynomial (a derivative of higher order than the degree, or of a constant weight): its products are skipped.
// Written here rather than with Bernstein<2> because the bound runs once per element of a tessellation: the
// workspace is reused, the components go together and products of equal degree accumulate in place.
struct Scaled {
  int m = -1, n = -1, dim = 1;
  bool zero = true;
  std::vector<double> c;  // (m + 1) x (n + 1) x dim: component fastest, then i
  void reset(int degree_u, int degree_v, int components) {
    m = degree_u;
    n = degree_v;
    dim = components;
    zero = m < 0 || n < 0;
    c.assign(zero ? 0 : static_cast<std::size_t>(m + 1) * static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(dim), 0.0);
  }
};

void binomial_row(int n, std::vector<double>& row) {
  row.resize(static_cast<std::size_t>(n + 1));
  row[0] = 1;
  for (int i = 1; i <= n; ++i) row[static_cast<std::size_t>(i)] = row[static_cast<std::size_t>(i - 1)] * (n - i + 1) / i;
}

struct Workspace {
  Scaled W, Wu, Wv, Wuu, Wvv, Wuv, WW, WWu, WWv, Cuu, Cvv, Cuv, W3;
  Scaled Y, Yu, Yv, Yuu, Yvv, Yuv, Nuu, Nvv, Nuv;
  std::vector<double> row_u, row_v;
};

// The derivative of order (a, b) <= (2, 2) of the Bernstein polynomial with coefficients c[k * stride + d]
// (degrees m, n; k = i + (m + 1) j; d < dim), scaled: m! / (m - a)! n! / (n - b)! times the differences of the
// coefficients.
void derivative(const double* c, std::size_t stride, int dim, int m, int n, int a, int b, Workspace& ws, Scaled& out) {
  out.reset(m - a, n - b, dim);
  if (out.zero) return;
  static constexpr double kDiff[3][3] = {{1, 0, 0}, {-1, 1, 0}, {1, -2, 1}};
  binomial_row(out.m, ws.row_u);
  binomial_row(out.n, ws.row_v);
  double falling = 1;
  for (int r = 0; r < a; ++r) falling *= m - r;
  for (int r = 0; r < b; ++r) falling *= n - r;
  bool zero = true;
  for (int j = 0; j <= out.n; ++j)
    for (int i = 0; i <= out.m; ++i)
      for (int d = 0; d < dim; ++d) {
        double x = 0;
        for (int s = 0; s <= b; ++s)
          for (int r = 0; r <= a; ++r)
            x += kDiff[b][s] * kDiff[a][r] * c[stride * static_cast<std::size_t>(i + r + (m + 1) * (j + s)) + static_cast<std::size_t>(d)];
        out.c[static_cast<std::size_t>((i + (out.m + 1) * j) * dim + d)] = x * falling * ws.row_u[static_cast<std::size_t>(i)] * ws.row_v[static_cast<std::size_t>(j)];
        zero = zero && x == 0;
      }
  out.zero = zero;
}

// out += f A B for a scalar A (out has the degrees of the product and B's components, or is zero). The inner
// loop runs along a whole row of B (its components and first index: contiguous in B and in out), held in a
// local array of L (its length when known at compile time, the common degrees: unrolled).
template <int L>
void add_rows(const Scaled& A, const Scaled& B, double f, Scaled& out, int len) {
  constexpr int kMax = L > 0 ? L : 3 * 32;
  const int n = L > 0 ? L : len, row = (out.m + 1) * B.dim;
  double b[kMax];
  for (int jb = 0; jb <= B.n; ++jb) {
    for (int t = 0; t < n; ++t) b[t] = f * B.c[static_cast<std::size_t>(len * jb + t)];
    // Consecutive updates go to different rows of out (neighbouring ia would overlap: a chain through memory).
    for (int ia = 0; ia <= A.m; ++ia)
      for (int ja = 0; ja <= A.n; ++ja) {
        const double a = A.c[static_cast<std::size_t>(ia + (A.m + 1) * ja)];
        double* o = out.c.data() + static_cast<std::ptrdiff_t>(ia * B.dim + row * (ja + jb));
        for (int t = 0; t < n; ++t) o[t] += a * b[t];
      }
  }
}

void add_product(const Scaled& A, const Scaled& B, double f, Scaled& out) {
  if (A.zero || B.zero || out.m < 0 || out.n < 0) return;
  out.zero = false;
  const int len = (B.m + 1) * B.dim;
  switch (len) {
    case 1: return add_rows<1>(A, B, f, out, len);
    case 2: return add_rows<2>(A, B, f, out, len);
    case 3: return add_rows<3>(A, B, f, out, len);
    case 4: return add_rows<4>(A, B, f, out, len);
    case 6: return add_rows<6>(A, B, f, out, len);
    case 9: return add_rows<9>(A, B, f, out, len);
    case 12: return add_rows<12>(A, B, f, out, len);
    default: return add_rows<0>(A, B, f, out, len);
  }
}

// The largest Euclidean norm of N's Bernstein coefficients.
double largest(const Scaled& N, Workspace& ws) {
  if (N.zero) return 0;
  binomial_row(N.m, ws.row_u);
  binomial_row(N.n, ws.row_v);
  double most = 0;
  for (int j = 0; j <= N.n; ++j)
    for (int i = 0; i <= N.m; ++i) {
      const double b = ws.row_u[static_cast<std::size_t>(i)] * ws.row_v[static_cast<std::size_t>(j)];
      const double* c = N.c.data() + static_cast<std::ptrdiff_t>((i + (N.m + 1) * j) * N.dim);
      double s = 0;
      for (int d = 0; d < N.dim; ++d) s += c[d] * c[d];
      most = std::max(most, s / (b * b));
    }
  return std::sqrt(most);
}

}  // namespace

SecondDerivativeBound second_derivative_bound(const BezierElement<2>& z) {
  const int p = z.degrees[0], q = z.degrees[1], dim = z.dim;
  require(dim >= 1 && dim <= 3, "second_derivative_bound: 1 to 3 components");
  const std::size_t stride = static_cast<std::size_t>(z.stride());
  thread_local Workspace ws;
  const double one = 1.0;  // W = 1 when not rational: every coefficient this one (stride 0)
  const double* w = z.rational ? z.coefs.data() + dim : &one;
  const std::size_t w_stride = z.rational ? stride : 0;
  derivative(w, w_stride, 1, p, q, 0, 0, ws, ws.W);
  derivative(w, w_stride, 1, p, q, 1, 0, ws, ws.Wu);
  derivative(w, w_stride, 1, p, q, 0, 1, ws, ws.Wv);
  derivative(w, w_stride, 1, p, q, 2, 0, ws, ws.Wuu);
  derivative(w, w_stride, 1, p, q, 0, 2, ws, ws.Wvv);
  derivative(w, w_stride, 1, p, q, 1, 1, ws, ws.Wuv);
  ws.WW.reset(2 * p, 2 * q, 1);
  add_product(ws.W, ws.W, 1, ws.WW);
  ws.WWu.reset(2 * p - 1, 2 * q, 1);
  add_product(ws.W, ws.Wu, 1, ws.WWu);
  ws.WWv.reset(2 * p, 2 * q - 1, 1);
  add_product(ws.W, ws.Wv, 1, ws.WWv);
  ws.Cuu.reset(2 * p - 2, 2 * q, 1);
  add_product(ws.Wu, ws.Wu, 2, ws.Cuu);
  add_product(ws.W, ws.Wuu, -1, ws.Cuu);
  ws.Cvv.reset(2 * p, 2 * q - 2, 1);
  add_product(ws.Wv, ws.Wv, 2, ws.Cvv);
  add_product(ws.W, ws.Wvv, -1, ws.Cvv);
  ws.Cuv.reset(2 * p - 1, 2 * q - 1, 1);
  add_product(ws.Wu, ws.Wv, 2, ws.Cuv);
  add_product(ws.W, ws.Wuv, -1, ws.Cuv);
  ws.W3.reset(3 * p, 3 * q, 1);
  add_product(ws.WW, ws.W, 1, ws.W3);
  // The smallest Bernstein coefficient of W^3.
  binomial_row(3 * p, ws.row_u);
  binomial_row(3 * q, ws.row_v);
  double w3 = std::numeric_limits<double>::infinity();
  for (int j = 0; j <= 3 * q; ++j)
    for (int i = 0; i <= 3 * p; ++i)
      w3 = std::min(w3, ws.W3.c[static_cast<std::size_t>(i + (3 * p + 1) * j)] /
                            (ws.row_u[static_cast<std::size_t>(i)] * ws.row_v[static_cast<std::size_t>(j)]));
  const double inf = std::numeric_limits<double>::infinity();
  if (!(w3 > 0)) return {inf, inf, inf};

  const double* y = z.coefs.data();
  derivative(y, stride, dim, p, q, 0, 0, ws, ws.Y);
  derivative(y, stride, dim, p, q, 1, 0, ws, ws.Yu);
  derivative(y, stride, dim, p, q, 0, 1, ws, ws.Yv);
  derivative(y, stride, dim, p, q, 2, 0, ws, ws.Yuu);
  derivative(y, stride, dim, p, q, 0, 2, ws, ws.Yvv);
  derivative(y, stride, dim, p, q, 1, 1, ws, ws.Yuv);
  ws.Nuu.reset(3 * p - 2, 3 * q, dim);
  add_product(ws.WW, ws.Yuu, 1, ws.Nuu);
  add_product(ws.WWu, ws.Yu, -2, ws.Nuu);
  add_product(ws.Cuu, ws.Y, 1, ws.Nuu);
  ws.Nvv.reset(3 * p, 3 * q - 2, dim);
  add_product(ws.WW, ws.Yvv, 1, ws.Nvv);
  add_product(ws.WWv, ws.Yv, -2, ws.Nvv);
  add_product(ws.Cvv, ws.Y, 1, ws.Nvv);
  ws.Nuv.reset(3 * p - 1, 3 * q - 1, dim);
  add_product(ws.WW, ws.Yuv, 1, ws.Nuv);
  add_product(ws.WWv, ws.Yu, -1, ws.Nuv);
  add_product(ws.WWu, ws.Yv, -1, ws.Nuv);
  add_product(ws.Cuv, ws.Y, 1, ws.Nuv);
  return {largest(ws.Nuu, ws) / w3, largest(ws.Nuv, ws) / w3, largest(ws.Nvv, ws) / w3};
}

}  // namespace trivar
