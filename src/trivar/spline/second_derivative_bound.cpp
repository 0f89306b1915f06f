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
  double largest = 0;  // of a derivative net: the largest Euclidean norm of its Bernstein coefficients
  std::vector<double> c;  // (m + 1) x (n + 1) x dim: component fastest, then i
  void reset(int degree_u, int degree_v, int components) {
    m = degree_u;
    n = degree_v;
    dim = components;
    zero = m < 0 || n < 0;
    largest = 0;
    c.assign(zero ? 0 : static_cast<std::size_t>(m + 1) * static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(dim), 0.0);
  }
};

void binomial_row(int n, std::vector<double>& row) {
  row.resize(static_cast<std::size_t>(n + 1));
  row[0] = 1;
  for (int i = 1; i <= n; ++i) row[static_cast<std::size_t>(i)] = row[static_cast<std::size_t>(i - 1)] * (n - i + 1) / i;
}

struct Workspace {
  Scaled W, Wu, Wv, Wuu, Wvv, Wuv, WW, W3;
  Scaled Y, Yu, Yv, Yuu, Yvv, Yuv, Zu, Zv, Zuu, Zuv, Zvv, Nuu, Nvv, Nuv;
  std::vector<double> row_u, row_v, y, z;
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
    for (int i = 0; i <= out.m; ++i) {
      double norm2 = 0;
      for (int d = 0; d < dim; ++d) {
        double x = 0;
        for (int s = 0; s <= b; ++s)
          for (int r = 0; r <= a; ++r)
            x += kDiff[b][s] * kDiff[a][r] * c[stride * static_cast<std::size_t>(i + r + (m + 1) * (j + s)) + static_cast<std::size_t>(d)];
        x *= falling;
        norm2 += x * x;
        out.c[static_cast<std::size_t>((i + (out.m + 1) * j) * dim + d)] = x * ws.row_u[static_cast<std::size_t>(i)] * ws.row_v[static_cast<std::size_t>(j)];
        zero = zero && x == 0;
      }
      out.largest = std::max(out.largest, norm2);
    }
  out.largest = std::sqrt(out.largest);
  out.zero = zero;
}

// The Bernstein coefficients of a scaled polynomial (into ws.z).
void unscale(const Scaled& f, Workspace& ws) {
  ws.z.clear();
  if (f.m < 0 || f.n < 0) return;
  binomial_row(f.m, ws.row_u);
  binomial_row(f.n, ws.row_v);
  ws.z.resize(f.c.size());
  for (int j = 0; j <= f.n; ++j)
    for (int i = 0; i <= f.m; ++i)
      for (int d = 0; d < f.dim; ++d) {
        const std::size_t k = static_cast<std::size_t>((i + (f.m + 1) * j) * f.dim + d);
        ws.z[k] = f.c[k] / (ws.row_u[static_cast<std::size_t>(i)] * ws.row_v[static_cast<std::size_t>(j)]);
      }
}

// out += f A B for a scalar A (out has the degrees of the product and B's components, or is zero). The inner
// loop runs along a whole row of B (its components and first index: contiguous in B and in out); when its
// length L is known at compile time (the common degrees) the row is copied to a local array and unrolled.
template <int L>
void add_rows(const Scaled& A, const Scaled& B, double f, Scaled& out, int len) {
  const int n = L > 0 ? L : len, row = (out.m + 1) * B.dim;
  double local[L > 0 ? L : 1];
  for (int jb = 0; jb <= B.n; ++jb) {
    const double* b = B.c.data() + static_cast<std::ptrdiff_t>(len * jb);
    if constexpr (L > 0) {
      for (int t = 0; t < L; ++t) local[t] = b[t];
      b = local;
    }
    // Consecutive updates go to different rows of out (neighbouring ia would overlap: a chain through memory).
    for (int ia = 0; ia <= A.m; ++ia)
      for (int ja = 0; ja <= A.n; ++ja) {
        const double a = f * A.c[static_cast<std::size_t>(ia + (A.m + 1) * ja)];
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
    case 15: return add_rows<15>(A, B, f, out, len);
    case 18: return add_rows<18>(A, B, f, out, len);
    case 21: return add_rows<21>(A, B, f, out, len);
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
  const std::size_t stride = static_cast<std::size_t>(z.stride()), count = static_cast<std::size_t>((p + 1) * (q + 1));
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

  // The numerators do not change when Y becomes Y - c W (x moves by -c): c is the centre of the net's box, so
  // that |Y| stays of the patch's size, not of its distance from the origin.
  double lo[3], hi[3];
  std::fill(lo, lo + 3, inf);
  std::fill(hi, hi + 3, -inf);
  for (std::size_t k = 0; k < count; ++k)
    for (int d = 0; d < dim; ++d) {
      const double x = z.coefs[k * stride + static_cast<std::size_t>(d)] / w[k * w_stride];
      lo[d] = std::min(lo[d], x);
      hi[d] = std::max(hi[d], x);
    }
  ws.y.resize(count * static_cast<std::size_t>(dim));
  for (std::size_t k = 0; k < count; ++k)
    for (int d = 0; d < dim; ++d)
      ws.y[k * static_cast<std::size_t>(dim) + static_cast<std::size_t>(d)] =
          z.coefs[k * stride + static_cast<std::size_t>(d)] - 0.5 * (lo[d] + hi[d]) * w[k * w_stride];
  const double* y = ws.y.data();
  derivative(y, static_cast<std::size_t>(dim), dim, p, q, 0, 0, ws, ws.Y);
  derivative(y, static_cast<std::size_t>(dim), dim, p, q, 1, 0, ws, ws.Yu);
  derivative(y, static_cast<std::size_t>(dim), dim, p, q, 0, 1, ws, ws.Yv);
  derivative(y, static_cast<std::size_t>(dim), dim, p, q, 2, 0, ws, ws.Yuu);
  derivative(y, static_cast<std::size_t>(dim), dim, p, q, 0, 2, ws, ws.Yvv);
  derivative(y, static_cast<std::size_t>(dim), dim, p, q, 1, 1, ws, ws.Yuv);
  // With Z = W Y_u - W_u Y (so x_u = Z / W^2), N_uu = W Z_u - 2 W_u Z and N_uv = W Z_v - 2 W_v Z; x_vv alike
  // from W Y_v - W_v Y. When the weights are equal or nearly so, each numerator is W^2 times a second derivative
  // of Y plus terms with derivatives of W whose coefficients are at most the products of their factors' largest
  // coefficients (a product's Bernstein coefficients are convex combinations of the factors' coefficient
  // products): below 1% of the first term's size (the smallest W^2 times the second derivative's largest
  // coefficient, or 1e-9 of the patch's size |Y| when that vanishes) they are added as they are; otherwise the
  // numerator is formed exactly.
  const double W = ws.W.largest, Wu = ws.Wu.largest, Wv = ws.Wv.largest, Y = ws.Y.largest;
  double wmin = inf;
  for (std::size_t k = 0; k < count; ++k) wmin = std::min(wmin, w[k * w_stride]);
  // Z (into Zu for u, Zv for v) and its derivatives.
  bool formed[2] = {false, false};
  const auto first_derivative_numerator = [&](int k) {
    if (formed[k]) return;
    formed[k] = true;
    Scaled& Z = k == 0 ? ws.Zu : ws.Zv;
    Z.reset(2 * p - (k == 0), 2 * q - (k == 1), dim);
    add_product(ws.W, k == 0 ? ws.Yu : ws.Yv, 1, Z);
    add_product(k == 0 ? ws.Wu : ws.Wv, ws.Y, -1, Z);
    unscale(Z, ws);
    const std::size_t n = static_cast<std::size_t>(dim);
    if (k == 0) {
      derivative(ws.z.data(), n, dim, Z.m, Z.n, 1, 0, ws, ws.Zuu);
      derivative(ws.z.data(), n, dim, Z.m, Z.n, 0, 1, ws, ws.Zuv);
    } else {
      derivative(ws.z.data(), n, dim, Z.m, Z.n, 0, 1, ws, ws.Zvv);
    }
  };
  // |N| / W^3 for N = W Zd - 2 Wd Z (Z of direction k), or by the shortcut.
  const auto bound = [&](Scaled& N, const Scaled& Y2, double rest, int k, const Scaled& Zd, const Scaled& Wd) {
    if (rest <= 0.01 * wmin * wmin * std::max(Y2.largest, 1e-9 * Y)) {
      add_product(ws.WW, Y2, 1, N);
      return (largest(N, ws) + rest) / w3;
    }
    first_derivative_numerator(k);
    add_product(ws.W, Zd, 1, N);
    add_product(Wd, k == 0 ? ws.Zu : ws.Zv, -2, N);
    return largest(N, ws) / w3;
  };
  ws.Nuu.reset(3 * p - 2, 3 * q, dim);
  const double uu = bound(ws.Nuu, ws.Yuu, 2 * W * Wu * ws.Yu.largest + (2 * Wu * Wu + W * ws.Wuu.largest) * Y, 0, ws.Zuu, ws.Wu);
  ws.Nvv.reset(3 * p, 3 * q - 2, dim);
  const double vv = bound(ws.Nvv, ws.Yvv, 2 * W * Wv * ws.Yv.largest + (2 * Wv * Wv + W * ws.Wvv.largest) * Y, 1, ws.Zvv, ws.Wv);
  ws.Nuv.reset(3 * p - 1, 3 * q - 1, dim);
  const double uv = bound(ws.Nuv, ws.Yuv, W * Wv * ws.Yu.largest + W * Wu * ws.Yv.largest + (2 * Wu * Wv + W * ws.Wuv.largest) * Y, 0,
                          ws.Zuv, ws.Wv);
  return {uu, uv, vv};
}

}  // namespace trivar
