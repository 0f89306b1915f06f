#pragma once
// Dorfler (bulk) marking for adaptive refinement: given per-element error indicators eta_e >= 0 and a fraction
// beta in (0, 1], the smallest set M of elements with sum_{e in M} eta_e^2 >= beta * sum_e eta_e^2 (the squared
// indicators add up to the squared error estimate). Elements are taken largest indicator first, ties by lower
// id, so the set is deterministic; the sums run in that order, so beta = 1 marks every element with eta_e > 0.
#include <span>
#include <vector>

#include "trivar/lr/lr_spline.hpp"
#include "trivar/lr/refinement.hpp"

namespace trivar {

// The marked element ids, ascending. Throws trivar::Error for beta outside (0, 1] or a negative or non-finite
// indicator (naming its index). All-zero indicators mark nothing.
std::vector<int> dorfler_mark(std::span<const double> indicators, double beta);

// Marks with dorfler_mark (one indicator per element of lr) and refines the marked elements; returns the
// number of rectangles that changed the spline.
template <int D>
int refine_dorfler(LRSpline<D>& lr, std::span<const double> indicators, double beta, const RefineOptions& opts);

}  // namespace trivar
