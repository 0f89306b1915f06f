#pragma once
// Knot refinement as a linear map between spline spaces. If knot vector `to` contains `from` (same degree,
// every knot of `from` present in `to` with at least the same multiplicity), every B-spline of `from` is a
// combination of B-splines of `to`: B_i^from = sum_k R(k, i) B_k^to. The coefficients come from inserting the
// missing knots one at a time into each B-spline's local knot vector (Boehm's rule on p+2 knots), which is
// the Oslo algorithm evaluated column by column and the same split that LR refinement uses.
#include <span>
#include <vector>

#include <Eigen/SparseCore>

#include "trivar/spline/knot_vector.hpp"

namespace trivar {

using SparseRowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// One B-spline of degree p on `local` knots (p+2 values) written in the B-splines of `to`:
// B[local] = sum_j coefs[j] * B_{first + j}^to. Throws trivar::Error when `to` does not refine `local`.
void express_in(std::span<const double> local, int p, const KnotVector& to, int& first, std::vector<double>& coefs);

// The (to.size() x from.size()) refinement matrix R above.
SparseRowMatrix refinement_matrix(const KnotVector& from, const KnotVector& to);

// `kv` with the given knots inserted (any order; repeated values insert several times).
KnotVector with_knots(const KnotVector& kv, std::span<const double> knots);

}  // namespace trivar
