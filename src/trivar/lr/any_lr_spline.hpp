#pragma once
// An LR spline of either parametric dimension, for file readers and writers and the CLI; algorithms stay
// templated on D and std::visit dispatches.
#include <variant>

#include "trivar/lr/lr_spline.hpp"

namespace trivar {

using AnyLRSpline = std::variant<LRSpline<2>, LRSpline<3>>;

inline int parametric_dimension(const AnyLRSpline& s) { return static_cast<int>(s.index()) + 2; }

}  // namespace trivar
