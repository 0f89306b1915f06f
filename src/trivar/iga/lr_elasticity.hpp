#pragma once
// Linear elasticity (elasticity.hpp) on an LR B-spline space: the element loop of lr_poisson with D
// components per function, traction loads on the element sides along the traction faces, displacement
// conditions per component by the LR Dirichlet projection (lr_boundary.hpp). Errors of the solution:
// error_norms_per_element (lr_poisson.hpp) with D components.
#include <vector>

#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/lr_space.hpp"

namespace trivar {

// Same conventions as the tensor-patch solve_elasticity: component-major dofs (c * num_basis + I), plane
// strain in 2-D, material_at called with patch 0. Throws trivar::Error for an invalid material (after the
// assembly).
template <int D>
SolveResult solve_elasticity(const LRSpline<D>& geometry, const std::vector<LRElementBasis<D>>& elements,
                             const ElasticityProblem<D>& problem, LinearSolver& solver, int threads = 0);

}  // namespace trivar
