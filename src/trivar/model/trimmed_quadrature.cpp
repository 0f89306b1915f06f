#include "trivar/model/trimmed_quadrature.hpp"

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"

namespace trivar {

namespace {

void gauss_box(const Box<3>& b, const QuadratureRule& r, std::vector<VolumePoint>& out) {
  const std::size_t n = r.nodes.size();
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i)
        out.push_back({{b.lo[0] + b.extent(0) * r.nodes[i], b.lo[1] + b.extent(1) * r.nodes[j],
                        b.lo[2] + b.extent(2) * r.nodes[k]},
                       b.extent(0) * b.extent(1) * b.extent(2) * r.weights[i] * r.weights[j] * r.weights[k]});
}

void line_leaf(const TrimmedSolid& s, const Box<3>& b, const QuadratureRule& r, std::vector<VolumePoint>& out) {
  thread_local std::vector<LineCrossing> cs;
  const int a = s.transversal_axis(b), e = (a + 1) % 3, f = (a + 2) % 3;
  const std::size_t n = r.nodes.size();
  std::vector<double> cuts;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      std::array<double, 3> p{};
      p[e] = b.lo[e] + b.extent(e) * r.nodes[i];
      p[f] = b.lo[f] + b.extent(f) * r.nodes[j];
      const double w = b.extent(e) * b.extent(f) * r.weights[i] * r.weights[j];
      s.axis_crossings(a, p, b.lo[a], b.hi[a], cs);
      cuts.assign(1, b.lo[a]);
      for (const LineCrossing& c : cs) cuts.push_back(c.t);
      cuts.push_back(b.hi[a]);
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double lo = cuts[k], len = cuts[k + 1] - lo;
        if (len <= 0) continue;
        // Whether the interval is inside is asked of its midpoint, not read off the crossings' directions, so a
        // crossing lost at a silhouette costs accuracy but never flips a whole interval.
        p[a] = lo + len / 2;
        if (!s.contains(p)) continue;
        for (std::size_t q = 0; q < n; ++q) {
          p[a] = lo + len * r.nodes[q];
          out.push_back({p, w * len * r.weights[q]});
        }
      }
    }
}

BoxPlacement place(const TrimmedSolid& s, const Box<3>& b) {
  if (s.boundary_meets(b)) return BoxPlacement::cut;
  return s.contains(b.center()) ? BoxPlacement::inside : BoxPlacement::outside;
}

void subdivide(const TrimmedSolid& s, const Box<3>& b, const QuadratureRule& r, int depth, std::vector<VolumePoint>& out) {
  if (depth == 0) {
    line_leaf(s, b, r, out);
    return;
  }
  const auto c = b.center();
  for (int o = 0; o < 8; ++o) {
    Box<3> child;
    for (int k = 0; k < 3; ++k) {
      const bool upper = (o >> k) & 1;
      child.lo[k] = upper ? c[k] : b.lo[k];
      child.hi[k] = upper ? b.hi[k] : c[k];
    }
    switch (place(s, child)) {
      case BoxPlacement::inside: gauss_box(child, r, out); break;
      case BoxPlacement::outside: break;
      case BoxPlacement::cut: subdivide(s, child, r, depth - 1, out); break;
    }
  }
}

}  // namespace

BoxPlacement trimmed_box_quadrature(const TrimmedSolid& solid, const Box<3>& box, const TrimmedQuadratureOptions& opts,
                                    std::vector<VolumePoint>& out) {
  require(opts.points >= 1 && opts.points <= 32 && opts.depth >= 0 && opts.depth <= 8,
          "trimmed quadrature: points must be in [1, 32] and the depth in [0, 8]");
  const BoxPlacement p = place(solid, box);
  if (p == BoxPlacement::cut) subdivide(solid, box, gauss_legendre(opts.points), opts.depth, out);
  return p;
}

void trimmed_face_quadrature(const TrimmedSolid& solid, int face, int points, std::vector<SurfacePoint>& out) {
  const TrimmedBoundary& b = solid.boundary();
  require(face >= 0 && face < static_cast<int>(b.faces.size()) && points >= 1 && points <= 32,
          "trimmed quadrature: no face " + std::to_string(face) + " or points not in [1, 32]");
  const TensorSpline<2>& S = b.faces[static_cast<std::size_t>(face)].surface;
  const double sign = b.faces[static_cast<std::size_t>(face)].reversed ? -1 : 1;
  const QuadratureRule r = gauss_legendre(points);
  for (std::size_t t = 0; t < b.triangle_face.size(); ++t) {
    if (b.triangle_face[t] != face) continue;
    const auto& q = b.triangle_uv[t];
    const double e1[2] = {q[1][0] - q[0][0], q[1][1] - q[0][1]}, e2[2] = {q[2][0] - q[0][0], q[2][1] - q[0][1]};
    const double jac = std::abs(e1[0] * e2[1] - e1[1] * e2[0]);
    if (jac == 0) continue;
    // Collapsed (Duffy) rule: (s, t) = (xi, eta (1 - xi)) maps the unit square onto the reference triangle.
    for (std::size_t i = 0; i < r.nodes.size(); ++i)
      for (std::size_t j = 0; j < r.nodes.size(); ++j) {
        const double xi = r.nodes[i], s2 = xi, t2 = r.nodes[j] * (1 - xi);
        const Param<2> uv{q[0][0] + s2 * e1[0] + t2 * e2[0], q[0][1] + s2 * e1[1] + t2 * e2[1]};
        double d[9];
        S.eval_derivs(uv, 1, d);
        const std::array<double, 3> n{d[4] * d[8] - d[5] * d[7], d[5] * d[6] - d[3] * d[8], d[3] * d[7] - d[4] * d[6]};
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len == 0) continue;  // a pole carries no area
        out.push_back({{d[0], d[1], d[2]},
                       {sign * n[0] / len, sign * n[1] / len, sign * n[2] / len},
                       len * jac * r.weights[i] * r.weights[j] * (1 - xi)});
      }
  }
}

}  // namespace trivar
