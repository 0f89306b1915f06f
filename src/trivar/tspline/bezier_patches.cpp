#include "trivar/tspline/bezier_patches.hpp"

namespace trivar {

std::vector<TensorSpline<2>> bezier_patches(const TSplineSurface& surface) {
  std::vector<TensorSpline<2>> out;
  out.reserve(surface.bezier_elements().size());
  for (const BezierElement<2>& e : surface.bezier_elements()) {
    std::array<KnotVector, 2> knots;
    for (int k = 0; k < 2; ++k) {
      const int p = e.degrees[k];
      std::vector<double> t(static_cast<std::size_t>(2 * (p + 1)), e.domain.lo[k]);
      std::fill(t.begin() + p + 1, t.end(), e.domain.hi[k]);
      knots[static_cast<std::size_t>(k)] = KnotVector(p, std::move(t));
    }
    out.emplace_back(knots, 3, true, e.coefs);
  }
  return out;
}

}  // namespace trivar
