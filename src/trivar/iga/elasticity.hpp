#pragma once
// Linear isotropic elasticity -div sigma(u) = f, sigma = lambda tr(eps) I + 2 mu eps, eps = (grad u + grad u^T)/2,
// on a tensor patch: displacement (Dirichlet, per component) and traction (sigma n = t) conditions. In 2-D the
// state is plane strain.
#include <array>
#include <functional>
#include <vector>

#include "trivar/iga/dirichlet.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

struct ElasticMaterial {
  double youngs_modulus = 1.0;
  double poisson_ratio = 0.3;
  double lambda() const;  // Lame's first parameter (plane strain / 3-D)
  double mu() const;      // shear modulus
};

template <int D>
struct ElasticityProblem {
  ElasticMaterial material;
  std::function<void(const double* x, double* f)> body_force;  // D values (null: none)
  std::vector<DirichletCondition<D>> displacement;
  std::vector<Face> traction_faces;
  std::function<void(const double* x, const double* normal, double* t)> traction;  // D values (null: free)
};

// Displacement coefficients component-major (component c of basis function I at c * num_basis() + I).
// Throws trivar::Error for E <= 0 or nu outside (-1, 0.5).
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
