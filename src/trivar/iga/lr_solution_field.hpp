#pragma once
// A discrete solution on an LR space as an LR spline: sum_i c_i gamma_i B_i over the geometry's own B-splines
// and mesh, so it is evaluated, written or refined like any LR spline (the LR counterpart of
// solution_field.hpp). Its element ids are the geometry's when the geometry has the mesh's own element order
// (LRSpline.hpp; not when a reader renumbered them): look elements up by parameter otherwise.
#include <Eigen/Core>

#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// coefs: one value per B-spline of the geometry (the coefficients of an LR solve). Throws trivar::Error for a
// rational geometry or a size mismatch.
template <int D>
LRSpline<D> lr_solution_field(const LRSpline<D>& geometry, const Eigen::VectorXd& coefs);

}  // namespace trivar
