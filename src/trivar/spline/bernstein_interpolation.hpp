#pragma once
// Bezier coefficients from values at the equally spaced nodes i / p of an element (tensor product, per
// direction the (p+1) x (p+1) Bernstein collocation matrix inverted once). With weights it interpolates in the
// rational Bernstein space of the element, f = sum_j f_j w_j B_j / sum_j w_j B_j: f W is interpolated as a
// polynomial and divided by the weights. So a function that lies in that space (a spline field on the
// geometry's knots and weights, restricted to the element) is reproduced exactly, and any other function is
// interpolated at the nodes. A constant stays exactly that constant.
#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "trivar/core/box.hpp"

namespace trivar {

template <int D>
class BernsteinInterpolation {
 public:
  // degrees >= 1 in every direction; throws trivar::Error otherwise.
  explicit BernsteinInterpolation(const Ints<D>& degrees);

  // values: prod(p_k + 1) nodes (first direction fastest) of `components` values each, replaced by the Bezier
  // coefficients; weights: one per node (the element's Bezier weights) or empty for a polynomial element.
  // Reuses internal buffers, so one object serves one thread.
  void apply(std::span<double> values, int components, std::span<const double> weights);

 private:
  // out = (A_0 x ... x A_{D-1}) in along every direction, `components` values per node.
  void tensor_apply(const std::array<Eigen::MatrixXd, D>& a, std::span<double> data, int components);

  Ints<D> p_{};
  int nodes_ = 1;
  std::array<Eigen::MatrixXd, D> collocation_, inverse_;
  std::vector<double> scratch_, denominator_, first_;
  std::vector<char> constant_;
};

extern template class BernsteinInterpolation<1>;
extern template class BernsteinInterpolation<2>;
extern template class BernsteinInterpolation<3>;

}  // namespace trivar
