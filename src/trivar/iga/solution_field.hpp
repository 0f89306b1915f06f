#pragma once
// A discrete solution as a spline on the patch: sum_I c_I R_I, with the geometry's knots and (for NURBS) its
// weights, so it can be evaluated, written or refined like any other spline field.
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/tensor_space.hpp"

namespace trivar {

template <int D>
struct MultipatchSpace;

// coefs: per dof, component-major, `components` values per basis function.
template <int D>
TensorSpline<D> solution_field(const TensorSpace<D>& space, const Eigen::VectorXd& coefs, int components);

// The solution on every patch of a multipatch space (coefs: per global dof, as above).
template <int D>
std::vector<TensorSpline<D>> solution_fields(const MultipatchSpace<D>& space, const Eigen::VectorXd& coefs,
                                             int components);

}  // namespace trivar
