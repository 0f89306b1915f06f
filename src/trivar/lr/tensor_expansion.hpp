#pragma once
// An LR spline written exactly as a tensor-product spline: the tensor knot vectors hold every knot value of the
// LR B-splines with the largest multiplicity any of them holds, so each LR B-spline's local knots are a
// subsequence of them and it is a combination of the tensor B-splines over its support (knot insertion per
// direction, express_in). For consumers that take tensor splines only (a cell's spline-field attribute, tensor
// file formats); an LR spline that is a tensor spline (no partial mesh lines) comes back with its own basis.
#include <map>
#include <vector>

#include "trivar/lr/lr_spline.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// Throws trivar::Error for a rational LR spline, or (memory_budget) when the tensor spline would not fit in memory.
template <int D>
TensorSpline<D> tensor_expansion(const LRSpline<D>& lr);

// Raises mult[v] to the multiplicity of each value v in the sorted local knot vector t. Over several local knot
// vectors this gives the multiplicities of the smallest knot vector holding each of them as a subsequence.
void raise_knot_multiplicities(const std::vector<double>& t, std::map<double, int>& mult);

}  // namespace trivar
