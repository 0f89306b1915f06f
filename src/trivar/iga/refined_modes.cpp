#include "trivar/iga/refined_modes.hpp"

#include <chrono>

#include "trivar/iga/material_check.hpp"
#include "trivar/iga/refined_assembly.hpp"
#include "trivar/iga/refined_elasticity.hpp"
#include "trivar/iga/refined_poisson.hpp"

namespace trivar {

namespace refined_modes {

// The mass integral rho u . v of a field with `components` components (rho from density(x)).
template <int D, class Density>
SparseMatrix mass_matrix(const RefinedSpace<D>& space, int components, int threads, const ElementPartition& part,
                         Density&& density) {
  return assemble_refined_system<D>(
             space, components, threads,
             [&](const RefinedPoint<D>& p, const std::vector<double>&, double dV, Eigen::MatrixXd& M, Eigen::VectorXd&) {
               const Eigen::Index m = static_cast<Eigen::Index>(p.R.size());
               const Eigen::Map<const Eigen::VectorXd> R(p.R.data(), m);
               const Eigen::MatrixXd RR = (density(p.x.data()) * dV) * R * R.transpose();
               for (int c = 0; c < components; ++c) M.block(c * m, c * m, m, m) += RR;
             },
             [](const RefinedElement<D>&, Eigen::VectorXd&) {}, part)
      .A;
}

}  // namespace refined_modes

template <int D>
ModesPencil laplace_pencil(const RefinedSpace<D>& space, const std::vector<Face>& dirichlet, int threads,
                           const ElementPartition& part) {
  ModesPencil p;
  p.K = poisson_system(space, PoissonProblem<D>{}, threads, part).A;
  p.M = refined_modes::mass_matrix<D>(space, 1, threads, part, [](const double*) { return 1.0; });
  p.fixed = refined_fixed_dofs(space, 1, {{dirichlet, {}, nullptr}});
  return p;
}

template <int D>
ModesPencil elastic_pencil(const RefinedSpace<D>& space, const ElasticityProblem<D>& problem, int threads,
                           const ElementPartition& part) {
  ElasticityProblem<D> unloaded = problem;
  unloaded.body_force = nullptr;
  unloaded.traction = nullptr;
  ModesPencil p;
  p.K = elasticity_system(space, unloaded, threads, part).A;
  // The stiffness checked every material met at its quadrature points, which the mass shares.
  p.M = refined_modes::mass_matrix<D>(space, D, threads, part,
                                      [&](const double* x) { return problem.material_of(0, x).density; });
  std::vector<DirichletCondition<D>> zero = problem.displacement;
  for (DirichletCondition<D>& c : zero) c.value = nullptr;
  p.fixed = refined_fixed_dofs(space, D, zero);
  return p;
}

template <int D>
ModesResult laplace_modes(const RefinedSpace<D>& space, const std::vector<Face>& dirichlet, int count, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const ModesPencil p = laplace_pencil(space, dirichlet, threads);
  return timed_lowest_modes(t0, p.K, p.M, p.fixed, count, 0.0);
}

template <int D>
ModesResult elastic_modes(const RefinedSpace<D>& space, const ElasticityProblem<D>& problem, int count, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const ModesPencil p = elastic_pencil(space, problem, threads);
  return timed_lowest_modes(t0, p.K, p.M, p.fixed, count, rigid_body_shift(p.K.diagonal().sum(), p.M.diagonal().sum()));
}

#define TRIVAR_INSTANTIATE(D)                                                                                     \
  template ModesPencil laplace_pencil(const RefinedSpace<D>&, const std::vector<Face>&, int, const ElementPartition&); \
  template ModesPencil elastic_pencil(const RefinedSpace<D>&, const ElasticityProblem<D>&, int,                     \
                                      const ElementPartition&);                                                    \
  template ModesResult laplace_modes(const RefinedSpace<D>&, const std::vector<Face>&, int, int);                   \
  template ModesResult elastic_modes(const RefinedSpace<D>&, const ElasticityProblem<D>&, int, int);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
