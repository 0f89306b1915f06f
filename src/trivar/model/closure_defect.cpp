#include "trivar/model/closure_defect.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/gauss_legendre.hpp"
#include "trivar/model/trimmed_integral.hpp"

namespace trivar {

namespace {

// Relative rounding of the area vector of a closed boundary: the quadrature aims at 1e-12 per trimming-curve
// span against its face's scale; the faces' terms cancel in the sum.
constexpr double kRounding = 1e-10;

// Arc length of a 3D curve, Gauss-Legendre on each knot span; it only scales the allowance, so a few points
// per span do (the spline layer has no length of its own).
double curve_length(const TensorSpline<1>& c) {
  static const QuadratureRule rule = gauss_legendre(4);
  const std::vector<double> br = c.knots(0).breakpoints();
  double length = 0;
  for (std::size_t s = 0; s + 1 < br.size(); ++s)
    for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
      double d[6];  // point, derivative
      c.eval_derivs({br[s] + rule.nodes[q] * (br[s + 1] - br[s])}, 1, d);
      length += rule.weights[q] * (br[s + 1] - br[s]) * std::hypot(d[3], d[4], d[5]);
    }
  return length;
}

}  // namespace

ClosureDefect closure_defect(const TrimmedBoundary& b) {
  ClosureDefect d;
  d.area_vector = trimmed_area_vector(b);
  d.norm = std::hypot(d.area_vector[0], d.area_vector[1], d.area_vector[2]);
  d.area = surface_area(b.mesh);
  d.relative = d.area > 0 ? d.norm / d.area : 0;
  std::array<double, 3> lo{}, hi{};
  if (!b.mesh.vertices.empty()) lo = hi = b.mesh.vertices.front();
  for (const auto& v : b.mesh.vertices)
    for (std::size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  d.volume_uncertainty = d.norm * std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  d.allowance = kRounding * d.area;
  for (const TrimEdge& e : b.edges)
    if (e.tolerance > 0 && e.curve.num_coefs() > 0) d.allowance += 2 * e.tolerance * curve_length(e.curve);
  return d;
}

}  // namespace trivar
