#pragma once
// Knot insertion and h-refinement of tensor-product splines. The geometry is unchanged (exactly, up to
// rounding); only the basis is refined.
#include <span>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// Inserts the given knots (any order, repeats allowed) in direction dir.
template <int D>
TensorSpline<D> insert_knots(const TensorSpline<D>& s, int dir, std::span<const double> knots);

// Inserts u `times` times in direction dir (Boehm).
template <int D>
TensorSpline<D> insert_knot(const TensorSpline<D>& s, int dir, double u, int times = 1);

// Uniform h-refinement: every element is split into n[k] equal parts in direction k (n[k] >= 1).
template <int D>
TensorSpline<D> refine_uniform(const TensorSpline<D>& s, const Ints<D>& n);

// The knots that split every non-empty interval of kv into n equal parts (n - 1 knots per interval).
std::vector<double> uniform_refinement_knots(const KnotVector& kv, int n);

}  // namespace trivar
