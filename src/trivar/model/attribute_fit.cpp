#include "trivar/model/attribute_fit.hpp"

#include <Eigen/LU>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

Attribute fit_attribute(const Box<3>& box, int components, const FieldFit& fit,
                        const std::function<void(const std::array<double, 3>&, double*)>& f) {
  require(fit.degree >= 1 && fit.degree <= 7, "attribute fit: degree " + std::to_string(fit.degree) + " outside [1, 7]");
  require(fit.elements >= 1 && fit.elements <= 64,
          "attribute fit: " + std::to_string(fit.elements) + " elements per direction, outside [1, 64]");
  require(components >= 1, "attribute fit: no components");
  for (int k = 0; k < 3; ++k)
    require(box.hi[k] > box.lo[k], "attribute fit: the box is empty in direction " + std::to_string(k));
  std::array<KnotVector, 3> knots;
  std::array<std::vector<double>, 3> greville;
  std::array<Eigen::PartialPivLU<Eigen::MatrixXd>, 3> lu;
  for (int d = 0; d < 3; ++d) {
    knots[d] = KnotVector::open_uniform(fit.degree, fit.elements, box.lo[d], box.hi[d]);
    greville[d] = knots[d].greville();
    const int n = knots[d].size();
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    double N[kMaxDegree + 1];
    for (int i = 0; i < n; ++i) {
      const int s = knots[d].find_span(greville[d][i]);
      basis_values(knots[d].data(), fit.degree, s, greville[d][i], N);
      for (int r = 0; r <= fit.degree; ++r) a(i, s - fit.degree + r) = N[r];
    }
    lu[d].compute(a);
  }
  const int n0 = knots[0].size(), n1 = knots[1].size(), n2 = knots[2].size();
  const int total = n0 * n1 * n2;
  std::vector<double> c(static_cast<std::size_t>(total) * components);
#pragma omp parallel for schedule(dynamic)
  for (int l = 0; l < total; ++l) {
    const int i = l % n0, j = (l / n0) % n1, k = l / (n0 * n1);
    f({greville[0][i], greville[1][j], greville[2][k]}, c.data() + static_cast<std::size_t>(l) * components);
  }
  // Solve along each direction in turn (the collocation matrix is the Kronecker product of the three).
  const std::array<int, 3> n{n0, n1, n2}, stride{1, n0, n0 * n1};
  for (int d = 0; d < 3; ++d) {
    const int lines = total / n[d];
#pragma omp parallel for
    for (int line = 0; line < lines; ++line) {
      // The line's first grid index: all indices but direction d from `line`.
      int rest = line, base = 0;
      for (int e = 0; e < 3; ++e) {
        if (e == d) continue;
        base += (rest % n[e]) * stride[e];
        rest /= n[e];
      }
      Eigen::MatrixXd rhs(n[d], components);
      for (int q = 0; q < n[d]; ++q)
        for (int m = 0; m < components; ++m)
          rhs(q, m) = c[static_cast<std::size_t>(base + q * stride[d]) * components + m];
      const Eigen::MatrixXd x = lu[d].solve(rhs);
      for (int q = 0; q < n[d]; ++q)
        for (int m = 0; m < components; ++m)
          c[static_cast<std::size_t>(base + q * stride[d]) * components + m] = x(q, m);
    }
  }
  return Attribute::field(TensorSpline<3>(knots, components, false, std::move(c)));
}

}  // namespace trivar
