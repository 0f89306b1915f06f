#pragma once
// The Poisson problem (poisson.hpp) on an LR B-spline space: element loop over the LR mesh with the element
// extraction operators, dense element matrices, strong Dirichlet conditions by L2 projection onto the
// functions clamped at the Dirichlet sides, L2 / H1 errors per element.
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/lr_space.hpp"
#include "trivar/iga/poisson.hpp"

namespace trivar {

// Neumann data is not supported on LR spaces yet (throws trivar::Error when given).
template <int D>
SolveResult solve_poisson(const LRSpline<D>& geometry, const std::vector<LRElementBasis<D>>& elements,
                          const PoissonProblem<D>& problem, LinearSolver& solver, int threads = 0);

// Squared L2 and H1-seminorm errors per element (sums give the squares of the global errors).
template <int D>
void error_norms_per_element(const LRSpline<D>& geometry, const std::vector<LRElementBasis<D>>& elements,
                             const Eigen::VectorXd& coefs, const ExactSolution<D>& exact, std::vector<double>& l2,
                             std::vector<double>& h1, int threads = 0);

// Physical side measure and outward normal at a point of the side (dir, side) of an element box:
// Nanson's formula as in boundary_integral.hpp. weight = |det J| |J^{-T} e_dir| (parametric measure not
// included).
template <int D>
void side_measure(const std::array<std::array<double, D>, D>& J, int dir, int side, double& weight,
                  std::array<double, D>& normal);

// Gauss points (n per direction) of a box, or of one side of it (dir >= 0: u_dir fixed at the side): calls
// body(u, weight) with the parametric weight.
template <int D, class Body>
void for_each_gauss_point(const Box<D>& box, int n, int dir, int side, Body&& body);

}  // namespace trivar

#include "trivar/core/gauss_legendre.hpp"

namespace trivar {

template <int D, class Body>
void for_each_gauss_point(const Box<D>& box, int n, int dir, int side, Body&& body) {
  const QuadratureRule rule = gauss_legendre(n);
  int count = 1;
  for (int k = 0; k < D; ++k)
    if (k != dir) count *= n;
  for (int q = 0; q < count; ++q) {
    Param<D> u;
    double w = 1;
    for (int k = 0, r = q; k < D; ++k) {
      if (k == dir) {
        u[k] = side == 0 ? box.lo[k] : box.hi[k];
        continue;
      }
      const int i = r % n;
      r /= n;
      u[k] = box.lo[k] + box.extent(k) * rule.nodes[static_cast<std::size_t>(i)];
      w *= box.extent(k) * rule.weights[static_cast<std::size_t>(i)];
    }
    body(u, w);
  }
}

}  // namespace trivar
