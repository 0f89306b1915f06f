#pragma once
// A tensor-product spline of any parametric dimension, for code that handles curves, surfaces and volumes
// alike (file readers and writers, the CLI). Algorithms stay templated on D; std::visit dispatches.
#include <variant>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

using AnySpline = std::variant<TensorSpline<1>, TensorSpline<2>, TensorSpline<3>>;

inline int parametric_dimension(const AnySpline& s) { return static_cast<int>(s.index()) + 1; }

}  // namespace trivar
