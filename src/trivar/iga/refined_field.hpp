#pragma once
// A field on a locally refined space (refined_space.hpp) at a parameter: a solution, a displacement or a mode
// shape given by its coefficients on the space's functions, evaluated on the element containing the parameter.
// What output writers call at their nodes (serial and parallel VTK of refined solutions).
#include <Eigen/Core>

#include "trivar/iga/refined_space.hpp"

namespace trivar {

// Writes `components` values to out; coefs holds them component-major (component c of function i at
// c * num_basis + i).
template <int D>
void refined_field_value(const RefinedSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                         const Param<D>& u, double* out);
// The same on a given element holding u (multi-block spaces, whose parameters are per block).
template <int D>
void refined_field_value(const RefinedSpace<D>& space, int element, const Eigen::VectorXd& coefs, int components,
                         const Param<D>& u, double* out);

}  // namespace trivar
