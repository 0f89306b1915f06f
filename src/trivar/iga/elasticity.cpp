#include "trivar/iga/elasticity.hpp"

#include <chrono>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/iga/material_check.hpp"
#include "trivar/iga/multipatch_assembly.hpp"

namespace trivar {

double ElasticMaterial::lambda() const {
  return youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
}

double ElasticMaterial::mu() const { return youngs_modulus / (2 * (1 + poisson_ratio)); }

bool ElasticMaterial::valid() const {
  return youngs_modulus > 0 && poisson_ratio > -1 && poisson_ratio < 0.5 && density > 0;
}

template <int D>
void stress(const ElasticMaterial& m, const double* grad, double* sigma) {
  const double lambda = m.lambda(), mu = m.mu();
  double tr = 0;
  for (int k = 0; k < D; ++k) tr += grad[k * D + k];
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) sigma[i * D + j] = mu * (grad[i * D + j] + grad[j * D + i]) + (i == j ? lambda * tr : 0.0);
}

template <int D>
double von_mises(const ElasticMaterial& m, const double* s) {
  if constexpr (D == 2) {
    const double szz = m.poisson_ratio * (s[0] + s[3]);
    const double d = (s[0] - s[3]) * (s[0] - s[3]) + (s[3] - szz) * (s[3] - szz) + (szz - s[0]) * (szz - s[0]);
    return std::sqrt(0.5 * d + 3 * s[1] * s[1]);
  } else {
    const double d = (s[0] - s[4]) * (s[0] - s[4]) + (s[4] - s[8]) * (s[4] - s[8]) + (s[8] - s[0]) * (s[8] - s[0]);
    return std::sqrt(0.5 * d + 3 * (s[1] * s[1] + s[2] * s[2] + s[5] * s[5]));
  }
}

namespace {

// A form whose coefficients depend on the material at the point only: fill(material, P).
template <int D, class Fill>
SparseMatrix assemble_material_form(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem,
                                    const BilinearForm<D>& shape, Fill fill, int threads,
                                    const ElementPartition& part) {
  MaterialCheck check;
  SparseMatrix A = assemble_matrix<D>(
      space,
      [&](int patch) {
        BilinearForm<D> form = shape;
        form.coefficients = [&, patch](const double* x, double* P) {
          fill(check(problem.material_of(patch, x), patch), P);
        };
        return form;
      },
      threads, part);
  check.report();
  return A;
}

}  // namespace

template <int D>
SparseMatrix elastic_stiffness(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem, int threads,
                               const ElementPartition& part) {
  constexpr int K = D + 1;
  BilinearForm<D> shape;
  shape.components = D;
  // a(u, v) = int lambda div u div v + 2 mu eps(u) : eps(v); for v = R_I e_c, u = R_J e_d:
  // lambda d_c R_I d_d R_J + mu delta_cd grad R_I . grad R_J + mu d_d R_I d_c R_J.
  return assemble_material_form<D>(
      space, problem, shape,
      [](const ElasticMaterial& m, double* P) {
        const double lambda = m.lambda(), mu = m.mu();
        for (int c = 0; c < D; ++c)
          for (int d = 0; d < D; ++d) {
            double* B = P + (c * D + d) * K * K;
            for (int e = 0; e < K * K; ++e) B[e] = 0.0;
            B[(c + 1) * K + (d + 1)] += lambda;
            B[(d + 1) * K + (c + 1)] += mu;
            if (c == d)
              for (int a = 1; a <= D; ++a) B[a * K + a] += mu;
          }
      },
      threads, part);
}

template <int D>
SparseMatrix elastic_mass(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem, int threads,
                          const ElementPartition& part) {
  constexpr int K = D + 1;
  BilinearForm<D> shape;
  shape.components = D;
  shape.value_terms = true;
  shape.gradient_terms = false;
  return assemble_material_form<D>(
      space, problem, shape,
      [](const ElasticMaterial& m, double* P) {
        for (int e = 0; e < D * D * K * K; ++e) P[e] = 0.0;
        for (int c = 0; c < D; ++c) P[(c * D + c) * K * K] = m.density;
      },
      threads, part);
}

template <int D>
SolveResult solve_elasticity(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem,
                             LinearSolver& solver, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  SparseMatrix A = elastic_stiffness(space, problem, threads);
  return solve_loaded(space, A, D, problem.body_force, problem.traction_faces, problem.traction,
                      problem.displacement, solver, t0, threads);
}

template <int D>
SolveResult solve_elasticity(const TensorSpace<D>& space, const ElasticityProblem<D>& problem, LinearSolver& solver,
                             int threads) {
  return solve_elasticity(single_patch_space(space), problem, solver, threads);
}

#define TRIVAR_INSTANTIATE(D)                                                                                      \
  template SparseMatrix elastic_stiffness(const MultipatchSpace<D>&, const ElasticityProblem<D>&, int,            \
                                          const ElementPartition&);                                             \
  template SparseMatrix elastic_mass(const MultipatchSpace<D>&, const ElasticityProblem<D>&, int,                 \
                                     const ElementPartition&);                                                  \
  template SolveResult solve_elasticity(const MultipatchSpace<D>&, const ElasticityProblem<D>&, LinearSolver&, int); \
  template SolveResult solve_elasticity(const TensorSpace<D>&, const ElasticityProblem<D>&, LinearSolver&, int);   \
  template void stress<D>(const ElasticMaterial&, const double*, double*);                                         \
  template double von_mises<D>(const ElasticMaterial&, const double*);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
