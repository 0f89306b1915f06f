#include "trivar/spline/affine_transform.hpp"

#include <string>

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
TensorSpline<D> transform(const TensorSpline<D>& s, const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  require(A.cols() == s.dim() && A.rows() >= 1 && b.size() == A.rows(),
          "transform: matrix is " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) + " and offset has " +
              std::to_string(b.size()) + " entries; expected m x " + std::to_string(s.dim()) + " and m");
  require(A.allFinite() && b.allFinite(), "transform: matrix or offset has non-finite entries");
  const int m = static_cast<int>(A.rows()), dim = s.dim();
  const int st_out = m + (s.is_rational() ? 1 : 0);
  std::vector<double> c(static_cast<std::size_t>(s.num_coefs()) * st_out);
  for (int l = 0; l < s.num_coefs(); ++l) {
    const Eigen::Map<const Eigen::VectorXd> x(s.coef(l), dim);
    const double w = s.weight(l);
    Eigen::Map<Eigen::VectorXd> y(c.data() + static_cast<std::size_t>(l) * st_out, m);
    y.noalias() = A * x + w * b;
    if (s.is_rational()) c[static_cast<std::size_t>(l) * st_out + m] = w;
  }
  return TensorSpline<D>(s.knot_vectors(), m, s.is_rational(), std::move(c));
}

template TensorSpline<1> transform(const TensorSpline<1>&, const Eigen::MatrixXd&, const Eigen::VectorXd&);
template TensorSpline<2> transform(const TensorSpline<2>&, const Eigen::MatrixXd&, const Eigen::VectorXd&);
template TensorSpline<3> transform(const TensorSpline<3>&, const Eigen::MatrixXd&, const Eigen::VectorXd&);

}  // namespace trivar
