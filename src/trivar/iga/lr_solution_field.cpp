#include "trivar/iga/lr_solution_field.hpp"

#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
LRSpline<D> lr_solution_field(const LRSpline<D>& g, const Eigen::VectorXd& coefs) {
  require(!g.is_rational(), "iga: LR solution fields need a polynomial geometry");
  require(coefs.size() == g.num_basis(), "iga: " + std::to_string(coefs.size()) + " coefficients for " +
                                             std::to_string(g.num_basis()) + " LR B-splines");
  std::vector<LRBSpline<D>> basis(g.basis_functions().begin(), g.basis_functions().end());
  for (std::size_t i = 0; i < basis.size(); ++i) basis[i].coef = {coefs[static_cast<Eigen::Index>(i)]};
  // The B-splines are already in id order (it depends on the knots only), so coefficient i stays with id i.
  return LRSpline<D>(g.degrees(), 1, false, std::move(basis), g.mesh());
}

template LRSpline<2> lr_solution_field(const LRSpline<2>&, const Eigen::VectorXd&);
template LRSpline<3> lr_solution_field(const LRSpline<3>&, const Eigen::VectorXd&);

}  // namespace trivar
