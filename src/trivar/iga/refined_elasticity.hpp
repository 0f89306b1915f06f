#pragma once
// Linear elasticity (elasticity.hpp) on a locally refined space (LR, HB, THB): the element loop of refined_poisson with D
// components per function, traction loads on the element sides along the traction faces, displacement
// conditions per component by the Dirichlet projection of refined_boundary.hpp. Errors of the solution:
// error_norms_per_element (refined_poisson.hpp) with D components.
#include <vector>

#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/refined_assembly.hpp"
#include "trivar/iga/refined_space.hpp"

namespace trivar {

// Same conventions as the tensor-patch solve_elasticity: component-major dofs (c * num_basis + I), plane
// strain in 2-D, material_at called with patch 0. Throws trivar::Error for an invalid material (after the
// assembly).
template <int D>
SolveResult solve_elasticity(const RefinedSpace<D>& geometry, const ElasticityProblem<D>& problem, LinearSolver& solver, int threads = 0);

// The stiffness and load of solve_elasticity over a part of the elements, before the displacement conditions.
template <int D>
RefinedSystem elasticity_system(const RefinedSpace<D>& geometry, const ElasticityProblem<D>& problem, int threads,
                                const ElementPartition& part);

}  // namespace trivar
