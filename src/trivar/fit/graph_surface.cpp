#include "trivar/fit/graph_surface.hpp"

#include "trivar/core/error.hpp"

namespace trivar {

LRSpline<2> graph_surface(const LRSpline<2>& height, const LRSpline<2>& parameters) {
  require(height.dim() == 1 && !height.is_rational(),
          "fit: a graph surface needs a polynomial height field of one component, not " + std::to_string(height.dim()));
  require(parameters.dim() == 2 && !parameters.is_rational() && parameters.num_basis() == height.num_basis(),
          "fit: a graph surface needs the identity map on the height field's " + std::to_string(height.num_basis()) +
              " B-splines");
  std::vector<LRBSpline<2>> basis(height.basis_functions().begin(), height.basis_functions().end());
  for (std::size_t i = 0; i < basis.size(); ++i) {
    const LRBSpline<2>& id = parameters.basis_functions()[i];
    // Both splines order their B-splines by knots alone, so equal knots at every id mean the same basis.
    require(id.knots == basis[i].knots, "fit: a graph surface needs the identity map on the same B-splines");
    basis[i].coef = {id.coef[0], id.coef[1], basis[i].coef[0]};
  }
  return LRSpline<2>(height.degrees(), 3, false, std::move(basis), height.mesh());
}

}  // namespace trivar
