#pragma once
// L2 and H1-seminorm errors of a discrete field on a tensor patch or a multipatch space against an exact
// solution, by Gauss quadrature with p + 2 points per direction (the solution and geometry are evaluated on
// each element's grid by sum factorisation).
#include <functional>

#include <Eigen/Core>

#include "trivar/iga/element_partition.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

struct ErrorNorms {
  double l2 = 0;  // ||u - u_h||_L2
  double h1 = 0;  // |u - u_h|_H1 = ||grad(u - u_h)||_L2
};

// exact(x, u, grad): u = components values, grad[c * D + k] = du_c/dx_k.
template <int D>
using ExactSolution = std::function<void(const double* x, double* u, double* grad)>;

// coefs: per dof, component-major. Deterministic for any thread count (per-element sums added in order). With
// a part of the elements (element_partition.hpp), the norms over those elements only: the parts' squares sum
// to the squares of the whole.
template <int D>
ErrorNorms error_norms(const TensorSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                       const ExactSolution<D>& exact, int threads = 0, const ElementPartition& part = {});
// Over all patches of a multipatch space (coefs on its global dofs).
template <int D>
ErrorNorms error_norms(const MultipatchSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                       const ExactSolution<D>& exact, int threads = 0, const ElementPartition& part = {});

}  // namespace trivar
