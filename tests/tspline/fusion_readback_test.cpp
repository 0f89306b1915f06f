// TSM files written by Autodesk Fusion 360 itself (tests/data/tsm/fusion, read back from Fusion with
// TSplineBody.getTSMDescription; README.md there): what trivar reads from them and the surface it evaluates,
// against closed forms of the Catmull-Clark limit surface and of the uniform cubic B-spline.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "face_continuity.hpp"
#include "fusion_cages.hpp"
#include "osd_reference.hpp"
#include "triangulation_loops.hpp"
#include "tsm_error.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar {
namespace {

io::TsmModel read_fusion_file(const std::string& name) { return io::read_tsm(std::string(TRIVAR_TEST_DATA) + "/tsm/fusion/" + name); }

std::array<double, 3> control_point(const TMesh& m, int v) {
  return m.points[static_cast<std::size_t>(m.vertices[static_cast<std::size_t>(v)].primary)].xyz;
}

// The face-local (u, v) of corner k (counter-clockwise from the first corner).
std::array<double, 2> corner_uv(int k) {
  static constexpr std::array<std::array<double, 2>, 4> uv{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  return uv[static_cast<std::size_t>(k)];
}

// A closed cage's surface: its tessellation t watertight with Euler characteristic 2 (a sphere), and across its
// `edges` edges no gap and one tangent plane.
void expect_closed_and_tangent_continuous(const TMeshSurface& s, const TSplineTriangulation& t, int edges) {
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, edges);
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-9);
}

// Every star point's limit position, evaluated at the star corner of each of its faces.
template <class Check>
void at_star_corners(const TMeshSurface& s, const Check& check) {
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    for (int k = 0; k < 4; ++k)
      if (std::find(s.stars().begin(), s.stars().end(), c[static_cast<std::size_t>(k)]) != s.stars().end()) {
        double o[9];
        s.eval(f, corner_uv(k)[0], corner_uv(k)[1], o);
        check(c[static_cast<std::size_t>(k)], std::array<double, 3>{o[0], o[1], o[2]});
      }
  }
}

// The box cages: 3 x 3 faces per side of the cube [-10, 10]^3 (inner vertices at +-10/3), a valence-3 star
// point at each corner, every interval 1.
TEST(FusionReadback, BoxInCentimetres) {
  const io::TsmModel m = read_fusion_file("gen_box3_cm_readback.tsm");
  EXPECT_EQ(m.report.units, "1 centimeters");
  EXPECT_EQ(m.report.end_conditions, "MULTIPLE_KNOTS");
  EXPECT_EQ(m.report.version, 2);
  EXPECT_EQ(m.report.behavior_version, "4.0.1");
  EXPECT_FALSE(m.report.grip_map);
  ASSERT_EQ(m.mesh.faces.size(), 54u);
  const TMeshSurface s(m.mesh);
  EXPECT_EQ(s.stars().size(), 8u);
  // The Catmull-Clark limit of a valence-n vertex: (n^2 P + 4 sum e + sum f) / (n (n + 5)); at the corner
  // (10, 10, 10) with edge neighbours (a, 10, 10) ... and face neighbours (a, a, 10) ..., a = 10/3, every
  // coordinate is (9 * 10 + 4 (a + 20) + (2 a + 10)) / 24 = 25/3.
  int corners = 0;
  at_star_corners(s, [&](int v, const std::array<double, 3>& p) {
    const auto cp = control_point(s.mesh(), v);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(p[static_cast<std::size_t>(i)], std::copysign(25.0 / 3, cp[static_cast<std::size_t>(i)]), 1e-12);
    ++corners;
  });
  EXPECT_EQ(corners, 24);
  // A side's centre face has four regular corners and eight quadrilaterals round it: the bicubic patch of its 16
  // points, which all lie on the side's plane. With every control point in [-10, 10]^3 the box is [-10, 10]^3.
  const TSplineTriangulation t = tessellate(s, 0.05);
  std::array<double, 3> lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (const auto& p : t.points)
    for (std::size_t i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(lo[i], -10, 1e-12);
    EXPECT_NEAR(hi[i], 10, 1e-12);
  }
  expect_closed_and_tangent_continuous(s, t, 108);
}

// The same box with Fusion's crease list: the 12 edges round the top side (z = 10) in 100edges, an empty
// 100verts, SUBD_CREASES, a grip map with `0m odd-grip-map`. The crease loop turns at the top side's corners,
// valence-3 star points with one face on the top side. Against OpenSubdiv's limit surface of the same cage with
// those edges infinitely sharp (value, d/du, d/dv at 6 x 6 points per face, 2e-3 and farther from the corners;
// Bfr's quadrilateral parametrisation starts at the face's first corner, as trivar's), written back with both
// records, and closed.
TEST(FusionReadback, CreaseListIsTheSubdivisionCrease) {
  const io::TsmModel m = read_fusion_file("gen_box3_crease_list_readback.tsm");
  EXPECT_EQ(m.report.end_conditions, "SUBD_CREASES");
  EXPECT_EQ(m.report.version, 245);
  EXPECT_EQ(m.report.behavior_version, "4.2.0");
  EXPECT_TRUE(m.report.grip_map);
  EXPECT_EQ(m.report.skipped_records.count("100edges"), 0u);
  EXPECT_EQ(m.report.crease_edges, 12);
  EXPECT_EQ(m.mesh.crease_edges, (std::vector<int>{24, 27, 30, 32, 33, 34, 40, 41, 42, 44, 46, 47}));
  EXPECT_TRUE(m.mesh.crease_vertices.empty());
  // Written back with both records, read again the same.
  std::ostringstream os;
  io::write_tsm(os, m.mesh, m.report);
  EXPECT_NE(os.str().find("100edges 24 27 30 32 33 34 40 41 42 44 46 47\n100verts\n"), std::string::npos);
  const io::TsmModel again = io::parse_tsm(os.str(), "again.tsm");
  EXPECT_EQ(again.mesh.crease_edges, m.mesh.crease_edges);
  EXPECT_TRUE(again.mesh.crease_vertices.empty());

  const TMesh& cage = m.mesh;
  test::PolyMesh poly;
  for (int v = 0; v < static_cast<int>(cage.vertices.size()); ++v) poly.points.push_back(control_point(cage, v));
  for (int f = 0; f < static_cast<int>(cage.faces.size()); ++f) {
    std::vector<int> loop;
    const int first = cage.first_corner(f);
    int l = first;
    do {
      loop.push_back(cage.links[static_cast<std::size_t>(l)].vertex);
      l = cage.links[static_cast<std::size_t>(l)].next;
    } while (l != first);
    ASSERT_EQ(loop.size(), 4u);
    poly.faces.push_back(loop);
  }
  std::map<int, int> rim;  // vertex -> crease edges there
  for (int e : cage.crease_edges)
    for (const TMeshLink& k : cage.links)
      if (k.edge == e && k.face >= 0) {
        const int a = k.vertex, b = cage.links[static_cast<std::size_t>(k.next)].vertex;
        poly.sharp_edges.push_back({a, b});
        EXPECT_EQ(poly.points[static_cast<std::size_t>(a)][2], 10);
        ++rim[a];
        ++rim[b];
        break;
      }
  EXPECT_EQ(rim.size(), 12u);  // one loop round the top side
  for (const auto& [v, n] : rim) EXPECT_EQ(n, 2) << v;
  const test::OsdLimitSurface osd(poly);
  const TMeshSurface s(m.mesh, 1);
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  double worst = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    for (double u : {0.0, 2e-3, 0.3, 0.7, 0.998, 1.0})
      for (double v : {0.0, 2e-3, 0.3, 0.7, 0.998, 1.0}) {
        double a[9];
        s.eval(f, u, v, a);
        const test::LimitSample b = osd.eval(f, u, v);
        const bool corner = (u == 0 || u == 1) && (v == 0 || v == 1);
        for (std::size_t k = 0; k < 3; ++k) {
          worst = std::max(worst, std::abs(a[k] - b.p[k]));
          if (!corner) worst = std::max({worst, std::abs(a[3 + k] - b.du[k]), std::abs(a[6 + k] - b.dv[k])});
        }
      }
  EXPECT_LT(worst, 1e-11);  // points of size 10, derivatives 2e-3 from a corner scaled by 2^9
  const TSplineTriangulation t = tessellate(s, 1e-2);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  std::printf("Fusion's box with its top rim creased: %d faces by local subdivision, %d at star points; against OpenSubdiv "
              "%.2e; %zu triangles closed\n", s.count(FaceMethod::crease), s.count(FaceMethod::star), worst, t.triangles.size());
}

// The box with the four inner control points of the top side moved to z = -25, below the bottom side (z = -10):
// the surface passes through itself. trivar evaluates it (self-intersection is a matter of the geometry, not
// checked). The top centre face is the bicubic patch of its 16 points: at its centre the weights
// (1, 23, 23, 1) / 48 per direction give z = (529 (-25) + 47 * 10) / 576.
TEST(FusionReadback, SelfIntersectingBoxLoads) {
  const io::TsmModel m = read_fusion_file("r2_box3_self_intersecting.tsm");
  EXPECT_EQ(m.report.version, 1);
  EXPECT_TRUE(m.report.behavior_version.empty());
  const TMeshSurface s(m.mesh);
  int found = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    if (!std::all_of(c.begin(), c.end(), [&](int v) { return control_point(s.mesh(), v)[2] == -25; })) continue;
    double o[9];
    s.eval(f, 0.5, 0.5, o);
    EXPECT_NEAR(o[0], 0, 1e-12);
    EXPECT_NEAR(o[1], 0, 1e-12);
    EXPECT_NEAR(o[2], (529.0 * -25 + 47.0 * 10) / 576, 1e-12);
    ++found;
  }
  EXPECT_EQ(found, 1);
  expect_closed_and_tangent_continuous(s, tessellate(s, 0.1), 108);
}

// The cylinders: 8 points on a circle of radius 10 per ring, rings at z = 0, 10, 20, 30, 40. Round the middle
// ring (z = 20) the faces have regular corners and quadrilaterals round them, so the surface is the uniform
// bicubic B-spline of the rings at z = 10, 20, 30: at a vertex of the middle ring z = 20 and the radius that of
// the closed uniform cubic B-spline of the octagon, 10 (4 + 2 cos(pi/4)) / 6; halfway between two vertices
// 10 (46 cos(pi/8) + 2 cos(3 pi/8)) / 48.
template <class Check>
void at_middle_ring(const TMeshSurface& s, const Check& check) {
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    for (int k = 0; k < 4; ++k) {
      const bool here = control_point(s.mesh(), c[static_cast<std::size_t>(k)])[2] == 20;
      const bool next = control_point(s.mesh(), c[static_cast<std::size_t>((k + 1) % 4)])[2] == 20;
      if (!here) continue;
      double o[9];
      s.eval(f, corner_uv(k)[0], corner_uv(k)[1], o);
      check(false, o);
      if (!next) continue;
      const auto a = corner_uv(k), b = corner_uv((k + 1) % 4);
      s.eval(f, (a[0] + b[0]) / 2, (a[1] + b[1]) / 2, o);
      check(true, o);
    }
  }
}

void expect_octagon_b_spline_ring(const TMeshSurface& s) {
  const double at_vertex = 10 * (2 + std::cos(2 * std::numbers::pi / 8)) / 3;
  const double halfway = 10 * (46 * std::cos(std::numbers::pi / 8) + 2 * std::cos(3 * std::numbers::pi / 8)) / 48;
  int vertices = 0, middles = 0;
  at_middle_ring(s, [&](bool middle, const double* o) {
    EXPECT_NEAR(o[2], 20, 1e-12);
    EXPECT_NEAR(std::hypot(o[0], o[1]), middle ? halfway : at_vertex, 1e-12);
    ++(middle ? middles : vertices);
  });
  EXPECT_EQ(vertices, 32);  // 8 vertices, 4 faces each
  EXPECT_EQ(middles, 16);   // 8 edges, 2 faces each
}

TEST(FusionReadback, CappedCylinder) {
  const io::TsmModel m = read_fusion_file("gen_cyl8x4_capped_readback.tsm");
  const TMeshSurface s(m.mesh);
  ASSERT_EQ(s.num_faces(), 40);
  // Each cap is four quadrilaterals (centre and three ring points): the odd ring points have three faces.
  EXPECT_EQ(s.stars().size(), 8u);
  expect_octagon_b_spline_ring(s);
  expect_closed_and_tangent_continuous(s, tessellate(s, 0.1), 80);
}

// The open tube: MULTIPLE_KNOTS without a grip map, `ec e 0` on its 16 boundary edges. Its boundary is
// trivar's reading of that case (crease_ends: the repeated-knot nodes on the boundary vertices, the boundary
// curve the cubic B-spline of the boundary points), not known from Fusion; the middle ring does not depend on it
// (the clamped knots 0, 0, 0, 0, 1, 2, 3, 4, 4, 4, 4 give the rows 10, 20, 30 the weights 1/6, 2/3, 1/6 at 2).
TEST(FusionReadback, OpenCylinder) {
  const io::TsmModel m = read_fusion_file("gen_cyl8x4_open_readback.tsm");
  EXPECT_EQ(m.mesh.conditions.size(), 16u);
  for (const auto& [e, flag] : m.mesh.conditions) EXPECT_EQ(flag, 0) << e;
  const TMeshSurface s(m.mesh);
  ASSERT_EQ(s.num_faces(), 32);
  EXPECT_TRUE(s.stars().empty());
  expect_octagon_b_spline_ring(s);
  // The boundary rings: z = 0 and 40, the octagon's B-spline radius at the vertices.
  const double at_vertex = 10 * (2 + std::cos(2 * std::numbers::pi / 8)) / 3;
  int boundary = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    for (int k = 0; k < 4; ++k) {
      const double z = control_point(s.mesh(), c[static_cast<std::size_t>(k)])[2];
      if (z != 0 && z != 40) continue;
      double o[9];
      s.eval(f, corner_uv(k)[0], corner_uv(k)[1], o);
      EXPECT_NEAR(o[2], z, 1e-12);
      EXPECT_NEAR(std::hypot(o[0], o[1]), at_vertex, 1e-12);
      ++boundary;
    }
  }
  EXPECT_EQ(boundary, 32);
  // Watertight (no crack: the two boundary circles are the only loops) and C2 across the 56 inner edges.
  EXPECT_EQ(test::boundary_loops(tessellate(s, 0.1)), 2);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, 56);
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.c1, 1e-12);
  // Written back as read: no grip map, one point per vertex (the block points are the evaluation's).
  EXPECT_EQ(s.mesh().points.size(), 56u);
  std::ostringstream os;
  io::write_tsm(os, s.source_mesh(), m.report);
  EXPECT_EQ(os.str().find("0m "), std::string::npos);
  EXPECT_EQ(io::parse_tsm(os.str(), "again.tsm").mesh.points.size(), 40u);
}

// The open 3 x 3 grid: the global T-spline (no star point, no closed strip).
TEST(FusionReadback, GridLoadsAsGlobalTSpline) {
  const io::TsmModel m = read_fusion_file("gen_grid3x3_multiknots_readback.tsm");
  EXPECT_FALSE(m.spline.image.faces.empty());
  EXPECT_EQ(m.mesh.conditions.size(), 12u);
}

// Unequal knot intervals among star points closer than non-uniform Catmull-Clark's three rings (the 3 x 3 box's
// corners are three edges apart): two global non-uniform Catmull-Clark steps (3 -> 12 edges apart), then each
// star point's own sectors. The `inconsistent knot` box is consistent as Fusion wrote it back: one strip of faces
// round the box carries 1.02 across (opposite sides equal to 9e-16), the rest 1 to 2.2e-15, and its 108 106ek
// records repeat the edges' intervals. The strip is the middle one of its axis, so the box with its intervals is
// symmetric under the three mirrors: the eight corner limit points are mirror images; with every interval 1 they
// would be (25/3, 25/3, 25/3) (BoxInCentimetres).
TEST(FusionReadback, UnequalIntervalsAmongCloseStarPointsAreSteppedApart) {
  const io::TsmModel m = read_fusion_file("a3_box3_inconsistent_knot3_readback.tsm");
  EXPECT_EQ(m.report.skipped_records.at("106ek"), 108);
  EXPECT_EQ(m.report.version, 289);
  int wide = 0;
  for (double d : m.mesh.intervals) {
    EXPECT_TRUE(std::abs(d - 1) < 3e-15 || std::abs(d - 1.02) < 3e-15) << d;
    wide += std::abs(d - 1.02) < 3e-15;
  }
  EXPECT_EQ(wide, 12);  // a ring of 12 faces round the box, 12 edges between them
  const TMeshSurface s(m.mesh, 1);
  EXPECT_EQ(s.global_steps(), 2);
  EXPECT_EQ(s.num_faces(), 16 * 54);
  EXPECT_EQ(s.source_mesh().faces.size(), 54u);
  EXPECT_EQ(s.stars().size(), 8u);
  EXPECT_EQ(s.non_uniform_stars(), 0);  // after the steps the strip lies beyond the corners' three rings
  std::map<int, std::array<double, 3>> limit;
  double spread = 0;
  at_star_corners(s, [&](int v, const std::array<double, 3>& p) {
    const auto [it, fresh] = limit.emplace(v, p);
    spread = std::max(spread, std::hypot(p[0] - it->second[0], p[1] - it->second[1], p[2] - it->second[2]));
  });
  ASSERT_EQ(limit.size(), 8u);
  EXPECT_LT(spread, 1e-12);  // the three faces at a corner agree
  const std::array<double, 3> first = limit.begin()->second;
  double mirror = 0, uniform = 0;
  for (const auto& [v, p] : limit) {
    const auto cp = control_point(s.mesh(), v);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_GT(p[i] * cp[i], 0);
      mirror = std::max(mirror, std::abs(std::abs(p[i]) - std::abs(first[i])));
      uniform = std::max(uniform, std::abs(std::abs(p[i]) - 25.0 / 3));
    }
  }
  EXPECT_LT(mirror, 1e-12);
  EXPECT_GT(uniform, 1e-4);  // the intervals move the limit points
  EXPECT_LT(uniform, 0.05);
  std::printf("box 3 x 3 with the 1.02 strip: corner limit point (%.12f, %.12f, %.12f) (mirror images to %.1e; uniform "
              "25/3 off by %.2e)\n", std::abs(first[0]), std::abs(first[1]), std::abs(first[2]), mirror, uniform);
  const TSplineTriangulation t = tessellate(s, 0.05);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, 16 * 108);
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-9);
  EXPECT_LT(c.c1, 0.02 + 1e-9);  // C1 in the knots: across the strip's sides the derivatives differ by the ratio 1.02
  std::printf("  %d faces (non-uniform %d, bicubic %d, exact %d), %zu triangles; across %d edges: gap %.1e, normals %.1e, "
              "C1 %.1e\n", s.num_faces(), s.count(FaceMethod::non_uniform), s.count(FaceMethod::bicubic),
              s.count(FaceMethod::exact), t.triangles.size(), c.edges, c.gap, c.normal_angle, c.c1);
  // Bezier patches of the refined faces: the 24 star faces' corner patches within the default tolerance.
  const TMeshPatches p = t_mesh_patches(s);
  EXPECT_EQ(p.corner_patches, 24);
  EXPECT_EQ(p.exact_patches + p.corner_patches, static_cast<int>(p.patches.size()));
  EXPECT_LE(p.deviation, p.tolerance);
}

// After the steps the file's faces are still what eval_source and the command line's `eval FACE U V` take: the
// corners of the 54 faces as given are the limit points of the file's 56 vertices, 3 faces at each of the 8 star
// points and 4 at the others (a face id or (u, v) taken as a refined face's would land inside faces), and the
// derivatives are d/du of the face as given (central differences).
TEST(FusionReadback, SteppedBoxIsEvaluatedOnTheFilesFaces) {
  const TMeshSurface s(read_fusion_file("a3_box3_inconsistent_knot3_readback.tsm").mesh, 1);
  ASSERT_EQ(s.global_steps(), 2);
  std::vector<std::array<double, 3>> points;
  std::vector<int> faces_at;
  for (int f = 0; f < 54; ++f)
    for (const auto& [u, v] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}) {
      double x[9];
      s.eval_source(f, u, v, x);
      std::size_t i = 0;
      while (i < points.size() && std::hypot(points[i][0] - x[0], points[i][1] - x[1], points[i][2] - x[2]) > 1e-11) ++i;
      if (i == points.size()) points.push_back({x[0], x[1], x[2]}), faces_at.push_back(0);
      ++faces_at[i];
    }
  EXPECT_EQ(points.size(), 56u);
  EXPECT_EQ(std::count(faces_at.begin(), faces_at.end(), 3), 8);
  EXPECT_EQ(std::count(faces_at.begin(), faces_at.end(), 4), 48);
  const double fd = test::finite_difference_error([&](int f, double u, double v, double* o) { s.eval_source(f, u, v, o); },
                                                  {0, 7, 14, 21, 28, 35, 42, 49}, {{0.3, 0.7}, {0.61, 0.2}});
  EXPECT_LT(fd, 1e-6);
  const test::TempDir dir;
  const std::string file = std::string(TRIVAR_TEST_DATA) + "/tsm/fusion/a3_box3_inconsistent_knot3_readback.tsm";
  double x[9];
  s.eval_source(53, 0.25, 0.75, x);
  const std::array<double, 3> cli = test::cli_face_point(dir, file, 53, 0.25, 0.75);
  EXPECT_LT(std::hypot(cli[0] - x[0], cli[1] - x[1], cli[2] - x[2]), 1e-14 * std::hypot(x[0], x[1], x[2]));
  const std::string refused = dir.file("refused.txt");
  EXPECT_NE(std::system((std::string(TRIVAR_CLI_PATH) + " eval " + file + " 54 0.5 0.5 > " + refused + " 2>&1").c_str()), 0);
  std::ifstream in(refused);
  const std::string line((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(line.find("has no face 54"), std::string::npos) << line;
  std::printf("box with the 1.02 strip, faces as given: 56 corner points (8 of 3 faces), finite differences %.1e\n", fd);
}

}  // namespace
}  // namespace trivar
