#include "trivar/spline/iso_extraction.hpp"

#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

template <int D>
TensorSpline<D - 1> iso_extract(const TensorSpline<D>& s, int dir, double u) {
  require(dir >= 0 && dir < D, "iso extraction: direction " + std::to_string(dir) + " out of range");
  const KnotVector& kv = s.knots(dir);
  require(u >= kv.start() && u <= kv.end(), "iso extraction: parameter " + std::to_string(u) +
                                                " is outside the domain [" + std::to_string(kv.start()) + ", " +
                                                std::to_string(kv.end()) + "] of direction " + std::to_string(dir));
  const int p = kv.degree();
  const int span = kv.find_span(u);
  double N[kMaxDegree + 1];
  basis_values(kv.data(), p, span, u, N);

  std::size_t pre = static_cast<std::size_t>(s.stride()), post = 1;
  for (int k = 0; k < dir; ++k) pre *= s.count(k);
  for (int k = dir + 1; k < D; ++k) post *= s.count(k);
  const std::size_t n = kv.size();
  std::vector<double> c(pre * post, 0.0);
  const double* src = s.coefs().data();
  for (std::size_t o = 0; o < post; ++o)
    for (int i = 0; i <= p; ++i) {
      const double* x = src + (static_cast<std::size_t>(span - p + i) + n * o) * pre;
      double* y = c.data() + o * pre;
      for (std::size_t j = 0; j < pre; ++j) y[j] += N[i] * x[j];
    }
  std::array<KnotVector, D - 1> knots;
  for (int k = 0, m = 0; k < D; ++k)
    if (k != dir) knots[m++] = s.knots(k);
  return TensorSpline<D - 1>(std::move(knots), s.dim(), s.is_rational(), std::move(c));
}

template <int D>
std::array<TensorSpline<D - 1>, 2 * D> boundary_faces(const TensorSpline<D>& s) {
  std::array<TensorSpline<D - 1>, 2 * D> faces;
  for (int k = 0; k < D; ++k) {
    faces[2 * k] = iso_extract(s, k, s.knots(k).start());
    faces[2 * k + 1] = iso_extract(s, k, s.knots(k).end());
  }
  return faces;
}

#define TRIVAR_INSTANTIATE(D)                                                        \
  template TensorSpline<D - 1> iso_extract(const TensorSpline<D>&, int, double); \
  template std::array<TensorSpline<D - 1>, 2 * D> boundary_faces(const TensorSpline<D>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
