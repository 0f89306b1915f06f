#pragma once
// A hierarchical spline of either parametric dimension, for file readers and writers and the CLI; algorithms
// stay templated on D and std::visit dispatches.
#include <variant>

#include "trivar/hier/hierarchical_spline.hpp"

namespace trivar {

using AnyHierarchicalSpline = std::variant<HierarchicalSpline<2>, HierarchicalSpline<3>>;

}  // namespace trivar
