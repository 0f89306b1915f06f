// Darts (a sharp crease ending at a vertex inside the mesh) and cone points (a creased vertex inside the mesh on no
// crease) of subdivision-crease T-meshes (Fusion's `100edges` / `100verts` with SUBD_CREASES), evaluated by local
// subdivision (crease_face), against OpenSubdiv's Catmull-Clark limit surface with the same infinitely sharp edges
// and vertices (an independent implementation: Bfr is exact to rounding farther than 2^-10 from irregular
// vertices and interpolates the limit point at them; Far's limit masks give the limit point and tangents at every
// vertex). At a dart OpenSubdiv's limit masks are the smooth vertex's, which miss its limit (the sharp edge's
// midpoint rule moves it): Bfr's value at the dart is that mask after 10 levels, Far's after the levels asked
// (osd_reference.hpp); both converge to the limit geometrically, and Aitken's extrapolation of the last three
// levels is the reference there. A cone point is interpolated (theory).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "face_continuity.hpp"
#include "fusion_cages.hpp"
#include "osd_reference.hpp"
#include "star_mesh_tsm.hpp"
#include "support/temp_dir.hpp"
#include "triangulation_loops.hpp"
#include "tsm_error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/sharp_creases.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar::dart_test {
namespace {

using P3 = std::array<double, 3>;
using Sharp = std::function<bool(int, int)>;

double ripple(double x, double y) { return 0.3 * std::sin(0.9 * x + 0.4 * y) + 0.05 * x * y; }

// OpenSubdiv's control mesh of the cage with the same sharp edges and vertices; `coordinates` replaces the points
// (homogeneous parts of a rational cage).
test::PolyMesh osd_cage(const test::QuadMesh& cage, const Sharp& sharp, const std::vector<int>& creased, const std::vector<P3>& coordinates = {}) {
  test::PolyMesh poly;
  poly.points = coordinates.empty() ? cage.points : coordinates;
  std::set<std::array<int, 2>> edges;
  for (const auto& q : cage.quads) {
    poly.faces.push_back({q.begin(), q.end()});
    for (std::size_t k = 0; k < 4; ++k) {
      const int a = q[k], b = q[(k + 1) % 4];
      if (sharp(a, b)) edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  poly.sharp_edges.assign(edges.begin(), edges.end());
  poly.sharp_vertices = creased;
  return poly;
}

const std::vector<double> kSamples{0.0, 2e-3, 0.1, 0.3, 0.5, 0.77, 0.998, 1.0};

struct Deviation {
  double off_vertices = 0;  // value, d/du, d/dv away from the face corners
  double at_vertices = 0;   // positions at the face corners (the limit points)
};

// Every face at 8 x 8 points (the nearest 2e-3 from a corner, beyond Bfr's approximated 2^-10; derivatives from
// sub-faces of level 9 there, scaled by 2^9, so about 1e-15 * 4 * 512 at worst), but at darts themselves
// (at_dart).
Deviation against_osd(const TMeshSurface& s, const test::OsdLimitSurface& ref) {
  const std::vector<int> dart_list = crease_singularities(s.mesh()).darts;
  const std::set<int> darts(dart_list.begin(), dart_list.end());
  Deviation d;
  for (int f = 0; f < s.num_faces(); ++f)
    for (double u : kSamples)
      for (double v : kSamples) {
        double a[9];
        s.eval(f, u, v, a);
        const test::LimitSample b = ref.eval(f, u, v);
        const bool corner = (u == 0 || u == 1) && (v == 0 || v == 1);
        if (corner && darts.count(s.corners(f)[static_cast<std::size_t>(u == 0 ? (v == 0 ? 0 : 3) : (v == 0 ? 1 : 2))])) continue;
        for (std::size_t k = 0; k < 3; ++k) {
          if (corner) d.at_vertices = std::max(d.at_vertices, std::abs(a[k] - b.p[k]));
          else d.off_vertices = std::max({d.off_vertices, std::abs(a[k] - b.p[k]), std::abs(a[3 + k] - b.du[k]), std::abs(a[6 + k] - b.dv[k])});
        }
      }
  return d;
}

P3 unit_normal(const P3& a, const P3& b) {
  const P3 n{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double l = std::hypot(n[0], n[1], n[2]);
  return {n[0] / l, n[1] / l, n[2] / l};
}

// The sine of the angle between two lines (normals of either orientation).
double line_angle(const P3& a, const P3& b) {
  return std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

// The faces round vertex v with v's corner in each.
std::vector<std::array<int, 2>> faces_at(const TMeshSurface& s, int v) {
  std::vector<std::array<int, 2>> out;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    for (int k = 0; k < 4; ++k)
      if (c[static_cast<std::size_t>(k)] == v) out.push_back({f, k});
  }
  return out;
}

constexpr std::array<std::array<double, 2>, 4> kCornerUv{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};

struct AtVertex {
  double to_osd_point = 0;   // limit position against Aitken's extrapolation of Far's masks after 4, 5, 6 levels
  double to_bfr = 0;         // against Bfr's value there (its mask after 10 levels)
  double approach = 0;       // against the surface 2^-30 from it along each face's diagonal
  double to_osd_normal = 0;  // the faces' normals there against Aitken's extrapolation of Far's normals
  double approach_normal = 0;  // against the normals 2^-30 from it along each face's diagonal
};

// Far's limit masks after 4, 5 and 6 uniform levels.
using OsdLevels = std::array<std::vector<test::LimitSample>, 3>;
OsdLevels osd_levels(const test::OsdLimitSurface& ref) { return {ref.vertex_limits(4), ref.vertex_limits(5), ref.vertex_limits(6)}; }

// At a dart v: the limit point from every face round it, against OpenSubdiv's and the surface approaching it; the
// tangent plane against OpenSubdiv's limit tangents and the normals approaching it.
AtVertex at_dart(const TMeshSurface& s, const test::OsdLimitSurface& ref, const OsdLevels& levels, int v) {
  std::array<test::LimitSample, 3> lim;
  for (std::size_t l = 0; l < 3; ++l) lim[l] = levels[l][static_cast<std::size_t>(v)];
  const auto aitken = [](const P3& x0, const P3& x1, const P3& x2) {
    P3 x{};
    for (std::size_t k = 0; k < 3; ++k) {
      const double d = x0[k] + x2[k] - 2 * x1[k];
      x[k] = std::abs(d) < 1e-15 ? x2[k] : (x0[k] * x2[k] - x1[k] * x1[k]) / d;
    }
    return x;
  };
  const P3 extrapolated = aitken(lim[0].p, lim[1].p, lim[2].p);
  std::array<P3, 3> normals;
  for (std::size_t l = 0; l < 3; ++l) normals[l] = unit_normal(lim[l].du, lim[l].dv);
  const P3 a_n = aitken(normals[0], normals[1], normals[2]);
  const double a_len = std::hypot(a_n[0], a_n[1], a_n[2]);
  const P3 n_osd{a_n[0] / a_len, a_n[1] / a_len, a_n[2] / a_len};
  AtVertex r;
  const double h = std::ldexp(1.0, -30);
  for (const auto& [f, c] : faces_at(s, v)) {
    const auto& uv = kCornerUv[static_cast<std::size_t>(c)];
    double a[9], b[9];
    s.eval(f, uv[0], uv[1], a);
    s.eval(f, uv[0] == 0 ? h : 1 - h, uv[1] == 0 ? h : 1 - h, b);
    const test::LimitSample bfr = ref.eval(f, uv[0], uv[1]);
    for (std::size_t k = 0; k < 3; ++k) {
      r.to_osd_point = std::max(r.to_osd_point, std::abs(a[k] - extrapolated[k]));
      r.to_bfr = std::max(r.to_bfr, std::abs(a[k] - bfr.p[k]));
      r.approach = std::max(r.approach, std::abs(a[k] - b[k]));
    }
    const P3 na = unit_normal({a[3], a[4], a[5]}, {a[6], a[7], a[8]});
    r.to_osd_normal = std::max(r.to_osd_normal, line_angle(na, n_osd));
    r.approach_normal = std::max(r.approach_normal, line_angle(na, unit_normal({b[3], b[4], b[5]}, {b[6], b[7], b[8]})));
  }
  return r;
}

// The bounds at a dart are those of OpenSubdiv's approximations (measured: Aitken's extrapolation of Far's masks
// 2e-9 to 6e-6 off in position, 7e-8 to 4e-4 rad in normal; Bfr's value 2e-9 to 3e-5, largest at a star point)
// and of the approach (the surface 2^-30 away 1e-10 to 4e-8, as the subdominant eigenvalue^30, the normals there
// 1e-7 to 2e-5 rad). The surface round the dart matches OpenSubdiv to 1e-12 down to 2e-3 from it (against_osd).
void expect_dart(const AtVertex& at, const std::string& where) {
  EXPECT_LT(at.to_osd_point, 2e-5) << where;
  EXPECT_LT(at.to_bfr, 1e-4) << where;
  EXPECT_LT(at.approach, 2e-7) << where;
  EXPECT_LT(at.to_osd_normal, 1e-3) << where;
  EXPECT_LT(at.approach_normal, 1e-4) << where;
  std::printf("  dart %s: limit point to OpenSubdiv's extrapolated %.2e, to Bfr's %.2e, to the surface 2^-30 away %.2e; "
              "normal to OpenSubdiv's %.2e rad, to the normals 2^-30 away %.2e rad\n", where.c_str(), at.to_osd_point, at.to_bfr,
              at.approach, at.to_osd_normal, at.approach_normal);
}

// Positions across every edge of the mesh as given (the sides of a crease edge evaluate the same crease curve),
// at its ends too (the limit points of darts and cone points).
double edge_gap(const TMeshSurface& s) {
  return test::continuity(s.source_mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); }, {0.0, 0.25, 0.5, 0.75, 1.0}).gap;
}

// The grid cage's vertex (i, j) of grid_cage(n, n).
int grid_vertex(int n, int i, int j) { return j * (n + 1) + i; }

// The surface against OpenSubdiv: every face (against_osd), every dart (at_dart), and positions across edges.
struct DartCheck {
  Deviation d;
  double gap = 0;
};
DartCheck check_darts(const TMeshSurface& s, const test::QuadMesh& cage, const Sharp& sharp, const std::string& what) {
  const test::OsdLimitSurface ref(osd_cage(cage, sharp, {}));
  const OsdLevels levels = osd_levels(ref);
  DartCheck c{against_osd(s, ref), edge_gap(s)};
  EXPECT_LT(c.d.off_vertices, 1e-12) << what;
  EXPECT_LT(c.d.at_vertices, 1e-13) << what;
  EXPECT_LT(c.gap, 1e-13) << what;
  for (int v : crease_singularities(s.mesh()).darts)
    expect_dart(at_dart(s, ref, levels, v), what + ": " + std::to_string(v) + " of " + std::to_string(faces_at(s, v).size()) + " faces");
  return c;
}

// A grid of 7 x 7 faces with one sharp edge in the middle, (3, 3) - (3, 4): two darts. Against OpenSubdiv on every
// face, the limit points and tangent planes at both darts; positions continuous across every edge; the
// tessellation one surface with one boundary loop.
TEST(Dart, OneSharpEdgeBetweenTwoDarts) {
  const int n = 7;
  const test::QuadMesh cage = test::grid_cage(n, n);
  const int a = grid_vertex(n, 3, 3), b = grid_vertex(n, 3, 4);
  const Sharp edge = [&](int x, int y) { return std::min(x, y) == a && std::max(x, y) == b; };
  const io::TsmModel model = io::parse_tsm(test::fusion_creased_text(cage, edge), "darts.tsm");
  EXPECT_EQ(model.report.crease_edges, 1);
  const TMeshSurface s(model.mesh, 1);
  const CreaseSingularities ends = crease_singularities(s.mesh());
  EXPECT_EQ(ends.darts, (std::vector<int>{a, b}));
  EXPECT_TRUE(ends.cone_points.empty());
  EXPECT_GE(s.count(FaceMethod::crease), 40);
  const DartCheck d = check_darts(s, cage, edge, "one edge");
  const TSplineTriangulation t = tessellate(s, 1e-3);
  EXPECT_EQ(test::boundary_loops(t), 1);
  std::printf("grid 7 x 7 with one sharp edge between two darts: %d faces by local subdivision; against OpenSubdiv %.2e "
              "(value, d/du, d/dv), limit points %.2e; position gap across edges %.2e; %zu triangles, one boundary loop\n",
              s.count(FaceMethod::crease), d.d.off_vertices, d.d.at_vertices, d.gap, t.triangles.size());
}

// A grid of 16 x 16 faces with a sharp chain of 3 edges in the middle, (8, 6) - (8, 9): the exact faces round the
// crease faces of its two darts form a ring, laid out in one chart (the faces on both sides of the chain, which
// would touch there without sharing an edge, are left out of it). Against OpenSubdiv on every exact face.
TEST(Dart, ExactFacesRoundTwoDartsShareOneChart) {
  const int n = 16;
  const test::QuadMesh cage = test::grid_cage(n, n);
  const Sharp chain = [&](int x, int y) {
    return x % (n + 1) == 8 && y % (n + 1) == 8 && std::min(x, y) / (n + 1) >= 6 && std::max(x, y) / (n + 1) <= 9;
  };
  const io::TsmModel model = io::parse_tsm(test::fusion_creased_text(cage, chain), "chain.tsm");
  EXPECT_EQ(model.report.crease_edges, 3);
  const TMeshSurface s(model.mesh, 1);
  EXPECT_EQ(crease_singularities(s.mesh()).darts, (std::vector<int>{grid_vertex(n, 8, 6), grid_vertex(n, 8, 9)}));
  std::set<const TSplineSurface*> charts;
  for (int f = 0; f < s.num_faces(); ++f)
    if (s.method(f) == FaceMethod::exact) charts.insert(s.chart_frame(f).chart);
  EXPECT_GT(s.count(FaceMethod::exact), 100);
  EXPECT_EQ(charts.size(), 1u);
  const test::OsdLimitSurface ref(osd_cage(cage, chain, {}));
  double worst = 0;  // the exact faces (the crease faces: the tests above)
  for (int f = 0; f < s.num_faces(); ++f)
    for (double u : kSamples)
      for (double v : kSamples) {
        if (s.method(f) != FaceMethod::exact) continue;
        double a[9];
        s.eval(f, u, v, a);
        const test::LimitSample b = ref.eval(f, u, v);
        for (std::size_t k = 0; k < 3; ++k)
          worst = std::max({worst, std::abs(a[k] - b.p[k]), std::abs(a[3 + k] - b.du[k]), std::abs(a[6 + k] - b.dv[k])});
      }
  EXPECT_LT(worst, 1e-12);
  std::printf("grid 16 x 16 with a chain of 3 sharp edges between two darts: %d exact faces in %zu chart; against OpenSubdiv "
              "(value, d/du, d/dv) %.2e\n", s.count(FaceMethod::exact), charts.size(), worst);
}

// A crease from the boundary, (3, 0) up to (3, 3), ending in a dart; with weights other than 1 too (rational
// Catmull-Clark: OpenSubdiv subdivides the homogeneous parts (w x, w y, w z) and w as two meshes).
TEST(Dart, CreaseFromTheBoundaryEndsInADart) {
  const int n = 7;
  const test::QuadMesh cage = test::grid_cage(n, n);
  const Sharp chain = [&](int x, int y) { return x % (n + 1) == 3 && y % (n + 1) == 3 && std::max(x, y) / (n + 1) <= 3; };
  const int dart = grid_vertex(n, 3, 3);
  const io::TsmModel model = io::parse_tsm(test::fusion_creased_text(cage, chain), "chain.tsm");
  EXPECT_EQ(model.report.crease_edges, 3);
  {
    const TMeshSurface s(model.mesh, 1);
    EXPECT_EQ(crease_singularities(s.mesh()).darts, std::vector<int>{dart});
    const DartCheck d = check_darts(s, cage, chain, "chain");
    EXPECT_EQ(test::boundary_loops(tessellate(s, 1e-3)), 1);
    std::printf("grid 7 x 7, crease from the boundary ending in a dart: against OpenSubdiv %.2e, limit points %.2e; "
                "position gap across edges %.2e\n", d.d.off_vertices, d.d.at_vertices, d.gap);
  }
  TMesh weighted = model.mesh;
  std::vector<P3> wx(cage.points.size()), w(cage.points.size());
  for (std::size_t v = 0; v < cage.points.size(); ++v) {
    RationalPoint& p = weighted.points[static_cast<std::size_t>(weighted.vertices[v].primary)];
    p.w = 1 + 0.4 * std::sin(1.7 * static_cast<double>(v));
    for (std::size_t k = 0; k < 3; ++k) wx[v][k] = p.w * p.xyz[k];
    w[v] = {p.w, 0, 0};
  }
  const TMeshSurface s(weighted, 1);
  const test::OsdLimitSurface ref_wx(osd_cage(cage, chain, {}, wx)), ref_w(osd_cage(cage, chain, {}, w));
  double worst = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    for (double u : kSamples)
      for (double v : kSamples) {
        if ((u == 0 || u == 1) && (v == 0 || v == 1)) continue;
        double a[9];
        s.eval(f, u, v, a);
        const test::LimitSample x = ref_wx.eval(f, u, v), y = ref_w.eval(f, u, v);
        for (std::size_t k = 0; k < 3; ++k) {
          const double p = x.p[k] / y.p[0];
          worst = std::max({worst, std::abs(a[k] - p), std::abs(a[3 + k] - (x.du[k] - p * y.du[0]) / y.p[0]),
                            std::abs(a[6 + k] - (x.dv[k] - p * y.dv[0]) / y.p[0])});
        }
      }
  EXPECT_LT(worst, 1e-12);
  std::printf("  with weights 0.6 to 1.4: against OpenSubdiv's homogeneous limit, projected, %.2e\n", worst);
}

// Darts at star points of valence 3 and 5: a sharp chain along spoke 0 from the star point to the second vertex
// out (a dart at each end), on fans of 5 x 5 faces per sector.
TEST(Dart, DartsAtStarPoints) {
  for (int valence : {3, 5}) {
    const test::QuadMesh cage = test::fan_mesh(valence, 5, ripple);
    const auto on_spoke = [&](int v) {
      const P3& p = cage.points[static_cast<std::size_t>(v)];
      return std::abs(p[1]) < 1e-9 && p[0] > -1e-9 && p[0] < 2.5;
    };
    const Sharp spoke = [&](int x, int y) { return on_spoke(x) && on_spoke(y); };
    const io::TsmModel model = io::parse_tsm(test::fusion_creased_text(cage, spoke), "fan.tsm");
    EXPECT_EQ(model.report.crease_edges, 2);
    const TMeshSurface s(model.mesh, 1);
    const std::vector<int> darts = crease_singularities(s.mesh()).darts;
    ASSERT_EQ(darts.size(), 2u);
    EXPECT_EQ(darts[0], 0);  // the star point
    const DartCheck d = check_darts(s, cage, spoke, "fan of " + std::to_string(valence));
    std::printf("fan of %d sectors with a dart at its star point: %d faces by local subdivision; against OpenSubdiv %.2e, "
                "limit points %.2e\n", valence, s.count(FaceMethod::crease), d.d.off_vertices, d.d.at_vertices);
  }
}

// Fusion's box of 3 x 3 faces per side with a crease from a cube corner along the cube's edge to the next vertex,
// turning there into the top face to its vertex (1, 1): darts at the corner (valence 3) and inside the top face.
// Closed: the tessellation is one closed surface of Euler characteristic 2.
TEST(Dart, CreaseIntoAFaceOfAClosedBox) {
  test::QuadMesh cage = test::cube_mesh(3);
  std::vector<std::array<int, 3>> grid;
  for (auto& p : cage.points) {
    std::array<int, 3> g{};
    for (std::size_t k = 0; k < 3; ++k) g[k] = static_cast<int>(std::lround((p[k] + 1) * 1.5));
    grid.push_back(g);
    const P3 q = p;
    p = {q[0] + 0.1 * std::sin(2 * q[1] + q[2]), q[1] + 0.07 * std::cos(q[0] - q[2]), q[2] * (1 + 0.05 * q[0] * q[1])};
  }
  const auto at = [&](int v, std::array<int, 3> g) { return grid[static_cast<std::size_t>(v)] == g; };
  const auto either = [&](int x, int y, std::array<int, 3> g, std::array<int, 3> h) { return (at(x, g) && at(y, h)) || (at(x, h) && at(y, g)); };
  const Sharp path = [&](int x, int y) { return either(x, y, {0, 0, 3}, {1, 0, 3}) || either(x, y, {1, 0, 3}, {1, 1, 3}); };
  const io::TsmModel model = io::parse_tsm(test::fusion_creased_text(cage, path), "box.tsm");
  EXPECT_EQ(model.report.crease_edges, 2);
  const TMeshSurface s(model.mesh, 1);
  const std::vector<int> darts = crease_singularities(s.mesh()).darts;
  ASSERT_EQ(darts.size(), 2u);
  const DartCheck d = check_darts(s, cage, path, "box");
  const TSplineTriangulation t = tessellate(s, 1e-3);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  std::printf("box 3 x 3 per side with a crease from a corner into the top face: %d faces by local subdivision; against "
              "OpenSubdiv %.2e, limit points %.2e; position gap across edges %.2e; %zu triangles closed\n",
              s.count(FaceMethod::crease), d.d.off_vertices, d.d.at_vertices, d.gap, t.triangles.size());
}

// Cone points: a creased vertex inside the mesh on no crease, of 4 faces (grid 6 x 6, vertex (3, 3)) and of 5 (the
// star point of a fan), against OpenSubdiv's infinitely sharp vertex; the limit point is the control point, and the
// faces round it meet without a common tangent plane.
TEST(Cone, ConePointsOfValenceFourAndFive) {
  const test::QuadMesh grid = test::grid_cage(6, 6);
  const test::QuadMesh fan = test::fan_mesh(5, 6, ripple);
  for (const auto& [cage, cone] : {std::pair{grid, grid_vertex(6, 3, 3)}, std::pair{fan, 0}}) {
    const Sharp none = [](int, int) { return false; };
    const io::TsmModel model = io::parse_tsm(test::fusion_creased_text(cage, none, {cone}), "cone.tsm");
    const TMeshSurface s(model.mesh, 1);
    const CreaseSingularities ends = crease_singularities(s.mesh());
    EXPECT_TRUE(ends.darts.empty());
    EXPECT_EQ(ends.cone_points, std::vector<int>{cone});
    const test::OsdLimitSurface ref(osd_cage(cage, none, {cone}));
    const Deviation d = against_osd(s, ref);
    EXPECT_LT(d.off_vertices, 1e-12);
    EXPECT_LT(d.at_vertices, 1e-13);
    double to_point = 0, spread = 0;
    std::vector<P3> normals;
    for (const auto& [f, c] : faces_at(s, cone)) {
      const auto& uv = kCornerUv[static_cast<std::size_t>(c)];
      double o[9];
      s.eval(f, uv[0], uv[1], o);
      for (std::size_t k = 0; k < 3; ++k) to_point = std::max(to_point, std::abs(o[k] - cage.points[static_cast<std::size_t>(cone)][k]));
      normals.push_back(unit_normal({o[3], o[4], o[5]}, {o[6], o[7], o[8]}));
    }
    for (const P3& x : normals)
      for (const P3& y : normals) spread = std::max(spread, line_angle(x, y));
    EXPECT_LT(to_point, 1e-15);
    EXPECT_GT(spread, 1e-2);
    EXPECT_LT(edge_gap(s), 1e-13);
    std::printf("cone point of %zu faces: %d faces by local subdivision; against OpenSubdiv %.2e, limit points %.2e; limit "
                "point to the control point %.2e; the faces' normals there spread %.2e rad\n", normals.size(),
                s.count(FaceMethod::crease), d.off_vertices, d.at_vertices, to_point, spread);
  }
}

// A crease ending inside the mesh at a creased vertex: a corner there (interpolated, OpenSubdiv's infinitely sharp
// vertex), a dart at its other end. Grid 6 x 6, sharp edge (3, 3) - (3, 4), (3, 3) creased.
TEST(Cone, CreasedEndOfACreaseIsACorner) {
  const int n = 6;
  const test::QuadMesh cage = test::grid_cage(n, n);
  const int a = grid_vertex(n, 3, 3), b = grid_vertex(n, 3, 4);
  const Sharp edge = [&](int x, int y) { return std::min(x, y) == a && std::max(x, y) == b; };
  const TMeshSurface s(io::parse_tsm(test::fusion_creased_text(cage, edge, {a}), "corner.tsm").mesh, 1);
  const CreaseSingularities ends = crease_singularities(s.mesh());
  EXPECT_EQ(ends.darts, std::vector<int>{b});
  EXPECT_TRUE(ends.cone_points.empty());  // on its crease: a corner of one fan, not a cone point
  const test::OsdLimitSurface ref(osd_cage(cage, edge, {a}));
  const Deviation d = against_osd(s, ref);
  EXPECT_LT(d.off_vertices, 1e-12);
  EXPECT_LT(d.at_vertices, 1e-13);
  double to_point = 0;
  for (const auto& [f, c] : faces_at(s, a)) {
    const auto& uv = kCornerUv[static_cast<std::size_t>(c)];
    double o[9];
    s.eval(f, uv[0], uv[1], o);
    for (std::size_t k = 0; k < 3; ++k) to_point = std::max(to_point, std::abs(o[k] - cage.points[static_cast<std::size_t>(a)][k]));
  }
  EXPECT_LT(to_point, 1e-15);
  std::printf("grid 6 x 6, a sharp edge from a creased vertex to a dart: against OpenSubdiv %.2e, limit points %.2e; the "
              "corner to its control point %.2e\n", d.off_vertices, d.at_vertices, to_point);
}

// The knot intervals of the strip of faces between grid columns 2 and 3 of grid_cage(n, n) set to `d` (the
// edges along x there; both sides of every face of the strip, so opposite sides agree).
void widen_column(TMesh& m, const test::QuadMesh& cage, double d) {
  for (const TMeshLink& k : m.links) {
    if (k.vertex < 0 || k.face < 0) continue;
    const auto& a = cage.points[static_cast<std::size_t>(k.vertex)];
    const auto& b = cage.points[static_cast<std::size_t>(m.links[static_cast<std::size_t>(k.next)].vertex)];
    if (std::abs(a[1] - b[1]) < 1e-9 && std::min(a[0], b[0]) == 2 && std::max(a[0], b[0]) == 3) m.intervals[static_cast<std::size_t>(k.edge)] = d;
  }
}

// A cone point with unequal knot intervals in its rings (the strip of faces beside it at 1.5): the interval-weighted
// rules of crease_face, the point interpolated (theory), the surface continuous and tangent-plane continuous across
// every edge but at the cone itself.
TEST(Cone, ConePointWithUnequalIntervalsNearby) {
  const int n = 6;
  const test::QuadMesh cage = test::grid_cage(n, n);
  const int cone = grid_vertex(n, 3, 3);
  const Sharp none = [](int, int) { return false; };
  TMesh m = io::parse_tsm(test::fusion_creased_text(cage, none, {cone}), "cone.tsm").mesh;
  widen_column(m, cage, 1.5);
  const TMeshSurface s(m, 1);
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  double to_point = 0;
  for (const auto& [f, c] : faces_at(s, cone)) {
    const auto& uv = kCornerUv[static_cast<std::size_t>(c)];
    double o[9];
    s.eval(f, uv[0], uv[1], o);
    for (std::size_t k = 0; k < 3; ++k) to_point = std::max(to_point, std::abs(o[k] - cage.points[static_cast<std::size_t>(cone)][k]));
  }
  EXPECT_LT(to_point, 1e-15);
  const test::Continuity c =
      test::continuity(s.source_mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); }, {0.1, 0.25, 0.5, 0.75, 0.9});
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-10);
  EXPECT_LT(edge_gap(s), 1e-12);  // the vertices too
  std::printf("cone point with the strip beside it at 1.5: %d faces by local subdivision; limit point to the control point "
              "%.2e; across edges (off the vertices) gap %.2e, normals %.2e\n", s.count(FaceMethod::crease), to_point, c.gap,
              c.normal_angle);
}

// Two darts (one sharp edge inside a 6 x 6 grid) with the strip of faces west of them at knot interval d: NURCC's
// smooth rule over each dart's fan from one side of its slit to the other.
TMeshSurface darts_with_strip(double d, double scale = 1) {
  const int n = 6;
  const test::QuadMesh cage = test::grid_cage(n, n);
  const int a = grid_vertex(n, 3, 2), b = grid_vertex(n, 3, 3);
  const Sharp edge = [&](int x, int y) { return std::min(x, y) == a && std::max(x, y) == b; };
  TMesh m = io::parse_tsm(test::fusion_creased_text(cage, edge), "darts.tsm").mesh;
  widen_column(m, cage, d);
  for (double& x : m.intervals) x *= scale;
  return TMeshSurface(m, 1);
}

// Darts with unequal knot intervals in their fans. No other tool evaluates them, so: (1) the rules are continuous
// in the intervals: with the strip at 1 + 1e-9 (the unequal-interval rules) the surface is the equal-interval one
// (uniform Catmull-Clark with OpenSubdiv's dart rule, tested against OpenSubdiv above) to about 1e-9; (2) they
// depend on ratios of intervals only: all intervals times 2.5 leave the surface as it is; (3) with the strip at 1.5
// the surface is continuous with one tangent plane across every edge off the darts, every face at a dart reaches
// the one limit point (the left eigenvector of the one ring's subdivision matrix) and normal 2^-30 away.
TEST(Dart, DartsWithUnequalIntervalsNearby) {
  const TMeshSurface equal = darts_with_strip(1.0), near = darts_with_strip(1 + 1e-9);
  const TMeshSurface s = darts_with_strip(1.5), scaled = darts_with_strip(1.5, 2.5);
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  // At a dart the derivatives are tangent directions of the eigen-analysis, of no fixed length: its corners are
  // compared by their points (and their normals below).
  const std::vector<int> darts = crease_singularities(s.mesh()).darts;
  ASSERT_EQ(darts.size(), 2u);
  double to_equal = 0, to_equal_d = 0, to_scaled = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    for (double u : kSamples)
      for (double v : kSamples) {
        const bool corner = (u == 0 || u == 1) && (v == 0 || v == 1);
        const int at = s.corners(f)[static_cast<std::size_t>(u == 0 ? (v == 0 ? 0 : 3) : (v == 0 ? 1 : 2))];
        const int values = corner && std::find(darts.begin(), darts.end(), at) != darts.end() ? 3 : 9;
        double a[9], b[9], c[9], e[9];
        equal.eval(f, u, v, a);
        near.eval(f, u, v, b);
        s.eval(f, u, v, c);
        scaled.eval(f, u, v, e);
        for (std::size_t k = 0; k < 3; ++k) to_equal = std::max(to_equal, std::abs(a[k] - b[k]));
        for (std::size_t k = 3; k < static_cast<std::size_t>(values); ++k) to_equal_d = std::max(to_equal_d, std::abs(a[k] - b[k]));
        for (std::size_t k = 0; k < static_cast<std::size_t>(values); ++k) to_scaled = std::max(to_scaled, std::abs(c[k] - e[k]) / (1 + std::abs(c[k])));
      }
  EXPECT_LT(to_equal, 1e-8);
  EXPECT_LT(to_equal_d, 1e-7);
  EXPECT_LT(to_scaled, 1e-12);
  // Off the sharp edge (C0 across it, the crease).
  const test::Continuity c = test::continuity(s.source_mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); },
                                              {0.1, 0.25, 0.5, 0.75, 0.9}, s.source_mesh().crease_edges);
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-10);
  EXPECT_LT(edge_gap(s), 1e-12);  // the darts' limit points from every face too
  double approach = 0, approach_normal = 0;
  const double h = std::ldexp(1.0, -30);
  for (int v : darts)
    for (const auto& [f, k] : faces_at(s, v)) {
      const auto& uv = kCornerUv[static_cast<std::size_t>(k)];
      double a[9], b[9];
      s.eval(f, uv[0], uv[1], a);
      s.eval(f, uv[0] == 0 ? h : 1 - h, uv[1] == 0 ? h : 1 - h, b);
      for (std::size_t i = 0; i < 3; ++i) approach = std::max(approach, std::abs(a[i] - b[i]));
      approach_normal = std::max(approach_normal, line_angle(unit_normal({a[3], a[4], a[5]}, {a[6], a[7], a[8]}),
                                                            unit_normal({b[3], b[4], b[5]}, {b[6], b[7], b[8]})));
    }
  EXPECT_LT(approach, 2e-7);
  EXPECT_LT(approach_normal, 1e-4);
  std::printf("darts with the strip beside them: at 1 + 1e-9 against equal intervals %.2e (derivatives %.2e); intervals "
              "times 2.5 %.2e; at 1.5 %d faces by local subdivision, across edges gap %.2e, normals %.2e; at the darts the "
              "surface 2^-30 away %.2e, its normals %.2e rad\n", to_equal, to_equal_d, to_scaled, s.count(FaceMethod::crease), c.gap,
              c.normal_angle, approach, approach_normal);
}

// The command line on a TSM with darts and a cone point: info counts them (text and JSON), eval evaluates a face at
// a dart as the library does, convert writes one triangle surface with one boundary loop.
TEST(Dart, CommandLine) {
  const test::TempDir dir;
  const int n = 7;
  const test::QuadMesh cage = test::grid_cage(n, n);
  const int a = grid_vertex(n, 3, 3), b = grid_vertex(n, 3, 4);
  const Sharp edge = [&](int x, int y) { return std::min(x, y) == a && std::max(x, y) == b; };
  const std::string path = dir.file("darts.tsm");
  std::ofstream(path) << test::fusion_creased_text(cage, edge, {grid_vertex(n, 5, 2)});
  const std::string info = test::run_cli(dir, "info " + path);
  EXPECT_NE(info.find("2 darts"), std::string::npos) << info;
  EXPECT_NE(info.find("1 cone point ("), std::string::npos) << info;
  EXPECT_EQ(info.find("with a closed strip of faces"), std::string::npos) << info;  // one description of the mesh
  EXPECT_NE(info.find("0 star points (0 after the mesh is cut open"), std::string::npos) << info;  // darts are no star points
  std::printf("%s", info.c_str());
  const std::string json = test::run_cli(dir, "info " + path + " --json");
  EXPECT_NE(json.find("\"darts\": 2"), std::string::npos) << json;
  EXPECT_NE(json.find("\"cone_points\": 1"), std::string::npos) << json;
  const int face = 3 * n + 3;  // corner 0 at the dart (3, 3)
  const std::string out = test::run_cli(dir, "eval " + path + " " + std::to_string(face) + " 0.25 0.5");
  EXPECT_NE(out.find("face " + std::to_string(face) + ": crease"), std::string::npos) << out;
  const TMeshSurface s(io::read_tsm(path).mesh, 1);
  double o[9];
  s.eval(face, 0.25, 0.5, o);
  P3 printed{};
  ASSERT_EQ(std::sscanf(out.c_str(), "S   = %lf %lf %lf", &printed[0], &printed[1], &printed[2]), 3) << out;
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(printed[k], o[k], 1e-9) << out;
  test::run_cli(dir, "convert " + path + " " + dir.file("darts.obj"));
  EXPECT_EQ(test::boundary_loops(test::obj_triangles(dir.file("darts.obj"))), 1);
  const std::string step = test::run_cli(dir, "convert " + path + " " + dir.file("darts.stp"));
  EXPECT_NE(step.find("Bezier patches"), std::string::npos) << step;
  std::printf("%s", step.c_str());
}

}  // namespace
}  // namespace trivar::dart_test
