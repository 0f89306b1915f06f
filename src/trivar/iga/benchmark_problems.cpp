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

std::vector<double> roller_cube_eigenvalues(const ElasticMaterial& m, int count) {
  require(count >= 1, "iga: at least one eigenvalue");
  const double pi2 = std::numbers::pi * std::numbers::pi, shear = m.mu() / m.density,
               pressure = (m.lambda() + 2 * m.mu()) / m.density;
  // Wave numbers l with every l_k <= L; any other has |l|^2 >= (L + 1)^2, so once the count-th value is below
  // shear pi^2 (L + 1)^2 the list is complete.
  for (int L = 1;; ++L) {
    std::vector<double> v;
    for (int i = 0; i <= L; ++i)
      for (int j = 0; j <= L; ++j)
        for (int k = 0; k <= L; ++k) {
          const int nonzero = (i > 0) + (j > 0) + (k > 0);
          if (nonzero == 0) continue;
          const double l2 = i * i + j * j + k * k;
          v.push_back(pressure * pi2 * l2);
          for (int s = 1; s < nonzero; ++s) v.push_back(shear * pi2 * l2);
        }
    std::sort(v.begin(), v.end());
    if (static_cast<int>(v.size()) >= count && v[static_cast<std::size_t>(count) - 1] <= shear * pi2 * (L + 1) * (L + 1)) {
      v.resize(static_cast<std::size_t>(count));
      return v;
    }
  }
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
    // A point in the removed quadrant is an edge point at the corner moved by rounding (a geometry map evaluated
    // one ulp off y = 0 would give theta = 2 pi, u = -0.87 r^(2/3)): the nearer edge's angle.
    if (x[0] > 0 && x[1] < 0) theta = x[0] > -x[1] ? 0.0 : 1.5 * std::numbers::pi;
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

void kirsch_stress(double T, double a, const double* x, double* sigma) {
  const double r2 = x[0] * x[0] + x[1] * x[1], t = std::atan2(x[1], x[0]);
  const double q2 = a * a / r2, q4 = q2 * q2;
  const double c2 = std::cos(2 * t), c4 = std::cos(4 * t), s2 = std::sin(2 * t), s4 = std::sin(4 * t);
  sigma[0] = T * (1 - q2 * (1.5 * c2 + c4) + 1.5 * q4 * c4);
  sigma[1] = T * (-q2 * (0.5 * c2 - c4) - 1.5 * q4 * c4);
  sigma[2] = T * (-q2 * (0.5 * s2 + s4) + 1.5 * q4 * s4);
}

ElasticityBenchmark<2> plate_with_hole(int degree, int elements) {
  const double a = 1, L = 4, T = 10;
  // Control points: the hole's two 45-degree arcs (middle points at the tangent intersections, weight
  // cos 22.5) and, with the same weights, the outer edges through the corner (a rational curve on a line
  // stays on it), so the ruled patch between them is exact on every boundary.
  const double tn = std::tan(std::numbers::pi / 8), c = std::cos(std::numbers::pi / 8), h = std::sqrt(0.5);
  const double hole[5][2] = {{a, 0}, {a, a * tn}, {a * h, a * h}, {a * tn, a}, {0, a}};
  const double edge[5][2] = {{L, 0}, {L, L * tn}, {L, L}, {L * tn, L}, {0, L}};
  const double weight[5] = {1, c, 1, c, 1};
  std::vector<double> pts, w;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 5; ++i) {
      pts.push_back(j == 0 ? hole[i][0] : edge[i][0]);
      pts.push_back(j == 0 ? hole[i][1] : edge[i][1]);
      w.push_back(weight[i]);
    }
  const TensorSpline<2> plate = TensorSpline<2>::from_cartesian(
      {KnotVector(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}), KnotVector::open_uniform(1, 1)}, 2, pts, w);
  ElasticityBenchmark<2> bm{make_tensor_space(plate, degree, elements), {}, {}};
  bm.problem.material = {1e5, 0.3};
  const ElasticMaterial m = bm.problem.material;
  bm.problem.displacement.push_back({{{0, 0}}, {1}, nullptr});  // y = 0
  bm.problem.displacement.push_back({{{0, 1}}, {0}, nullptr});  // x = 0
  bm.problem.traction_faces = {{1, 1}};
  bm.problem.traction = [T, a](const double* x, const double* n, double* tr) {
    double s[3];
    kirsch_stress(T, a, x, s);
    tr[0] = s[0] * n[0] + s[2] * n[1];
    tr[1] = s[2] * n[0] + s[1] * n[1];
  };
  auto displacement = [T, a, m](const double* x, double* u) {
    const double mu = m.mu(), k = 3 - 4 * m.poisson_ratio;
    const double r = std::hypot(x[0], x[1]), t = std::atan2(x[1], x[0]), q = a / r, f = T * a / (8 * mu);
    u[0] = f * (r / a * (k + 1) * std::cos(t) + 2 * q * ((1 + k) * std::cos(t) + std::cos(3 * t)) -
                2 * q * q * q * std::cos(3 * t));
    u[1] = f * (r / a * (k - 3) * std::sin(t) + 2 * q * ((1 - k) * std::sin(t) + std::sin(3 * t)) -
                2 * q * q * q * std::sin(3 * t));
  };
  // The gradient by central differences of the closed form (step 1e-5 of the plate size: truncation and
  // rounding both near 1e-10 relative, far below the discretisation errors measured with it).
  bm.exact = [displacement](const double* x, double* u, double* g) {
    displacement(x, u);
    const double step = 4e-5;
    for (int j = 0; j < 2; ++j) {
      double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]}, up[2], um[2];
      xp[j] += step;
      xm[j] -= step;
      displacement(xp, up);
      displacement(xm, um);
      for (int i = 0; i < 2; ++i) g[i * 2 + j] = (up[i] - um[i]) / (2 * step);
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
