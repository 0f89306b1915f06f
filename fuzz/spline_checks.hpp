#pragma once
// What every spline a reader accepts must survive: evaluation with first derivatives at the corners and the
// centre of its domain, and a JSON round trip to the same knots and coefficients. A violation traps.
#include <array>
#include <vector>

#include "trivar/io/json_format.hpp"
#include "trivar/spline/any_spline.hpp"

namespace trivar::fuzz {

// The 2^D corners of a domain (corner < 2^D, bit k set: the upper end in direction k), then its centre
// (corner == 2^D): the points every read spline is evaluated at.
template <int D>
Param<D> corner_or_centre(const Box<D>& dom, int corner) {
  Param<D> u;
  for (int k = 0; k < D; ++k)
    u[k] = corner == (1 << D) ? dom.lo[k] + 0.5 * dom.extent(k) : (corner >> k) & 1 ? dom.hi[k] : dom.lo[k];
  return u;
}

inline void check_spline(const AnySpline& any) {
  std::visit(
      [](const auto& s) {
        constexpr int D = std::decay_t<decltype(s)>::kDim;
        const Box<D> dom = s.domain();
        std::vector<double> out(static_cast<std::size_t>((D + 1) * s.dim()));
        for (int corner = 0; corner <= (1 << D); ++corner) s.eval_derivs(corner_or_centre(dom, corner), 1, out.data());
        // Knots, weights and Cartesian points come back exactly; the homogeneous coefficients are rebuilt
        // from them, so only the knot vectors are compared bit for bit here.
        const AnySpline back = io::spline_from_json(io::to_json(AnySpline(s)), "round trip");
        if (!(std::get<std::decay_t<decltype(s)>>(back).knot_vectors() == s.knot_vectors())) __builtin_trap();
      },
      any);
}

}  // namespace trivar::fuzz
