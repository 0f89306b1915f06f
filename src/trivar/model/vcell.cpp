#include "trivar/model/vcell.hpp"

#include <cmath>

namespace trivar {

VCell::VCell(TensorSpline<3> geometry, std::shared_ptr<const TrimmedSolid> trim) : VCell(std::move(geometry)) {
  require(trim != nullptr, "V-cell: a trimmed cell needs its trimming boundary");
  const TensorSpline<3>& g = trivariates_.front();
  const Box<3> dom = g.domain();
  const double scale = dom.diagonal();
  const std::array<std::vector<double>, 3> gr{g.knots(0).greville(), g.knots(1).greville(), g.knots(2).greville()};
  for (int i = 0; i < g.num_coefs(); ++i) {
    const auto idx = g.multi_index(i);
    double x[3];
    g.control_point(i, x);
    for (int k = 0; k < 3; ++k)
      require(std::abs(x[k] - gr[k][idx[k]]) <= 1e-12 * scale && std::abs(g.weight(i) - 1) <= 1e-12,
              "V-cell: a trimmed cell's trivariate must be the identity on a box (control point " +
                  std::to_string(i) + " is not at its Greville point)");
  }
  const Box<3>& tb = trim->bounding_box();
  for (int k = 0; k < 3; ++k)
    require(tb.lo[k] >= dom.lo[k] - 1e-9 * scale && tb.hi[k] <= dom.hi[k] + 1e-9 * scale,
            "V-cell: the trimming boundary reaches outside the cell's box in direction " + std::to_string(k));
  trim_ = std::move(trim);
}

TensorSpline<3> identity_box(const Box<3>& b) {
  std::vector<double> pts;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) pts.insert(pts.end(), {i ? b.hi[0] : b.lo[0], j ? b.hi[1] : b.lo[1], k ? b.hi[2] : b.lo[2]});
  return TensorSpline<3>::from_cartesian({KnotVector::open_uniform(1, 1, b.lo[0], b.hi[0]),
                                          KnotVector::open_uniform(1, 1, b.lo[1], b.hi[1]),
                                          KnotVector::open_uniform(1, 1, b.lo[2], b.hi[2])},
                                         3, pts);
}

bool VCell::contains_param(const Param<3>& u) const {
  if (!geometry().domain().contains(u)) return false;
  return !trim_ || trim_->contains(u);
}

}  // namespace trivar
