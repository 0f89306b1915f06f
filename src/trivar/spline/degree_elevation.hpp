#pragma once
// Degree elevation of tensor-product splines (exact: the elevated space contains the original). Every knot
// keeps its continuity, so each distinct knot gains one in multiplicity per degree raised.
#include "trivar/spline/knot_refinement.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// Knot vector of degree p+1 with every distinct knot's multiplicity raised by one.
KnotVector elevated_knots(const KnotVector& kv);

// (elevated_knots(kv).size() x kv.size()) matrix E with B_i^p = sum_k E(k, i) B_k^{p+1}, from the identity
// (Prautzsch) B_i^p = 1/(p+1) sum_{j=i}^{i+p+1} B^{p+1}[t_i .. t_{i+p+1} with t_j doubled], each term
// written in the elevated basis by knot insertion.
SparseRowMatrix elevation_matrix(const KnotVector& kv);

// Raises the degree in direction dir by `by` (>= 0).
template <int D>
TensorSpline<D> elevate_degree(const TensorSpline<D>& s, int dir, int by);

// Raises the degree in every direction k by by[k].
template <int D>
TensorSpline<D> elevate_degree(const TensorSpline<D>& s, const Ints<D>& by);

}  // namespace trivar
