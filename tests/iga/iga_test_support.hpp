#pragma once
// Shared geometry for the analysis tests: a box whose control points and weights are perturbed, so the map is
// a genuinely curved NURBS with a valid Jacobian, and the identity on its boundary faces' planes is kept; and
// a local refinement of an LR space near a corner, so LR tests run on spaces that are not tensor spaces.
#include <random>
#include <vector>

#include "trivar/iga/tensor_space.hpp"
#include "trivar/lr/refinement.hpp"

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

// FULLSPAN refinement of the elements whose centre lies in the parameter box [lo, lo + fraction * extent]
// (per direction): the new mesh lines end inside the domain (T-junctions), so the space is not a tensor one.
template <int D>
void refine_corner(trivar::LRSpline<D>& lr, double fraction) {
  std::vector<int> marked;
  const trivar::Box<D>& dom = lr.domain();
  for (int e = 0; e < lr.num_elements(); ++e) {
    bool inside = true;
    for (int k = 0; k < D; ++k)
      inside = inside && lr.element(e).center()[k] < dom.lo[k] + fraction * dom.extent(k);
    if (inside) marked.push_back(e);
  }
  trivar::refine_elements(lr, std::span<const int>(marked), trivar::RefineOptions{});
}

// True when some mesh rectangle does not span the whole domain across its direction.
template <int D>
bool has_t_junction(const trivar::LRSpline<D>& lr) {
  for (const auto& r : lr.mesh())
    for (int k = 0; k < D; ++k)
      if (k != r.dir && (r.extent.lo[k] > lr.domain().lo[k] || r.extent.hi[k] < lr.domain().hi[k])) return true;
  return false;
}

}  // namespace iga_test
