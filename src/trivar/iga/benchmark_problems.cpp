#include "trivar/iga/benchmark_problems.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
PoissonBenchmark<D> sine_box(int degree, int elements) {
  constexpr double pi = std::numbers::pi;
  Param<D> lo, hi;
  lo.fill(0.0);
  hi.fill(1.0);
  PoissonBenchmark<D> b{{box_geometry<D>(lo, hi, degree, elements)}, {}, {}};
  b.problem.source = [](const double* x) {
    double u = D * pi * pi;
    for (int k = 0; k < D; ++k) u *= std::sin(pi * x[k]);
    return u;
  };
  b.problem.dirichlet.push_back({all_faces<D>(), {}, nullptr});
  b.exact = [](const double* x, double* u, double* g) {
    double s[D], c[D];
    for (int k = 0; k < D; ++k) {
      s[k] = std::sin(pi * x[k]);
      c[k] = std::cos(pi * x[k]);
    }
    u[0] = 1.0;
    for (int k = 0; k < D; ++k) {
      u[0] *= s[k];
      g[k] = pi;
      for (int l = 0; l < D; ++l) g[k] *= (l == k ? c[l] : s[l]);
    }
  };
  return b;
}

std::vector<double> unit_box_laplace_eigenvalues(int dim, int count) {
  require(dim == 2 || dim == 3, "iga: box eigenvalues for 2 or 3 dimensions");
  require(count >= 1, "iga: at least one eigenvalue");
  // Every eigenvalue below (count + dim)^2 pi^2 has all indices below count + dim, so enumerating them is enough.
  const int m = count + dim;
  std::vector<double> v;
  for (int i = 1; i <= m; ++i)
    for (int j = 1; j <= m; ++j)
      for (int k = 1; k <= (dim == 3 ? m : 1); ++k) v.push_back(i * i + j * j + (dim == 3 ? k * k : 0));
  std::sort(v.begin(), v.end());
  v.resize(static_cast<std::size_t>(count));
  for (double& x : v) x *= std::numbers::pi * std::numbers::pi;
  return v;
}

template <int D>
TensorSpline<D> quarter_annulus(double r_in, double r_out, double height) {
  require(0 < r_in && r_in < r_out && height > 0, "iga: quarter annulus needs 0 < r_in < r_out and height > 0");
  std::array<KnotVector, D> knots;
  knots[0] = KnotVector::open_uniform(1, 1);
  knots[1] = KnotVector::open_uniform(2, 1);
  if constexpr (D == 3) knots[2] = KnotVector::open_uniform(1, 1);
  const double s = std::sqrt(0.5);
  const double arc[3][3] = {{1, 0, 1}, {1, 1, s}, {0, 1, 1}};  // unit arc: x, y, weight
  std::vector<double> pts, w;
  for (int k = 0; k < (D == 3 ? 2 : 1); ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) {
        const double r = i == 0 ? r_in : r_out;
        pts.push_back(r * arc[j][0]);
        pts.push_back(r * arc[j][1]);
        if constexpr (D == 3) pts.push_back(k * height);
        w.push_back(arc[j][2]);
      }
  return TensorSpline<D>::from_cartesian(knots, D, pts, w);
}

PoissonBenchmark<2> l_shape(int degree, int elements) {
  const KnotVector ku(1, {0, 0, 0.5, 1, 1}), kv = KnotVector::open_uniform(1, 1);
  const std::vector<double> pts = {1, 0, 0, 0, 0, -1, 1, 1, -1, 1, -1, -1};
  const TensorSpline<2> g = TensorSpline<2>::from_cartesian({ku, kv}, 2, pts);
  PoissonBenchmark<2> b{make_tensor_space(g, degree, elements), {}, {}};
  b.exact = [](const double* x, double* u, double* grad) {
    const double r = std::hypot(x[0], x[1]);
    double theta = std::atan2(x[1], x[0]);
    if (theta < 0) theta += 2 * std::numbers::pi;
    const double a = 2.0 / 3.0;
    u[0] = std::pow(r, a) * std::sin(a * theta);
    if (r == 0) {
      grad[0] = grad[1] = 0;
      return;
    }
    const double ur = a * std::pow(r, a - 1) * std::sin(a * theta), ut = a * std::pow(r, a - 1) * std::cos(a * theta);
    grad[0] = ur * std::cos(theta) - ut * std::sin(theta);
    grad[1] = ur * std::sin(theta) + ut * std::cos(theta);
  };
  auto exact = b.exact;
  b.problem.dirichlet.push_back({all_faces<2>(), {}, [exact](const double* x, double* u) {
                                   double g2[2];
                                   exact(x, u, g2);
                                 }});
  return b;
}

template <int D>
ElasticityBenchmark<D> lame_cylinder(int degree, int elements) {
  const double a = 1, b = 2, p = 1;
  ElasticityBenchmark<D> bm{make_tensor_space(quarter_annulus<D>(a, b, 0.5), degree, elements), {}, {}};
  bm.problem.material = {1000.0, 0.3};
  const ElasticMaterial m = bm.problem.material;
  bm.problem.displacement.push_back({{{1, 0}}, {1}, nullptr});
  bm.problem.displacement.push_back({{{1, 1}}, {0}, nullptr});
  if constexpr (D == 3) bm.problem.displacement.push_back({{{2, 0}, {2, 1}}, {2}, nullptr});
  bm.problem.traction_faces = {{0, 0}};
  bm.problem.traction = [p](const double*, const double* n, double* t) {
    for (int k = 0; k < D; ++k) t[k] = -p * n[k];
  };
  const double A = p * a * a / (b * b - a * a), B = p * a * a * b * b / (b * b - a * a);
  bm.exact = [m, A, B](const double* x, double* u, double* g) {
    const double c = (1 + m.poisson_ratio) / m.youngs_modulus;
    const double r2 = x[0] * x[0] + x[1] * x[1], r = std::sqrt(r2);
    const double ur = c * ((1 - 2 * m.poisson_ratio) * A * r + B / r);
    const double dur = c * ((1 - 2 * m.poisson_ratio) * A - B / r2);
    for (int i = 0; i < D; ++i) {
      u[i] = i < 2 ? ur * x[i] / r : 0.0;
      for (int j = 0; j < D; ++j)
        g[i * D + j] = (i < 2 && j < 2) ? (i == j ? ur / r : 0.0) + (dur - ur / r) * x[i] * x[j] / r2 : 0.0;
    }
  };
  return bm;
}

template ElasticityBenchmark<2> lame_cylinder(int, int);
template ElasticityBenchmark<3> lame_cylinder(int, int);
template PoissonBenchmark<2> sine_box(int, int);
template PoissonBenchmark<3> sine_box(int, int);
template TensorSpline<2> quarter_annulus(double, double, double);
template TensorSpline<3> quarter_annulus(double, double, double);

}  // namespace trivar
