#pragma once
// Knot refinement: one B-spline written in the B-splines of a finer knot sequence. This is the one primitive
// behind the refinement matrix of a knot vector, Bezier extraction (the finer sequence is the element's ends,
// each p + 1 times), the LR split of a B-spline by new mesh lines, and the exact linear-independence test.
//
// If a knot sequence `fine` contains every knot of `local` (p + 2 knots) that lies strictly between
// fine.front() and fine.back(), at least as often as `local`, then on [fine_p, fine_{n}] (n = fine.size() - p - 1)
//   B[local] = sum_{j < n} c_j B[fine_j .. fine_{j+p+1}],
// and on the whole real line when `fine` also holds local's end knots with local's multiplicities (an exact
// split of B[local]). c_j is the blossom of B[local] at fine_{j+1}, ..., fine_{j+p} (Oslo algorithm), evaluated
// on one polynomial piece of B[local] under B[fine_j ..] by de Boor's algorithm with those arguments; so every
// coefficient is a rational function of the knots, computed with convex combinations only.
#include <algorithm>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/knot_vector.hpp"

namespace trivar {

using SparseRowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// c_j above for j < fine.size() - p - 1, into coefs; p = local.size() - 2 in 0..kMaxDegree (not checked here:
// callers hold p + 2 local knots by construction). T is double or an exact number type constructible from
// double (the knots are exact dyadic rationals, so the coefficients are exact in such a type). No allocation.
template <class T>
void express_in(std::span<const double> local, std::span<const double> fine, T* coefs) {
  const int p = static_cast<int>(local.size()) - 2;
  const int n = static_cast<int>(fine.size()) - p - 1;
  // local padded with p copies of each end: B[local] is B-spline number p of t, and de Boor's algorithm on any
  // knot interval of t inside the support reads only knots of t.
  double t[3 * kMaxDegree + 2];
  std::fill(t, t + p, local.front());
  std::copy(local.begin(), local.end(), t + p);
  std::fill(t + 2 * p + 2, t + 3 * p + 2, local.back());
  for (int j = 0; j < n; ++j) {
    // A non-empty knot interval of `fine` under B[fine_j ..]: B[local] is one polynomial there.
    int r = j;
    while (r <= j + p && !(fine[static_cast<std::size_t>(r)] < fine[static_cast<std::size_t>(r) + 1])) ++r;
    const double x = r <= j + p ? fine[static_cast<std::size_t>(r)] : local.back();
    if (!(local.front() <= x && x < local.back())) {
      coefs[j] = T(0);
      continue;
    }
    const int span = static_cast<int>(std::upper_bound(t + p, t + 2 * p + 1, x) - t) - 1;  // t[span] <= x < t[span+1]
    T d[kMaxDegree + 1];
    for (int q = 0; q <= p; ++q) d[q] = T(span - p + q == p ? 1 : 0);
    for (int level = 1; level <= p; ++level) {
      const T z(fine[static_cast<std::size_t>(j + level)]);
      for (int q = p; q >= level; --q) {
        const int i = span - p + q;
        const T lo(t[i]);
        const T alpha = (z - lo) / (T(t[i + p + 1 - level]) - lo);
        T mixed = (T(1) - alpha) * d[q - 1] + alpha * d[q];  // a named value: no aliasing in exact types
        d[q] = std::move(mixed);
      }
    }
    coefs[j] = d[p];
  }
}

// The Bernstein coefficients of B[local] on [a, b] (no knot of local strictly inside, a < b): express_in with
// the finer sequence a (p + 1 times), b (p + 1 times). row: p + 1 values.
template <class T>
void bernstein_coefficients(std::span<const double> local, double a, double b, T* row) {
  const std::size_t p1 = local.size() - 1;
  double ends[2 * (kMaxDegree + 1)];
  std::fill(ends, ends + p1, a);
  std::fill(ends + p1, ends + 2 * p1, b);
  express_in<T>(local, std::span<const double>(ends, 2 * p1), row);
}

// One B-spline of degree p on `local` knots (p+2 values) written in the B-splines of the knot vector `to`:
// B[local] = sum_j coefs[j] * B_{first + j}^to. Throws trivar::Error when `to` does not refine `local`.
void express_in(std::span<const double> local, int p, const KnotVector& to, int& first, std::vector<double>& coefs);

// The (to.size() x from.size()) refinement matrix R: B_i^from = sum_k R(k, i) B_k^to.
SparseRowMatrix refinement_matrix(const KnotVector& from, const KnotVector& to);

// `kv` with the given knots inserted (any order; repeated values insert several times).
KnotVector with_knots(const KnotVector& kv, std::span<const double> knots);

}  // namespace trivar
