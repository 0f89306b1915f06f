#include "trivar/model/block.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
TensorSpline<D> make_block(const Ints<D>& degrees, const Ints<D>& elements, const Param<D>& size) {
  std::array<KnotVector, D> kv;
  std::array<std::vector<double>, D> greville;
  for (int k = 0; k < D; ++k) {
    const std::string where = " in direction " + std::to_string(k);
    require(degrees[k] >= 1, "block: degree must be >= 1" + where + ", got " + std::to_string(degrees[k]));
    require(elements[k] >= 1, "block: element count must be >= 1" + where + ", got " + std::to_string(elements[k]));
    require(std::isfinite(size[k]) && size[k] > 0, "block: size must be positive" + where + ", got " + std::to_string(size[k]));
    kv[k] = KnotVector::open_uniform(degrees[k], elements[k]);
    // Greville abscissae reproduce the linear function u exactly, hence x_k = size_k * u_k.
    greville[k] = kv[k].greville();
  }
  std::size_t n = 1;
  for (int k = 0; k < D; ++k) n *= static_cast<std::size_t>(kv[k].size());
  std::vector<double> pts(n * 3, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t rest = i;  // u fastest
    for (int k = 0; k < D; ++k) {
      const std::size_t nk = static_cast<std::size_t>(kv[k].size());
      pts[i * 3 + k] = size[k] * greville[k][rest % nk];
      rest /= nk;
    }
  }
  return TensorSpline<D>::from_cartesian(std::move(kv), 3, pts);
}

TensorSpline<2> make_rectangle_profile(const Param<2>& heights, const Param<2>& radii, const Ints<2>& degrees,
                                       const Ints<2>& elements) {
  const auto [z0, z1] = heights;
  const auto [r0, r1] = radii;
  require(std::isfinite(z0) && std::isfinite(z1) && z0 < z1,
          "rectangle profile: heights must satisfy z0 < z1, got " + std::to_string(z0) + " " + std::to_string(z1));
  require(std::isfinite(r0) && std::isfinite(r1) && r0 < r1,
          "rectangle profile: radii must satisfy r0 < r1, got " + std::to_string(r0) + " " + std::to_string(r1));
  TensorSpline<2> s = make_block<2>(degrees, elements, {z1 - z0, r1 - r0});
  // The block (axial, radial, 0) lies in the xy-plane; map it to (radius, 0, height).
  for (int i = 0; i < s.num_coefs(); ++i) {
    double* c = s.coefs().data() + static_cast<std::size_t>(i) * 3;
    const double axial = c[0], radial = c[1];
    c[0] = r0 + radial;
    c[1] = 0;
    c[2] = z0 + axial;
  }
  return s;
}

template TensorSpline<1> make_block<1>(const Ints<1>&, const Ints<1>&, const Param<1>&);
template TensorSpline<2> make_block<2>(const Ints<2>&, const Ints<2>&, const Param<2>&);
template TensorSpline<3> make_block<3>(const Ints<3>&, const Ints<3>&, const Param<3>&);

}  // namespace trivar
