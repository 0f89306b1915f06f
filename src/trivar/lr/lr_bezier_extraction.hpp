#pragma once
// Bezier extraction for a collection of scaled tensor-product B-splines (LR, hierarchical, T-splines) over a
// box partition: on an element every B-spline whose support contains it is a polynomial, written in the
// element's tensor Bernstein basis. Also the element / B-spline incidence ("which B-splines live on which
// element") that extraction and the linear-independence tests are built on.
//
// The functions take the collection as spans (degrees, B-splines, elements), so they serve any locally
// refined kind; supports are assumed to be unions of elements (true for minimal-support B-splines of a box
// mesh), so "support contains element" is decided by the element's centre.
#include <span>
#include <vector>

#include <Eigen/Core>

#include "trivar/core/box.hpp"
#include "trivar/lr/incidence.hpp"
#include "trivar/lr/lr_bspline.hpp"
#include "trivar/spline/bezier_extraction.hpp"

namespace trivar {

// For every B-spline, the elements its support contains (the lists element_supports transposes).
template <int D>
Incidence support_elements(std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements, int threads = 0);

// For every element, the B-splines whose support contains it. A k-d tree over the element centres makes the
// cost O(total support size + #basis log #elements); threads as parallel_for (<= 0: all).
template <int D>
Incidence element_supports(std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements, int threads = 0);

// Extraction operator of one element: row r belongs to B-spline ids[r], column j to the tensor Bernstein
// polynomial j of the element (prod (p_k + 1) columns, u fastest), and
//   gamma_i B_i restricted to the element = sum_j C(r, j) Bernstein_j
// (per direction the Bernstein coefficients of bernstein_coefficients, knot_refinement.hpp).
// Rows of a collection that is a partition of unity sum to the all-ones row.
template <int D>
Eigen::MatrixXd extraction_operator(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                                    std::span<const int> ids, const Box<D>& element);

// The element's Bezier control net of the spline sum_i gamma_i B_i c_i: Bezier value j = sum_r C(r, j) c_{ids[r]},
// stride = dim + rational values per point (homogeneous when rational, as the B-spline coefficients).
template <int D>
BezierElement<D> bezier_element(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                                std::span<const int> ids, const Box<D>& element, int dim, bool rational);

// Every element's Bezier net, in the order of `elements`.
template <int D>
std::vector<BezierElement<D>> bezier_elements(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                                              std::span<const Box<D>> elements, int dim, bool rational,
                                              int threads = 0);

}  // namespace trivar
