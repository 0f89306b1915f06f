// Local non-uniform subdivision (crease faces of a mesh without creases) in a closed mesh that also has
// T-junctions away from the star points, so that the global steps (nurcc_step) do not apply. The mesh is a long
// box of 3 x 3 faces across (eight valence-3 star points, 3 edges apart on each end) with a strip of knot interval
// 1.5 round it, and a T-junction pair halfway along: a knot inserted into some rows of the tube by Boehm's rule,
// which leaves the surface unchanged. References that do not come from the code under test: the bicubic B-spline
// of the tube (periodic round it, the knots of its strip) for every face whose 4 x 4 points lie in the tube, the
// box without the T-junctions after two global non-uniform Catmull-Clark steps for the faces at the star points,
// and OpenSubdiv's limit surface of the box without T-junctions and with equal intervals.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include "chart_comparison.hpp"
#include "crease_nets.hpp"
#include "face_continuity.hpp"
#include "osd_reference.hpp"
#include "star_mesh_tsm.hpp"
#include "tsm_error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/tspline/non_uniform_subdivision.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar {
namespace {

// The box of 3 x 3 x kTubeRows faces (box_mesh): its four long sides are a tube of 12 x kTubeRows faces, vertex
// (c, z) at girth position c (0..11, from the corner x = y = 0 along y = 0) and row z (0..kTubeRows).
constexpr int kTubeRows = 17;
constexpr int kGirth = 12;

struct TubeBox {
  test::QuadMesh mesh;
  std::vector<int> grid;                       // (c, z) -> vertex, c * (kTubeRows + 1) + z
  std::vector<std::array<double, 2>> knot;     // per vertex: (s, t) in the tube's knots; NaN off the tube
  std::array<double, kGirth + 1> girth_knot{}; // s of girth position c (0 .. kGirth: one period)
  int vertex(int c, int z) const { return grid[static_cast<std::size_t>(((c % kGirth + kGirth) % kGirth) * (kTubeRows + 1) + z)]; }
  // s of girth position c for any integer c (periodic).
  double s(int c) const {
    const int p = (c % kGirth + kGirth) % kGirth;
    return girth_knot[static_cast<std::size_t>(p)] + (c - p) / kGirth * girth_knot[kGirth];
  }
};

// The box with knot interval `wide` on the strip between the x grid lines 1 and 2 (girth 1..2 on the side y = 0,
// 7..8 on y = 3, and across both ends), its points moved off the box.
TubeBox tube_box(double wide) {
  TubeBox b;
  b.mesh = test::box_mesh({3, 3, kTubeRows});
  auto& q = b.mesh;
  const std::size_t nv = q.points.size();
  std::vector<std::array<int, 3>> g(nv);
  for (std::size_t v = 0; v < nv; ++v)
    for (std::size_t k = 0; k < 3; ++k) g[v][k] = static_cast<int>(std::lround((q.points[v][k] + 1) * 1.5));  // box_mesh's scale 2 / 3
  for (auto& p : q.points) {
    const auto r = p;
    p = {r[0] + 0.06 * std::sin(1.9 * r[1] + 0.5 * r[2]), r[1] + 0.05 * std::cos(1.3 * r[2] - 0.4 * r[0]),
         r[2] + 0.04 * std::sin(1.1 * r[0] + 0.8 * r[1])};
  }
  for (const auto& f : q.quads)
    for (std::size_t k = 0; k < 4; ++k) {
      const auto& a = g[static_cast<std::size_t>(f[k])];
      const auto& c = g[static_cast<std::size_t>(f[(k + 1) % 4])];
      if (std::min(a[0], c[0]) == 1 && std::max(a[0], c[0]) == 2) q.intervals[{f[k], f[(k + 1) % 4]}] = wide;
    }
  for (int c = 0; c < kGirth; ++c)
    b.girth_knot[static_cast<std::size_t>(c + 1)] = b.girth_knot[static_cast<std::size_t>(c)] + (c == 1 || c == 7 ? wide : 1.0);
  b.grid.assign(kGirth * (kTubeRows + 1), -1);
  b.knot.assign(nv, {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()});
  for (std::size_t v = 0; v < nv; ++v) {
    const auto [x, y, z] = g[v];
    const int c = y == 0 ? x : x == 3 ? 3 + y : y == 3 ? 9 - x : x == 0 ? (12 - y) % kGirth : -1;
    if (c < 0) continue;
    b.grid[static_cast<std::size_t>(c * (kTubeRows + 1) + z)] = static_cast<int>(v);
    b.knot[v] = {b.girth_knot[static_cast<std::size_t>(c)], static_cast<double>(z)};
  }
  return b;
}

// T-spline refinement of the box: the knot s = s(column) + fraction x interval inserted into the vertex rows
// first .. last of the tube (Boehm's rule on each row, the rows' other points unchanged), which splits the faces of
// that column between the rows and leaves T-junctions on the faces below row first and above row last. The
// blending functions of the rows outside keep their knots (their rays miss the new line), so the T-spline is the
// same surface. New vertices are appended (the box's keep their ids).
TubeBox insert_knot_segment(const TubeBox& box, int column, double fraction, int first, int last) {
  TubeBox b = box;
  auto& q = b.mesh;
  const int a = column;
  const double k = box.s(a) + fraction * (box.s(a + 1) - box.s(a));
  std::map<int, int> added;  // row -> new vertex
  for (int z = first; z <= last; ++z) {
    const auto P = [&](int c) { return box.mesh.points[static_cast<std::size_t>(box.vertex(c, z))]; };
    const auto blend = [&](int c, double alpha) {
      std::array<double, 3> r{};
      for (std::size_t i = 0; i < 3; ++i) r[i] = alpha * P(c)[i] + (1 - alpha) * P(c - 1)[i];
      return r;
    };
    // Boehm's rule for cubics: the three functions whose supports hold k in their interior change; the refined
    // row's point at vertex j is alpha P_j + (1 - alpha) P_(j-1), alpha = (k - s_(j-2)) / (s_(j+1) - s_(j-2)),
    // for j = a, the new vertex (its old neighbours a + 1 and a) and a + 1 (a + 2 and a + 1).
    const auto at_a = blend(a, (k - box.s(a - 2)) / (box.s(a + 1) - box.s(a - 2)));
    const auto at_k = blend(a + 1, (k - box.s(a - 1)) / (box.s(a + 2) - box.s(a - 1)));
    const auto at_a1 = blend(a + 2, (k - box.s(a)) / (box.s(a + 3) - box.s(a)));
    q.points[static_cast<std::size_t>(box.vertex(a, z))] = at_a;
    q.points[static_cast<std::size_t>(box.vertex(a + 1, z))] = at_a1;
    added[z] = static_cast<int>(q.points.size());
    q.points.push_back(at_k);
    b.knot.push_back({k, static_cast<double>(z)});
    q.intervals[{box.vertex(a, z), added[z]}] = k - box.s(a);
    q.intervals[{added[z], box.vertex(a + 1, z)}] = box.s(a + 1) - k;
  }
  // The faces of the column from row first - 1 to row last: the new vertices on their sides along the girth.
  std::vector<std::array<int, 4>> quads;
  for (const auto& f : q.quads) {
    std::vector<int> loop;
    std::vector<char> is_new;
    for (std::size_t i = 0; i < 4; ++i) {
      loop.push_back(f[i]);
      is_new.push_back(0);
      const int u = f[i], w = f[(i + 1) % 4];
      for (const auto& [z, n] : added)
        if ((u == box.vertex(a, z) && w == box.vertex(a + 1, z)) || (w == box.vertex(a, z) && u == box.vertex(a + 1, z))) {
          loop.push_back(n);
          is_new.push_back(1);
        }
    }
    if (loop.size() == 4) {
      quads.push_back(f);
    } else if (loop.size() == 5) {
      q.t_faces.push_back({loop, is_new});
    } else {  // split at the two new vertices into two quadrilaterals
      const auto i = static_cast<std::size_t>(std::find(is_new.begin(), is_new.end(), 1) - is_new.begin());
      const auto j = static_cast<std::size_t>(std::find(is_new.begin() + static_cast<std::ptrdiff_t>(i) + 1, is_new.end(), 1) - is_new.begin());
      quads.push_back({loop[i], loop[i + 1], loop[j - 1], loop[j]});
      quads.push_back({loop[j], loop[(j + 1) % 6], loop[(j + 2) % 6], loop[(j + 3) % 6]});
    }
  }
  q.quads = std::move(quads);
  return b;
}

TMesh tsm_mesh(const TubeBox& b) { return io::parse_tsm(test::tsm_text(b.mesh), "tube_box.tsm").mesh; }

// Face f of a surface in the tube's knots: (s, t) = origin + u du + v dv (the girth unwrapped at its first corner).
struct KnotFrame {
  std::array<double, 2> origin{}, du{}, dv{};
  bool tube = false;
};
KnotFrame knot_frame(const TubeBox& b, const std::array<int, 4>& c) {
  KnotFrame k;
  std::array<std::array<double, 2>, 4> st{};
  for (std::size_t i = 0; i < 4; ++i) {
    st[i] = b.knot[static_cast<std::size_t>(c[i])];
    if (std::isnan(st[i][0])) return k;
    const double period = b.girth_knot[kGirth];
    while (st[i][0] - st[0][0] > period / 2) st[i][0] -= period;
    while (st[i][0] - st[0][0] < -period / 2) st[i][0] += period;
  }
  k.tube = true;
  k.origin = st[0];
  k.du = {st[1][0] - st[0][0], st[1][1] - st[0][1]};
  k.dv = {st[3][0] - st[0][0], st[3][1] - st[0][1]};
  return k;
}

// The face's (u, v) at knots (s, t), and the surface's derivatives by s and t from those by u and v.
std::array<double, 2> face_uv(const KnotFrame& k, double s, double t) {
  const double det = k.du[0] * k.dv[1] - k.du[1] * k.dv[0], x = s - k.origin[0], y = t - k.origin[1];
  return {(x * k.dv[1] - y * k.dv[0]) / det, (k.du[0] * y - k.du[1] * x) / det};
}
void to_knot_derivatives(const KnotFrame& k, double* o) {
  const double det = k.du[0] * k.dv[1] - k.du[1] * k.dv[0];
  for (int c = 0; c < 3; ++c) {
    const double du = o[3 + c], dv = o[6 + c];
    o[3 + c] = (k.dv[1] * du - k.du[1] * dv) / det;
    o[6 + c] = (k.du[0] * dv - k.dv[0] * du) / det;
  }
}

// The tube's bicubic B-spline (the box's points, knots s(c) round the tube and t = z along it) at (s, t) in cell
// [s(c), s(c + 1)] x [r, r + 1], 1 <= r - 1 and r + 2 <= kTubeRows - 1 (its 4 x 4 points off the ends): value,
// d/ds, d/dt. Cox-de Boor on the cell's eight knots per direction.
void tube_spline(const TubeBox& box, int c, int r, double s, double t, double* out) {
  std::vector<double> ks, kt;
  for (int i = -3; i <= 4; ++i) {
    ks.push_back(box.s(c + i));
    kt.push_back(r + i);
  }
  const KnotVector us(3, ks), ut(3, kt);
  double ns[4], dns[4], nt[4], dnt[4];
  basis_values_first_derivatives<3>(us, 3, s, ns, dns);
  basis_values_first_derivatives<3>(ut, 3, t, nt, dnt);
  std::fill(out, out + 9, 0.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const auto& p = box.mesh.points[static_cast<std::size_t>(box.vertex(c - 1 + i, r - 1 + j))];
      for (std::size_t x = 0; x < 3; ++x) {
        out[x] += ns[i] * nt[j] * p[x];
        out[3 + x] += dns[i] * nt[j] * p[x];
        out[6 + x] += ns[i] * dnt[j] * p[x];
      }
    }
}

const std::vector<std::array<double, 2>>& face_samples() {
  static const std::vector<std::array<double, 2>> uv = [] {
    std::vector<std::array<double, 2>> r;
    for (double u : {0.0, 0.3, 0.65, 1.0})
      for (double v : {0.0, 0.4, 0.75, 1.0}) r.push_back({u, v});
    // Near each corner (a star corner's neighbourhood; OpenSubdiv is exact beyond 2^-10 from it).
    for (double a : {0.0, 1.0})
      for (double b : {0.0, 1.0})
        for (const auto& n : {std::array<double, 2>{1.0 / 128, 1.0 / 256}, {2e-3, 1e-3}, {0.3, 2e-3}})
          r.push_back({a == 0 ? n[0] : 1 - n[0], b == 0 ? n[1] : 1 - n[1]});
    return r;
  }();
  return uv;
}

struct SurfaceGap {
  int faces = 0;
  double position = 0, derivative = 0;
  void add(const double* x, const double* y, bool derivatives) {
    for (int k = 0; k < 3; ++k) position = std::max(position, std::abs(x[k] - y[k]));
    if (derivatives)
      for (int k = 3; k < 9; ++k) derivative = std::max(derivative, std::abs(x[k] - y[k]));
  }
};

// Every face whose 4 x 4 points lie in the tube against the tube's B-spline (box: without the knot segment), value
// and derivatives by the knots: faces of corners `corners` (vertices of `mesh`), eval(f, u, v, out[9]).
template <class Eval>
SurfaceGap against_tube_spline(const TubeBox& box, const TubeBox& mesh, const std::vector<std::array<int, 4>>& corners, const Eval& eval) {
  SurfaceGap d;
  for (int f = 0; f < static_cast<int>(corners.size()); ++f) {
    const KnotFrame k = knot_frame(mesh, corners[static_cast<std::size_t>(f)]);
    if (!k.tube) continue;
    const double sc = k.origin[0] + 0.5 * (k.du[0] + k.dv[0]), tc = k.origin[1] + 0.5 * (k.du[1] + k.dv[1]);
    const int r = static_cast<int>(std::floor(tc));
    if (r < 2 || r > kTubeRows - 3) continue;
    int c = 0;
    while (box.s(c + 1) <= sc) ++c;
    while (box.s(c) > sc) --c;
    ++d.faces;
    for (const auto& [u, v] : face_samples()) {
      double x[9], y[9];
      eval(f, u, v, x);
      to_knot_derivatives(k, x);
      tube_spline(box, c, r, k.origin[0] + u * k.du[0] + v * k.dv[0], k.origin[1] + u * k.du[1] + v * k.dv[1], y);
      d.add(x, y, true);
    }
  }
  return d;
}

// The corners of the faces of the mesh as given (from each face's first corner link).
std::vector<std::array<int, 4>> given_corners(const TMesh& m) {
  std::vector<std::array<int, 4>> r;
  for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    const auto first = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), m.first_corner(f)) - loop.begin());
    std::array<int, 4> c{};
    for (std::size_t i = 0; i < 4; ++i) c[i] = m.links[static_cast<std::size_t>(loop[(first + i) % loop.size()])].vertex;
    r.push_back(c);
  }
  return r;
}

// The corners of the surface's faces (its mesh's, after lines or global steps).
std::vector<std::array<int, 4>> surface_corners(const TMeshSurface& s) {
  std::vector<std::array<int, 4>> r;
  for (int f = 0; f < s.num_faces(); ++f) r.push_back(s.corners(f));
  return r;
}

// Surface `a` of the refined box against a surface of the box, reference(f, u, v, out[9]) on its faces of corners
// `box` (by their (u, v) from the first corner): each sample is taken from the face of the refined box that holds
// it, found by the corners (the box's vertices keep their ids; new ones lie on the tube, located by their knots).
// Faces with skip(f) are left out.
template <class Reference, class Skip>
SurfaceGap against_box(const TubeBox& refined, const TMeshSurface& a, const std::vector<std::array<int, 4>>& box, const Reference& reference,
                      const Skip& skip) {
  SurfaceGap d;
  for (int f = 0; f < static_cast<int>(box.size()); ++f) {
    if (skip(f)) continue;
    const std::array<int, 4>& fc = box[static_cast<std::size_t>(f)];
    // The position of a vertex in f's (u, v): a corner, or by the knots of the tube.
    static constexpr std::array<std::array<double, 2>, 4> unit{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
    const auto in_f = [&](int v) -> std::optional<std::array<double, 2>> {
      for (std::size_t i = 0; i < 4; ++i)
        if (fc[i] == v) return unit[i];
      const auto& o = refined.knot[static_cast<std::size_t>(fc[0])];
      const auto& x = refined.knot[static_cast<std::size_t>(v)];
      if (std::isnan(o[0]) || std::isnan(x[0])) return std::nullopt;
      const auto& p1 = refined.knot[static_cast<std::size_t>(fc[1])];
      const auto& p3 = refined.knot[static_cast<std::size_t>(fc[3])];
      const KnotFrame k{o, {p1[0] - o[0], p1[1] - o[1]}, {p3[0] - o[0], p3[1] - o[1]}, true};
      if (std::abs(k.du[0]) > 2 || std::abs(k.dv[0]) > 2) return std::nullopt;  // across the girth's wrap
      return face_uv(k, x[0], x[1]);
    };
    // The refined faces inside f, as frames in f's (u, v).
    std::vector<std::pair<int, KnotFrame>> parts;
    for (int g = 0; g < a.num_faces(); ++g) {
      const auto gc = a.corners(g);
      int shared = 0;
      for (int v : gc) shared += static_cast<int>(std::count(fc.begin(), fc.end(), v));
      if (shared < 2) continue;
      std::array<std::array<double, 2>, 4> q{};
      bool inside = true;
      for (std::size_t i = 0; i < 4 && inside; ++i) {
        const auto p = in_f(gc[i]);
        inside = p && (*p)[0] > -1e-12 && (*p)[0] < 1 + 1e-12 && (*p)[1] > -1e-12 && (*p)[1] < 1 + 1e-12;
        if (inside) q[i] = *p;
      }
      if (inside) parts.push_back({g, KnotFrame{q[0], {q[1][0] - q[0][0], q[1][1] - q[0][1]}, {q[3][0] - q[0][0], q[3][1] - q[0][1]}, true}});
    }
    ++d.faces;
    int taken = 0;
    for (const auto& [u, v] : face_samples()) {
      for (const auto& [g, k] : parts) {
        const auto w = face_uv(k, u, v);
        if (w[0] < -1e-12 || w[0] > 1 + 1e-12 || w[1] < -1e-12 || w[1] > 1 + 1e-12) continue;
        double x[9], y[9];
        a.eval(g, std::clamp(w[0], 0.0, 1.0), std::clamp(w[1], 0.0, 1.0), x);
        to_knot_derivatives(k, x);  // by f's (u, v)
        reference(f, u, v, y);
        d.add(x, y, !((u == 0 || u == 1) && (v == 0 || v == 1)));  // at a star corner the derivatives are directions
        ++taken;
        break;
      }
    }
    EXPECT_EQ(taken, static_cast<int>(face_samples().size())) << "face " << f;
  }
  return d;
}

// A knot segment: the split faces' girth column, where the knot divides its interval, and the vertex rows it is
// inserted into (T-junctions on the faces of rows first - 1 and last). Rows 7 to 10 keep the T-junctions 6 face
// rings from the star points' faces (the faces of rows 0 and 16).
struct Segment {
  int column;
  double fraction;
  int first, last;
};
constexpr Segment kNextToStrip{2, 0.35, 7, 10}, kInStrip{7, 0.6, 7, 9};

// s + n period nearest to `near`.
double unwrapped(double s, double near, double period) { return s + period * std::round((near - s) / period); }

// Continuity across the sides of the faces with T-junctions (which test::continuity, for edges between
// quadrilaterals, leaves out): position, normal and the derivatives by the knots (C2 there: equal).
test::Continuity across_t_junction_faces(const TubeBox& b, const TMeshSurface& s) {
  test::Continuity c;
  const TMesh& m = s.mesh();
  const double period = b.girth_knot[kGirth];
  for (const TMeshLink& l : m.links) {
    if (l.vertex < 0 || l.face < 0 || m.faces[static_cast<std::size_t>(l.face)].size() == 4) continue;
    const int other = m.links[static_cast<std::size_t>(l.opp)].face;
    const KnotFrame ka = knot_frame(b, s.corners(l.face)), kb = knot_frame(b, s.corners(other));
    const auto& p = b.knot[static_cast<std::size_t>(l.vertex)];
    const auto& q = b.knot[static_cast<std::size_t>(m.links[static_cast<std::size_t>(l.next)].vertex)];
    if (!ka.tube || !kb.tube) continue;
    ++c.edges;
    for (double t : test::tenths()) {
      const double x = unwrapped(p[0] + t * (unwrapped(q[0], p[0], period) - p[0]), ka.origin[0], period), y = p[1] + t * (q[1] - p[1]);
      double oa[9], ob[9];
      const auto ua = face_uv(ka, x, y), ub = face_uv(kb, unwrapped(x, kb.origin[0], period), y);
      s.eval(l.face, ua[0], ua[1], oa);
      s.eval(other, ub[0], ub[1], ob);
      to_knot_derivatives(ka, oa);
      to_knot_derivatives(kb, ob);
      c.gap = std::max(c.gap, std::hypot(oa[0] - ob[0], oa[1] - ob[1], oa[2] - ob[2]));
      const auto na = test::unit_normal(oa), nb = test::unit_normal(ob);
      c.normal_angle = std::max(c.normal_angle, std::hypot(na[0] - nb[0], na[1] - nb[1], na[2] - nb[2]));
      double size = 0, d = 0;
      for (int k = 3; k < 9; ++k) {
        size = std::max(size, std::abs(oa[k]));
        d = std::max(d, std::abs(oa[k] - ob[k]));
      }
      c.c1 = std::max(c.c1, d / size);
    }
  }
  return c;
}

// The exact faces against the T-spline of a chart of their three face rings (the rings a bicubic blending
// function's support spans from a face; a chart of two rings of a split face lacks a knot of the function of the
// vertex diagonally below it, whose row has no knot in the column, and is 1e-3 off there).
SurfaceGap against_charts(const TMesh& mesh, const TMeshSurface& s) {
  SurfaceGap r;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) != FaceMethod::exact) continue;
    const TChart chart = t_spline_chart(mesh, test::face_rings(mesh, f, 3), f, false);
    const TSplineSurface ts(chart.spline, 1);
    std::array<std::array<double, 2>, 4> st{};
    const auto c = s.corners(f);
    for (std::size_t i = 0; i < 4; ++i) {
      const TVertex& x = chart.spline.image.vertices[static_cast<std::size_t>(chart.vertex[static_cast<std::size_t>(c[i])])];
      st[i] = {x.s, x.t};
    }
    const KnotFrame k{st[0], {st[1][0] - st[0][0], st[1][1] - st[0][1]}, {st[3][0] - st[0][0], st[3][1] - st[0][1]}, true};
    ++r.faces;
    for (const auto& [u, v] : face_samples()) {
      double a[9], b[9];
      s.eval(f, u, v, a);
      to_knot_derivatives(k, a);
      ts.eval_first_derivatives(Param<2>{k.origin[0] + u * k.du[0] + v * k.dv[0], k.origin[1] + u * k.du[1] + v * k.dv[1]}, b);
      r.add(a, b, true);
    }
  }
  return r;
}

// The largest spread, over the star points, of the limit positions and unit normals of the faces round each.
std::array<double, 2> star_point_spread(const TMeshSurface& s) {
  std::array<double, 2> r{};
  for (int star : s.stars()) {
    std::vector<std::array<double, 6>> at;  // position, unit normal
    for (int f = 0; f < s.num_faces(); ++f) {
      const auto c = s.corners(f);
      const auto k = std::find(c.begin(), c.end(), star) - c.begin();
      if (k == 4) continue;
      double o[9];
      s.eval(f, k == 1 || k == 2 ? 1 : 0, k >= 2 ? 1 : 0, o);
      const auto n = test::unit_normal(o);
      at.push_back({o[0], o[1], o[2], n[0], n[1], n[2]});
    }
    for (const auto& x : at)
      for (const auto& y : at) {
        r[0] = std::max(r[0], std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
        r[1] = std::max(r[1], std::hypot(x[3] - y[3], x[4] - y[4], x[5] - y[5]));
      }
  }
  return r;
}

// The mesh with the knot segment: its faces near the close star points are crease faces (local subdivision; the
// T-junctions keep the global steps away), the others exact or bicubic. It is the box's surface: against the
// tube's B-spline, against the box evaluated the same way and after its two global steps, and against the
// T-spline in charts; continuous across every edge; one limit point and tangent plane per star point.
void check_knot_segment(const Segment& seg) {
  const TubeBox box = tube_box(1.5), refined = insert_knot_segment(box, seg.column, seg.fraction, seg.first, seg.last);
  const TMesh plain = tsm_mesh(box), mesh = tsm_mesh(refined);
  EXPECT_EQ(nurcc_steps_needed(plain, TMeshSurface::kStarsApart), 2);
  EXPECT_EQ(nurcc_steps_needed(mesh, TMeshSurface::kStarsApart), 0);  // T-junctions: no global steps
  const TMeshSurface s(mesh, 1);
  ASSERT_EQ(s.num_faces(), 2 * 9 + 12 * kTubeRows + (seg.last - seg.first));
  EXPECT_EQ(s.global_steps(), 0);
  EXPECT_EQ(s.stars().size(), 8u);
  int t_faces = 0;
  for (const auto& loop : s.mesh().faces) t_faces += loop.size() == 5;
  EXPECT_EQ(t_faces, 2);
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  EXPECT_GT(s.count(FaceMethod::exact), 0);
  // The box's vertices keep their ids and points where the segment leaves them.
  for (std::size_t v = 0; v < refined.mesh.points.size(); ++v) {
    const auto& p = mesh.points[static_cast<std::size_t>(mesh.vertices[v].primary)].xyz;
    ASSERT_EQ(p, refined.mesh.points[v]) << v;
  }

  const TMeshSurface local(plain, 1, 0), stepped(plain, 1);
  ASSERT_EQ(stepped.global_steps(), 2);
  const SurfaceGap tube = against_tube_spline(box, refined, surface_corners(s), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  const SurfaceGap tube_plain = against_tube_spline(box, box, surface_corners(local), [&](int f, double u, double v, double* o) { local.eval(f, u, v, o); });
  EXPECT_GT(tube.faces, 12 * (kTubeRows - 4));
  EXPECT_LT(tube.position, 1e-13);
  EXPECT_LT(tube.derivative, 1e-12);
  EXPECT_LT(tube_plain.position, 1e-13);
  EXPECT_LT(tube_plain.derivative, 1e-12);

  const auto whole_box = [](int) { return false; };
  const std::vector<std::array<int, 4>> box_faces = given_corners(plain);
  const auto eval_local = [&](int f, double u, double v, double* o) { local.eval_source(f, u, v, o); };
  const auto eval_stepped = [&](int f, double u, double v, double* o) { stepped.eval_source(f, u, v, o); };
  const SurfaceGap same = against_box(refined, s, box_faces, eval_local, whole_box), after_steps = against_box(refined, s, box_faces, eval_stepped, whole_box);
  std::vector<char> crease_of_box(local.source_mesh().faces.size(), 0);
  for (int f = 0; f < local.num_faces(); ++f) crease_of_box[static_cast<std::size_t>(f)] = local.method(f) == FaceMethod::crease;
  const SurfaceGap crease = against_box(refined, s, box_faces, eval_stepped, [&](int f) { return !crease_of_box[static_cast<std::size_t>(f)]; });
  EXPECT_EQ(same.faces, 2 * 9 + 12 * kTubeRows);
  EXPECT_EQ(crease.faces, local.count(FaceMethod::crease));
  EXPECT_LT(same.position, 1e-13);
  EXPECT_LT(same.derivative, 1e-11);
  EXPECT_LT(after_steps.position, 1e-13);
  EXPECT_LT(after_steps.derivative, 1e-11);

  const SurfaceGap charts = against_charts(mesh, s);
  EXPECT_EQ(charts.faces, s.count(FaceMethod::exact));
  EXPECT_LT(charts.position, 1e-12);
  EXPECT_LT(charts.derivative, 1e-11);

  const test::Continuity c = test::continuity(s.mesh(), test::knot_units(s)), ct = across_t_junction_faces(refined, s);
  EXPECT_EQ(c.edges + ct.edges, 2 * s.num_faces() + 1);  // every edge: (4 F + 2) / 2 with two faces of five sides
  EXPECT_LT(c.gap, 1e-13);
  EXPECT_LT(c.normal_angle, 1e-10);
  EXPECT_LT(c.c1, 1e-10);
  EXPECT_LT(ct.gap, 1e-13);
  EXPECT_LT(ct.normal_angle, 1e-12);
  EXPECT_LT(ct.c1, 1e-12);
  const auto spread = star_point_spread(s);
  EXPECT_LT(spread[0], 1e-13);
  EXPECT_LT(spread[1], 1e-10);
  std::printf("box 3 x 3 x %d, strip at 1.5, knot segment in column %d at %.2f over rows %d..%d: %d faces (crease %d, exact %d, bicubic %d, star %d, "
              "subdivided %d, non-uniform %d); against the tube's B-spline on %d faces %.1e / %.1e (position / derivatives by the "
              "knots); against the box without it: the same methods %.1e / %.1e, two global steps %.1e / %.1e (its %d crease "
              "faces %.1e / %.1e); exact faces against %d three-ring charts %.1e / %.1e; continuity across %d + %d edges gap "
              "%.1e / %.1e, normals %.1e / %.1e, C1 %.1e / %.1e (knot units); star points: positions %.1e, normals %.1e\n",
              kTubeRows, seg.column, seg.fraction, seg.first, seg.last, s.num_faces(), s.count(FaceMethod::crease), s.count(FaceMethod::exact), s.count(FaceMethod::bicubic),
              s.count(FaceMethod::star), s.count(FaceMethod::subdivided), s.count(FaceMethod::non_uniform), tube.faces, tube.position,
              tube.derivative, same.position, same.derivative, after_steps.position, after_steps.derivative, crease.faces, crease.position,
              crease.derivative, charts.faces, charts.position, charts.derivative, c.edges, ct.edges, c.gap, ct.gap, c.normal_angle,
              ct.normal_angle, c.c1, ct.c1, spread[0], spread[1]);
}

TEST(TJunctionLocalSubdivision, KnotSegmentNextToTheStrip) { check_knot_segment(kNextToStrip); }
TEST(TJunctionLocalSubdivision, KnotSegmentInTheStrip) { check_knot_segment(kInStrip); }

// Equal intervals (the knot segment alone unequal): the box without it is a Catmull-Clark limit surface, and the
// refined mesh must be OpenSubdiv's limit surface of the box on every face.
TEST(TJunctionLocalSubdivision, EqualIntervalsAreOpenSubdivsLimitSurface) {
  const Segment seg = kNextToStrip;
  const TubeBox box = tube_box(1.0), refined = insert_knot_segment(box, seg.column, seg.fraction, seg.first, seg.last);
  const TMeshSurface s(tsm_mesh(refined), 1);
  const std::vector<std::array<int, 4>> box_faces = given_corners(tsm_mesh(box));
  test::PolyMesh p;
  p.points = box.mesh.points;
  for (const auto& c : box_faces) p.faces.push_back({c.begin(), c.end()});
  const test::OsdLimitSurface osd(p);
  const auto eval_osd = [&](int f, double u, double v, double* o) {
    const test::LimitSample l = osd.eval(f, u, v);
    for (std::size_t k = 0; k < 3; ++k) {
      o[k] = l.p[k];
      o[3 + k] = l.du[k];
      o[6 + k] = l.dv[k];
    }
  };
  const SurfaceGap d = against_box(refined, s, box_faces, eval_osd, [](int) { return false; });
  EXPECT_EQ(d.faces, 2 * 9 + 12 * kTubeRows);
  EXPECT_LT(d.position, 1e-12);
  EXPECT_LT(d.derivative, 1e-10);
  std::printf("box 3 x 3 x %d, equal intervals, knot segment over rows %d..%d: %d faces (star %d, subdivided %d, exact %d, bicubic %d) "
              "against OpenSubdiv's limit surface of the box %.1e / %.1e (position / derivatives)\n", kTubeRows, seg.first, seg.last, s.num_faces(),
              s.count(FaceMethod::star), s.count(FaceMethod::subdivided), s.count(FaceMethod::exact), s.count(FaceMethod::bicubic),
              d.position, d.derivative);
}

// T-junctions 3, 4 and 5 face rings from the star points' faces: their lines are completed first (t_junction_lines).
// The knot segment at 0.35 of column 2 then runs the whole tube and on into both end caps, where it crosses a cap's
// edge next to a star point (the star point's row goes on past it as the subdivision rules' interval does). Along the
// tube the line is knot insertion, so every face whose 4 x 4 points lie in the tube is the tube's B-spline; the
// surface is continuous with one tangent plane across every edge and at every star point.
TEST(TJunctionLocalSubdivision, TJunctionsWithinFiveRingsCompleteIntoLinesThroughTheEndCaps) {
  for (const Segment& seg : {Segment{2, 0.35, 4, 10}, Segment{2, 0.35, 5, 10}, Segment{2, 0.35, 6, 10}}) {
    const TubeBox box = tube_box(1.5), refined = insert_knot_segment(box, seg.column, seg.fraction, seg.first, seg.last);
    const TMeshSurface s(tsm_mesh(refined), 1);
    ASSERT_NE(s.completed_lines(), nullptr);
    EXPECT_EQ(s.completed_lines()->lines, 1);  // round the tube, closing on the segment's other T-junction
    const TMesh& given = s.source_mesh();
    const std::vector<std::array<int, 4>> corners = given_corners(given);
    std::vector<std::array<int, 4>> quads;
    std::vector<int> face_of;
    for (int f = 0; f < static_cast<int>(given.faces.size()); ++f)
      if (given.faces[static_cast<std::size_t>(f)].size() == 4) {
        quads.push_back(corners[static_cast<std::size_t>(f)]);
        face_of.push_back(f);
      }
    const SurfaceGap tube = against_tube_spline(box, refined, quads, [&](int i, double u, double v, double* o) {
      s.eval_source(face_of[static_cast<std::size_t>(i)], u, v, o);
    });
    EXPECT_GT(tube.faces, 12 * (kTubeRows - 6));
    EXPECT_LT(tube.position, 1e-13);
    EXPECT_LT(tube.derivative, 1e-12);
    const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
    EXPECT_EQ(c.edges, 2 * s.num_faces());
    EXPECT_LT(c.gap, 1e-13);
    EXPECT_LT(c.normal_angle, 1e-9);
    const auto spread = star_point_spread(s);
    EXPECT_LT(spread[0], 1e-13);
    EXPECT_LT(spread[1], 1e-9);
    std::printf("box 3 x 3 x %d, strip at 1.5, knot segment in column %d at %.2f over rows %d..%d: %d lines (%d vertices inserted), "
                "%d faces; against the tube's B-spline on %d faces %.1e / %.1e; across %d edges gap %.1e, normals %.1e; star "
                "points: positions %.1e, normals %.1e\n", kTubeRows, seg.column, seg.fraction, seg.first, seg.last,
                s.completed_lines()->lines, s.completed_lines()->vertices, s.num_faces(), tube.faces, tube.position, tube.derivative,
                c.edges, c.gap, c.normal_angle, spread[0], spread[1]);
  }
}

}  // namespace
}  // namespace trivar
