#include "trivar/model/trimmed_solid.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/core/vec3.hpp"
#include "trivar/model/triangle_mesh.hpp"
#include "trivar/model/trimmed_integral.hpp"

namespace trivar {

namespace {

using P2 = std::array<double, 2>;

// Orientation of x against the directed line p -> q, computed in one canonical vertex order so that the edge
// (q, p) of the neighbouring triangle gets exactly the negated value; zero is broken by the symbolic
// perturbation x + (eps, eps^2), which is antisymmetric as well. So every perturbed point lies inside exactly
// the triangles of a closed mesh that a ray through it really crosses (the "simulation of simplicity").
int edge_sign(const P2& p, const P2& q, const P2& x) {
  const bool canonical = p < q;
  const P2& a = canonical ? p : q;
  const P2& b = canonical ? q : p;
  double e = (b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]);
  if (e == 0) e = -(b[1] - a[1]) != 0 ? -(b[1] - a[1]) : (b[0] - a[0]);
  const int s = e > 0 ? 1 : e < 0 ? -1 : 0;
  return canonical ? s : -s;
}

using P3 = Vec3;

// All control points (Cartesian) within rounding of the plane through the first one, the one farthest from
// it and the one farthest from their line: the face is a plane, which the mesh reproduces exactly.
bool is_flat(const TensorSpline<2>& s) {
  const int n = s.num_coefs();
  std::vector<P3> x(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) s.control_point(i, x[static_cast<std::size_t>(i)].data());
  P3 far{0, 0, 0};
  for (const P3& p : x)
    if (dot(sub(p, x[0]), sub(p, x[0])) > dot(far, far)) far = sub(p, x[0]);
  const double size = std::sqrt(dot(far, far));
  if (size == 0) return true;
  P3 best{0, 0, 0};
  for (const P3& p : x) {
    const P3 c = cross(far, sub(p, x[0]));
    if (dot(c, c) > dot(best, best)) best = c;
  }
  const double len = std::sqrt(dot(best, best));
  if (len == 0) return true;
  for (const P3& p : x)
    if (std::abs(dot(sub(p, x[0]), best)) / len > 1e-12 * size) return false;
  return true;
}

}  // namespace

TrimmedSolid::TrimmedSolid(TrimmedBoundary boundary) : boundary_(std::move(boundary)) {
  const TrimmedBoundary& b = boundary_;
  const std::size_t nt = b.mesh.triangles.size();
  require(!b.faces.empty() && nt > 0, "trimmed solid: the boundary has no faces");
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    const TrimmedFace& face = b.faces[f];
    const std::string where = "trimmed solid: face " + std::to_string(f) + (face.name.empty() ? "" : " (" + face.name + ")");
    require(face.surface.dim() == 3, where + ": the surface must have control dimension 3");
    require(!face.loops.empty(), where + ": no trimming loop");
    for (const TrimLoop& l : face.loops) {
      require(!l.curves.empty(), where + ": an empty trimming loop");
      for (const TrimCurve& c : l.curves) {
        require(c.pcurve.dim() == 2, where + ": a trimming curve must have control dimension 2");
        require(c.edge >= -1 && c.edge < static_cast<int>(b.edges.size()), where + ": a trimming curve names a missing edge");
      }
    }
  }
  require(b.triangle_face.size() == nt && b.triangle_uv.size() == nt,
          "trimmed solid: the mesh needs one face and one parameter triple per triangle");
  for (std::size_t t = 0; t < nt; ++t) {
    require(b.triangle_face[t] >= 0 && b.triangle_face[t] < static_cast<int>(b.faces.size()),
            "trimmed solid: triangle " + std::to_string(t) + " names a missing face");
    for (int v : b.mesh.triangles[t])
      require(v >= 0 && v < static_cast<int>(b.mesh.vertices.size()),
              "trimmed solid: triangle " + std::to_string(t) + " names a missing vertex");
  }
  require(is_watertight(b.mesh), "trimmed solid: the boundary mesh is not closed and consistently oriented");
  require(enclosed_volume(b.mesh) > 0, "trimmed solid: the boundary mesh is oriented inwards or encloses nothing");

  box_ = Box<3>::empty();
  for (const auto& v : b.mesh.vertices) box_.extend(v.data());
  for (int k = 0; k < 3; ++k) {
    box_.lo[k] -= b.chordal_tolerance;
    box_.hi[k] += b.chordal_tolerance;
  }

  // About four triangles per grid cell in projection.
  const int n = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(nt) / 4.0)), 1, 512);
  for (int axis = 0; axis < 3; ++axis) {
    AxisGrid& g = grids_[axis];
    g.b = (axis + 1) % 3;
    g.c = (axis + 2) % 3;
    g.nb = g.nc = n;
    g.lo_b = box_.lo[g.b];
    g.lo_c = box_.lo[g.c];
    g.inv_hb = n / std::max(box_.extent(g.b), 1e-300);
    g.inv_hc = n / std::max(box_.extent(g.c), 1e-300);
    auto cell = [&](double x, double lo, double inv) { return std::clamp(static_cast<int>((x - lo) * inv), 0, n - 1); };
    std::vector<std::array<int, 4>> range(nt);
    std::vector<int> count(static_cast<std::size_t>(n) * n + 1, 0);
    for (std::size_t t = 0; t < nt; ++t) {
      double lb = INFINITY, hb = -INFINITY, lc = INFINITY, hc = -INFINITY;
      for (int v : b.mesh.triangles[t]) {
        lb = std::min(lb, b.mesh.vertices[v][g.b]);
        hb = std::max(hb, b.mesh.vertices[v][g.b]);
        lc = std::min(lc, b.mesh.vertices[v][g.c]);
        hc = std::max(hc, b.mesh.vertices[v][g.c]);
      }
      range[t] = {cell(lb, g.lo_b, g.inv_hb), cell(hb, g.lo_b, g.inv_hb), cell(lc, g.lo_c, g.inv_hc), cell(hc, g.lo_c, g.inv_hc)};
      for (int j = range[t][2]; j <= range[t][3]; ++j)
        for (int i = range[t][0]; i <= range[t][1]; ++i) ++count[static_cast<std::size_t>(j) * n + i + 1];
    }
    for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    g.start = count;
    g.triangles.resize(static_cast<std::size_t>(count.back()));
    for (std::size_t t = 0; t < nt; ++t)
      for (int j = range[t][2]; j <= range[t][3]; ++j)
        for (int i = range[t][0]; i <= range[t][1]; ++i) g.triangles[count[static_cast<std::size_t>(j) * n + i]++] = static_cast<int>(t);
  }
  {
    // About two triangles per cell, cells as cubic as the box allows.
    SpaceGrid& g = space_;
    double vol = 1;
    for (int k = 0; k < 3; ++k) vol *= std::max(box_.extent(k), 1e-12 * box_.diagonal());
    const double h = std::cbrt(vol / std::max(1.0, static_cast<double>(nt) / 2));
    for (int k = 0; k < 3; ++k) {
      g.n[k] = std::clamp(static_cast<int>(box_.extent(k) / h), 1, 256);
      g.lo[k] = box_.lo[k];
      g.inv_h[k] = g.n[k] / std::max(box_.extent(k), 1e-300);
    }
    const auto cell = [&](double x, int k) { return std::clamp(static_cast<int>((x - g.lo[k]) * g.inv_h[k]), 0, g.n[k] - 1); };
    std::vector<std::array<int, 6>> range(nt);
    const std::size_t cells = static_cast<std::size_t>(g.n[0]) * g.n[1] * g.n[2];
    std::vector<int> count(cells + 1, 0);
    const auto each_cell = [&](const std::array<int, 6>& r, auto&& f) {
      for (int c = r[4]; c <= r[5]; ++c)
        for (int b2 = r[2]; b2 <= r[3]; ++b2)
          for (int a = r[0]; a <= r[1]; ++a) f((static_cast<std::size_t>(c) * g.n[1] + b2) * g.n[0] + a);
    };
    for (std::size_t t = 0; t < nt; ++t) {
      Box<3> tb = Box<3>::empty();
      for (int v : b.mesh.triangles[t]) tb.extend(b.mesh.vertices[v].data());
      range[t] = {cell(tb.lo[0], 0), cell(tb.hi[0], 0), cell(tb.lo[1], 1), cell(tb.hi[1], 1), cell(tb.lo[2], 2), cell(tb.hi[2], 2)};
      each_cell(range[t], [&](std::size_t c) { ++count[c + 1]; });
    }
    for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    g.start = count;
    g.triangles.resize(static_cast<std::size_t>(count.back()));
    for (std::size_t t = 0; t < nt; ++t) each_cell(range[t], [&](std::size_t c) { g.triangles[count[c]++] = static_cast<int>(t); });
  }
  // The trim polygons: a straight span (degree 1, rational or not: its image is the chord) is one chord; a
  // curved one starts with 4 uniform chords, halved until the trimming curve's point over each chord's
  // parameter midpoint lies, on the face in model space, within a quarter of the mesh's chordal tolerance of
  // the face's point over the chord's midpoint (at most 64 chords per span). The largest gap between a chord's
  // midpoint and the curve, measured per face, widens the polygon's edge into a band that counts as on the
  // trim, so the polygon never cuts off a sliver of the face.
  trim_polygons_.resize(b.faces.size());
  trim_slack_.assign(b.faces.size(), 0.0);
  trim_boxes_.resize(b.faces.size());
  const double gap_3d = b.chordal_tolerance / 4;
  // The faces on all threads: each writes its own entries only.
  parallel_for(static_cast<std::ptrdiff_t>(b.faces.size()), 0, [&](std::ptrdiff_t fi) {
    const auto f = static_cast<std::size_t>(fi);
    const TensorSpline<2>& surface = b.faces[f].surface;
    std::vector<P2> ends, mids, finer_ends, finer_mids;
    for (const TrimLoop& l : b.faces[f].loops) {
      std::vector<P2> poly;
      for (const TrimCurve& c : l.curves) {
        const std::vector<double> br = c.pcurve.knots(0).breakpoints();
        const auto at = [&](double t) {
          P2 q;
          c.pcurve.eval({t}, q.data());
          return q;
        };
        for (std::size_t s = 0; s + 1 < br.size(); ++s) {
          if (c.pcurve.degree(0) == 1) {
            poly.push_back(at(br[s]));
            continue;
          }
          constexpr int kFirst = 4, kMost = 64;
          const double a = br[s], len = br[s + 1] - br[s];
          int chords = kFirst;
          ends.resize(chords + 1);
          mids.resize(chords);
          for (int k = 0; k <= chords; ++k) ends[k] = at(k < chords ? a + len * k / chords : br[s + 1]);
          for (int k = 0; k < chords; ++k) mids[k] = at(a + len * (k + 0.5) / chords);
          for (;;) {
            double worst = 0;
            for (int k = 0; k < chords && worst <= gap_3d; ++k) {
              const P2 chord{(ends[k][0] + ends[k + 1][0]) / 2, (ends[k][1] + ends[k + 1][1]) / 2};
              P3 x, y;
              surface.eval({mids[k][0], mids[k][1]}, x.data());
              surface.eval({chord[0], chord[1]}, y.data());
              worst = std::max(worst, norm(sub(x, y)));
            }
            if (worst <= gap_3d || chords == kMost) break;
            // Halve every chord: the midpoints become ends, and the quarter points the new midpoints.
            finer_ends.resize(2 * chords + 1);
            finer_mids.resize(2 * chords);
            for (int k = 0; k < chords; ++k) {
              finer_ends[2 * k] = ends[k];
              finer_ends[2 * k + 1] = mids[k];
              finer_mids[2 * k] = at(a + len * (k + 0.25) / chords);
              finer_mids[2 * k + 1] = at(a + len * (k + 0.75) / chords);
            }
            finer_ends[2 * chords] = ends[chords];
            std::swap(ends, finer_ends);
            std::swap(mids, finer_mids);
            chords *= 2;
          }
          for (int k = 0; k < chords; ++k) {
            const P2 &q = ends[k], &e = ends[k + 1], &m = mids[k];
            trim_slack_[f] = std::max(trim_slack_[f], std::hypot(m[0] - (q[0] + e[0]) / 2, m[1] - (q[1] + e[1]) / 2));
            poly.push_back(q);
          }
        }
      }
      Box<2> pb = Box<2>::empty();
      for (const P2& q : poly) pb.extend(q.data());
      trim_boxes_[f].push_back(pb);
      trim_polygons_[f].push_back(std::move(poly));
    }
  });
  flat_.assign(b.faces.size(), 0);
  for (std::size_t f = 0; f < b.faces.size(); ++f) flat_[f] = is_flat(b.faces[f].surface);
  volume_ = trimmed_volume(b);
}

template <class F>
bool TrimmedSolid::SpaceGrid::any_triangle_in(const std::array<double, 3>& from, const std::array<double, 3>& to,
                                              F&& f) const {
  std::array<int, 3> a, z;
  for (int k = 0; k < 3; ++k) {
    a[k] = std::clamp(static_cast<int>((from[k] - lo[k]) * inv_h[k]), 0, n[k] - 1);
    z[k] = std::clamp(static_cast<int>((to[k] - lo[k]) * inv_h[k]), 0, n[k] - 1);
  }
  for (int c = a[2]; c <= z[2]; ++c)
    for (int j = a[1]; j <= z[1]; ++j)
      for (int i = a[0]; i <= z[0]; ++i) {
        const std::size_t cell = (static_cast<std::size_t>(c) * n[1] + j) * n[0] + i;
        for (int k = start[cell]; k < start[cell + 1]; ++k)
          if (f(triangles[static_cast<std::size_t>(k)])) return true;
      }
  return false;
}

template <class F>
bool TrimmedSolid::any_triangle_meeting(const Box<3>& q, F&& f) const {
  const SpaceGrid& g = space_;
  const TrimmedBoundary& bd = boundary_;
  // The open box: shrunk by rounding, so that triangles in its side planes stay out.
  Box<3> in = q;
  const double eps = 1e-12 * box_.diagonal();
  for (int k = 0; k < 3; ++k) {
    in.lo[k] += eps;
    in.hi[k] -= eps;
  }
  const double grow = bd.chordal_tolerance;
  std::array<double, 3> lo, hi;
  for (int k = 0; k < 3; ++k) {
    if (in.hi[k] + grow < box_.lo[k] || in.lo[k] - grow > box_.hi[k]) return false;
    lo[k] = in.lo[k] - grow;
    hi[k] = in.hi[k] + grow;
  }
  return g.any_triangle_in(lo, hi, [&](int t) {
    const double r = flat_[static_cast<std::size_t>(bd.triangle_face[t])] ? 0.0 : grow;
    for (int d = 0; d < 3; ++d) {
      double a = INFINITY, z = -INFINITY;
      for (int v : bd.mesh.triangles[t]) {
        a = std::min(a, bd.mesh.vertices[v][d]);
        z = std::max(z, bd.mesh.vertices[v][d]);
      }
      if (z + r < in.lo[d] || a - r > in.hi[d]) return false;
    }
    return f(t);
  });
}

bool TrimmedSolid::boundary_meets(const Box<3>& b) const {
  return any_triangle_meeting(b, [](int) { return true; });
}

int TrimmedSolid::transversal_axis(const Box<3>& b) const {
  const TrimmedBoundary& bd = boundary_;
  std::array<double, 3> worst{1, 1, 1};
  bool any = false;
  any_triangle_meeting(b, [&](int t) {
    const auto& tri = bd.mesh.triangles[static_cast<std::size_t>(t)];
    const P3 &a = bd.mesh.vertices[tri[0]], &p = bd.mesh.vertices[tri[1]], &c = bd.mesh.vertices[tri[2]];
    const P3 u = sub(p, a), v = sub(c, a);
    const P3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(dot(n, n));
    if (len == 0) return false;
    any = true;
    for (int k = 0; k < 3; ++k) worst[k] = std::min(worst[k], std::abs(n[k]) / len);
    return false;
  });
  if (!any) return 0;
  return static_cast<int>(std::max_element(worst.begin(), worst.end()) - worst.begin());
}

bool TrimmedSolid::inside_trim(int face, const Param<2>& uv) const {
  // Points on the trim (a seam, a pole, the edge the closest point was clamped to) count as on the face.
  const Box<2> dom = boundary_.faces[face].surface.domain();
  const double eps = 2 * trim_slack_[face] + 1e-9 * (dom.extent(0) + dom.extent(1));
  bool inside = false;
  for (std::size_t l = 0; l < trim_polygons_[face].size(); ++l) {
    // A closed loop whose box does not hold the point is crossed an even number of times by the ray.
    if (!trim_boxes_[face][l].contains(uv, eps)) continue;
    const auto& poly = trim_polygons_[face][l];
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
      const P2 &a = poly[j], &b = poly[i];
      const double ex = b[0] - a[0], ey = b[1] - a[1], len2 = ex * ex + ey * ey;
      const double s = len2 > 0 ? std::clamp(((uv[0] - a[0]) * ex + (uv[1] - a[1]) * ey) / len2, 0.0, 1.0) : 0.0;
      if (std::hypot(uv[0] - a[0] - s * ex, uv[1] - a[1] - s * ey) <= eps) return true;
      if ((b[1] > uv[1]) != (a[1] > uv[1]) && uv[0] < a[0] + ex * (uv[1] - a[1]) / ey) inside = !inside;
    }
  }
  return inside;
}

void TrimmedSolid::mesh_crossings(int axis, const std::array<double, 3>& p, std::vector<LineCrossing>& out) const {
  out.clear();
  const AxisGrid& g = grids_[axis];
  const double xb = p[g.b], xc = p[g.c];
  if (xb < box_.lo[g.b] || xb > box_.hi[g.b] || xc < box_.lo[g.c] || xc > box_.hi[g.c]) return;
  const int i = std::clamp(static_cast<int>((xb - g.lo_b) * g.inv_hb), 0, g.nb - 1);
  const int j = std::clamp(static_cast<int>((xc - g.lo_c) * g.inv_hc), 0, g.nc - 1);
  const std::size_t cell = static_cast<std::size_t>(j) * g.nb + i;
  const P2 x{xb, xc};
  const TrimmedBoundary& bd = boundary_;
  for (int k = g.start[cell]; k < g.start[cell + 1]; ++k) {
    const int t = g.triangles[k];
    const auto& tri = bd.mesh.triangles[t];
    P2 q[3];
    for (int m = 0; m < 3; ++m) q[m] = {bd.mesh.vertices[tri[m]][g.b], bd.mesh.vertices[tri[m]][g.c]};
    // Most triangles of the cell miss the line: a point strictly outside the projected triangle's box is outside
    // the triangle for the perturbed point too (the perturbation is infinitesimal), so the edge signs agree.
    if ((x[0] < q[0][0] && x[0] < q[1][0] && x[0] < q[2][0]) || (x[0] > q[0][0] && x[0] > q[1][0] && x[0] > q[2][0]) ||
        (x[1] < q[0][1] && x[1] < q[1][1] && x[1] < q[2][1]) || (x[1] > q[0][1] && x[1] > q[1][1] && x[1] > q[2][1]))
      continue;
    const int s0 = edge_sign(q[1], q[2], x), s1 = edge_sign(q[2], q[0], x), s2 = edge_sign(q[0], q[1], x);
    if (s0 == 0 || s0 != s1 || s1 != s2) continue;
    // Barycentric weights from the unperturbed edge functions (the point may lie on an edge: weights >= 0).
    auto area = [](const P2& a, const P2& b2, const P2& c) {
      return (b2[0] - a[0]) * (c[1] - a[1]) - (b2[1] - a[1]) * (c[0] - a[0]);
    };
    double w[3] = {area(q[1], q[2], x), area(q[2], q[0], x), area(q[0], q[1], x)};
    const double sum = w[0] + w[1] + w[2];
    if (sum == 0) {
      w[0] = w[1] = w[2] = 1.0 / 3;
    } else {
      for (double& wi : w) wi = std::max(wi / sum, 0.0);
    }
    const double ws = w[0] + w[1] + w[2];
    LineCrossing c;
    c.face = bd.triangle_face[t];
    for (int m = 0; m < 3; ++m) {
      c.t += w[m] / ws * bd.mesh.vertices[tri[m]][axis];
      c.uv[0] += w[m] / ws * bd.triangle_uv[t][m][0];
      c.uv[1] += w[m] / ws * bd.triangle_uv[t][m][1];
    }
    // Counter-clockwise in the (b, c) plane: the outward normal points along +axis, so the line leaves.
    c.entering = s0 < 0;
    out.push_back(c);
  }
  std::sort(out.begin(), out.end(), [](const LineCrossing& a, const LineCrossing& b2) { return a.t < b2.t; });
}

void TrimmedSolid::refine(int axis, const std::array<double, 3>& p, LineCrossing& c) const {
  const TrimmedFace& f = boundary_.faces[c.face];
  const Box<2> dom = f.surface.domain();
  constexpr int kIterations = 8;
  double u = c.uv[0], v = c.uv[1], t = c.t;
  const double band = std::max(4 * boundary_.chordal_tolerance, 1e-12 * box_.diagonal());
  for (int it = 0; it < kIterations; ++it) {
    double d[9];
    f.surface.eval_derivs({u, v}, 1, d);
    // Residual r = S(u, v) - (p + t e_axis); Jacobian columns S_u, S_v, -e_axis.
    double r[3] = {d[0] - p[0], d[1] - p[1], d[2] - p[2]};
    r[axis] -= t;
    // Eliminating t leaves the 2x2 system in the two other coordinates.
    const int b = (axis + 1) % 3, cc = (axis + 2) % 3;
    const double a11 = d[3 + b], a12 = d[6 + b], a21 = d[3 + cc], a22 = d[6 + cc];
    const double det = a11 * a22 - a12 * a21;
    if (det == 0) return;
    const double du = (r[b] * a22 - a12 * r[cc]) / det, dv = (a11 * r[cc] - a21 * r[b]) / det;
    u = std::clamp(u - du, dom.lo[0], dom.hi[0]);
    v = std::clamp(v - dv, dom.lo[1], dom.hi[1]);
    double x[3];
    f.surface.eval({u, v}, x);
    t = x[axis];
    if (std::abs(t - c.t) > band) return;  // strayed: keep the mesh crossing
    if (std::abs(du) + std::abs(dv) <= 1e-14 * (dom.extent(0) + dom.extent(1))) break;
  }
  double x[3];
  f.surface.eval({u, v}, x);
  const int b = (axis + 1) % 3, cc = (axis + 2) % 3;
  if (std::hypot(x[b] - p[b], x[cc] - p[cc]) > 1e-9 * box_.diagonal()) return;
  c.t = t;
  c.uv = {u, v};
}

void TrimmedSolid::axis_crossings(int axis, const std::array<double, 3>& p, double t_lo, double t_hi,
                                  std::vector<LineCrossing>& out) const {
  require(axis >= 0 && axis < 3, "trimmed solid: the axis must be 0, 1 or 2");
  mesh_crossings(axis, p, out);
  for (LineCrossing& c : out) refine(axis, p, c);
  std::stable_sort(out.begin(), out.end(), [](const LineCrossing& a, const LineCrossing& b) { return a.t < b.t; });
  out.erase(std::remove_if(out.begin(), out.end(), [&](const LineCrossing& c) { return c.t <= t_lo || c.t >= t_hi; }),
            out.end());
}

int TrimmedSolid::classify_near(const std::array<double, 3>& x, double band) const {
  const TrimmedBoundary& bd = boundary_;
  // Per face within the band: its nearest triangle and the barycentric coordinates of the nearest point there.
  struct Near {
    int face, triangle;
    double d2;
    std::array<double, 3> w;
  };
  thread_local std::vector<Near> near;
  near.clear();
  space_.any_triangle_in({x[0] - band, x[1] - band, x[2] - band}, {x[0] + band, x[1] + band, x[2] + band}, [&](int t) {
    const auto& tri = bd.mesh.triangles[t];
    const P3 &a = bd.mesh.vertices[tri[0]], &b = bd.mesh.vertices[tri[1]], &cc = bd.mesh.vertices[tri[2]];
    const auto w = closest_on_triangle(x, a, b, cc);
    const P3 q{w[0] * a[0] + w[1] * b[0] + w[2] * cc[0], w[0] * a[1] + w[1] * b[1] + w[2] * cc[1],
               w[0] * a[2] + w[1] * b[2] + w[2] * cc[2]};
    const P3 d = sub(x, q);
    const double d2 = dot(d, d);
    if (d2 > band * band) return false;
    const int f = bd.triangle_face[t];
    auto it = std::find_if(near.begin(), near.end(), [f](const Near& n) { return n.face == f; });
    if (it == near.end())
      near.push_back({f, t, d2, w});
    else if (d2 < it->d2)
      *it = {f, t, d2, w};
    return false;
  });
  // The exact closest point on each of those faces (Gauss-Newton from the triangle's parameters, kept in the
  // domain), on faces where it lies within the trim. When the nearest is a foot (x - S along the normal), that
  // face's normal decides; otherwise the nearest point is on an edge or corner of the solid and the sum of the
  // unit normals of the faces meeting there (the edge's pseudo-normal) decides.
  struct Foot {
    P3 s, r, n;  // closest point, x - s, unit outward normal
    double dist;
    bool clean;
  };
  thread_local std::vector<Foot> feet;
  feet.clear();
  for (const Near& n : near) {
    const TrimmedFace& f = bd.faces[n.face];
    const Box<2> dom = f.surface.domain();
    double u = 0, v = 0;
    for (int m = 0; m < 3; ++m) {
      u += n.w[m] * bd.triangle_uv[n.triangle][m][0];
      v += n.w[m] * bd.triangle_uv[n.triangle][m][1];
    }
    constexpr int kIterations = 10;
    double d[9];
    for (int it = 0; it < kIterations; ++it) {
      f.surface.eval_derivs({u, v}, 1, d);
      const P3 r = sub(x, {d[0], d[1], d[2]}), su{d[3], d[4], d[5]}, sv{d[6], d[7], d[8]};
      const double a11 = dot(su, su), a12 = dot(su, sv), a22 = dot(sv, sv), det = a11 * a22 - a12 * a12;
      if (det <= 0) break;
      const double b1 = dot(su, r), b2 = dot(sv, r);
      u = std::clamp(u + (a22 * b1 - a12 * b2) / det, dom.lo[0], dom.hi[0]);
      v = std::clamp(v + (a11 * b2 - a12 * b1) / det, dom.lo[1], dom.hi[1]);
    }
    f.surface.eval_derivs({u, v}, 1, d);
    const P3 r = sub(x, {d[0], d[1], d[2]});
    const double dist = std::sqrt(dot(r, r));
    if (dist > band + bd.chordal_tolerance || !inside_trim(n.face, {u, v})) continue;
    P3 nrm{d[4] * d[8] - d[5] * d[7], d[5] * d[6] - d[3] * d[8], d[3] * d[7] - d[4] * d[6]};
    const double len = std::sqrt(dot(nrm, nrm));
    if (len == 0) continue;  // a pole: its neighbours decide
    const double sign = f.reversed ? -1 / len : 1 / len;
    nrm = {nrm[0] * sign, nrm[1] * sign, nrm[2] * sign};
    constexpr double kParallel = 1 - 1e-6;
    feet.push_back({{d[0], d[1], d[2]}, r, nrm, dist, std::abs(dot(r, nrm)) >= kParallel * dist});
  }
  if (feet.empty()) return -1;
  const Foot& best = *std::min_element(feet.begin(), feet.end(), [](const Foot& a, const Foot& b) { return a.dist < b.dist; });
  // A foot on a face is the answer unless it is much farther than the nearest point (a clamped point on the
  // trim of another face may come out slightly nearer than the true foot, by the trim polygon's slack).
  const Foot* clean = nullptr;
  for (const Foot& f : feet)
    if (f.clean && f.dist <= best.dist + 2 * bd.chordal_tolerance && (!clean || f.dist < clean->dist)) clean = &f;
  if (clean) return dot(clean->r, clean->n) < 0 ? 1 : 0;
  // No foot: the nearest point is on an edge or corner, where the faces' clamped points (nearly) meet.
  P3 pseudo{0, 0, 0};
  for (const Foot& f : feet) {
    const P3 gap = sub(f.s, best.s);
    if (std::sqrt(dot(gap, gap)) <= 0.1 * best.dist + 1e-12 * box_.diagonal())
      for (int k = 0; k < 3; ++k) pseudo[k] += f.n[k];
  }
  return dot(best.r, pseudo) < 0 ? 1 : 0;
}

bool TrimmedSolid::contains(const std::array<double, 3>& x) const {
  if (!box_.contains(x)) return false;
  // Points farther from the mesh than the mesh is from the faces are classified by the mesh alone.
  const double band = 2 * boundary_.chordal_tolerance + 1e-12 * box_.diagonal();
  if (const int near = classify_near(x, band); near >= 0) return near == 1;
  thread_local std::vector<LineCrossing> cs;
  mesh_crossings(0, x, cs);
  int after = 0;
  for (const LineCrossing& c : cs)
    if (c.t > x[0]) ++after;
  return after % 2 == 1;
}

}  // namespace trivar
