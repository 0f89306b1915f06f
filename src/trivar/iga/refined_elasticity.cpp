#include "trivar/iga/refined_elasticity.hpp"

#include <chrono>

#include "trivar/iga/refined_assembly.hpp"
#include "trivar/iga/refined_boundary.hpp"
#include "trivar/iga/material_check.hpp"
#include "trivar/iga/refined_poisson.hpp"

namespace trivar {

template <int D>
RefinedSystem elasticity_system(const RefinedSpace<D>& g, const ElasticityProblem<D>& problem, int threads,
                                const ElementPartition& part) {
  MaterialCheck check;
  RefinedSystem system = assemble_refined_system<D>(
      g, D, threads,
      [&](const RefinedPoint<D>& p, const std::vector<double>& grad, double dV, Eigen::MatrixXd& K, Eigen::VectorXd& b) {
        const Eigen::Index m = static_cast<Eigen::Index>(p.R.size());
        const ElasticMaterial mat = check(problem.material_of(0, p.x.data()), 0);
        const double lambda = mat.lambda() * dV, mu = mat.mu() * dV;
        const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, D, Eigen::RowMajor>> G(grad.data(), m, D);
        const Eigen::MatrixXd GG = G * G.transpose();
        // Block (c, d) of a(u, v) for v = R_I e_c, u = R_J e_d (see elastic_stiffness):
        // lambda d_c R_I d_d R_J + mu d_d R_I d_c R_J + mu delta_cd grad R_I . grad R_J.
        for (int c = 0; c < D; ++c)
          for (int d = 0; d < D; ++d) {
            auto B = K.block(c * m, d * m, m, m);
            B.noalias() += lambda * G.col(c) * G.col(d).transpose() + mu * G.col(d) * G.col(c).transpose();
            if (c == d) B += mu * GG;
          }
        if (problem.body_force) {
          double f[D];
          problem.body_force(p.x.data(), f);
          const Eigen::Map<const Eigen::VectorXd> R(p.R.data(), m);
          for (int c = 0; c < D; ++c) b.segment(c * m, m) += (f[c] * dV) * R;
        }
      },
      [&](const RefinedElement<D>& el, Eigen::VectorXd& b) {
        if (problem.traction) add_side_loads<D>(g, el, problem.traction_faces, D, problem.traction, b);
      },
      part);
  check.report();
  return system;
}

template <int D>
SolveResult solve_elasticity(const RefinedSpace<D>& g, const ElasticityProblem<D>& problem, LinearSolver& solver, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  auto [A, rhs] = elasticity_system(g, problem, threads, {});
  return solve_constrained(A, rhs, refined_fixed_dofs(g, D, problem.displacement), solver, t0);
}

#define TRIVAR_INSTANTIATE(D)                                                                                  \
  template RefinedSystem elasticity_system(const RefinedSpace<D>&, const ElasticityProblem<D>&, int,             \
                                           const ElementPartition&);                                            \
  template SolveResult solve_elasticity(const RefinedSpace<D>&, \
                                        const ElasticityProblem<D>&, LinearSolver&, int);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
