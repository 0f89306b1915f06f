// T-meshes with star points against OpenSubdiv (osd_reference), an independent implementation of Catmull-Clark
// subdivision: face by face, positions and first derivatives, with equal knot intervals (uniform Catmull-Clark
// is what OpenSubdiv computes). Closed cages as Fusion 360 writes them (subdivided, star, bicubic and exact faces)
// and open meshes with Fusion's SUBD_CREASES boundary (trivar's Bezier end-condition form of the crease, against
// OpenSubdiv's infinitely sharp boundary edges and corners).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>

#include "fusion_cages.hpp"
#include "osd_reference.hpp"
#include "star_mesh_tsm.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar::osd_comparison_test {

using P3 = std::array<double, 3>;
using test::LimitSample;
using test::OsdLimitSurface;
using test::PolyMesh;
using test::QuadMesh;

// The control mesh of a T-mesh surface as OpenSubdiv's: the vertices' points and each face's corners in trivar's
// order (first corner link, then counter-clockwise), so that trivar's face frame (u along the first corner link,
// v turning left) is OpenSubdiv's (u, v) of the face (corners at (0, 0), (1, 0), (1, 1), (0, 1)).
PolyMesh poly_mesh(const TMeshSurface& s, bool sharp_corners) {
  const TMesh& m = s.source_mesh();
  PolyMesh p;
  for (const TMeshVertex& v : m.vertices) p.points.push_back(m.points[static_cast<std::size_t>(v.primary)].xyz);
  for (int f = 0; f < s.num_faces(); ++f) {
    EXPECT_EQ(m.faces[static_cast<std::size_t>(f)].size(), 4u) << "face " << f << " is not a quadrilateral";
    const auto c = s.corners(f);
    p.faces.push_back({c.begin(), c.end()});
  }
  p.sharp_corners = sharp_corners;
  return p;
}

struct Deviation {
  double position = 0, derivative = 0;
  int samples = 0;
  void add(const double* a, const LimitSample& b, bool derivatives) {
    const auto gap = [](const double* x, const P3& y) { return std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]); };
    position = std::max(position, gap(a, b.p));
    if (derivatives) derivative = std::max({derivative, gap(a + 3, b.du), gap(a + 6, b.dv)});
    ++samples;
  }
};

constexpr std::array<std::array<double, 2>, 4> kCorners{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};

// trivar against OpenSubdiv on the faces `faces` (all when empty): a 4 x 4 grid of (u, v) per face including its
// corners, and at each star corner four points from 2^-7 down to 1.1e-3 of it. OpenSubdiv is exact outside 2^-10
// of an extraordinary corner (osd_reference.hpp), so only the star corners themselves are approximated: their
// positions are the exact limit point in both, their derivatives are not compared (the face parametrisation is
// singular at a star point for valence != 4: they vanish or diverge).
Deviation compare(const TMeshSurface& s, const OsdLimitSurface& osd, const std::vector<int>& faces = {}) {
  const std::set<int> stars(s.stars().begin(), s.stars().end());
  std::vector<int> all = faces;
  if (all.empty())
    for (int f = 0; f < s.num_faces(); ++f) all.push_back(f);
  Deviation d;
  for (int f : all) {
    const auto c = s.corners(f);
    std::vector<std::array<double, 2>> uv;
    for (double u : {0.0, 0.3, 0.65, 1.0})
      for (double v : {0.0, 0.4, 0.75, 1.0}) uv.push_back({u, v});
    for (int k = 0; k < 4; ++k)
      if (stars.count(c[static_cast<std::size_t>(k)]))
        for (const auto& n : {std::array<double, 2>{1.0 / 128, 1.0 / 256}, {1.0 / 512, 0}, {0, 1.0 / 200}, {1.1e-3, 0.55e-3}}) {
          const auto& o = kCorners[static_cast<std::size_t>(k)];
          uv.push_back({o[0] == 0 ? n[0] : 1 - n[0], o[1] == 0 ? n[1] : 1 - n[1]});
        }
    for (const auto& [u, v] : uv) {
      double a[9];
      s.eval(f, u, v, a);
      bool at_star = false;
      for (int k = 0; k < 4; ++k)
        at_star |= u == kCorners[static_cast<std::size_t>(k)][0] && v == kCorners[static_cast<std::size_t>(k)][1] &&
                   stars.count(c[static_cast<std::size_t>(k)]);
      d.add(a, osd.eval(f, u, v), !at_star);
    }
  }
  return d;
}

TMeshSurface fusion_surface(const QuadMesh& q, const char* name) {
  return TMeshSurface(io::parse_tsm(test::fusion_text(q), name).mesh, 1);
}

void report(const char* name, const TMeshSurface& s, const Deviation& d) {
  std::printf("%s: %d faces (exact %d, bicubic %d, star %d, subdivided %d), %d samples: position %.2e, d/du d/dv %.2e\n",
              name, s.num_faces(), s.count(FaceMethod::exact), s.count(FaceMethod::bicubic), s.count(FaceMethod::star),
              s.count(FaceMethod::subdivided), d.samples, d.position, d.derivative);
}

double wave(double x, double y) { return 0.4 * std::sin(0.9 * x + 0.3) * std::cos(0.6 * y - 0.2) + 0.03 * x * y; }

// A closed cage: an n-gonal prism whose caps are fans of n sectors of m x m faces (a star point of valence n at
// each centre, n valence-3 star points at the caps' sector corners on the rims) and whose side has h rows of
// faces. Points are perturbed so that no symmetry hides a wrong face frame.
QuadMesh prism_cage(int n, int m, int h) {
  const double height = 0.7 * m;
  QuadMesh q = test::fan_mesh(n, m, [&](double x, double y) { return height + 0.3 * wave(x, y); });
  const int cap = static_cast<int>(q.points.size());
  // The rim: the cap's boundary edges (each once, counter-clockwise round the cap) chained into a loop.
  std::map<int, int> next;
  std::set<std::array<int, 2>> edges;
  for (const auto& f : q.quads)
    for (int k = 0; k < 4; ++k) edges.insert({f[k], f[(k + 1) % 4]});
  for (const auto& e : edges)
    if (!edges.count({e[1], e[0]})) next[e[0]] = e[1];
  std::vector<int> rim{next.begin()->first};
  while (next.at(rim.back()) != rim.front()) rim.push_back(next.at(rim.back()));
  // The bottom cap: the top mirrored (its faces turned round) and bent differently.
  const std::vector<std::array<int, 4>> top_quads = q.quads;
  for (int v = 0; v < cap; ++v) {
    const P3 p = q.points[static_cast<std::size_t>(v)];
    q.points.push_back({p[0], p[1], -height - 0.2 * wave(p[1], p[0])});
  }
  for (const auto& f : top_quads) q.quads.push_back({f[3] + cap, f[2] + cap, f[1] + cap, f[0] + cap});
  // Rings of the side from the top rim (r = 0) to the bottom one (r = h), bulging out.
  const int r_count = static_cast<int>(rim.size());
  std::vector<std::vector<int>> ring(static_cast<std::size_t>(h + 1));
  ring[0] = rim;
  for (int v : rim) ring[static_cast<std::size_t>(h)].push_back(v + cap);
  for (int r = 1; r < h; ++r)
    for (int v : rim) {
      const double t = double(r) / h, bulge = 1 + 0.15 * std::sin(std::numbers::pi * t);
      const P3 a = q.points[static_cast<std::size_t>(v)], b = q.points[static_cast<std::size_t>(v + cap)];
      ring[static_cast<std::size_t>(r)].push_back(static_cast<int>(q.points.size()));
      q.points.push_back({bulge * a[0], bulge * a[1], (1 - t) * a[2] + t * b[2]});
    }
  for (int r = 0; r < h; ++r)
    for (int i = 0; i < r_count; ++i) {
      const auto& a = ring[static_cast<std::size_t>(r)];
      const auto& b = ring[static_cast<std::size_t>(r + 1)];
      const int j = (i + 1) % r_count;
      q.quads.push_back({a[j], a[i], b[i], b[j]});
    }
  return q;
}

// Closed cages (no boundary), every kind of Catmull-Clark face trivar has: the cube of one face per side
// (subdivided faces: four star corners each), of 3 x 3 faces per side (valence-3 star faces), the torus (no star
// point: exact faces, each the T-spline of its chart), prisms with fan caps (star points of valence 3, 5, 6 and 8)
// and the cube with a turned edge (valence-3 and 5 star points joined by edges: subdivided faces among star
// faces). Equal knot intervals, weights 1 (OpenSubdiv has no rational Catmull-Clark).
TEST(OsdComparison, ClosedCagesAgreeOnEveryFace) {
  struct Case {
    const char* name;
    QuadMesh cage;
  };
  const std::vector<Case> cases{{"cube 1 x 1", test::cube_mesh(1)},       {"cube 3 x 3", test::cube_mesh(3)},
                                {"torus 12 x 8", test::torus_cage(12, 8)}, {"prism 3", prism_cage(3, 3, 3)},
                                {"prism 5", prism_cage(5, 3, 3)},          {"prism 6", prism_cage(6, 3, 2)},
                                {"prism 8", prism_cage(8, 3, 2)},          {"cube with a turned edge", test::turned_edge_cube()}};
  for (const Case& c : cases) {
    const TMeshSurface s = fusion_surface(c.cage, "cage.tsm");
    const Deviation d = compare(s, OsdLimitSurface(poly_mesh(s, true)));
    report(c.name, s, d);
    // Measured: positions to 1.5e-14 (the torus, 26 units across), derivatives to 1.2e-12 (Stam's evaluation near
    // the star points, whose eigenvector rounding grows with the subdivision level of the sample).
    EXPECT_LT(d.position, 1e-13) << c.name;
    EXPECT_LT(d.derivative, 5e-12) << c.name;
  }
  const TMeshSurface cube(io::parse_tsm(test::fusion_text(test::cube_mesh(1)), "cube.tsm").mesh, 1);
  EXPECT_EQ(cube.count(FaceMethod::subdivided), 6);
}

// Fusion's SUBD_CREASES boundary (trivar: its Bezier end-condition form, crease_ends) is OpenSubdiv's boundary
// with infinitely sharp edges and sharp corners (VTX_BOUNDARY_EDGE_AND_CORNER): the same surface on every face of
// a grid and of a fan round an interior star point of valence 5 (whose boundary has five convex corners). With
// sharp edges only (VTX_BOUNDARY_EDGE_ONLY) a vertex of one face is a smooth boundary vertex, not interpolated:
// exactly the corner faces differ.
TEST(OsdComparison, CreaseBoundaryIsTheSharpBoundaryWithSharpCorners) {
  const TMeshSurface grid = fusion_surface(test::grid_cage(6, 5), "grid.tsm");
  const Deviation sharp = compare(grid, OsdLimitSurface(poly_mesh(grid, true)));
  report("grid 6 x 5, sharp corners", grid, sharp);
  EXPECT_LT(sharp.position, 1e-13);
  EXPECT_LT(sharp.derivative, 1e-13);
  const OsdLimitSurface smooth(poly_mesh(grid, false));
  const std::set<int> corner_faces{0, 5, 24, 29};
  for (int f = 0; f < grid.num_faces(); ++f) {
    const Deviation d = compare(grid, smooth, {f});
    if (corner_faces.count(f))
      EXPECT_GT(d.position, 0.1) << f;
    else
      EXPECT_LT(std::max(d.position, d.derivative), 1e-13) << f;
  }

  const TMeshSurface fan = fusion_surface(test::fan_mesh(5, 7, wave), "fan.tsm");
  EXPECT_EQ(fan.count(FaceMethod::star), 5);
  const Deviation d = compare(fan, OsdLimitSurface(poly_mesh(fan, true)));
  report("crease fan round a valence-5 star point", fan, d);
  EXPECT_LT(d.position, 1e-13);
  EXPECT_LT(d.derivative, 1e-12);
}

// A star point on a SUBD_CREASES boundary (K = 4 and 5 faces on a straight boundary). OpenSubdiv applies the
// crease rules there (Hoppe et al. 1994; boundary vertex (P- + 6 P + P+) / 8, boundary edge midpoints), so its
// boundary curve is the uniform cubic B-spline of the boundary points and the limit point (P- + 4 P + P+) / 6,
// checked here in closed form; trivar evaluates the faces round it by local subdivision with the same rules
// (crease_face) and agrees with both, on every face.
TEST(OsdComparison, CreaseBoundaryStarPointFollowsTheCreaseRule) {
  for (int k : {4, 5}) {
    const TMeshSurface s = fusion_surface(test::half_fan_mesh(k, 6, wave), "half_fan.tsm");
    ASSERT_EQ(s.stars().size(), 1u);
    EXPECT_GT(s.count(FaceMethod::crease), 0);
    const int star = s.stars()[0];
    const PolyMesh mesh = poly_mesh(s, true);
    const OsdLimitSurface osd(mesh);
    // The boundary as a chain of directed edges (faces counter-clockwise: the boundary runs with the faces).
    std::set<std::array<int, 2>> edges;
    for (const auto& f : mesh.faces)
      for (std::size_t i = 0; i < 4; ++i) edges.insert({f[i], f[(i + 1) % 4]});
    std::map<int, int> next, prev;
    for (const auto& e : edges)
      if (!edges.count({e[1], e[0]})) next[e[0]] = e[1], prev[e[1]] = e[0];
    const auto point = [&](int v) { return mesh.points[static_cast<std::size_t>(v)]; };
    const std::array<P3, 4> b{point(prev.at(star)), point(star), point(next.at(star)), point(next.at(next.at(star)))};
    P3 crease{};
    for (int c = 0; c < 3; ++c) crease[c] = (b[0][c] + 4 * b[1][c] + b[2][c]) / 6;
    const auto gap = [](const P3& x, const P3& y) { return std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]); };
    EXPECT_LT(gap(osd.vertex_limits()[static_cast<std::size_t>(star)].p, crease), 1e-14) << k;
    // The star face along the boundary edge star -> next(star), and that edge as a curve of the face's (u, v).
    int face = -1, corner = -1;
    for (int f = 0; f < s.num_faces(); ++f)
      for (int c = 0; c < 4; ++c)
        if (mesh.faces[static_cast<std::size_t>(f)][static_cast<std::size_t>(c)] == star &&
            mesh.faces[static_cast<std::size_t>(f)][static_cast<std::size_t>((c + 1) % 4)] == next.at(star))
          face = f, corner = c;
    ASSERT_GE(face, 0);
    double curve_osd = 0, curve_trivar = 0;
    for (double t : {0.0, 0.25, 0.5, 0.75}) {
      const std::array<std::array<double, 2>, 4> along{{{t, 0}, {1, t}, {1 - t, 1}, {0, 1 - t}}};
      const auto [u, v] = along[static_cast<std::size_t>(corner)];
      const double w[4] = {(1 - t) * (1 - t) * (1 - t) / 6, (3 * t * t * t - 6 * t * t + 4) / 6,
                           (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
      P3 x{};
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) x[c] += w[i] * b[static_cast<std::size_t>(i)][c];
      double a[9];
      s.eval(face, u, v, a);
      curve_osd = std::max(curve_osd, gap(osd.eval(face, u, v).p, x));
      curve_trivar = std::max(curve_trivar, gap({a[0], a[1], a[2]}, x));
    }
    EXPECT_LT(curve_osd, 1e-14) << k;
    EXPECT_LT(curve_trivar, 1e-14) << k;
    double a[9];
    s.eval(face, corner == 0 || corner == 3 ? 0 : 1, corner < 2 ? 0 : 1, a);
    EXPECT_LT(gap({a[0], a[1], a[2]}, crease), 1e-14) << k;
    const Deviation d = compare(s, osd);
    EXPECT_LT(d.position, 1e-13) << k;
    EXPECT_LT(d.derivative, 1e-11) << k;
    std::printf("crease boundary star point of %d faces: %d faces by local subdivision; against OpenSubdiv %d samples: "
                "position %.2e, d/du d/dv %.2e; boundary curve of its face off the B-spline of the boundary points: "
                "OpenSubdiv %.2e, trivar %.2e; trivar's limit point %.2e from the crease rule's\n",
                k, s.count(FaceMethod::crease), d.samples, d.position, d.derivative, curve_osd, curve_trivar, gap({a[0], a[1], a[2]}, crease));
  }
}

// The exact faces of crease meshes round irregular vertices share charts as large as their layout allows: round a
// boundary vertex of 4 faces the chart's two boundary sides would lie on one line (they must not touch), of 5
// faces the chart would overlap itself by a sector, round an interior star point it would close on itself. Every
// face against OpenSubdiv, and the exact faces in at most two charts.
TEST(OsdComparison, ExactFacesRoundIrregularVerticesShareCharts) {
  struct Case {
    const char* name;
    QuadMesh cage;
  };
  const std::vector<Case> cases{{"half fan of 4 sectors", test::half_fan_mesh(4, 10, wave)},
                                {"half fan of 5 sectors", test::half_fan_mesh(5, 10, wave)},
                                {"fan of 5 sectors", test::fan_mesh(5, 10, wave)}};
  for (const Case& c : cases) {
    const TMeshSurface s = fusion_surface(c.cage, "fan.tsm");
    std::set<const TSplineSurface*> charts;
    for (int f = 0; f < s.num_faces(); ++f)
      if (s.method(f) == FaceMethod::exact) charts.insert(s.chart_frame(f).chart);
    EXPECT_GT(s.count(FaceMethod::exact), 200) << c.name;
    EXPECT_LE(charts.size(), 2u) << c.name;
    const Deviation d = compare(s, OsdLimitSurface(poly_mesh(s, true)));
    EXPECT_LT(d.position, 1e-13) << c.name;
    EXPECT_LT(d.derivative, 1e-11) << c.name;
    std::printf("%s, crease boundary: %d exact faces in %zu charts; against OpenSubdiv %d samples: position %.2e, d/du d/dv %.2e\n",
                c.name, s.count(FaceMethod::exact), charts.size(), d.samples, d.position, d.derivative);
  }
}

}  // namespace trivar::osd_comparison_test
