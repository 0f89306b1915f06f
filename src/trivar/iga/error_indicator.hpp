#pragma once
// Residual-based a-posteriori error indicator for the Poisson problem on locally refined spaces (Babuska-Rheinboldt /
// Verfurth): per element K
//   eta_K^2 = h_K^2 ||f + lap u_h||_K^2 + 1/2 sum over interior sides S of K of h_K ||[du_h/dn]||_S^2
//             + sum over Neumann sides S of K of h_K ||g - du_h/dn||_S^2,
// h_K = |K|^(1/D). Neumann sides are the element sides on boundary faces that are not Dirichlet: g is the
// problem's flux on its Neumann faces and 0 on the others (the natural condition the solve imposes there);
// Dirichlet sides contribute nothing. The sum of eta_K^2 bounds the squared energy error from above up to a
// constant. On C^1 spline spaces the jumps vanish except across C^0 lines (repeated knots, kinks of the
// geometry map).
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/refined_space.hpp"
#include "trivar/iga/poisson.hpp"

namespace trivar {

// The element just across side (dir, side) of element `element` at parameter u of that side, and u in that
// element's parameters (`across`; u itself inside one parameter domain, the neighbour block's parameter across an
// interface of a multi-block space): the neighbour of the jump terms.
template <int D>
using ElementAcross = std::function<int(int element, int dir, int side, const Param<D>& u, Param<D>& across)>;

// One indicator eta_K per element. On a multi-block space (RefinedSpace::blocks) the element sides on interfaces
// are interior sides whose neighbours `across` finds (fit/multiblock_adaptive.hpp), the other sides of a block's
// domain are boundary sides of Face{dir, side, block}; on one parameter domain `across` may be null (the space's
// locator). Throws trivar::Error when the problem has a variable conductivity (only k = 1 is supported) or for a
// multi-block space without `across`.
template <int D>
std::vector<double> residual_indicators(const RefinedSpace<D>& geometry, const PoissonProblem<D>& problem, const Eigen::VectorXd& coefs,
                                        int threads = 0, const ElementAcross<D>& across = {});

}  // namespace trivar
