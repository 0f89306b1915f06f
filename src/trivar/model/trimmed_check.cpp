#include "trivar/model/trimmed_check.hpp"

#include <algorithm>
#include <cmath>

namespace trivar {

namespace {

using P3 = std::array<double, 3>;

double dist(const P3& a, const P3& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

P3 on_surface(const TensorSpline<2>& s, const Param<2>& uv) {
  P3 x;
  s.eval(uv, x.data());
  return x;
}

Param<2> curve_point(const TensorSpline<1>& c, double t) {
  Param<2> uv;
  double x[2];
  c.eval({t}, x);
  uv = {x[0], x[1]};
  return uv;
}

}  // namespace

TrimCheck check_trim(const TrimmedSolid& solid, double tolerance) {
  const TrimmedBoundary& b = solid.boundary();
  const double base = tolerance > 0 ? tolerance : 1e-6 * solid.bounding_box().diagonal();
  TrimCheck r;
  auto defect = [&r](std::string s) {
    r.valid = false;
    if (r.defects.size() < 20) r.defects.push_back(std::move(s));
  };
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    const TrimmedFace& face = b.faces[f];
    const double tol = std::max(base, face.tolerance);
    const std::string name = "face " + std::to_string(f) + (face.name.empty() ? "" : " (" + face.name + ")");
    const Box<2> dom = face.surface.domain();
    const double slack = 1e-9 * (dom.extent(0) + dom.extent(1));
    for (std::size_t l = 0; l < face.loops.size(); ++l) {
      const auto& cs = face.loops[l].curves;
      for (std::size_t i = 0; i < cs.size(); ++i) {
        const TensorSpline<1>& c = cs[i].pcurve;
        const Box<1> cd = c.domain();
        const Param<2> start = curve_point(c, cd.lo[0]), end = curve_point(c, cd.hi[0]);
        const std::string where = name + " loop " + std::to_string(l) + " curve " + std::to_string(i);
        for (const Param<2>& uv : {start, end})
          if (!dom.contains(uv, slack)) defect(where + ": leaves the surface's parameter domain");
        const Param<2> next = curve_point(cs[(i + 1) % cs.size()].pcurve, cs[(i + 1) % cs.size()].pcurve.domain().lo[0]);
        const double gap = dist(on_surface(face.surface, end), on_surface(face.surface, next));
        r.largest_loop_gap = std::max(r.largest_loop_gap, gap);
        if (gap > tol) defect(where + ": the loop does not close (gap " + std::to_string(gap) + ")");
        if (cs[i].edge < 0) continue;
        const TrimEdge& e = b.edges[static_cast<std::size_t>(cs[i].edge)];
        P3 e0, e1;
        e.curve.eval({e.curve.domain().lo[0]}, e0.data());
        e.curve.eval({e.curve.domain().hi[0]}, e1.data());
        if (cs[i].edge_reversed) std::swap(e0, e1);
        const double eg = std::max(dist(on_surface(face.surface, start), e0), dist(on_surface(face.surface, end), e1));
        r.largest_edge_gap = std::max(r.largest_edge_gap, eg);
        if (eg > std::max(tol, e.tolerance)) defect(where + ": does not run along its edge (gap " + std::to_string(eg) + ")");
      }
    }
  }
  // Each face's orientation flag against the (outward) mesh: the exact normal at the centre of the face's
  // largest triangle must point the way the triangle does.
  std::vector<int> largest(b.faces.size(), -1);
  std::vector<double> area(b.faces.size(), 0.0);
  const auto tri_normal = [&](std::size_t t) {
    const auto& v = b.mesh.triangles[t];
    const P3 &p0 = b.mesh.vertices[v[0]], &p1 = b.mesh.vertices[v[1]], &p2 = b.mesh.vertices[v[2]];
    const P3 u{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, w{p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    return P3{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  };
  for (std::size_t t = 0; t < b.mesh.triangles.size(); ++t) {
    const P3 n = tri_normal(t);
    const double a = std::hypot(n[0], n[1], n[2]);
    const std::size_t f = static_cast<std::size_t>(b.triangle_face[t]);
    if (a > area[f]) {
      area[f] = a;
      largest[f] = static_cast<int>(t);
    }
  }
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    if (largest[f] < 0) continue;
    const std::size_t t = static_cast<std::size_t>(largest[f]);
    const auto& uv = b.triangle_uv[t];
    double d[9];
    b.faces[f].surface.eval_derivs({(uv[0][0] + uv[1][0] + uv[2][0]) / 3, (uv[0][1] + uv[1][1] + uv[2][1]) / 3}, 1, d);
    const P3 n{d[4] * d[8] - d[5] * d[7], d[5] * d[6] - d[3] * d[8], d[3] * d[7] - d[4] * d[6]};
    const P3 m = tri_normal(t);
    const double s = (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]) * (b.faces[f].reversed ? -1 : 1);
    if (s < 0)
      defect("face " + std::to_string(f) + (b.faces[f].name.empty() ? "" : " (" + b.faces[f].name + ")") +
             ": its orientation flag disagrees with the outward boundary mesh");
  }
  r.watertight = is_watertight(b.mesh);
  if (!r.watertight) defect("the boundary mesh is not closed and consistently oriented");
  r.exact_volume = solid.volume();
  r.mesh_volume = enclosed_volume(b.mesh);
  // The mesh lies within the chordal tolerance of the faces: the volumes differ by at most area x tolerance.
  r.volume_band = surface_area(b.mesh) * b.chordal_tolerance + 1e-9 * std::abs(r.mesh_volume);
  if (r.exact_volume <= 0) defect("the faces enclose no positive volume (orientation flags inverted?)");
  if (std::abs(r.exact_volume - r.mesh_volume) > r.volume_band)
    defect("the exact faces enclose volume " + std::to_string(r.exact_volume) + " but the mesh " +
           std::to_string(r.mesh_volume) + ": a face's orientation or trim disagrees with the mesh");
  return r;
}

}  // namespace trivar
