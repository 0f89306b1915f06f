#include "trivar/spline/degree_elevation.hpp"

#include <algorithm>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/tensor_map.hpp"

namespace trivar {

KnotVector elevated_knots(const KnotVector& kv) {
  std::vector<double> t;
  const auto u = kv.unique();
  const auto m = kv.multiplicities();
  for (std::size_t i = 0; i < u.size(); ++i) t.insert(t.end(), m[i] + 1, u[i]);
  return KnotVector(kv.degree() + 1, std::move(t));
}

SparseRowMatrix elevation_matrix(const KnotVector& kv) {
  const int p = kv.degree();
  const KnotVector to = elevated_knots(kv);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> local(p + 3), c;
  int first = 0;
  for (int i = 0; i < kv.size(); ++i) {
    for (int j = 0; j <= p + 1; ++j) {
      std::copy(kv.data() + i, kv.data() + i + p + 2, local.begin());
      local.insert(local.begin() + j, kv[i + j]);
      local.resize(p + 3);
      express_in(local, p + 1, to, first, c);
      for (int k = 0; k < static_cast<int>(c.size()); ++k)
        if (c[k] != 0.0) entries.emplace_back(first + k, i, c[k] / (p + 1));
    }
  }
  // setFromTriplets sums duplicate entries, which is exactly the sum over j.
  SparseRowMatrix E(to.size(), kv.size());
  E.setFromTriplets(entries.begin(), entries.end());
  return E;
}

template <int D>
TensorSpline<D> elevate_degree(const TensorSpline<D>& s, int dir, int by) {
  require(dir >= 0 && dir < D, "degree elevation: direction " + std::to_string(dir) + " out of range");
  require(by >= 0, "degree elevation: cannot elevate by " + std::to_string(by));
  require(s.degree(dir) + by <= kMaxDegree, "degree elevation: degree " + std::to_string(s.degree(dir) + by) +
                                                " exceeds the maximum " + std::to_string(kMaxDegree));
  TensorSpline<D> r = s;
  for (int b = 0; b < by; ++b) {
    const KnotVector& kv = r.knots(dir);
    r = apply_along(r, dir, elevated_knots(kv), elevation_matrix(kv));
  }
  return r;
}

template <int D>
TensorSpline<D> elevate_degree(const TensorSpline<D>& s, const Ints<D>& by) {
  TensorSpline<D> r = s;
  for (int k = 0; k < D; ++k) r = elevate_degree(r, k, by[k]);
  return r;
}

#define TRIVAR_INSTANTIATE(D)                                                       \
  template TensorSpline<D> elevate_degree(const TensorSpline<D>&, int, int); \
  template TensorSpline<D> elevate_degree(const TensorSpline<D>&, const Ints<D>&);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
