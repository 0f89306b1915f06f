#pragma once
// The basis of a tensor space at one parameter: the (p+1)^D functions R_I that can be non-zero there, their
// parametric gradients, and the geometry (point, Jacobian). The per-point counterpart of the sum-factorised
// grid evaluation, for boundary integrals and point queries where there is no grid to share work over.
#include <array>
#include <vector>

#include "trivar/iga/tensor_space.hpp"

namespace trivar {

template <int D>
struct PointBasis {
  std::vector<int> ids;       // global basis indices, u fastest
  std::vector<double> R;      // R_I
  std::vector<double> dR;     // [l * D + a]: d R_I / d u_a
  std::array<double, D> x{};  // geometry point
  std::array<std::array<double, D>, D> J{};  // J[c][a] = d x_c / d u_a
};

template <int D>
void point_basis(const TensorSpace<D>& space, const Param<D>& u, PointBasis<D>& out);

}  // namespace trivar
