#pragma once
// Linear isotropic elasticity -div sigma(u) = f, sigma = lambda tr(eps) I + 2 mu eps, eps = (grad u + grad u^T)/2,
// on a tensor patch or a multipatch space (materials per patch): displacement (Dirichlet, per component) and
// traction (sigma n = t) conditions. In 2-D the state is plane strain.
#include <array>
#include <functional>
#include <vector>

#include "trivar/iga/dirichlet.hpp"
#include "trivar/iga/element_partition.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

struct ElasticMaterial {
  double youngs_modulus = 1.0;
  double poisson_ratio = 0.3;
  double density = 1.0;  // mass per volume: the inertia of free vibration
  double lambda() const;  // Lame's first parameter (plane strain / 3-D)
  double mu() const;      // shear modulus
  bool valid() const;     // E > 0, -1 < nu < 0.5, density > 0
};

template <int D>
struct ElasticityProblem {
  ElasticMaterial material;
  // Material of a patch at a point (per-cell attributes, graded materials); null: `material` everywhere.
  std::function<ElasticMaterial(int patch, const double* x)> material_at;
  std::function<void(const double* x, double* f)> body_force;  // D values (null: none)
  std::vector<DirichletCondition<D>> displacement;
  std::vector<Face> traction_faces;
  std::function<void(const double* x, const double* normal, double* t)> traction;  // D values (null: free)

  ElasticMaterial material_of(int patch, const double* x) const {
    return material_at ? material_at(patch, x) : material;
  }
};

// The stiffness matrix a(u, v) = int sigma(u) : eps(v) and the mass matrix int rho u . v on the global dofs
// (component-major). Throws trivar::Error when a material met at a quadrature point is not valid(). With a part
// of the elements, their share only (multipatch_assembly.hpp).
template <int D>
SparseMatrix elastic_stiffness(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem, int threads = 0,
                               const ElementPartition& part = {});
template <int D>
SparseMatrix elastic_mass(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem, int threads = 0,
                          const ElementPartition& part = {});

// Displacement coefficients component-major (component c of global basis function I at c * num_basis + I).
// Throws trivar::Error for an invalid material (see elastic_stiffness).
template <int D>
SolveResult solve_elasticity(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem,
                             LinearSolver& solver, int threads = 0);
template <int D>
SolveResult solve_elasticity(const TensorSpace<D>& space, const ElasticityProblem<D>& problem, LinearSolver& solver,
                             int threads = 0);

// Stress from a displacement gradient (grad[c * D + k] = du_c/dx_k): sigma[i * D + j].
template <int D>
void stress(const ElasticMaterial& m, const double* grad, double* sigma);

// Von Mises equivalent stress; in 2-D (plane strain) with sigma_zz = nu (sigma_xx + sigma_yy).
template <int D>
double von_mises(const ElasticMaterial& m, const double* sigma);

}  // namespace trivar
