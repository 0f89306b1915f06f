#pragma once
// Certified validity of a spline map R^D -> R^D (planar surface D = 2, volume D = 3): is det J > 0 on the
// whole parameter domain? Johnen, Remacle, Geuzaine (2013): on each Bezier element det J is itself a
// polynomial (polynomial maps) and is written exactly in Bernstein form; its coefficients bound it from below
// and above, its corner coefficients are its corner values, and de Casteljau subdivision tightens the bounds.
//
// Polynomial map of degrees (p_k): det[S_u, S_v, S_w] of the derivative nets, degree D p_k - 1.
// Rational map: with S^ = (w, w x, ...) homogeneous, N = det[S^, S^_u, S^_v, S^_w] = w^(D+1) det J (degree
// (D+1) p_k - 1), so sign(N) = sign(det J). The bounds reported are bounds of det J itself: with N and
// W = w^(D+1) written at a common degree, det J = sum_i (N_i / W_i) W_i B_i / sum_j W_j B_j and W_i > 0, so
// det J lies between the smallest and largest ratio N_i / W_i (rational convex hull; tighter than
// min N / max w^(D+1), and converging under subdivision). Corner ratios are actual values of det J.
//
// What is certified: min_lower_bound is the smallest coefficient (ratio) over all sub-boxes minus an
// a-priori bound of its floating-point error (first order, from the magnitudes of the Bezier nets and the
// operation counts; see jacobian.cpp), so `valid` is not claimed for a map whose minimum is zero up to
// rounding, e.g. a collapsed face. min_value and `invalid` use corner values as computed in double precision,
// like any evaluation of det J.
#include "trivar/core/box.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

struct JacobianOptions {
  int max_depth = 8;            // subdivision levels per element (each level halves one direction)
  double relative_gap = 1e-3;   // stop refining an element when (upper - lower) <= gap * |upper|
};

template <int D>
struct JacobianReport {
  bool valid = false;    // certified: lower bound of det J > 0 everywhere
  bool invalid = false;  // certified: det J <= 0 attained at `where` (an actual value, not a bound)
  // neither valid nor invalid = undecided after max_depth
  double min_lower_bound = 0;  // certified lower bound of min det J over the domain
  double min_value = 0;        // smallest actual det J value found (upper bound of the minimum)
  Param<D> where{};            // parameter where min_value is attained
  int elements = 0, subdivisions = 0;
};

// Branch and bound per Bezier element (elements in parallel, results independent of the thread count):
// sub-boxes are refined lowest lower bound first, split at the middle of the direction in which the det J
// coefficients vary most, until the element's bound is within relative_gap of its smallest corner value or
// max_depth is reached. min_value is a corner value of some sub-box; on an element boundary where the map is
// only C^0, it is the limit of det J from inside the element it was found in. Requires s.dim() == D (throws
// trivar::Error otherwise).
template <int D>
JacobianReport<D> check_jacobian(const TensorSpline<D>& s, const JacobianOptions& opts = {});

}  // namespace trivar
