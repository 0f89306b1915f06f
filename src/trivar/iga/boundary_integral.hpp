#pragma once
// Integrals over one face of a tensor patch (Neumann and traction loads, the L2 projection of Dirichlet data):
// Gauss quadrature on the face's elements, surface measure and outward normal by Nanson's formula
// dS n = det(J) J^{-T} N dA (N the parametric normal), which holds in 2-D and 3-D alike.
#include <array>
#include <functional>
#include <span>

#include "trivar/iga/tensor_space.hpp"

namespace trivar {

template <int D>
struct FacePoint {
  std::array<double, D> x{};       // point on the face
  std::array<double, D> normal{};  // outward unit normal
  double weight = 0;               // surface measure times quadrature weight
  std::span<const int> ids;        // basis functions of the patch that may be non-zero there
  std::span<const double> values;  // their values
};

// Surface measure and outward unit normal at a point of the parametric side (dir, side) from the Jacobian
// J[c][a] = dx_c/du_a there: weight = |det J| |J^{-T} e_dir|, per unit parametric (D-1)-measure. Shared by
// the tensor and the LR face integrals, so both use one orientation convention.
template <int D>
void side_measure(const std::array<std::array<double, D>, D>& J, int dir, int side, double& weight,
                  std::array<double, D>& normal);

// Calls body at each of `points`^(D-1) Gauss points of every element of the face (serially).
template <int D>
void integrate_face(const TensorSpace<D>& space, const Face& face, int points,
                    const std::function<void(const FacePoint<D>&)>& body);

}  // namespace trivar
