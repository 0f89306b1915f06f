#include "trivar/tspline/classification.hpp"

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/tspline/knot_rays.hpp"

namespace trivar {

std::vector<TJunctionExtension> t_junction_extensions(const TSpline& ts) {
  const KnotRays rays(ts.image);
  std::vector<TJunctionExtension> out;
  for (int v = 0; v < static_cast<int>(ts.image.vertices.size()); ++v) {
    const TVertex& x = ts.image.vertices[static_cast<std::size_t>(v)];
    int present = 0;
    for (int l : x.links) present += l >= 0;
    if (present != 3) continue;
    for (int d = 0; d < 4; ++d) {
      if (x.links[static_cast<std::size_t>(d)] >= 0) continue;
      const int k = tdir_axis(d), sign = tdir_sign(d);
      const double c[2] = {x.s, x.t};
      const double at = c[k], line = c[1 - k];
      const double next = rays.next(k, sign, at, line);
      double mid[2];
      mid[k] = 0.5 * (at + next);
      mid[1 - k] = line;
      if (next == at || !rays.inside(mid[0], mid[1])) continue;  // a boundary vertex, not a T-junction
      const int p = ts.degrees[static_cast<std::size_t>(k)];
      const auto walk = [&](int dir_sign, int steps) {
        double y = at;
        for (int i = 0; i < steps; ++i) {
          const double z = rays.next(k, dir_sign, y, line);
          double m[2];
          m[k] = 0.5 * (y + z);
          m[1 - k] = line;
          if (z == y || !rays.inside(m[0], m[1])) break;
          y = z;
        }
        return y;
      };
      const double face_end = walk(sign, (p + 1) / 2), edge_end = walk(-sign, (p - 1) / 2);
      out.push_back({v, d, k, line, std::min(face_end, edge_end), std::max(face_end, edge_end)});
    }
  }
  return out;
}

std::string TSplineClass::part42_type() const {
  if (analysis_suitable.value_or(false)) return "ANALYSIS_SUITABLE_T_SPLINE";
  if (semi_standard) return "SEMI_STANDARD_T_SPLINE";
  return "STANDARD_T_SPLINE";
}

TSplineClass classify(const TSpline& ts, const TSplineSurface& surface, bool exact) {
  TSplineClass c;
  const auto ext = t_junction_extensions(ts);
  c.t_junctions = static_cast<int>(ext.size());
  double area = 0;
  for (int f = 0; f < static_cast<int>(ts.image.faces.size()); ++f) {
    const Box<2> b = ts.image.face_box(f);
    area += b.extent(0) * b.extent(1);
  }
  const Box<2> dom = ts.image.domain();
  c.rectangular_domain = std::abs(area - dom.extent(0) * dom.extent(1)) <= 1e-12 * dom.extent(0) * dom.extent(1);
  if (ts.degrees[0] % 2 == 1 && ts.degrees[1] % 2 == 1) {
    for (const auto& a : ext)
      for (const auto& b : ext)
        if (a.axis == 0 && b.axis == 1 && a.lo <= b.line && b.line <= a.hi && b.lo <= a.line && a.line <= b.hi)
          ++c.crossing_extensions;
    c.analysis_suitable = c.crossing_extensions == 0 && c.rectangular_domain;
  }
  constexpr double kTol = 1e-12;
  c.standard = surface.partition_of_unity().max_defect <= kTol;
  c.semi_standard = true;
  for (const auto& e : surface.bezier_elements())
    for (std::size_t j = 3; j < e.coefs.size(); j += 4)
      if (std::abs(e.coefs[j] - 1.0) > kTol) c.semi_standard = false;
  try {
    const PeelingResult peel = peeling_test<2>(surface.degrees(), surface.basis(), surface.elements());
    c.independence = peel.status;
    if (peel.status != Independence::independent && exact)
      c.independence = exact_test<2>(surface.degrees(), surface.basis(), surface.elements()).status;
  } catch (const Error&) {
    c.independence = Independence::not_tested;  // an element without a full polynomial space: no test applies
  }
  return c;
}

}  // namespace trivar
