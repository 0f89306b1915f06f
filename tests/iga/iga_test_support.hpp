#pragma once
// Shared geometry for the analysis tests: a box whose control points and weights are perturbed, so the map is
// a genuinely curved NURBS with a valid Jacobian, and the identity on its boundary faces' planes is kept.
#include <random>

#include "trivar/iga/tensor_space.hpp"

namespace iga_test {

// Unit box, degree p, n elements per direction; interior control points moved by up to 0.15 / n per
// coordinate and every weight drawn from [0.8, 1.25] when rational.
template <int D>
trivar::TensorSpline<D> distorted_box(int p, int n, bool rational, unsigned seed) {
  using namespace trivar;
  Param<D> lo, hi;
  lo.fill(0.0);
  hi.fill(1.0);
  const TensorSpline<D> box = box_geometry<D>(lo, hi, p, n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> move(-0.15 / n, 0.15 / n), weight(0.8, 1.25);
  std::vector<double> pts(box.coefs().begin(), box.coefs().end()), w;
  for (int i = 0; i < box.num_coefs(); ++i) {
    const auto m = box.multi_index(i);
    bool interior = true;
    for (int k = 0; k < D; ++k) interior = interior && m[k] > 0 && m[k] < box.count(k) - 1;
    for (int k = 0; k < D; ++k)
      if (interior) pts[static_cast<std::size_t>(i * D + k)] += move(rng);
    if (rational) w.push_back(weight(rng));
  }
  return TensorSpline<D>::from_cartesian(box.knot_vectors(), D, pts, w);
}

}  // namespace iga_test
