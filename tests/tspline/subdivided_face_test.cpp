// Coarse Catmull-Clark cages whose faces have several star corners or whose star points are joined by an edge
// (the cube of one face per side; a cube side with an edge turned, which makes adjacent valence-3 and 5 star
// points): evaluated through one local subdivision step, checked against the closed-form limit points, against
// the existing evaluation of the cage subdivided once here with the textbook rules, and for continuity,
// watertightness and the Bezier patches.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "face_continuity.hpp"
#include "star_mesh_tsm.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar {
namespace {

using P4h = std::array<double, 4>;
constexpr std::array<std::array<double, 2>, 4> kCornerUv{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};

// The closed-form Catmull-Clark limit point of vertex v of valence n: (n^2 v + 4 sum e_j + sum f_j) / (n (n + 5))
// with e_j its edge neighbours and f_j the diagonal corners of its faces.
std::array<double, 3> limit_point_formula(const test::QuadMesh& m, int v) {
  std::set<int> edge_nbrs;
  std::vector<int> diagonals;
  for (const auto& q : m.quads)
    for (std::size_t i = 0; i < 4; ++i)
      if (q[i] == v) {
        edge_nbrs.insert(q[(i + 1) % 4]);
        edge_nbrs.insert(q[(i + 3) % 4]);
        diagonals.push_back(q[(i + 2) % 4]);
      }
  const double n = static_cast<double>(diagonals.size());
  EXPECT_EQ(edge_nbrs.size(), diagonals.size());
  std::array<double, 3> r{};
  for (std::size_t k = 0; k < 3; ++k) {
    double s = n * n * m.points[static_cast<std::size_t>(v)][k];
    for (int e : edge_nbrs) s += 4 * m.points[static_cast<std::size_t>(e)][k];
    for (int f : diagonals) s += m.points[static_cast<std::size_t>(f)][k];
    r[k] = s / (n * (n + 5));
  }
  return r;
}

struct Cage {
  test::QuadMesh quads;
  io::TsmModel model;
  explicit Cage(test::QuadMesh q, double interval = 1.0) : quads(std::move(q)), model(io::parse_tsm(tsm_text(quads, interval), "cage.tsm")) {
    // The TSM vertices are the quad mesh's points in order.
    for (std::size_t v = 0; v < quads.points.size(); ++v)
      for (std::size_t k = 0; k < 3; ++k)
        EXPECT_EQ(model.mesh.points[static_cast<std::size_t>(model.mesh.vertices[v].primary)].xyz[k], quads.points[v][k]);
  }
};

double limit_point_error(const Cage& c, const TMeshSurface& s) {
  double worst = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto corners = s.corners(f);
    for (std::size_t k = 0; k < 4; ++k) {
      double o[9];
      s.eval(f, kCornerUv[k][0], kCornerUv[k][1], o);
      const auto x = limit_point_formula(c.quads, corners[k]);
      worst = std::max(worst, std::hypot(o[0] - x[0], o[1] - x[1], o[2] - x[2]));
    }
  }
  return worst;
}

void expect_closed_watertight(const TSplineTriangulation& t) {
  std::map<std::array<int, 2>, int> use;
  for (const auto& tri : t.triangles)
    for (std::size_t k = 0; k < 3; ++k) ++use[{tri[k], tri[(k + 1) % 3]}];
  for (const auto& [e, n] : use) {
    ASSERT_EQ(n, 1) << "an edge used twice in the same direction";
    ASSERT_TRUE(use.count({e[1], e[0]})) << "an edge without its twin";
  }
  EXPECT_EQ(static_cast<long>(t.points.size()) - static_cast<long>(use.size() / 2) + static_cast<long>(t.triangles.size()), 2);
}

void expect_smooth(const TMeshSurface& s, const char* name) {
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  std::printf("%s: %d edges, position gap %.2e, normal defect (sin) %.2e, C1 defect %.2e\n", name, c.edges, c.gap,
              c.normal_angle, c.c1);
  EXPECT_LT(c.gap, 1e-13) << name;
  EXPECT_LT(c.normal_angle, 1e-12) << name;
  EXPECT_LT(c.c1, 1e-11) << name;
}

TEST(SubdividedFaces, CubeOfOneFacePerSide) {
  const Cage c(test::cube_mesh(1));
  const TMeshSurface s(c.model.mesh);
  EXPECT_EQ(s.count(FaceMethod::subdivided), 6);
  EXPECT_EQ(s.stars().size(), 8u);
  for (int q = 0; q < 4; ++q) EXPECT_EQ(s.subdivided(0).valence(q), 3);
  const double e = limit_point_error(c, s);
  std::printf("cube 1 x 1: limit points off the closed form by %.2e\n", e);
  EXPECT_LT(e, 1e-12);
  // By symmetry (and the formula: (9 + 4 - 1) / 24) the corner (1, 1, 1) goes to (1, 1, 1) / 2.
  double o[9];
  s.eval(0, 0, 0, o);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(std::abs(o[k]), 0.5, 1e-15);
  expect_smooth(s, "cube 1 x 1");
  expect_closed_watertight(tessellate(s, 1e-3));
}

TEST(SubdividedFaces, AdjacentStarPointsOfValenceThreeAndFive) {
  const Cage c(test::turned_edge_cube());
  const TMeshSurface s(c.model.mesh);
  std::map<int, int> valences;
  for (int v : s.stars()) ++valences[s.valence(v)];
  EXPECT_EQ(valences[3], 10);
  EXPECT_EQ(valences[5], 2);
  // The two turned quads (three star corners each), the two across the edges joining a valence-3 to a
  // valence-5 point, and the one at the cube's corner diagonal to a valence-5 point (the hexagon of the turned
  // edge spans the side's inner points from one side's border to the other).
  EXPECT_EQ(s.count(FaceMethod::subdivided), 5);
  const double e = limit_point_error(c, s);
  std::printf("turned-edge cube: limit points off the closed form by %.2e\n", e);
  EXPECT_LT(e, 1e-12);
  expect_smooth(s, "turned-edge cube");
  expect_closed_watertight(tessellate(s, 1e-3));
}

// One uniform Catmull-Clark step of the whole cage with the textbook rules, on homogeneous points (w x, w):
// quad 4 f + k is the sub-face at corner k of face f (in the order of `corners`, the faces' (u, v) corners).
struct SubdividedCage {
  test::QuadMesh quads;
  std::vector<double> weights;
};
SubdividedCage subdivide_cage(const test::QuadMesh& m, const std::vector<double>& w, const std::vector<std::array<int, 4>>& corners) {
  const auto h = [&](int v) {
    const auto& p = m.points[static_cast<std::size_t>(v)];
    const double x = w[static_cast<std::size_t>(v)];
    return P4h{x * p[0], x * p[1], x * p[2], x};
  };
  const auto mean = [](const std::vector<P4h>& ps) {
    P4h r{};
    for (const P4h& p : ps)
      for (std::size_t k = 0; k < 4; ++k) r[k] += p[k] / static_cast<double>(ps.size());
    return r;
  };
  std::vector<P4h> face_pts;
  for (const auto& q : corners) face_pts.push_back(mean({h(q[0]), h(q[1]), h(q[2]), h(q[3])}));
  std::map<std::array<int, 2>, std::vector<int>> edge_faces;
  for (std::size_t f = 0; f < corners.size(); ++f)
    for (std::size_t i = 0; i < 4; ++i) {
      const int a = corners[f][i], b = corners[f][(i + 1) % 4];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  std::vector<P4h> pts;
  // Vertex points: (F + 2 R + (n - 3) P) / n, F the mean of the adjacent face points, R of the edge midpoints.
  for (int v = 0; v < static_cast<int>(m.points.size()); ++v) {
    std::vector<P4h> fs, mids;
    for (std::size_t f = 0; f < corners.size(); ++f)
      if (std::find(corners[f].begin(), corners[f].end(), v) != corners[f].end()) fs.push_back(face_pts[f]);
    for (const auto& [e, fl] : edge_faces)
      if (e[0] == v || e[1] == v) mids.push_back(mean({h(e[0]), h(e[1])}));
    const double n = static_cast<double>(fs.size());
    const P4h F = mean(fs), R = mean(mids), P = h(v);
    P4h r{};
    for (std::size_t k = 0; k < 4; ++k) r[k] = (F[k] + 2 * R[k] + (n - 3) * P[k]) / n;
    pts.push_back(r);
  }
  std::map<std::array<int, 2>, int> edge_pt;
  for (const auto& [e, fl] : edge_faces) {
    edge_pt[e] = static_cast<int>(pts.size());
    pts.push_back(mean({h(e[0]), h(e[1]), face_pts[static_cast<std::size_t>(fl[0])], face_pts[static_cast<std::size_t>(fl[1])]}));
  }
  const int first_face_pt = static_cast<int>(pts.size());
  pts.insert(pts.end(), face_pts.begin(), face_pts.end());
  SubdividedCage out;
  for (const P4h& p : pts) {
    out.quads.points.push_back({p[0] / p[3], p[1] / p[3], p[2] / p[3]});
    out.weights.push_back(p[3]);
  }
  const auto ep = [&](int a, int b) { return edge_pt.at({std::min(a, b), std::max(a, b)}); };
  for (std::size_t f = 0; f < corners.size(); ++f)
    for (std::size_t k = 0; k < 4; ++k) {
      const auto& c = corners[f];
      out.quads.quads.push_back({c[k], ep(c[k], c[(k + 1) % 4]), first_face_pt + static_cast<int>(f), ep(c[(k + 3) % 4], c[k])});
    }
  return out;
}

void set_weights(TMesh& m, const std::vector<double>& w) {
  for (std::size_t v = 0; v < w.size(); ++v) m.points[static_cast<std::size_t>(m.vertices[v].primary)].w = w[v];
}

// The 1 x 1 cube's surface against the existing evaluation (Stam and bicubic patches, no local step) of the
// cube subdivided once here: each quarter of a face is the sub-face, values and derivatives (factor 2).
void expect_quarters_are_the_subdivided_cage(const std::vector<double>& weights, const char* name) {
  const Cage coarse(test::cube_mesh(1));
  TMesh cm = coarse.model.mesh;
  set_weights(cm, weights);
  const TMeshSurface s(cm);
  std::vector<std::array<int, 4>> corners;
  for (int f = 0; f < s.num_faces(); ++f) corners.push_back(s.corners(f));
  const SubdividedCage sub = subdivide_cage(coarse.quads, weights, corners);
  const Cage fine(sub.quads);
  TMesh fm = fine.model.mesh;
  set_weights(fm, sub.weights);
  const TMeshSurface t(fm);
  EXPECT_EQ(t.count(FaceMethod::subdivided), 0) << name;
  EXPECT_EQ(t.count(FaceMethod::star), 24) << name;
  double value = 0, derivative = 0, derivative_near = 0;  // derivatives away from / within 0.1 of the star point
  int points = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    for (int k = 0; k < 4; ++k) {
      const int g = 4 * f + k;
      // The sub-face's own frame: the corner at the coarse face's corner k, turning the same way.
      const auto gc = t.corners(g);
      const int r = static_cast<int>(std::find(gc.begin(), gc.end(), corners[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)]) - gc.begin());
      ASSERT_LT(r, 4);
      ASSERT_EQ(gc[static_cast<std::size_t>((r + 2) % 4)], sub.quads.quads[static_cast<std::size_t>(g)][2]);
      const CornerFrame cf = corner_frame(k), gf = corner_frame(r);
      for (double a : {0.0, 1e-7, 0.13, 0.5, 0.71, 1.0})
        for (double b : {0.0, 0.02, 0.38, 0.5, 0.9, 1.0}) {
          double x[9], y[9];
          s.eval(f, cf.origin[0] + (a * cf.a[0] + b * cf.b[0]) / 2, cf.origin[1] + (a * cf.a[1] + b * cf.b[1]) / 2, x);
          t.eval(g, gf.origin[0] + a * gf.a[0] + b * gf.b[0], gf.origin[1] + a * gf.a[1] + b * gf.b[1], y);
          ++points;
          for (int c = 0; c < 3; ++c) {
            value = std::max(value, std::abs(x[c] - y[c]));
            if (a == 0 && b == 0) continue;  // at the star point the derivatives are only directions
            // d/da and d/db: a half of the coarse face's derivatives along the frame, the sub-face's in full.
            const double da_coarse = (cf.a[0] * x[3 + c] + cf.a[1] * x[6 + c]) / 2, da_fine = gf.a[0] * y[3 + c] + gf.a[1] * y[6 + c];
            const double db_coarse = (cf.b[0] * x[3 + c] + cf.b[1] * x[6 + c]) / 2, db_fine = gf.b[0] * y[3 + c] + gf.b[1] * y[6 + c];
            double& d = std::max(a, b) < 0.1 ? derivative_near : derivative;
            d = std::max({d, std::abs(da_coarse - da_fine), std::abs(db_coarse - db_fine)});
          }
        }
    }
  std::printf("%s: 1 x 1 cube against the cage subdivided once at %d points: values %.2e, first derivatives %.2e "
              "(%.2e within 0.1 of the star point)\n", name, points, value, derivative, derivative_near);
  EXPECT_LT(value, 1e-12) << name;
  // Near the star point the derivatives carry the rounding of the subdivided points times 2^level (level 23 at
  // 1e-7): the same in both evaluations, not to the last bit.
  EXPECT_LT(derivative, 1e-14) << name;
  EXPECT_LT(derivative_near, 1e-11) << name;
}

TEST(SubdividedFaces, CubeIsItsCageSubdividedOnce) {
  expect_quarters_are_the_subdivided_cage(std::vector<double>(8, 1.0), "polynomial");
  // Rational Catmull-Clark: the rules act on (w x, w).
  expect_quarters_are_the_subdivided_cage({1.0, 0.7, 1.3, 2.0, 0.9, 1.1, 0.6, 1.5}, "rational");
}

TEST(SubdividedFaces, BezierPatchesOfTheQuarters) {
  const Cage c(test::turned_edge_cube());
  const TMeshSurface s(c.model.mesh);
  const TMeshPatches p = t_mesh_patches(s);
  int on_subdivided = 0;
  double worst = 0;
  std::vector<double> area(static_cast<std::size_t>(s.num_faces()), 0.0);
  for (const FacePatch& fp : p.patches) {
    area[static_cast<std::size_t>(fp.face)] += fp.piece.extent(0) * fp.piece.extent(1);
    if (s.method(fp.face) != FaceMethod::subdivided) continue;
    ++on_subdivided;
    EXPECT_LE(fp.piece.hi[0] - fp.piece.lo[0], 0.5 + 1e-15);
    if (!fp.exact) continue;
    for (double a : {0.0, 0.3, 1.0})
      for (double b : {0.0, 0.6, 1.0}) {
        const double u = fp.piece.lo[0] + a * fp.piece.extent(0), v = fp.piece.lo[1] + b * fp.piece.extent(1);
        double x[9];
        s.eval(fp.face, u, v, x);
        double y[3];
        fp.surface.eval({u, v}, y);
        worst = std::max(worst, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
      }
  }
  for (double a : area) EXPECT_NEAR(a, 1.0, 1e-12);
  std::printf("turned-edge cube: %zu patches (%d on subdivided faces, %d levels), exact patches off the surface by %.2e, "
              "corner patches by %.2e\n", p.patches.size(), on_subdivided, p.levels, worst, p.deviation);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LE(p.deviation, p.tolerance);
  // Every subdivided face has a star corner in each turned quad: more than 4 patches each.
  EXPECT_GT(on_subdivided, 16);
}

// Unequal intervals at faces with several star corners take local non-uniform subdivision, which needs one interval
// per strip: the cube with only two sides of one face longer is refused in one line.
TEST(SubdividedFaces, UnequalIntervalsOnOneStripAreRefused) {
  test::QuadMesh m = test::cube_mesh(1);
  m.intervals[{m.quads[0][0], m.quads[0][1]}] = 2.0;
  m.intervals[{m.quads[0][3], m.quads[0][2]}] = 2.0;
  const io::TsmModel model = io::parse_tsm(tsm_text(m), "cube.tsm");
  try {
    const TMeshSurface s(model.mesh);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("evaluated by local subdivision"), std::string::npos) << what;
    EXPECT_NE(what.find("on opposite sides; local subdivision takes one interval per strip"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace trivar
