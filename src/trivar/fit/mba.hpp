#pragma once
// Multilevel B-spline approximation (MBA; Lee, Wolberg and Shin 1997) on the B-splines of an LR spline, as SINTEF's
// LRSurfApprox uses it: no linear system, one pass over the points per refinement level. Each point x_i with
// residual r_i = f_i - s(x_i) asks every B-spline j that is non-zero there for the coefficient
//   phi_ij = w_ij r_i / sum_k w_ik^2    (w_ij = gamma_j B_j(x_i), the scaled B-spline's value),
// the smallest correction that interpolates r_i by those B-splines alone; B-spline j takes the weighted mean
//   delta_j = sum_i w_ij^2 phi_ij / sum_i w_ij^2
// of its points' wishes (0 where it holds no point). Levels add up: after refinement the fitted function is kept
// exactly (re-expressed in the finer B-splines) and the next pass fits what is left of the residual, so the finer
// B-splines only model the detail the coarser ones missed. Costs O(points x B-splines per element) per level.
#include <span>
#include <vector>

#include "trivar/fit/least_squares.hpp"

namespace trivar {

// `passes` MBA passes, each fitting what the last left: adds the corrections to `coefs` (num_basis * data.dim,
// B-spline-major) and subtracts their values from `residuals` (data.size() * data.dim, point-major, f - s on
// entry), so `residuals` stays f - s exactly.
template <int D>
void mba_update(const LRSpline<D>& lr, const ScatteredData<D>& data, const PointsByElement& where,
                std::span<double> coefs, std::span<double> residuals, int passes = 1, int threads = 1);

}  // namespace trivar
