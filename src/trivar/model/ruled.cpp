#include "trivar/model/ruled.hpp"

#include "trivar/spline/compatibility.hpp"

namespace trivar {

template <int D>
TensorSpline<D> ruled(const TensorSpline<D - 1>& a, const TensorSpline<D - 1>& b) {
  static_assert(D == 2 || D == 3, "ruled makes surfaces from curves and volumes from surfaces");
  const auto c = make_compatible<D - 1>({a, b});
  std::array<KnotVector, D> kv;
  for (int k = 0; k + 1 < D; ++k) kv[k] = c[0].knots(k);
  kv[D - 1] = KnotVector(1, {0, 0, 1, 1});
  // The ruling direction is the slowest in the control grid: the two nets are its two layers.
  std::vector<double> h(c[0].coefs().begin(), c[0].coefs().end());
  h.insert(h.end(), c[1].coefs().begin(), c[1].coefs().end());
  return TensorSpline<D>(std::move(kv), c[0].dim(), c[0].is_rational(), std::move(h));
}

template TensorSpline<2> ruled<2>(const TensorSpline<1>&, const TensorSpline<1>&);
template TensorSpline<3> ruled<3>(const TensorSpline<2>&, const TensorSpline<2>&);

}  // namespace trivar
