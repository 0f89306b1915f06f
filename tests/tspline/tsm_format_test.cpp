#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "face_continuity.hpp"
#include "tsm_error.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

std::string patch_text() {
  std::ifstream f(std::string(TRIVAR_TEST_DATA) + "/tsm/bezier_patch.tsm");
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto i = s.find(from);
  EXPECT_NE(i, std::string::npos) << from;
  return s.replace(i, from.size(), to);
}

// The Bezier patch the file was written from (tests/data/tsm: P_ij = (i, j, round(sin(i + 2j), 3)), weight 2 at
// (1, 2)), built independently as a tensor NURBS.
TensorSpline<2> reference_patch() {
  std::vector<double> c;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const double w = (i == 1 && j == 2) ? 2.0 : 1.0;
      const double z = std::round(std::sin(i + 2.0 * j) * 1000.0) / 1000.0;
      for (double x : {double(i), double(j), z}) c.push_back(w * x);
      c.push_back(w);
    }
  const KnotVector k(3, {0, 0, 0, 0, 1, 1, 1, 1});
  return TensorSpline<2>({k, k}, 3, true, c);
}

void expect_patch(const std::string& text) {
  const io::TsmModel m = io::parse_tsm(text, "patch.tsm");
  EXPECT_EQ(m.spline.connect.nodes.size(), 16u);
  EXPECT_EQ(m.report.repeated_knot_nodes, 12);
  EXPECT_EQ(m.report.units, "1 millimeters");
  EXPECT_EQ(m.report.skipped_records.at("100001uv"), 1);
  const TSplineSurface surf(m.spline);
  EXPECT_LT(surf.partition_of_unity().max_defect, 1e-14);
  const TensorSpline<2> ref = reference_patch();
  for (double s : {0.0, 0.13, 0.5, 0.77, 1.0})
    for (double t : {0.0, 0.31, 0.62, 1.0}) {
      double a[9], b[9];
      surf.eval_first_derivatives({s, t}, a);
      ref.eval_derivs({s, t}, 1, b);
      for (int d = 0; d < 9; ++d) EXPECT_NEAR(a[d], b[d], 1e-13) << s << " " << t << " " << d;
    }
}

TEST(Tsm, HandWrittenBezierPatchIsTheTensorPatch) { expect_patch(patch_text()); }

TEST(Tsm, GripBlocksAreReadInTheVertexFrame) {
  // Vertex 0's frame turned a quarter: its link 0 (east) is NORTH there, so its block lists the east layer
  // (frame north) first.
  std::string t = replaced(patch_text(), "v 0 EAST", "v 0 NORTH");
  t = replaced(t, "cg 0 4 1 0 0 1 4 5 6", "cg 0 4 1 1 0 0 5 6 4");
  expect_patch(t);
  // Windows line ends and comments.
  std::string crlf;
  for (char c : patch_text()) {
    if (c == '\n') crlf += " # comment\r";
    crlf += c;
  }
  expect_patch(crlf);
}

// Three quadrilaterals around vertex 0 (a cube corner): the face angles there sum to 270 degrees, a star point.
// Vertices 1, 3, 5 lie between two faces on the boundary (180 degrees), 2, 4, 6 are corners (90). The model
// loads as its mesh; the Catmull-Clark region around the star point reads the boundary's ghost layer, which
// closes round it: one surface, continuous across the three edges at the star point.
TEST(Tsm, StarPointsLoadAsTheMesh) {
  const std::string text = R"(#TS0200
degree 3
force-bezier-end-conditions 0
f 0 0
f 4 0
f 8 0
e 0 1
e 3 1
e 7 1
e 1 1
e 2 1
e 5 1
e 6 1
e 9 1
e 10 1
v 0 EAST
v 1 EAST
v 2 EAST
v 5 EAST
v 6 EAST
v 9 EAST
v 10 EAST
l 3 1 11 0 0 0 0
l 0 2 12 1 0 3 0
l 1 3 13 2 0 4 0
l 2 0 4 3 0 1 0
l 7 5 3 0 1 1 0
l 4 6 14 3 1 5 0
l 5 7 15 4 1 6 0
l 6 4 8 5 1 2 0
l 11 9 7 0 2 2 0
l 8 10 16 5 2 7 0
l 9 11 17 6 2 8 0
l 10 8 0 1 2 0 0
l 13 17 1 2 -1 3 2
l 14 12 2 3 -1 4 1
l 15 13 5 4 -1 5 2
l 16 14 6 5 -1 6 1
l 17 15 9 6 -1 7 2
l 12 16 10 1 -1 8 1
0m gvp 0
0m gvp 1
0m gvp 2
0m gvp 3
0m gvp 4
0m gvp 5
0m gvp 6
0g 0 0 0 1
0g 1 0 0 1
0g 1 1 0 1
0g 0 1 0 1
0g 0 1 1 1
0g 0 0 1 1
0g 1 0 1 1
)";
  const io::TsmModel m = io::parse_tsm(text, "corner.tsm");
  EXPECT_EQ(m.report.star_points, 1);
  EXPECT_EQ(star_points(m.mesh), std::vector<int>{0});
  EXPECT_TRUE(m.spline.image.faces.empty());
  const TMeshSurface s(m.mesh);
  EXPECT_EQ(s.count(FaceMethod::star), 3);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, 3);
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-10);
}

TEST(Tsm, MalformedFilesGiveOneLineErrors) {
  const std::string p = patch_text();
  test::expect_tsm_error(replaced(p, "#TS0200", "#TS0100"), "#TS0200");
  test::expect_tsm_error(replaced(p, "l 3 1 4 0 0 0 0", "l 3 1 44 0 0 0 0"), "does not exist");     // dangling id
  test::expect_tsm_error(replaced(p, "l 3 1 4 0 0 0 0", "l 3 1 5 0 0 0 0"), "inconsistent links");  // opp not mutual
  test::expect_tsm_error(replaced(p, "l 0 2 5 1 0 1 0", "l 0 2 5 1 0 1 1"), "not rectangular");     // three corners
  test::expect_tsm_error(replaced(p, "l 0 2 5 1 0 1 0", "l 0 2 5 1 0 1 2"), "not rectangular");     // reflex corner
  test::expect_tsm_error(replaced(p, "l 0 2 5 1 0 1 0", "l 0 2 5 1 0 1 -1"), "corner flag -1 is not 0, 1 or 2");  // in a face
  test::expect_tsm_error(replaced(p, "l 5 7 0 1 -1 0 2", "l 5 7 0 1 -1 0 -1"), "flag -1 on the boundary at vertex 1");  // a corner's outside
  test::expect_tsm_error(replaced(p, "e 1 1", "e 1 2"), "contradictory knot intervals");
  test::expect_tsm_error(replaced(p, "e 1 1", "e 1 x"), "bad knot interval");
  test::expect_tsm_error(replaced(p, "0m cg 0 4 1 0 0 1 4 5 6", "0m cg 0 4 1 0 0 1 4 5"), "grip block");
  test::expect_tsm_error(replaced(p, "0m gvp 3", "0m gv 3"), "neither a primary grip nor in a grip block");
  test::expect_tsm_error(replaced(p, "f 0 0", "f 9 0"), "does not exist");
}

}  // namespace
}  // namespace trivar

namespace trivar {
namespace {

std::string t_junction_text() {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 6.0}});
  }
  const TSpline ts = t_spline_from_segments({3, 3}, g, [](double s, double t, int a, int b) {
    return RationalPoint{{s + 0.1 * a, t + 0.1 * b, std::sin(s + t)}, 1.0 + 0.01 * s};
  });
  std::ostringstream os;
  io::write_tsm(os, ts);
  return os.str();
}

TEST(Tsm, WrittenAndReadBackGivesTheSameSurface) {
  // The hand-written patch, and a T-junction mesh written by trivar.
  for (const std::string& text : {patch_text(), t_junction_text()}) {
    const io::TsmModel a = io::parse_tsm(text, "a.tsm");
    std::ostringstream out;
    io::write_tsm(out, a.spline);
    const io::TsmModel b = io::parse_tsm(out.str(), "b.tsm");
    EXPECT_EQ(b.spline.connect.nodes.size(), a.spline.connect.nodes.size());
    EXPECT_EQ(b.report.repeated_knot_nodes, a.report.repeated_knot_nodes);
    const TSplineSurface sa(a.spline), sb(b.spline);
    const Box<2> dom = sa.domain();
    for (double fs : {0.0, 0.3, 0.8, 1.0})
      for (double ft : {0.0, 0.45, 1.0}) {
        const double s = dom.lo[0] + fs * dom.extent(0), t = dom.lo[1] + ft * dom.extent(1);
        double x[9], y[9];
        sa.eval_first_derivatives({s, t}, x);
        sb.eval_first_derivatives({s, t}, y);
        for (int d = 0; d < 9; ++d) EXPECT_EQ(x[d], y[d]);
      }
    // Written again, the same text.
    std::ostringstream again;
    io::write_tsm(again, b.spline);
    EXPECT_EQ(again.str(), out.str());
  }
}

}  // namespace
}  // namespace trivar
