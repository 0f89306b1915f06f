#include "trivar/spline/tensor_map.hpp"

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
TensorSpline<D> apply_along(const TensorSpline<D>& s, int dir, KnotVector new_knots, const SparseRowMatrix& R) {
  require(dir >= 0 && dir < D, "spline: direction " + std::to_string(dir) + " out of range");
  require(R.cols() == s.count(dir) && R.rows() == new_knots.size(), "spline: linear map has the wrong shape");
  std::size_t pre = static_cast<std::size_t>(s.stride()), post = 1;
  for (int k = 0; k < dir; ++k) pre *= s.count(k);
  for (int k = dir + 1; k < D; ++k) post *= s.count(k);
  const std::size_t n_old = s.count(dir), n_new = new_knots.size();
  std::vector<double> c(pre * n_new * post, 0.0);
  const double* src = s.coefs().data();
  for (std::size_t o = 0; o < post; ++o)
    for (std::size_t k = 0; k < n_new; ++k) {
      double* d = c.data() + (k + n_new * o) * pre;
      for (SparseRowMatrix::InnerIterator it(R, static_cast<Eigen::Index>(k)); it; ++it) {
        const double* x = src + (static_cast<std::size_t>(it.col()) + n_old * o) * pre;
        const double r = it.value();
        for (std::size_t j = 0; j < pre; ++j) d[j] += r * x[j];
      }
    }
  auto knots = s.knot_vectors();
  knots[dir] = std::move(new_knots);
  return TensorSpline<D>(std::move(knots), s.dim(), s.is_rational(), std::move(c));
}

template TensorSpline<1> apply_along(const TensorSpline<1>&, int, KnotVector, const SparseRowMatrix&);
template TensorSpline<2> apply_along(const TensorSpline<2>&, int, KnotVector, const SparseRowMatrix&);
template TensorSpline<3> apply_along(const TensorSpline<3>&, int, KnotVector, const SparseRowMatrix&);

}  // namespace trivar
