#pragma once
// Eigenmodes (eigen_modes.hpp) on a locally refined space (LR, HB, THB): Laplace eigenvalues and free vibration
// with the stiffness matrices of refined_poisson and refined_elasticity and the consistent mass matrix of the same
// element loop (refined_assembly.hpp).
#include <vector>

#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/element_partition.hpp"
#include "trivar/iga/refined_space.hpp"

namespace trivar {

// The generalised eigenproblem K x = lambda M x before the conditions are applied.
struct ModesPencil {
  SparseMatrix K, M;
  FixedDofs fixed;
};

// -Laplace u = lambda u, u = 0 on the `dirichlet` faces (Face{dir, side, 0}), natural elsewhere; with a part of
// the elements, their share of K and M only (the fixed dofs are always the whole space's).
template <int D>
ModesPencil laplace_pencil(const RefinedSpace<D>& space, const std::vector<Face>& dirichlet, int threads,
                           const ElementPartition& part = {});
// Free vibration: the elastic stiffness and the density-weighted mass of the problem's material (material_at is
// called with patch 0), its displacement conditions fixing components to zero; loads play no part. Throws
// trivar::Error for an invalid material.
template <int D>
ModesPencil elastic_pencil(const RefinedSpace<D>& space, const ElasticityProblem<D>& problem, int threads,
                           const ElementPartition& part = {});

// As the tensor and multipatch laplace_modes and elastic_modes (eigen_modes.hpp).
template <int D>
ModesResult laplace_modes(const RefinedSpace<D>& space, const std::vector<Face>& dirichlet, int count, int threads = 0);
template <int D>
ModesResult elastic_modes(const RefinedSpace<D>& space, const ElasticityProblem<D>& problem, int count,
                          int threads = 0);

}  // namespace trivar
