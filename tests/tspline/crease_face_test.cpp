// Irregular vertices of crease boundaries in subdivision-crease T-meshes (boundary star points, a crease turning
// at a vertex, a corner with a side of several faces), evaluated by local subdivision (crease_face), against
// OpenSubdiv's Catmull-Clark limit surface with the same infinitely sharp creases (an independent implementation:
// Bfr is exact to rounding farther than 2^-L from irregular vertices, L = 10 here, and interpolates the limit
// point at them).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "crease_nets.hpp"
#include "face_continuity.hpp"
#include "fusion_cages.hpp"
#include "osd_reference.hpp"
#include "patch_check.hpp"
#include "star_mesh_tsm.hpp"
#include "support/temp_dir.hpp"
#include "triangulation_loops.hpp"
#include "tsm_error.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/crease_face.hpp"
#include "trivar/tspline/sharp_creases.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar::crease_face_test {
namespace {

using test::cartesian;
using test::knot_units;
using test::net_of;

using Crease = std::function<bool(int, int)>;

double wavy(double x, double y) { return 0.3 * std::sin(0.9 * x + 0.4 * y) + 0.05 * x * y; }

struct OsdDeviation {
  double off_vertices = 0;  // value, d/du, d/dv away from the face corners
  double at_vertices = 0;   // limit positions at the face corners
  int samples = 0;
};

// The surface against OpenSubdiv at 8 x 8 points per face of every face (Bfr's quadrilateral parametrisation is
// the face's (u, v)); the nearest lie 2e-3 from a corner, beyond Bfr's 2^-10. Tolerance 1e-12: both are exact
// up to rounding of points of size up to about 4, and the derivatives 2e-3 from an irregular corner come from a
// sub-face of level 9, scaled by 2^9 (about 1e-15 * 4 * 512 = 2e-12 at worst; measured below 5e-13).
OsdDeviation against_osd(const TMeshSurface& s, const test::QuadMesh& cage, const Crease& crease, const std::vector<int>& creased = {}) {
  test::PolyMesh poly;
  poly.points = cage.points;
  std::set<std::array<int, 2>> sharp;
  for (const auto& q : cage.quads) {
    poly.faces.push_back({q.begin(), q.end()});
    for (int k = 0; k < 4; ++k) {
      const int a = q[static_cast<std::size_t>(k)], b = q[static_cast<std::size_t>((k + 1) % 4)];
      if (crease(a, b)) sharp.insert({std::min(a, b), std::max(a, b)});
    }
  }
  poly.sharp_edges.assign(sharp.begin(), sharp.end());
  poly.sharp_vertices = creased;
  const test::OsdLimitSurface ref(poly);
  EXPECT_EQ(s.num_faces(), static_cast<int>(cage.quads.size()));
  OsdDeviation d;
  for (int f = 0; f < s.num_faces(); ++f)
    for (double u : {0.0, 2e-3, 0.1, 0.3, 0.5, 0.77, 0.998, 1.0})
      for (double v : {0.0, 2e-3, 0.1, 0.3, 0.5, 0.77, 0.998, 1.0}) {
        double a[9];
        s.eval(f, u, v, a);
        const test::LimitSample b = ref.eval(f, u, v);
        const bool corner = (u == 0 || u == 1) && (v == 0 || v == 1);
        for (std::size_t k = 0; k < 3; ++k) {
          d.at_vertices = std::max(d.at_vertices, corner ? std::abs(a[k] - b.p[k]) : 0.0);
          if (!corner) d.off_vertices = std::max({d.off_vertices, std::abs(a[k] - b.p[k]), std::abs(a[3 + k] - b.du[k]), std::abs(a[6 + k] - b.dv[k])});
        }
        ++d.samples;
      }
  return d;
}

// How far the surface at face (u, v) lies from the point p (a corner that interpolates its control point).
double gap_to(const TMeshSurface& s, int face, double u, double v, const std::array<double, 3>& p) {
  double o[9];
  s.eval(face, u, v, o);
  return std::max({std::abs(o[0] - p[0]), std::abs(o[1] - p[1]), std::abs(o[2] - p[2])});
}

// The grid cage's vertex (i, j) of grid_cage(n, n).
struct GridIndex {
  int n;
  int i(int v) const { return v % (n + 1); }
  int j(int v) const { return v / (n + 1); }
};

TEST(CreaseFace, BoundaryStarPointsAgainstOpenSubdiv) {
  // Half fans of 3, 4, 5 sectors of 7 x 7 faces round a vertex on the straight boundary: crease vertices of 3, 4, 5
  // faces (the boundary is a crease; 3 faces: a concave corner of the T-mesh).
  for (int sectors : {3, 4, 5}) {
    const test::QuadMesh cage = test::half_fan_mesh(sectors, 7, wavy);
    const TMeshSurface s(io::parse_tsm(test::fusion_text(cage), "fan.tsm").mesh, 1);
    EXPECT_EQ(s.boundary_star_faces(), 0);
    EXPECT_GT(s.count(FaceMethod::crease), sectors * 16);  // the sectors' faces within 4 rings
    const OsdDeviation d = against_osd(s, cage, [](int, int) { return false; });
    EXPECT_LT(d.off_vertices, 1e-12) << sectors;
    EXPECT_LT(d.at_vertices, 1e-13) << sectors;
    // At the vertex (cage vertex 0, face 0's first corner): the normal of the derivatives there against the
    // normals 2^-30 from it along the face's diagonal and along the boundary spoke (its side v = 0), and against
    // OpenSubdiv's limit tangents (Far's limit masks). With 3 faces the surface has one tangent plane there and the
    // evaluation gives it (from the eigenstructure); with 4 and 5 faces the crease rules leave the surface without
    // one (the normals along the spoke and along the diagonal tend to planes apart, as OpenSubdiv's surface does:
    // they agree to rounding beyond 2e-3), and the derivatives there are those 2^-30 along the diagonal.
    const auto normal = [](const double* x) {
      const std::array<double, 3> n{x[4] * x[8] - x[5] * x[7], x[5] * x[6] - x[3] * x[8], x[3] * x[7] - x[4] * x[6]};
      const double l = std::hypot(n[0], n[1], n[2]);
      return std::array<double, 3>{n[0] / l, n[1] / l, n[2] / l};
    };
    const auto angle = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
      return std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
    };
    const double h = std::ldexp(1.0, -30);
    double at[9], diagonal[9], spoke[9];
    s.eval(0, 0, 0, at);
    s.eval(0, h, h, diagonal);
    s.eval(0, h, 0, spoke);
    const auto n0 = normal(at);
    const double to_diagonal = angle(n0, normal(diagonal)), to_spoke = angle(n0, normal(spoke));
    test::PolyMesh poly{cage.points, {}, {}, {}, true};
    for (const auto& q : cage.quads) poly.faces.push_back({q.begin(), q.end()});
    const test::LimitSample lim = test::OsdLimitSurface(poly).vertex_limits()[0];
    const double ld[9] = {0, 0, 0, lim.du[0], lim.du[1], lim.du[2], lim.dv[0], lim.dv[1], lim.dv[2]};
    const double to_osd = angle(n0, normal(ld));
    if (sectors == 3) {
      EXPECT_LT(to_diagonal, 1e-4);
      EXPECT_LT(to_spoke, 1e-5);
    } else {
      EXPECT_GT(angle(normal(diagonal), normal(spoke)), 1e-3);
    }
    std::printf("  at the vertex: normal to the normals 2^-30 away along the diagonal %.2e rad, along the spoke %.2e rad; "
                "to OpenSubdiv's limit tangents %.2e rad\n", to_diagonal, to_spoke, to_osd);
    std::printf("crease half fan of %d sectors of 7 x 7 faces: %d faces by local subdivision, %d exact; against OpenSubdiv "
                "(%d samples) %.2e (value, d/du, d/dv), limit points %.2e\n",
                sectors, s.count(FaceMethod::crease), s.count(FaceMethod::exact), d.samples, d.off_vertices, d.at_vertices);
  }
}

TEST(CreaseFace, CreaseTurningAtAVertexOfFourFaces) {
  // Grid of 6 x 6: a crease up from the boundary at i = 3 to (3, 3), turning there along j = 3 to the boundary. At
  // (3, 3) the side of one face is a crease vertex (the crease curve's (P_prev + 4 P + P_next) / 6), not a corner.
  const GridIndex g{6};
  const test::QuadMesh cage = test::grid_cage(6, 6);
  const Crease turn = [&](int a, int b) {
    return (g.i(a) == 3 && g.i(b) == 3 && std::max(g.j(a), g.j(b)) <= 3) || (g.j(a) == 3 && g.j(b) == 3 && std::min(g.i(a), g.i(b)) >= 3);
  };
  const io::TsmModel model = io::parse_tsm(test::fusion_creased_text(cage, turn), "turn.tsm");
  EXPECT_EQ(model.report.crease_edges, 6);
  const TMeshSurface s(model.mesh, 1);
  const OsdDeviation d = against_osd(s, cage, turn);
  EXPECT_LT(d.off_vertices, 1e-12);
  EXPECT_LT(d.at_vertices, 1e-13);
  // The limit point at the turn from the face of the one-face side ((3, 2) -> face 2 * 6 + 3, corner 3 at (3, 3)).
  const auto p = [&](int i, int j) { return cage.points[static_cast<std::size_t>(j * 7 + i)]; };
  double o[9];
  s.eval(2 * 6 + 3, 0, 1, o);
  double rule = 0;
  for (std::size_t k = 0; k < 3; ++k) rule = std::max(rule, std::abs(o[k] - (p(3, 2)[k] + 4 * p(3, 3)[k] + p(4, 3)[k]) / 6));
  EXPECT_LT(rule, 1e-15);
  std::printf("grid with a crease turning at a vertex of four faces: %d faces by local subdivision; against OpenSubdiv %.2e, "
              "limit points %.2e, crease rule at the turn %.2e\n", s.count(FaceMethod::crease), d.off_vertices, d.at_vertices, rule);
}

TEST(CreaseFace, CornerWithASideOfTwoFaces) {
  // Grid of 6 x 6: a crease across at i = 3 and one from (3, 3) to the right boundary: three sharp edges at (3, 3),
  // a corner whose left side has two faces.
  const GridIndex g{6};
  const test::QuadMesh cage = test::grid_cage(6, 6);
  const Crease tee = [&](int a, int b) {
    return (g.i(a) == 3 && g.i(b) == 3) || (g.j(a) == 3 && g.j(b) == 3 && std::min(g.i(a), g.i(b)) >= 3);
  };
  const TMeshSurface s(io::parse_tsm(test::fusion_creased_text(cage, tee), "tee.tsm").mesh, 1);
  const OsdDeviation d = against_osd(s, cage, tee);
  EXPECT_LT(d.off_vertices, 1e-12);
  EXPECT_LT(d.at_vertices, 1e-13);
  // Interpolated from the side of two faces (face (2, 3) -> 3 * 6 + 2, corner 1 at (3, 3)).
  EXPECT_LT(gap_to(s, 3 * 6 + 2, 1, 0, cage.points[3 * 7 + 3]), 1e-15);
  std::printf("grid with a corner of three creases and a side of two faces: %d faces by local subdivision; against "
              "OpenSubdiv %.2e, limit points %.2e\n", s.count(FaceMethod::crease), d.off_vertices, d.at_vertices);
}

TEST(CreaseFace, CreasedVertexOnACreaseIsACorner) {
  // Grid of 6 x 6 with a straight crease across at i = 3 and its middle vertex (3, 3) in Fusion's creased vertex
  // list: a corner (interpolated, the crease curve kinked there) with two faces on each side, against
  // OpenSubdiv's infinitely sharp vertex. A creased vertex on the boundary, (6, 3), a corner of two faces, too.
  const GridIndex g{6};
  const test::QuadMesh cage = test::grid_cage(6, 6);
  const Crease across = [&](int a, int b) { return g.i(a) == 3 && g.i(b) == 3; };
  const std::vector<int> creased{3 * 7 + 3, 3 * 7 + 6};
  const TMeshSurface s(io::parse_tsm(test::fusion_creased_text(cage, across, creased), "creased_vertex.tsm").mesh, 1);
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  const OsdDeviation d = against_osd(s, cage, across, creased);
  EXPECT_LT(d.off_vertices, 1e-12);
  EXPECT_LT(d.at_vertices, 1e-13);
  // Interpolated: the corner of face (3, 3) -> 3 * 6 + 3 at its first corner (3, 3), and of face (5, 3) at its
  // second corner (6, 3).
  EXPECT_LT(gap_to(s, 3 * 6 + 3, 0, 0, cage.points[3 * 7 + 3]), 1e-15);
  EXPECT_LT(gap_to(s, 3 * 6 + 5, 1, 0, cage.points[3 * 7 + 6]), 1e-15);
  std::printf("grid with a creased vertex on its crease and one on its boundary: %d faces by local subdivision; against "
              "OpenSubdiv %.2e, limit points %.2e\n", s.count(FaceMethod::crease), d.off_vertices, d.at_vertices);
}

// The cube cage of 3 x 3 faces per side, points moved off the cube, and which vertices lie round its top (z = 1).
struct TopBox {
  test::QuadMesh cage = test::cube_mesh(3);
  std::vector<char> rim;  // on the top face's border
  TopBox() {
    for (auto& p : cage.points) {
      rim.push_back(std::abs(p[2] - 1) < 1e-9 && (std::abs(std::abs(p[0]) - 1) < 1e-9 || std::abs(std::abs(p[1]) - 1) < 1e-9));
      const auto q = p;
      p = {q[0] + 0.1 * std::sin(2 * q[1] + q[2]), q[1] + 0.07 * std::cos(q[0] - q[2]), q[2] * (1 + 0.05 * q[0] * q[1])};
    }
  }
  // Cage edges join grid neighbours, so an edge between two vertices of the border runs along it.
  bool rim_edge(int a, int b) const { return rim[static_cast<std::size_t>(a)] && rim[static_cast<std::size_t>(b)]; }
};

TEST(CreaseFace, BoxWithItsTopRimCreased) {
  // Fusion's box of 3 x 3 faces per side with the 12 edges round its top face creased: the crease turns at the
  // four top corners, valence-3 star points of the cage, whose top side has one face (a crease vertex of one
  // face) and whose other side two. Closed: the triangulation has Euler characteristic 2.
  const TopBox box;
  const Crease rim = [&](int a, int b) { return box.rim_edge(a, b); };
  const io::TsmModel model = io::parse_tsm(test::fusion_creased_text(box.cage, rim), "box.tsm");
  EXPECT_EQ(model.report.crease_edges, 12);
  const TMeshSurface s(model.mesh, 1);
  EXPECT_EQ(irregular_crease_vertices(s.mesh()).size(), 0u);  // the converted mesh has Bezier end conditions
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  const OsdDeviation d = against_osd(s, box.cage, rim);
  EXPECT_LT(d.off_vertices, 1e-12);
  EXPECT_LT(d.at_vertices, 1e-13);
  const TSplineTriangulation t = tessellate(s, 1e-3);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  std::printf("box 3 x 3 per side, top rim creased: %d faces by local subdivision, %d exact, %d at star points; against "
              "OpenSubdiv %.2e, limit points %.2e; %zu triangles closed\n", s.count(FaceMethod::crease), s.count(FaceMethod::exact),
              s.count(FaceMethod::star), d.off_vertices, d.at_vertices, t.triangles.size());
}

// The command line counts the faces by local subdivision, writes a closed triangle mesh and STEP patches.
TEST(CreaseFace, CommandLineCounts) {
  const test::TempDir dir;
  const TopBox box;
  const std::string path = dir.file("box.tsm");
  std::ofstream(path) << test::fusion_creased_text(box.cage, [&](int a, int b) { return box.rim_edge(a, b); });
  const TMeshSurface s(io::read_tsm(path).mesh, 1);
  const std::string info = test::run_cli(dir, "info " + path);
  EXPECT_NE(info.find(std::to_string(s.count(FaceMethod::crease)) + " faces within 4 rings of irregular vertices of a crease boundary"),
            std::string::npos) << info;
  EXPECT_NE(test::run_cli(dir, "info " + path + " --json").find("\"faces_crease_subdivision\": " + std::to_string(s.count(FaceMethod::crease))),
            std::string::npos);
  test::run_cli(dir, "convert " + path + " " + dir.file("box.obj"));
  EXPECT_EQ(test::closed_euler_characteristic(test::obj_triangles(dir.file("box.obj"))), 2);
  const std::string step = test::run_cli(dir, "convert " + path + " " + dir.file("box.stp"));
  EXPECT_NE(step.find("Bezier patches"), std::string::npos) << step;
  std::printf("%s", step.c_str());
}

// Unequal knot intervals. A strip of a quad mesh without T-junctions (the faces crossed from one side to the
// opposite) has one interval: every edge of the strip's rungs through `link` gets d.
void set_strip(TMesh& m, int link, double d) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  for (int start : {link, L(link).opp})
    for (int l = start; l >= 0 && L(l).face >= 0;) {
      m.intervals[static_cast<std::size_t>(L(l).edge)] = d;
      const int across = L(L(L(l).next).next).opp;  // the opposite side, from the face beyond
      if (across == start || across == L(start).opp) break;
      m.intervals[static_cast<std::size_t>(L(across).edge)] = d;
      l = across;
    }
}

// Spoke k's edge i (from i - 1 to i) of a fan cage: interval 1.4 + 0.8 sin(1 + 2.3 k + 1.1 i) (0.6 to 2.2).
double spoke_interval(int k, int i) { return 1.4 + 0.8 * std::sin(1.0 + 2.3 * k + 1.1 * i); }

// The strips of a fan cage's spokes (spoke k at angle k turn from the origin, found by the cage's positions)
// at spoke_interval.
void set_spoke_strips(TMesh& m, const test::QuadMesh& cage, int spokes, double turn) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
    if (L(l).vertex < 0 || L(l).face < 0) continue;
    const auto& a = cage.points[static_cast<std::size_t>(L(l).vertex)];
    const auto& b = cage.points[static_cast<std::size_t>(L(L(l).next).vertex)];
    for (int k = 0; k < spokes; ++k) {
      const double c = std::cos(turn * k), sn = std::sin(turn * k);
      const double ra = a[0] * c + a[1] * sn, rb = b[0] * c + b[1] * sn;
      if (std::abs(a[1] * c - a[0] * sn) < 1e-9 && std::abs(b[1] * c - b[0] * sn) < 1e-9 && std::min(ra, rb) > -1e-9)
        set_strip(m, l, spoke_interval(k, static_cast<int>(std::lround(std::max(ra, rb)))));
    }
  }
}

TEST(CreaseFace, UnequalIntervalsAreKnotInsertionOfTheExactSurface) {
  // A grid of 7 x 6 faces with a crease boundary, regular corners, strips of intervals 1, r, 1 / r and some
  // weights other than 1: the exact surface is the T-spline of crease_ends' natural-end Bezier form (charts).
  // Local subdivision of every face's net along several paths of quarters (refine) ends in sub-faces whose 4 x 4
  // points are regular: B-spline cells of the refined points on their knots, with the clamped natural end at the
  // boundary. They must be the same surface: the rules are midpoint knot insertion of the exact surface.
  const test::QuadMesh cage = test::grid_cage(7, 6);
  for (double r : {1.02, 1.5, 3.0})
    for (bool rational : {false, true}) {
      TMesh m = io::parse_tsm(test::fusion_text(cage), "grid.tsm").mesh;
      const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
      const std::array<double, 3> ratio{1, r, 1 / r};
      // Strips by the rungs on the boundary rows j = 0 (columns) and i = 0 (rows).
      for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
        if (L(l).vertex < 0 || L(l).face < 0) continue;
        const auto& a = cage.points[static_cast<std::size_t>(L(l).vertex)];
        const auto& b = cage.points[static_cast<std::size_t>(L(L(l).next).vertex)];
        if (std::abs(a[1]) < 1e-9 && std::abs(b[1]) < 1e-9) set_strip(m, l, ratio[static_cast<std::size_t>(std::lround(std::min(a[0], b[0]))) % 3]);
        if (std::abs(a[0]) < 1e-9 && std::abs(b[0]) < 1e-9) set_strip(m, l, ratio[static_cast<std::size_t>(std::lround(std::min(a[1], b[1]) / 1.3) + 1) % 3]);
      }
      EXPECT_EQ(std::set<double>(m.intervals.begin(), m.intervals.end()).size(), 3u);
      if (rational)
        for (std::size_t i = 0; i < m.points.size(); ++i) m.points[i].w = 1 + 0.3 * std::sin(1.7 * static_cast<double>(i));
      const TMeshSurface s(m, 1);
      ASSERT_EQ(s.count(FaceMethod::exact), s.num_faces());
      double value = 0, derivative = 0;
      int cells = 0;
      for (int f = 0; f < s.num_faces(); ++f) {
        const CreaseNet net = net_of(m, f);
        for (const std::vector<int>& path : std::vector<std::vector<int>>{{}, {0}, {2}, {1, 3}, {3, 0, 2}, {0, 0, 0, 1}}) {
          CreaseNet sub = net;
          double ox = 0, oy = 0, size = 1;
          for (int k : path) {
            sub = refine(sub, k);
            size /= 2;
            ox += k == 1 || k == 2 ? size : 0;
            oy += k >= 2 ? size : 0;
          }
          const CreaseFace cf(sub);
          ++cells;
          for (double u : {0.0, 0.3, 0.71, 1.0})
            for (double v : {0.0, 0.45, 1.0}) {
              double h[12], e[9];
              cf.eval(u, v, h);
              s.eval(f, ox + size * u, oy + size * v, e);
              const auto c = cartesian(h);
              double scale = 0;
              for (int i = 3; i < 9; ++i) scale = std::max(scale, std::abs(e[i]) * size);
              for (int i = 0; i < 3; ++i) value = std::max(value, std::abs(c[static_cast<std::size_t>(i)] - e[i]));
              for (int i = 3; i < 9; ++i) derivative = std::max(derivative, std::abs(c[static_cast<std::size_t>(i)] - e[i] * size) / scale);
            }
        }
      }
      EXPECT_LT(value, 1e-13) << r << " " << rational;
      EXPECT_LT(derivative, 1e-12) << r << " " << rational;
      std::printf("grid 7 x 6, crease boundary, intervals 1, %.2f, %.2f%s: %d sub-faces by local subdivision against the exact "
                  "surface: values %.2e, derivatives %.2e (relative)\n", r, 1 / r, rational ? ", rational" : "", cells, value, derivative);
    }
}

// The clamped cubic B-spline on knots 0, 0, 0, 0, t_1, ..., t_(n-1), T, T, T, T at t (de Boor's algorithm).
template <std::size_t N>
std::array<double, N> de_boor(const std::vector<double>& knots, const std::vector<std::array<double, N>>& q, double t) {
  std::size_t k = 3;
  while (k + 1 < q.size() && t >= knots[k + 1]) ++k;
  std::array<std::array<double, N>, 4> d{};
  for (std::size_t j = 0; j < 4; ++j) d[j] = q[k - 3 + j];
  for (std::size_t r = 1; r <= 3; ++r)
    for (std::size_t j = 3; j >= r; --j) {
      const std::size_t i = k - 3 + j;
      const double a = (t - knots[i]) / (knots[i + 4 - r] - knots[i]);
      for (std::size_t c = 0; c < N; ++c) d[j][c] = (1 - a) * d[j - 1][c] + a * d[j][c];
    }
  return d[3];
}

TEST(CreaseFace, UnequalIntervalsAtABoundaryStarPoint) {
  // Half fans of 3 and 4 sectors of 6 x 6 faces round a crease vertex of 3 (4) faces, every strip its own interval
  // (0.6 to 2.2): the faces within 4 rings are crease faces with unequal intervals, the others exact (the
  // T-spline of crease_ends). Measured: position gaps, normals and C1 across every edge; the boundary curve
  // against the natural-end cubic B-spline of the boundary vertices on their intervals (de Boor here); with 3
  // faces the tangent plane at the vertex (the normals 2^-k from it along the boundary and the diagonal). Also
  // rational (weights 0.75 to 1.25; the curve then the rational B-spline, de Boor on (w x, w)).
  for (const auto& [sectors, rational] : std::vector<std::pair<int, bool>>{{3, false}, {3, true}, {4, false}, {4, true}}) {
    const int n = 6;
    const test::QuadMesh cage = test::half_fan_mesh(sectors, n, wavy);
    TMesh m = io::parse_tsm(test::fusion_text(cage), "fan.tsm").mesh;
    const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
    const auto P = [&](int l) { return cage.points[static_cast<std::size_t>(L(l).vertex)]; };
    set_spoke_strips(m, cage, sectors + 1, std::numbers::pi / sectors);
    const auto weight = [&](std::size_t v) { return rational ? 1 + 0.25 * std::sin(1.3 * static_cast<double>(v)) : 1.0; };
    for (std::size_t v = 0; v < m.vertices.size(); ++v) m.points[static_cast<std::size_t>(m.vertices[v].primary)].w = weight(v);
    const TMeshSurface s(m, 1);
    EXPECT_GT(s.count(FaceMethod::crease), sectors * 16);
    const test::Continuity c = test::continuity(s.face_mesh(), knot_units(s));
    EXPECT_LT(c.gap, 1e-12) << sectors;
    EXPECT_LT(c.normal_angle, 1e-12) << sectors;
    EXPECT_LT(c.c1, 1e-12) << sectors;
    // The boundary curve: knots along the x axis from -n (spoke `sectors`, reversed) to n (spoke 0).
    std::vector<double> t{0};
    for (int i = n; i >= 1; --i) t.push_back(t.back() + spoke_interval(sectors, i));
    for (int i = 1; i <= n; ++i) t.push_back(t.back() + spoke_interval(0, i));
    std::vector<std::array<double, 4>> pts(2 * n + 1);  // homogeneous
    for (std::size_t v = 0; v < cage.points.size(); ++v) {
      const auto& p = cage.points[v];
      if (std::abs(p[1]) > 1e-9) continue;
      const int i = static_cast<int>(std::lround(p[0])) + n;
      pts[static_cast<std::size_t>(i)] = {weight(v) * p[0], weight(v) * p[1], weight(v) * p[2], weight(v)};
    }
    // Clamped natural ends: Q1 = ((d1 + d2) P0 + d1 P1) / (2 d1 + d2) (crease_ends' derivation) at both ends.
    std::vector<std::array<double, 4>> q{pts[0]};
    const auto end_point = [](const std::array<double, 4>& p0, const std::array<double, 4>& p1, double d1, double d2) {
      std::array<double, 4> r{};
      for (std::size_t k = 0; k < 4; ++k) r[k] = ((d1 + d2) * p0[k] + d1 * p1[k]) / (2 * d1 + d2);
      return r;
    };
    const std::size_t last = pts.size() - 1;
    q.push_back(end_point(pts[0], pts[1], t[1] - t[0], t[2] - t[1]));
    for (std::size_t i = 1; i < last; ++i) q.push_back(pts[i]);
    q.push_back(end_point(pts[last], pts[last - 1], t[last] - t[last - 1], t[last - 1] - t[last - 2]));
    q.push_back(pts[last]);
    std::vector<double> knots{0, 0, 0};
    for (double x : t) knots.push_back(x);
    for (int r = 0; r < 3; ++r) knots.push_back(t.back());
    double curve = 0;
    for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
      if (L(l).vertex < 0 || L(l).face < 0 || L(L(l).opp).face >= 0) continue;
      const auto a = P(l), b = P(L(l).next);
      if (std::abs(a[1]) > 1e-9 || std::abs(b[1]) > 1e-9) continue;
      const std::size_t ia = static_cast<std::size_t>(std::lround(a[0]) + n), ib = static_cast<std::size_t>(std::lround(b[0]) + n);
      const int side = test::side_of(s.face_mesh(), L(l).face, l);
      for (double sigma : {0.0, 0.25, 0.5, 0.9}) {
        const auto uv = test::side_uv(side, sigma);
        double o[9];
        s.eval(L(l).face, uv[0], uv[1], o);
        const auto e = de_boor(knots, q, t[ia] + sigma * (t[ib] - t[ia]));
        curve = std::max({curve, std::abs(o[0] - e[0] / e[3]), std::abs(o[1] - e[1] / e[3]), std::abs(o[2] - e[2] / e[3])});
      }
    }
    EXPECT_LT(curve, 1e-13) << sectors;
    // Normals 2^-k from the vertex (face 0's first corner: the cage's vertex 0) in every face round it, along its
    // diagonal and sides: their largest angle to one another.
    ASSERT_EQ(L(m.first_corner(0)).vertex, 0);
    std::printf("crease half fan of %d sectors, intervals 0.6 to 2.2%s: %d crease faces, %d exact; across %d edges gap %.2e, normals "
                "%.2e, C1 %.2e; boundary curve against de Boor %.2e\n", sectors, rational ? ", rational" : "", s.count(FaceMethod::crease), s.count(FaceMethod::exact),
                c.edges, c.gap, c.normal_angle, c.c1, curve);
    for (int k : {10, 20, 30}) {
      const double h = std::ldexp(1.0, -k);
      std::vector<std::array<double, 3>> normals;
      for (int f = 0; f < s.num_faces(); ++f) {
        const auto corner = s.corners(f);
        const int at = static_cast<int>(std::find(corner.begin(), corner.end(), 0) - corner.begin());
        if (at == 4) continue;
        static constexpr std::array<std::array<double, 2>, 4> uv{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
        const auto& cu = uv[static_cast<std::size_t>(at)];
        for (const auto& [du, dv] : std::vector<std::array<double, 2>>{{h, h}, {h, 0}, {0, h}}) {
          double o[9];
          s.eval(f, cu[0] == 0 ? du : 1 - du, cu[1] == 0 ? dv : 1 - dv, o);
          normals.push_back(test::unit_normal(o));
        }
      }
      const auto angle = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
        return std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
      };
      // At the vertex itself (face 0's first corner): the plane of the one ring's eigenvectors, where it has one.
      double o[9];
      s.eval(0, 0, 0, o);
      const auto at_vertex = test::unit_normal(o);
      double spread = 0, to_vertex = 0;
      for (const auto& a : normals) {
        to_vertex = std::max(to_vertex, angle(a, at_vertex));
        for (const auto& b : normals) spread = std::max(spread, angle(a, b));
      }
      if (sectors == 3 && k == 30) {
        EXPECT_LT(spread, 1e-4);
        EXPECT_LT(to_vertex, 1e-4);
      }
      std::printf("  normals 2^-%d from the vertex: spread %.2e rad, to the normal at the vertex %.2e rad\n", k, spread, to_vertex);
    }
  }
}

TEST(CreaseFace, UnequalIntervalsAtAnInteriorStarPointAreNonUniformCatmullClark) {
  // Fans of valence 3 and 5 (6 rings, crease boundary far out), every spoke strip its own interval: the surface
  // evaluates the star point's faces by NonUniformStar (exact B-spline cells of the NURCC levels). Local
  // subdivision of the same faces (the crease net's NURCC rules, cells of 16 regular points, the limit and tangent
  // plane from the one ring's map) must be the same surface.
  for (int valence : {3, 5}) {
    const test::QuadMesh cage = test::fan_mesh(valence, 6, wavy);
    TMesh m = io::parse_tsm(test::fusion_text(cage), "fan.tsm").mesh;
    set_spoke_strips(m, cage, valence, 2 * std::numbers::pi / valence);
    const TMeshSurface s(m, 1);
    ASSERT_EQ(s.count(FaceMethod::non_uniform), 4 * valence);  // the faces of cells (0..1, 0..1) of each sector
    double value = 0, derivative = 0, star = 0;
    for (int f = 0; f < s.num_faces(); ++f) {
      if (s.method(f) != FaceMethod::non_uniform) continue;
      const CreaseFace cf(net_of(m, f));
      for (double u : {0.0, 1e-3, 0.3, 1.0})
        for (double v : {0.0, 1e-3, 0.45, 1.0}) {
          double h[12], e[9];
          cf.eval(u, v, h);
          s.eval(f, u, v, e);
          const auto c = cartesian(h);
          const bool at_star = (u == 0 || u == 1) && (v == 0 || v == 1) && s.corners(f)[u == 0 ? (v == 0 ? 0 : 3) : (v == 0 ? 1 : 2)] == 0;
          double scale = 0;
          for (int i = 3; i < 9; ++i) scale = std::max(scale, std::abs(e[i]));
          for (int i = 0; i < 3; ++i) (at_star ? star : value) = std::max(at_star ? star : value, std::abs(c[static_cast<std::size_t>(i)] - e[i]));
          if (!at_star)
            for (int i = 3; i < 9; ++i) derivative = std::max(derivative, std::abs(c[static_cast<std::size_t>(i)] - e[i]) / scale);
        }
    }
    EXPECT_LT(value, 1e-12) << valence;
    EXPECT_LT(star, 1e-12) << valence;
    EXPECT_LT(derivative, 1e-11) << valence;
    std::printf("fan of valence %d, intervals 0.6 to 2.2: %d faces by NonUniformStar against local subdivision: values %.2e, "
                "derivatives %.2e (relative), limit point %.2e\n", valence, s.count(FaceMethod::non_uniform), value, derivative, star);
  }
}

TEST(CreaseFace, UnequalIntervalsAtCreasesInsideTheMesh) {
  // The grids of 6 x 6 above (a crease turning at a vertex of four faces, a corner of three creases with a side of
  // two faces, a creased vertex on a crease and one on the boundary), every column and row strip its own interval
  // (1, 1.5, 0.6, 2.2, ...): normals and C1 across every edge but the creases (the mesh cut open along them), C0
  // across every edge (the two sides of a crease share its curve), corners interpolated.
  const GridIndex g{6};
  const test::QuadMesh cage = test::grid_cage(6, 6);
  const std::array<double, 6> strip{1, 1.5, 0.6, 2.2, 0.9, 1.3};
  struct Case {
    const char* name;
    Crease crease;
    std::vector<int> creased, corners;
  };
  const std::vector<Case> cases{
      {"a crease turning at a vertex of four faces",
       [&](int a, int b) {
         return (g.i(a) == 3 && g.i(b) == 3 && std::max(g.j(a), g.j(b)) <= 3) || (g.j(a) == 3 && g.j(b) == 3 && std::min(g.i(a), g.i(b)) >= 3);
       },
       {},
       {}},
      {"a corner of three creases with a side of two faces",
       [&](int a, int b) { return (g.i(a) == 3 && g.i(b) == 3) || (g.j(a) == 3 && g.j(b) == 3 && std::min(g.i(a), g.i(b)) >= 3); },
       {},
       {3 * 7 + 3}},
      {"a creased vertex on a crease and on the boundary", [&](int a, int b) { return g.i(a) == 3 && g.i(b) == 3; }, {3 * 7 + 3, 3 * 7 + 6},
       {3 * 7 + 3, 3 * 7 + 6}}};
  for (const Case& c : cases) {
    io::TsmModel model = io::parse_tsm(test::fusion_creased_text(cage, c.crease, c.creased), "creases.tsm");
    TMesh& m = model.mesh;
    const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
    for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
      if (L(l).vertex < 0 || L(l).face < 0) continue;
      const int a = L(l).vertex, b = L(L(l).next).vertex;
      if (g.j(a) == 0 && g.j(b) == 0) set_strip(m, l, strip[static_cast<std::size_t>(std::min(g.i(a), g.i(b)))]);
      if (g.i(a) == 0 && g.i(b) == 0) set_strip(m, l, strip[static_cast<std::size_t>(5 - std::min(g.j(a), g.j(b)))]);
    }
    const TMeshSurface s(m, 1);
    EXPECT_GT(s.count(FaceMethod::crease), 0) << c.name;
    const test::Continuity inside = test::continuity(split_creases(m), knot_units(s));
    const test::Continuity all = test::continuity(s.face_mesh(), knot_units(s));
    EXPECT_LT(inside.gap, 1e-12) << c.name;
    EXPECT_LT(inside.normal_angle, 1e-12) << c.name;
    EXPECT_LT(inside.c1, 1e-12) << c.name;
    EXPECT_LT(all.gap, 1e-12) << c.name;
    double corner = 0;
    for (int v : c.corners)
      for (int f = 0; f < s.num_faces(); ++f) {
        const auto k = s.corners(f);
        const int at = static_cast<int>(std::find(k.begin(), k.end(), v) - k.begin());
        if (at < 4) corner = std::max(corner, gap_to(s, f, at == 1 || at == 2 ? 1 : 0, at >= 2 ? 1 : 0, cage.points[static_cast<std::size_t>(v)]));
      }
    EXPECT_LT(corner, 1e-14) << c.name;
    std::printf("grid with %s, strips at 0.6 to 2.2: %d crease faces; across %d edges off the creases gap %.2e, normals %.2e, C1 "
                "%.2e (knot units); across the creases gap %.2e; corners %.2e\n", c.name, s.count(FaceMethod::crease), inside.edges,
                inside.gap, inside.normal_angle, inside.c1, all.gap, corner);
  }
}

TEST(CreaseFace, RefusesRepeatedKnotsNearAnIrregularVertex) {
  // A half fan of 4 sectors whose strip of spoke 1's first edge has interval 0 (a repeated knot line through the
  // crease faces): refused in one line naming the edge.
  const test::QuadMesh cage = test::half_fan_mesh(4, 5, wavy);
  TMesh m = io::parse_tsm(test::fusion_text(cage), "fan.tsm").mesh;
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  int spoke = -1;
  for (int l = 0; l < static_cast<int>(m.links.size()) && spoke < 0; ++l) {
    if (L(l).vertex != 0 || L(l).face < 0) continue;
    const auto& b = cage.points[static_cast<std::size_t>(L(L(l).next).vertex)];
    if (std::abs(b[0] - std::cos(std::numbers::pi / 4)) < 1e-9 && std::abs(b[1] - std::sin(std::numbers::pi / 4)) < 1e-9) spoke = l;
  }
  ASSERT_GE(spoke, 0);
  set_strip(m, spoke, 0);
  test::expect_surface_refusal(m, "nearby has knot interval 0.000000; local subdivision takes positive intervals");
}

// The box with its top rim creased and the strip of faces at x in [1/3, 1] at interval `wide`, and the strip's
// rung from (1, 1, 1) to (1/3, 1, 1).
struct StripBox {
  io::TsmModel model;
  int rung = -1;
};
StripBox strip_box(const TopBox& box, double wide) {
  const Crease rim = [&](int a, int b) { return box.rim_edge(a, b); };
  StripBox r{io::parse_tsm(test::fusion_creased_text(box.cage, rim), "box.tsm")};
  TMesh& m = r.model.mesh;
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const test::QuadMesh cube = test::cube_mesh(3);  // the box before its warp: the same vertex ids
  const auto near = [&](int v, std::array<double, 3> p) {
    const auto& q = cube.points[static_cast<std::size_t>(v)];
    return std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]) < 1e-9;
  };
  int rung = -1;
  for (int l = 0; l < static_cast<int>(m.links.size()) && rung < 0; ++l)
    if (L(l).vertex >= 0 && L(l).face >= 0 && near(L(l).vertex, {1, 1, 1}) && near(L(L(l).next).vertex, {1.0 / 3, 1, 1})) rung = l;
  require(rung >= 0, "strip box: no rung from (1, 1, 1) to (1/3, 1, 1)");
  set_strip(m, rung, wide);
  r.rung = rung;
  return r;
}

TEST(CreaseFace, BoxWithAStripOfUnequalIntervals) {
  // The box with its top rim creased (the crease turning at four valence-3 corners) and the strip of faces at
  // x in [1/3, 1] (over the top, down two sides, along the bottom) at interval 1.5: it passes by two top corners
  // (crease vertices of 3 faces) and two bottom ones (interior star points near the crease), as exact edge
  // insertion leaves Fusion's boxes. Loads; closed triangulation; continuity across every edge; the rim curve
  // against the periodic cubic B-spline of the rim vertices on their intervals (de Boor here); the command line.
  const TopBox box;
  const StripBox strip_box_15 = strip_box(box, 1.5);
  const io::TsmModel& model = strip_box_15.model;
  const TMesh& m = model.mesh;
  const int rung = strip_box_15.rung;
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const auto strip = std::count(m.intervals.begin(), m.intervals.end(), 1.5);
  EXPECT_EQ(strip, 12);  // the strip's 12 faces round the box, a closed loop of 12 rungs
  const TMeshSurface s(m, 1);
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  const TSplineTriangulation t = tessellate(s, 1e-3);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  // Across the edges but the rim's (cut open by split_creases: the same faces and frames).
  const test::Continuity c = test::continuity(split_creases(m), knot_units(s));
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-12);
  EXPECT_LT(c.c1, 1e-12);
  // The rim: 12 vertices in order round the top, each rim edge's interval.
  std::vector<int> loop;
  std::vector<double> gaps;
  for (int l = 0; l < static_cast<int>(m.links.size()) && loop.empty(); ++l)
    if (L(l).vertex >= 0 && L(l).face >= 0 && box.rim_edge(L(l).vertex, L(L(l).next).vertex)) loop.push_back(L(l).vertex);
  while (loop.size() < 13) {
    for (int l = 0; l < static_cast<int>(m.links.size()); ++l)
      if (L(l).vertex == loop.back() && L(l).face >= 0 && box.rim_edge(L(l).vertex, L(L(l).next).vertex) &&
          (loop.size() < 2 || L(L(l).next).vertex != loop[loop.size() - 2])) {
        loop.push_back(L(L(l).next).vertex);
        gaps.push_back(m.intervals[static_cast<std::size_t>(L(l).edge)]);
        break;
      }
  }
  ASSERT_EQ(loop.front(), loop.back());
  double curve = 0;
  const std::size_t n = 12;
  for (std::size_t i = 0; i < n; ++i) {
    // Span i (loop[i] -> loop[i + 1]): knots t_(i-2) .. t_(i+3), points loop[i - 1 .. i + 2].
    std::vector<double> knots{0};
    double at = 0;
    for (int r = -2; r <= 3; ++r) {
      knots.push_back(at);
      at += gaps[(i + n + static_cast<std::size_t>(r + 12)) % n];
    }
    // knots[1 + r + 2] = t_(i + r) relative: make t_i = 0.
    const double ti = knots[3];
    for (double& k : knots) k -= ti;
    knots[0] = knots[1];
    std::vector<std::array<double, 3>> q;
    for (int r = -1; r <= 2; ++r) q.push_back(box.cage.points[static_cast<std::size_t>(loop[(i + n + static_cast<std::size_t>(r + 12)) % n])]);
    int link = -1;
    for (int l = 0; l < static_cast<int>(m.links.size()); ++l)
      if (L(l).vertex == loop[i] && L(l).face >= 0 && L(L(l).next).vertex == loop[i + 1]) link = l;
    ASSERT_GE(link, 0);
    const int side = test::side_of(s.face_mesh(), L(link).face, link);
    for (double sigma : {0.0, 0.3, 0.6, 0.95}) {
      const auto uv = test::side_uv(side, sigma);
      double o[9];
      s.eval(L(link).face, uv[0], uv[1], o);
      const auto e = de_boor(knots, q, sigma * knots[4]);
      curve = std::max({curve, std::abs(o[0] - e[0]), std::abs(o[1] - e[1]), std::abs(o[2] - e[2])});
    }
  }
  EXPECT_LT(curve, 1e-13);
  // The command line on the file written back: info counts the crease faces, eval gives the surface's point.
  const test::TempDir dir;
  const std::string path = dir.file("box_strip.tsm");
  io::write_tsm(path, m, model.report);
  const std::string info = test::run_cli(dir, "info " + path);
  EXPECT_NE(info.find(std::to_string(s.count(FaceMethod::crease)) + " faces within 4 rings of irregular vertices of a crease boundary"),
            std::string::npos) << info;
  const int face = L(rung).face;
  double x[9];
  s.eval_source(face, 0.25, 0.75, x);
  const std::array<double, 3> cli = test::cli_face_point(dir, path, face, 0.25, 0.75);
  EXPECT_LT(std::hypot(cli[0] - x[0], cli[1] - x[1], cli[2] - x[2]), 1e-14 * std::hypot(x[0], x[1], x[2]));
  std::printf("box 3 x 3 per side, top rim creased, a strip at interval 1.5 (%td rungs) by two crease corners: %d faces by local "
              "subdivision, %d exact, %d star, %d non-uniform; %zu triangles closed; across %d edges gap %.2e, normals %.2e, C1 %.2e "
              "(knot units); rim against de Boor %.2e\n", strip, s.count(FaceMethod::crease), s.count(FaceMethod::exact),
              s.count(FaceMethod::star), s.count(FaceMethod::non_uniform), t.triangles.size(), c.edges, c.gap, c.normal_angle, c.c1, curve);
}

// Within 2^-13 of an irregular corner a face with equal intervals is refined on past its cached sub-faces: the
// surface stays continuous across the boundaries of the sub-faces of every level there (2^-l from the corner
// of the creased box's faces).
TEST(CreaseFace, ContinuousPastTheCachedLevels) {
  const TopBox box;
  const TMeshSurface s(io::parse_tsm(test::fusion_creased_text(box.cage, [&](int a, int b) { return box.rim_edge(a, b); }), "box.tsm").mesh, 1);
  double worst = 0;
  int corners = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) != FaceMethod::crease || !s.crease_face(f).irregular(0)) continue;
    const CreaseFace& z = s.crease_face(f);
    ++corners;
    for (int l = 10; l <= 16; ++l) {
      const double a = std::ldexp(1.0, -l), e = 1e-12 * a;
      for (const auto& [p, q] : {std::pair{std::array{a - e, 0.3 * a}, std::array{a + e, 0.3 * a}},
                                 std::pair{std::array{0.3 * a, a - e}, std::array{0.3 * a, a + e}}}) {
        double x[12], y[12];
        z.eval(p[0], p[1], x);
        z.eval(q[0], q[1], y);
        worst = std::max(worst, std::hypot(x[0] / x[3] - y[0] / y[3], x[1] / x[3] - y[1] / y[3], x[2] / x[3] - y[2] / y[3]));
      }
    }
  }
  EXPECT_GT(corners, 0);
  EXPECT_LT(worst, 1e-13);  // points 1e-12 of a sub-face's side apart
  std::printf("creased box, %d faces with an irregular first corner: jump across the sub-faces 2^-10 .. 2^-16 from it %.1e\n",
              corners, worst);
}

// The limit surface of a refined net is the net's own on the sub-face (subdivision does not change the surface).
// A face's sub-faces towards an irregular corner come from one subdivision of each level's net shared by the four
// sub-faces, cached to 2^-12 and subdivided on past it: the face evaluated on its sub-face at corner c of level
// l (1 .. 15) against the face of the net refined l times towards c on its own (refine), at dyadic points (exact
// in both parametrisations), the derivatives per unit of the sub-face. Half fans of 3 and 5 sectors: crease
// vertices of 3 and 5 faces; the creased box: crease vertices of one face where the rim turns.
TEST(CreaseFace, SubFacesOfASharedSubdivisionAreTheFaceRestricted) {
  const TopBox box;
  const std::vector<TMesh> meshes{io::parse_tsm(test::fusion_text(test::half_fan_mesh(3, 5, wavy)), "fan3.tsm").mesh,
                                  io::parse_tsm(test::fusion_text(test::half_fan_mesh(5, 5, wavy)), "fan5.tsm").mesh,
                                  io::parse_tsm(test::fusion_creased_text(box.cage, [&](int a, int b) { return box.rim_edge(a, b); }), "box.tsm").mesh};
  double value = 0, derivative = 0;
  int corners = 0;
  for (const TMesh& m : meshes)
    for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
      const CreaseNet net = net_of(m, f);
      const CreaseFace face(net);
      for (int c = 0; c < 4; ++c) {
        if (!face.irregular(c)) continue;
        ++corners;
        CreaseNet sub = net;
        for (int l = 1; l <= 15; ++l) {
          sub = refine(sub, c);
          const CreaseFace part(sub);
          const double size = std::ldexp(1.0, -l);
          const double ox = c == 1 || c == 2 ? 1 - size : 0, oy = c >= 2 ? 1 - size : 0;
          for (const auto& [u, v] : {std::pair{0.375, 0.75}, std::pair{0.625, 0.125}, std::pair{0.875, 0.875}}) {
            double whole[12], own[12];
            face.eval(ox + size * u, oy + size * v, whole);
            part.eval(u, v, own);
            double scale = 0;
            for (int i = 4; i < 12; ++i) scale = std::max(scale, std::abs(own[i]));
            for (int i = 0; i < 4; ++i) value = std::max(value, std::abs(whole[i] - own[i]) / std::max(1.0, std::abs(own[i])));
            for (int i = 4; i < 12; ++i) derivative = std::max(derivative, std::abs(whole[i] * size - own[i]) / scale);
          }
        }
      }
    }
  EXPECT_GE(corners, 3 + 5 + 4 * 3);
  EXPECT_LT(value, 1e-13);
  EXPECT_LT(derivative, 1e-13);
  std::printf("%d irregular face corners, sub-faces 2^-1 .. 2^-15 against their refined nets: values %.1e, derivatives %.1e "
              "(relative)\n", corners, value, derivative);
}

// The Bezier patches of the box with its strip at 1.5: near the irregular vertices a quarter of a crease face is
// several B-spline cells, each one exact patch (the surface to rounding, sampled at 5 x 5 points against the
// face's own evaluation), and only the corner patches at the irregular corners are constructed, within the
// tolerance. The pieces tile each face and meet C0; the command line states the counts.
TEST(CreaseFace, PatchesWithUnequalIntervals) {
  const TopBox box;
  const StripBox b = strip_box(box, 1.5);
  const TMeshSurface s(b.model.mesh, 1);
  const TMeshPatches p = t_mesh_patches(s);
  int corners = s.count(FaceMethod::star);
  for (int f = 0; f < s.num_faces(); ++f)
    for (int c = 0; c < 4 && s.method(f) == FaceMethod::crease; ++c) corners += s.crease_face(f).irregular(c);
  EXPECT_EQ(p.corner_patches, corners);
  const test::PatchCheck c = test::expect_patches_hold(s, p);
  const test::TempDir dir;
  const std::string path = dir.file("box_strip.tsm");
  io::write_tsm(path, b.model.mesh, b.model.report);
  const std::string step = test::run_cli(dir, "convert " + path + " " + dir.file("box_strip.stp"));
  EXPECT_NE(step.find(std::to_string(p.patches.size()) + " Bezier patches (" + std::to_string(p.exact_patches) + " exact, " +
                      std::to_string(p.corner_patches) + " corner patches"),
            std::string::npos) << step;
  std::printf("%s", step.c_str());
  std::printf("box 3 x 3, rim creased, strip at 1.5: %zu patches (%d corner), %d levels; exact patches off the surface by %.1e, "
              "corner patches by %.2e (tolerance %.2e); areas off 1 by %.1e; gaps: exact pieces %.1e, at corner patches %.1e, "
              "across edges %.1e\n",
              p.patches.size(), p.corner_patches, p.levels, c.exact, c.constructed, p.tolerance, c.area, c.inner_gap, c.corner_gap,
              c.edge_gap);
}

}  // namespace
}  // namespace trivar::crease_face_test
