#pragma once
// Bezier extraction (Borden et al. 2011): on every element a B-spline basis is a linear combination of the
// Bernstein polynomials of that element. Per direction this is the extraction operator C^e with
// B_{first+i}(u) = sum_j C^e(i, j) Bernstein_j(u) on element e; for a tensor spline it is the per-element
// Bezier control net (homogeneous when rational), the input of the Jacobian check, point-inversion bounding
// boxes and the quadrature loop.
#include <vector>

#include <Eigen/Core>

#include "trivar/core/box.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// One element of a knot vector: parameter interval, first active B-spline, extraction operator.
struct ElementExtraction {
  double lo = 0, hi = 0;
  int first = 0;          // global index of the first of the p+1 B-splines active on the element
  Eigen::MatrixXd C;      // (p+1) x (p+1): row i = B-spline first+i in the Bernstein basis
};

std::vector<ElementExtraction> extraction_operators(const KnotVector& kv);

// Bezier control net of one element: degrees per direction, (p_k + 1) points per direction u fastest,
// `stride` values per point (dim + 1 when rational, homogeneous).
template <int D>
struct BezierElement {
  Box<D> domain;
  std::array<int, D> degrees{};
  int dim = 0;
  bool rational = false;
  std::vector<double> coefs;
  int stride() const { return dim + (rational ? 1 : 0); }
};

// All elements, u fastest, then v, then w.
template <int D>
std::vector<BezierElement<D>> bezier_elements(const TensorSpline<D>& s);

// Evaluates a Bezier element at a parameter of its domain (de Casteljau-free: Bernstein sums).
template <int D>
void eval_bezier(const BezierElement<D>& e, const Param<D>& u, double* out);

}  // namespace trivar
