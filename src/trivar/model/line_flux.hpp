#pragma once
// LineFlux: Gauss sums of F(S) (S_u x S_v)_x (or of S_u x S_v itself) along the parameter lines of one direction
// of a surface, the inner integral of the exact-boundary quadrature (trimmed_integral), asked for at every point
// of every trimming loop.
//
// A general surface evaluation with first derivatives at each node recomputes both directions' B-splines, by
// the generic derivative triangle for degree pairs without a fixed-degree kernel (most rational faces: the
// quadratic-by-linear cylinders, the blends). Along one line the fixed direction's B-splines (value and
// derivative) are the same at every node: the surface is contracted with them once per line into two
// homogeneous curves (the points and the cross derivatives), and the running direction's B-splines and their
// derivatives at the rule's nodes are tabulated once per face for whole spans (computed, for the degrees 1 to
// 3 unrolled, only on the partial spans at a line's ends). A node then costs three (p + 1)-term sums of
// homogeneous points, the quotient rule and one cross-product component.
#include <array>
#include <functional>
#include <vector>

#include "trivar/core/gauss_legendre.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

class LineFlux {
public:
  // `dir`: the running direction (0: u, 1: v). The surface (control dimension 3) and the rule are kept by
  // reference. One object per thread (it keeps the contracted curves between calls).
  LineFlux(const TensorSpline<2>& s, int dir, const QuadratureRule& rule);

  // sum over the running direction's knot spans cut to [lo, hi] of the rule's sum of F(S) (S_u x S_v)_x, on
  // the line whose other parameter is t (clamped to the domain, as evaluation does); lo <= hi inside the
  // domain. `linear`: F(x) = x[0] - shift (the volume), `general`: any F.
  double linear(double t, double lo, double hi, double shift) const;
  double general(double t, double lo, double hi, const std::function<double(const std::array<double, 3>&)>& F) const;
  // The same sums of S_u x S_v (the area vector's density), its three components in one pass.
  std::array<double, 3> area(double t, double lo, double hi) const;

private:
  // Calls add(weight, S, S_u x S_v) at every node.
  template <int P, bool kRational, class Acc>
  void sum(double t, double lo, double hi, const Acc& add) const;
  template <class Acc>
  void dispatch(double t, double lo, double hi, const Acc& add) const;

  const TensorSpline<2>& s_;
  const QuadratureRule& rule_;
  int dir_;
  std::vector<double> breaks_;  // the running direction's distinct knots
  std::vector<int> span_;       // per break interval: its knot span index
  // Per break interval and node: the running B-splines (p + 1) and their derivatives (p + 1).
  std::vector<double> table_;
  mutable std::vector<double> points_, cross_;  // the contracted homogeneous curves' control values
};

}  // namespace trivar
