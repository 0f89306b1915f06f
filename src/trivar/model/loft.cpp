#include "trivar/model/loft.hpp"

#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/compatibility.hpp"

namespace trivar {

namespace {

void check_sections(std::size_t count, int degree) {
  require(count >= 2, "loft: needs at least 2 sections, got " + std::to_string(count));
  require(degree >= 1 && static_cast<std::size_t>(degree) < count,
          "loft: degree " + std::to_string(degree) + " must be in [1, " + std::to_string(count - 1) + "] for " +
              std::to_string(count) + " sections");
}

template <int E>
TensorSpline<E + 1> interpolate(const std::vector<TensorSpline<E>>& c, const std::vector<double>& params, int degree) {
  const int n = static_cast<int>(c.size());
  std::vector<double> t(static_cast<std::size_t>(degree) + 1, 0.0);
  for (int j = 1; j + degree < n; ++j) {
    double sum = 0;
    for (int i = j; i < j + degree; ++i) sum += params[i];
    t.push_back(sum / degree);
  }
  t.insert(t.end(), static_cast<std::size_t>(degree) + 1, 1.0);
  KnotVector kv(degree, std::move(t));

  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  std::vector<double> N(static_cast<std::size_t>(degree) + 1);
  for (int j = 0; j < n; ++j) {
    const int s = kv.find_span(params[j]);
    basis_values(kv, s, params[j], N.data());
    for (int r = 0; r <= degree; ++r) A(j, s - degree + r) = N[r];
  }
  const auto width = static_cast<Eigen::Index>(c[0].coefs().size());
  Eigen::MatrixXd rhs(n, width);
  for (int j = 0; j < n; ++j)
    rhs.row(j) = Eigen::Map<const Eigen::RowVectorXd>(c[j].coefs().data(), width);
  // Schoenberg-Whitney holds for averaged knots, so A is non-singular; LU with pivoting is robust for the
  // small, banded systems that occur here.
  const Eigen::MatrixXd X = A.partialPivLu().solve(rhs);
  if (c[0].is_rational()) {
    const int stride = c[0].stride();
    for (Eigen::Index col = stride - 1; col < width; col += stride)
      for (int k = 0; k < n; ++k)
        require(X(k, col) > 0, [&] {
          return "loft: interpolated weight " + std::to_string(X(k, col)) + " at section layer " + std::to_string(k) +
                 " is not positive; the sections' weights vary too much for degree " + std::to_string(degree);
        });
  }

  // The lofting direction is the slowest in the control grid: row k of X is layer k.
  std::vector<double> h(static_cast<std::size_t>(n) * static_cast<std::size_t>(width));
  for (int k = 0; k < n; ++k)
    Eigen::Map<Eigen::RowVectorXd>(h.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(width), width) =
        X.row(k);
  std::array<KnotVector, E + 1> knots;
  for (int k = 0; k < E; ++k) knots[k] = c[0].knots(k);
  knots[E] = std::move(kv);
  return TensorSpline<E + 1>(std::move(knots), c[0].dim(), c[0].is_rational(), std::move(h));
}

}  // namespace

template <int D>
TensorSpline<D> loft(const std::vector<TensorSpline<D - 1>>& sections, const std::vector<double>& params,
                     int degree) {
  static_assert(D == 2 || D == 3, "loft makes surfaces from curves and volumes from surfaces");
  check_sections(sections.size(), degree);
  require(params.size() == sections.size(), "loft: " + std::to_string(params.size()) + " parameters for " +
                                                std::to_string(sections.size()) + " sections");
  require(params.front() == 0.0 && params.back() == 1.0, "loft: parameters must run from 0 to 1");
  for (std::size_t j = 1; j < params.size(); ++j)
    require(params[j] > params[j - 1], [&] { return "loft: parameter " + std::to_string(j) + " is not increasing"; });
  return interpolate(make_compatible(sections), params, degree);
}

template <int D>
TensorSpline<D> loft(const std::vector<TensorSpline<D - 1>>& sections, int degree) {
  static_assert(D == 2 || D == 3, "loft makes surfaces from curves and volumes from surfaces");
  check_sections(sections.size(), degree);
  const auto c = make_compatible(sections);
  const int dim = c[0].dim(), n = c[0].num_coefs();
  std::vector<double> params{0.0};
  std::vector<double> x(dim), y(dim);
  for (std::size_t j = 1; j < c.size(); ++j) {
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      c[j - 1].control_point(i, x.data());
      c[j].control_point(i, y.data());
      double d2 = 0;
      for (int d = 0; d < dim; ++d) d2 += (x[d] - y[d]) * (x[d] - y[d]);
      sum += std::sqrt(d2);
    }
    require(sum > 0, [&] {
      return "loft: sections " + std::to_string(j - 1) + " and " + std::to_string(j) + " coincide";
    });
    params.push_back(params.back() + sum / n);
  }
  const double total = params.back();
  for (double& p : params) p /= total;
  params.back() = 1.0;
  return interpolate(c, params, degree);
}

template TensorSpline<2> loft<2>(const std::vector<TensorSpline<1>>&, const std::vector<double>&, int);
template TensorSpline<3> loft<3>(const std::vector<TensorSpline<2>>&, const std::vector<double>&, int);
template TensorSpline<2> loft<2>(const std::vector<TensorSpline<1>>&, int);
template TensorSpline<3> loft<3>(const std::vector<TensorSpline<2>>&, int);

}  // namespace trivar
