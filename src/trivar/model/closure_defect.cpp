#include "trivar/model/closure_defect.hpp"

#include <cmath>

#include "trivar/core/box.hpp"
#include "trivar/model/trimmed_integral.hpp"
#include "trivar/spline/measure.hpp"

namespace trivar {

namespace {

// Relative rounding of the area vector of a closed boundary: the quadrature aims at 1e-12 per trimming-curve
// span against its face's scale; the faces' terms cancel in the sum.
constexpr double kRounding = 1e-10;

}  // namespace

ClosureDefect closure_defect(const TrimmedBoundary& b) {
  ClosureDefect d;
  d.area_vector = trimmed_area_vector(b);
  d.norm = std::hypot(d.area_vector[0], d.area_vector[1], d.area_vector[2]);
  d.area = surface_area(b.mesh);
  d.relative = d.area > 0 ? d.norm / d.area : 0;
  Box<3> box = Box<3>::empty();
  for (const auto& v : b.mesh.vertices) box.extend(v.data());
  d.volume_uncertainty = b.mesh.vertices.empty() ? 0 : d.norm * box.diagonal();
  d.allowance = kRounding * d.area;
  for (const TrimEdge& e : b.edges)
    // The edge's arc length (4 Gauss points per span: it only scales the allowance).
    if (e.tolerance > 0 && e.curve.num_coefs() > 0) d.allowance += 2 * e.tolerance * measure(e.curve, 4, 1);
  return d;
}

}  // namespace trivar
