#pragma once
// An attribute given as a function of model points, made a spline field on a box by interpolation: what a
// Boolean stores where the attribute of a result cell has no closed form among the attribute kinds (a blend
// by distance to the operands' boundaries, an operand's field or parametric formula carried to a cell with a
// new parameter box).
#include <array>
#include <functional>

#include "trivar/core/box.hpp"
#include "trivar/model/attribute.hpp"

namespace trivar {

struct FieldFit {
  int degree = 3;
  int elements = 6;  // per direction
};

// Attribute::field of `components` values on `box`, degree and uniform elements per direction as `fit` says,
// interpolating f at the tensor grid of Greville points (one 1-D collocation solve per grid line and
// direction). f(x, out) writes components values at model point x; it is called from several threads. For a
// trimmed cell whose trivariate is the identity on `box`, the field's parameters are model coordinates.
// Throws trivar::Error for an empty box, degree outside [1, 7] or elements outside [1, 64].
Attribute fit_attribute(const Box<3>& box, int components, const FieldFit& fit,
                        const std::function<void(const std::array<double, 3>&, double*)>& f);

}  // namespace trivar
