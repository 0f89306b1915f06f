#pragma once
// Penalised least squares on the space of an LR spline: the coefficients c (num_basis x dim) minimising
//   sum_i |s(x_i) - f_i|^2 + w sum_e (h_e / L)^2 E_e(s),   E_e(s) = integral over element e of
//   sum_{j,k} |d^2 s / du_j du_k|^2 (the thin-plate energy, every component),
// with w = smoothing * N * L^4 / |domain| for N points, L = |domain|^(1/D) and h_e = |e|^(1/D), so `smoothing` is
// dimensionless (the energy weighed as if measured on the unit box with the points' density). The factor
// (h_e / L)^2 keeps the penalty in proportion to the data term as elements shrink: at a kink (a crater rim) the
// energy of a good fit grows like 1/h_e^2 per element, which would otherwise stall the refinement.
//
// The normal equations are assembled per element in its tensor Bernstein basis (a point adds b b^T with b its
// (p+1)^D Bernstein values; the energy is a sum of Kronecker products of three 1-D Bernstein matrices scaled by the
// element's sides), then mapped to the element's B-splines by the extraction operator C (lr_bezier_extraction):
// C (G + w K) C^T. So a point costs one symmetric rank-one update of a (p+1)^D matrix, independent of how many
// B-splines overlap the element. The system is solved by sparse Cholesky (CHOLMOD).
#include <span>
#include <vector>

#include "trivar/fit/scattered_data.hpp"
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// The points of each element: element e holds points[offsets[e] .. offsets[e+1]), ascending.
struct PointsByElement {
  std::vector<int> offsets;
  std::vector<int> points;
};

template <int D>
PointsByElement locate_points(const LRSpline<D>& lr, std::span<const Param<D>> params, int threads = 1);

struct LeastSquaresResult {
  std::vector<double> coefs;   // num_basis * dim, B-spline-major (id order of the LR spline)
  std::vector<double> errors;  // per point, the largest |s(x_i) - f_i| over the components
};

// Fits data.dim components on lr's space (lr's own coefficients are ignored). Throws trivar::Error when the system
// is singular (too few points for the space and smoothing 0).
template <int D>
LeastSquaresResult least_squares_fit(const LRSpline<D>& lr, const ScatteredData<D>& data, const PointsByElement& where,
                                     double smoothing, int threads = 1);

// lr's mesh and B-splines with the given coefficients (num_basis * dim values, B-spline-major).
template <int D>
LRSpline<D> with_coefficients(const LRSpline<D>& lr, int dim, std::span<const double> coefs);

}  // namespace trivar
