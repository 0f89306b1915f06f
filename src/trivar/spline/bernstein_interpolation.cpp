#include "trivar/spline/bernstein_interpolation.hpp"

#include <cmath>
#include <string>

#include <Eigen/LU>

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
BernsteinInterpolation<D>::BernsteinInterpolation(const Ints<D>& degrees) : p_(degrees) {
  for (int k = 0; k < D; ++k) {
    const int p = p_[k];
    require(p >= 1, "Bernstein interpolation needs degree >= 1, got " + std::to_string(p));
    nodes_ *= p + 1;
    Eigen::MatrixXd m(p + 1, p + 1);
    for (int i = 0; i <= p; ++i) {
      const double t = static_cast<double>(i) / p;
      double binomial = 1;
      for (int j = 0; j <= p; ++j) {
        m(i, j) = binomial * std::pow(t, j) * std::pow(1 - t, p - j);
        binomial = binomial * (p - j) / (j + 1);
      }
    }
    collocation_[k] = m;
    inverse_[k] = m.inverse();
  }
}

template <int D>
void BernsteinInterpolation<D>::tensor_apply(const std::array<Eigen::MatrixXd, D>& a, std::span<double> data,
                                             int components) {
  scratch_.resize(data.size());
  int stride = components;  // distance between neighbouring nodes along direction k
  for (int k = 0; k < D; ++k) {
    const int n = p_[k] + 1;
    const int lines = static_cast<int>(data.size()) / (n * stride);
    for (int outer = 0; outer < lines; ++outer)
      for (int inner = 0; inner < stride; ++inner) {
        const std::size_t base = static_cast<std::size_t>(outer) * n * stride + inner;
        for (int i = 0; i < n; ++i) {
          double s = 0;
          for (int j = 0; j < n; ++j) s += a[k](i, j) * data[base + static_cast<std::size_t>(j * stride)];
          scratch_[base + static_cast<std::size_t>(i * stride)] = s;
        }
      }
    std::copy(scratch_.begin(), scratch_.end(), data.begin());
    stride *= n;
  }
}

template <int D>
void BernsteinInterpolation<D>::apply(std::span<double> values, int components, std::span<const double> weights) {
  require(values.size() == static_cast<std::size_t>(nodes_) * components && (weights.empty() || weights.size() ==
                                                                              static_cast<std::size_t>(nodes_)),
          "Bernstein interpolation: value or weight count does not match the degrees");
  // A component that is constant on the element keeps its value exactly (its coefficients are that constant;
  // the inverse would reproduce it only up to rounding, and indices or material ids should stay exact).
  constant_.assign(static_cast<std::size_t>(components), 1);
  for (int n = 1; n < nodes_; ++n)
    for (int c = 0; c < components; ++c)
      if (values[static_cast<std::size_t>(n * components + c)] != values[static_cast<std::size_t>(c)]) constant_[c] = 0;
  first_.assign(values.begin(), values.begin() + components);
  if (!weights.empty()) {
    denominator_.assign(weights.begin(), weights.end());
    tensor_apply(collocation_, denominator_, 1);
    for (int n = 0; n < nodes_; ++n)
      for (int c = 0; c < components; ++c) values[static_cast<std::size_t>(n * components + c)] *= denominator_[n];
  }
  tensor_apply(inverse_, values, components);
  for (int n = 0; n < nodes_; ++n)
    for (int c = 0; c < components; ++c) {
      double& v = values[static_cast<std::size_t>(n * components + c)];
      if (constant_[c])
        v = first_[c];
      else if (!weights.empty())
        v /= weights[n];
    }
}

template class BernsteinInterpolation<1>;
template class BernsteinInterpolation<2>;
template class BernsteinInterpolation<3>;

}  // namespace trivar
