#include "trivar/fit/graph_surface.hpp"

#include <numeric>

#include "trivar/core/error.hpp"

namespace trivar {

LRSpline<2> graph_surface(const LRSpline<2>& height) {
  require(height.dim() == 1 && !height.is_rational(),
          "fit: a graph surface needs a polynomial height field of one component, not " + std::to_string(height.dim()));
  std::vector<LRBSpline<2>> basis(height.basis_functions().begin(), height.basis_functions().end());
  for (LRBSpline<2>& b : basis) {
    double g[2];
    for (int k = 0; k < 2; ++k) {
      const std::vector<double>& t = b.knots[static_cast<std::size_t>(k)];
      g[k] = std::accumulate(t.begin() + 1, t.end() - 1, 0.0) / height.degree(k);
    }
    b.coef = {g[0], g[1], b.coef[0]};
  }
  return LRSpline<2>(height.degrees(), 3, false, std::move(basis), height.mesh());
}

}  // namespace trivar
