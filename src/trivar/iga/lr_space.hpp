#pragma once
// Analysis on LR B-spline surfaces and volumes: the basis functions are the LR spline's scaled B-splines
// gamma_i B_i, written on each element in its tensor Bernstein basis by Bezier extraction
// (lr_bezier_extraction.hpp). Every element evaluation goes through that operator: values, first and second
// parametric derivatives of the active functions and of the geometry map at any point of the element.
// The geometry must be polynomial (LR NURBS are not supported by the analysis yet).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "trivar/lr/lr_spline.hpp"

namespace trivar {

template <int D>
struct LRElementBasis {
  std::vector<int> ids;  // active B-splines (element_support)
  Eigen::MatrixXd C;     // extraction operator: ids.size() x prod(p_k + 1), rows include gamma
  Box<D> box;
};

// Every element's extraction (threads as parallel_for). Throws trivar::Error for a rational or non-D-dim
// geometry.
template <int D>
std::vector<LRElementBasis<D>> lr_element_bases(const LRSpline<D>& geometry, int threads = 0);

// The active functions and the geometry at parameter u of an element (u inside its box, boundary included).
template <int D>
struct LRPoint {
  std::vector<double> R;    // values
  std::vector<double> dR;   // [l * D + a]: d/du_a
  std::vector<double> d2R;  // [(l * D + a) * D + b]: d2/du_a du_b
  std::array<double, D> x{};
  std::array<std::array<double, D>, D> J{};               // J[c][a] = dx_c/du_a
  std::array<std::array<std::array<double, D>, D>, D> H{};  // H[c][a][b] = d2x_c/du_a du_b
};

template <int D>
void lr_point(const LRSpline<D>& geometry, const LRElementBasis<D>& element, const Param<D>& u, LRPoint<D>& out);

// Physical gradients grad[l * D + k] = dR_l/dx_k of the active functions at p; returns |det J|.
template <int D>
double physical_gradients(const LRPoint<D>& p, std::vector<double>& grad);

// Functions non-zero on the side (dir, side) of the domain: local knots clamped (p + 1 equal) at that side.
template <int D>
std::vector<int> lr_face_basis(const LRSpline<D>& geometry, int dir, int side);

}  // namespace trivar
