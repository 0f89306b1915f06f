#include "trivar/model/extrude.hpp"

#include <string>

#include "trivar/core/error.hpp"
#include "trivar/model/ruled.hpp"
#include "trivar/spline/affine_transform.hpp"

namespace trivar {

template <int D>
TensorSpline<D> extrude(const TensorSpline<D - 1>& base, const Eigen::VectorXd& direction) {
  static_assert(D == 2 || D == 3, "extrude makes surfaces from curves and volumes from surfaces");
  require(direction.size() == base.dim() && direction.allFinite(),
          "extrude: direction must have " + std::to_string(base.dim()) + " finite entries (the base's dimension)");
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(base.dim(), base.dim());
  return ruled<D>(base, transform(base, identity, direction));
}

template <int D>
TensorSpline<D> extrude_along(const TensorSpline<D - 1>& base, const TensorSpline<1>& path) {
  static_assert(D == 2 || D == 3, "extrude_along makes surfaces from curves and volumes from surfaces");
  const int dim = base.dim();
  require(path.dim() == dim, "extrude_along: path has control dimension " + std::to_string(path.dim()) +
                                 ", base has " + std::to_string(dim));
  std::vector<double> origin(dim);
  path.eval({path.knots(0).start()}, origin.data());

  const bool rational = base.is_rational() || path.is_rational();
  const int stride = dim + (rational ? 1 : 0);
  const int nb = base.num_coefs(), np = path.num_coefs();
  std::vector<double> h(static_cast<std::size_t>(nb) * np * stride);
  std::vector<double> p(dim), q(dim);
  for (int k = 0; k < np; ++k) {
    path.control_point(k, q.data());
    for (int i = 0; i < nb; ++i) {
      base.control_point(i, p.data());
      const double w = base.weight(i) * path.weight(k);
      double* c = h.data() + (static_cast<std::size_t>(k) * nb + i) * stride;
      for (int d = 0; d < dim; ++d) c[d] = w * (p[d] + q[d] - origin[d]);
      if (rational) c[dim] = w;
    }
  }
  std::array<KnotVector, D> kv;
  for (int k = 0; k + 1 < D; ++k) kv[k] = base.knots(k);
  kv[D - 1] = path.knots(0);
  return TensorSpline<D>(std::move(kv), dim, rational, std::move(h));
}

template TensorSpline<2> extrude<2>(const TensorSpline<1>&, const Eigen::VectorXd&);
template TensorSpline<3> extrude<3>(const TensorSpline<2>&, const Eigen::VectorXd&);
template TensorSpline<2> extrude_along<2>(const TensorSpline<1>&, const TensorSpline<1>&);
template TensorSpline<3> extrude_along<3>(const TensorSpline<2>&, const TensorSpline<1>&);

}  // namespace trivar
