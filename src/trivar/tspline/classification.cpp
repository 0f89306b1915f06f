#include "trivar/tspline/classification.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/tspline/knot_rays.hpp"

namespace trivar {

std::vector<TJunctionExtension> t_junction_extensions(const TSpline& ts, int* gap_junctions) {
  const KnotRays rays(ts.image);
  std::vector<TJunctionExtension> out;
  // The anchors' extents per axis: a ray along one axis starts at an anchor's coordinate on the other.
  std::array<std::vector<std::array<double, 2>>, 2> anchors;
  for (const TNode& n : ts.connect.nodes) {
    Box<2> b;
    if (n.kind == TAnchorKind::vertex) {
      const TVertex& x = ts.image.vertices[static_cast<std::size_t>(n.anchor)];
      b = {{x.s, x.t}, {x.s, x.t}};
    } else if (n.kind == TAnchorKind::link) {
      b = ts.image.edge_box(ts.image.links[static_cast<std::size_t>(n.anchor)].edge);
    } else {
      b = ts.image.face_box(n.anchor);
    }
    for (std::size_t k = 0; k < 2; ++k) anchors[k].push_back({b.lo[k], b.hi[k]});
  }
  if (gap_junctions) *gap_junctions = 0;
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
      // A gap: the missing edge ends at a vertex that misses the edge back, and no anchor lies strictly between
      // (so no ray crosses the gap: every ray near it meets the two vertices). The blending functions are
      // those of the T-mesh with the edge, which has neither T-junction; their extensions are left out.
      const bool gap = std::any_of(ts.image.vertices.begin(), ts.image.vertices.end(), [&](const TVertex& w) {
        const double wc[2] = {w.s, w.t};
        return wc[k] == next && wc[1 - k] == line && w.links[static_cast<std::size_t>((d + 2) % 4)] < 0;
      }) && std::none_of(anchors[static_cast<std::size_t>(k)].begin(), anchors[static_cast<std::size_t>(k)].end(),
                         [&](const std::array<double, 2>& r) {
                           return r[0] < std::max(at, next) && r[1] > std::min(at, next);
                         });
      if (gap) {
        if (gap_junctions) ++*gap_junctions;
        continue;
      }
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
      // ceil(p / 2) and floor(p / 2) knot lines (Beirao da Veiga et al. 2013; (p + 1) / 2 and (p - 1) / 2 for odd p).
      const double face_end = walk(sign, (p + 1) / 2), edge_end = walk(-sign, p / 2);
      out.push_back({v, d, k, line, std::min(face_end, edge_end), std::max(face_end, edge_end)});
    }
  }
  return out;
}

namespace {

// Whether two local knot vectors are windows of one knot vector (the one's knots from some index on are the
// other's first knots, and the rest lies beyond).
bool windows_of_one(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size();
  for (std::size_t shift = 0; shift < n; ++shift) {
    bool ok = true;
    for (std::size_t i = 0; i + shift < n && ok; ++i) ok = a[i + shift] == b[i];
    if (ok) return true;
  }
  return false;
}

bool overlap(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (windows_of_one(a, b) || windows_of_one(b, a));
}

}  // namespace

DualCompatibility dual_compatibility(const TSplineSurface& surface) {
  DualCompatibility dc;
  const auto basis = surface.basis();
  const Incidence& on = surface.element_supports();
  std::vector<std::pair<int, int>> seen;
  for (int e = 0; e < on.size(); ++e) {
    const auto f = on[e];
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t j = i + 1; j < f.size(); ++j) {
        const int a = std::min(f[i], f[j]), b = std::max(f[i], f[j]);
        const auto& ka = basis[static_cast<std::size_t>(a)].knots;
        const auto& kb = basis[static_cast<std::size_t>(b)].knots;
        if (overlap(ka[0], kb[0]) || overlap(ka[1], kb[1])) continue;
        if (std::find(seen.begin(), seen.end(), std::pair{a, b}) != seen.end()) continue;
        seen.push_back({a, b});
        ++dc.failing_pairs;
        if (dc.first_pair[0] < 0) dc.first_pair = {a, b};
      }
  }
  dc.compatible = dc.failing_pairs == 0;
  return dc;
}

std::string TSplineClass::part42_type() const {
  if (analysis_suitable) return "ANALYSIS_SUITABLE_T_SPLINE";
  if (semi_standard) return "SEMI_STANDARD_T_SPLINE";
  return "STANDARD_T_SPLINE";
}

TSplineClass classify(const TSpline& ts, const TSplineSurface& surface, bool exact) {
  TSplineClass c;
  const auto ext = t_junction_extensions(ts, &c.gap_junctions);
  c.t_junctions = static_cast<int>(ext.size()) + c.gap_junctions;
  double area = 0;
  for (int f = 0; f < static_cast<int>(ts.image.faces.size()); ++f) {
    const Box<2> b = ts.image.face_box(f);
    area += b.extent(0) * b.extent(1);
  }
  const Box<2> dom = ts.image.domain();
  c.rectangular_domain = std::abs(area - dom.extent(0) * dom.extent(1)) <= 1e-12 * dom.extent(0) * dom.extent(1);
  for (const auto& a : ext)
    for (const auto& b : ext)
      // Closed segments: an extension ending on another crosses it (tests: then the blending functions are not
      // dual-compatible either).
      if (a.axis == 0 && b.axis == 1 && a.lo <= b.line && b.line <= a.hi && b.lo <= a.line && a.line <= b.hi)
        ++c.crossing_extensions;
  constexpr double kTol = 1e-12;
  c.standard = surface.partition_of_unity().max_defect <= kTol;
  c.dual = dual_compatibility(surface);
  c.analysis_suitable = c.crossing_extensions == 0 && (c.rectangular_domain || (c.dual.compatible && c.standard));
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
