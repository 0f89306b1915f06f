// Sharp creases inside a subdivision-crease T-mesh (Fusion's `ec` records between two faces with SUBD_CREASES),
// evaluated as infinitely sharp subdivision creases (sharp_creases): each side is the surface that side has with
// the crease as its open crease boundary. The references are built independently with TensorSpline: on regular
// grids the crease (and boundary) rule of Catmull-Clark is the uniform bicubic B-spline of the points extended by
// the ghost rows 2 P0 - P1 (Hoppe et al. 1994), corners the tensor product of the two ends; and at a crease
// vertex the crease curve is (P_prev + 4 P + P_next) / 6.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fusion_cages.hpp"
#include "triangulation_loops.hpp"
#include "knot_grid.hpp"
#include "osd_reference.hpp"
#include "star_mesh_tsm.hpp"
#include "support/temp_dir.hpp"
#include "trivar/iga/t_mesh_space.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/sharp_creases.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar::sharp_crease_test {
namespace {

using Point3 = std::array<double, 3>;
using GridPoint = std::function<Point3(int, int)>;

// The natural-end bicubic of the points P(i, j), i = 0 .. n, j = 0 .. m: the uniform B-spline on the knots
// -3 .. n + 3 of the grid extended by a ghost row 2 P0 - P1 beyond each end, first along j, then along i (the
// corners the tensor product). `periodic_j`: j runs round (m points, P(i, m) = P(i, 0)), no ghosts that way.
TensorSpline<2> natural_end_patch(const GridPoint& p, int n, int m, bool periodic_j) {
  const auto knots = [](int k) {
    std::vector<double> t;
    for (int i = -3; i <= k + 3; ++i) t.push_back(i);
    return KnotVector(3, t);
  };
  const auto along_j = [&](int i, int j) -> Point3 {
    if (periodic_j) return p(i, ((j % m) + m) % m);
    if (j < 0 || j > m) {
      const Point3 a = p(i, j < 0 ? 0 : m), b = p(i, j < 0 ? 1 : m - 1);
      return {2 * a[0] - b[0], 2 * a[1] - b[1], 2 * a[2] - b[2]};
    }
    return p(i, j);
  };
  std::vector<double> coefs;
  for (int j = -1; j <= m + 1; ++j)
    for (int i = -1; i <= n + 1; ++i) {
      Point3 x = along_j(i < 0 ? 0 : i > n ? n : i, j);
      if (i < 0 || i > n) {
        const Point3 b = along_j(i < 0 ? 1 : n - 1, j);
        x = {2 * x[0] - b[0], 2 * x[1] - b[1], 2 * x[2] - b[2]};
      }
      coefs.insert(coefs.end(), x.begin(), x.end());
    }
  return TensorSpline<2>({knots(n), knots(m)}, 3, false, coefs);
}

// One side of the creases: its reference and where the cage's vertices lie in its (s, t); `period`: the (s, t)
// distance at which a vertex's coordinates repeat (0: none), for cages that close.
struct Side {
  TensorSpline<2> spline;
  std::map<int, std::array<double, 2>> at;
  std::array<double, 2> period{0, 0};
};

int source_vertex(const TMeshSurface& s, int v) {
  const int from = s.mesh().vertices[static_cast<std::size_t>(v)].split_from;
  return from >= 0 ? from : v;
}

// The largest difference (value, d/du, d/dv) at 5 x 4 points per face between the surface and the side of each
// face: the face's corners 0, 1, 3 give its (u, v) in the side's (s, t).
double deviation(const TMeshSurface& s, const std::vector<int>& face_side, const std::vector<Side>& sides) {
  double worst = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const Side& side = sides[static_cast<std::size_t>(face_side[static_cast<std::size_t>(f)])];
    const std::array<int, 4> c = s.corners(f);
    const auto at = [&](int k) { return side.at.at(source_vertex(s, c[static_cast<std::size_t>(k)])); };
    const std::array<double, 2> g0 = at(0);
    std::array<std::array<double, 2>, 2> d{};
    for (int k = 0; k < 2; ++k) {
      const std::array<double, 2> g = at(k == 0 ? 1 : 3);
      for (int a = 0; a < 2; ++a) {
        double x = g[static_cast<std::size_t>(a)] - g0[static_cast<std::size_t>(a)];
        const double per = side.period[static_cast<std::size_t>(a)];
        if (per > 0 && std::abs(x) > 1.5) x -= std::copysign(per, x);
        d[static_cast<std::size_t>(k)][static_cast<std::size_t>(a)] = x;
      }
    }
    for (double u : {0.0, 0.21, 0.5, 0.83, 1.0})
      for (double v : {0.0, 0.37, 0.64, 1.0}) {
        double a[9], b[9];
        s.eval(f, u, v, a);
        std::array<double, 2> st{g0[0] + u * d[0][0] + v * d[1][0], g0[1] + u * d[0][1] + v * d[1][1]};
        if (side.period[1] > 0 && st[1] > side.period[1]) st[1] -= side.period[1];
        side.spline.eval_derivs({st[0], st[1]}, 1, b);
        for (int k = 0; k < 3; ++k) {
          worst = std::max(worst, std::abs(a[k] - b[k]));
          worst = std::max(worst, std::abs(a[3 + k] - (b[3 + k] * d[0][0] + b[6 + k] * d[0][1])));
          worst = std::max(worst, std::abs(a[6 + k] - (b[3 + k] * d[1][0] + b[6 + k] * d[1][1])));
        }
      }
  }
  return worst;
}

// The edges of a parsed cage whose end vertices satisfy `crease`, as `ec` records.
std::string ec_records(const TMesh& m, const std::function<bool(int, int)>& crease, int* count = nullptr) {
  std::set<int> edges;
  for (const TMeshLink& k : m.links)
    if (k.vertex >= 0 && crease(k.vertex, m.links[static_cast<std::size_t>(k.opp)].vertex)) edges.insert(k.edge);
  std::string out;
  for (int e : edges) out += "ec " + std::to_string(e) + " 0\n";
  if (count) *count = static_cast<int>(edges.size());
  return out;
}

// A Fusion cage with the edges `crease` picks marked as creases.
std::string creased_text(const test::QuadMesh& cage, const std::function<bool(int, int)>& crease, int* count = nullptr) {
  const TMesh plain = io::parse_tsm(test::fusion_text(cage), "plain.tsm").mesh;
  return test::fusion_text(cage, "SUBD_CREASES", 1.0, ec_records(plain, crease, count));
}

// The cube cage of n x n faces per side with every point moved off the cube, and each vertex's grid position.
struct Cube {
  test::QuadMesh cage;
  std::vector<std::array<int, 3>> grid;
};
Cube moved_cube(int n) {
  Cube c{test::cube_mesh(n), {}};
  for (auto& p : c.cage.points) {
    std::array<int, 3> g{};
    for (int a = 0; a < 3; ++a) g[static_cast<std::size_t>(a)] = static_cast<int>(std::lround((p[static_cast<std::size_t>(a)] + 1) * n / 2));
    c.grid.push_back(g);
    const Point3 q = p;
    p = {q[0] + 0.1 * std::sin(2 * q[1] + q[2]), q[1] + 0.07 * std::cos(q[0] - q[2]), q[2] * (1 + 0.05 * q[0] * q[1])};
  }
  return c;
}

// Whether the cube cage's vertices a and b lie on one edge of the cube (two grid coordinates shared at 0 or n).
bool on_cube_edge(const Cube& c, int n, int a, int b) {
  int shared = 0;
  for (int k = 0; k < 3; ++k) {
    const int x = c.grid[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)];
    if ((x == 0 || x == n) && x == c.grid[static_cast<std::size_t>(b)][static_cast<std::size_t>(k)]) ++shared;
  }
  return shared >= 2;
}

// A cube cage with all twelve cube edges creased falls into six open n x n patches, each the natural-end bicubic
// of its own points; the crease curve at a crease vertex is (P_prev + 4 P + P_next) / 6 and cube corners are
// interpolated. The triangulation is closed, of Euler characteristic 2.
TEST(SharpCrease, CubeWithCreasedEdgesIsSixNaturalEndPatches) {
  const int n = 3;
  const Cube cube = moved_cube(n);
  int count = 0;
  const io::TsmModel model = io::parse_tsm(creased_text(cube.cage, [&](int a, int b) { return on_cube_edge(cube, n, a, b); }, &count), "cube.tsm");
  EXPECT_EQ(count, 12 * n);
  EXPECT_EQ(model.report.crease_edges, 12 * n);
  EXPECT_EQ(model.report.star_points, 8);
  EXPECT_TRUE(model.spline.image.faces.empty());
  const TMeshSurface s(model.mesh, 1);
  EXPECT_TRUE(s.stars().empty());  // the cube's corners became the patches' corners
  EXPECT_EQ(crease_edges(s.source_mesh()).size(), static_cast<std::size_t>(12 * n));
  // The six sides in the order cube_mesh lists them (n x n faces each).
  std::vector<Side> sides;
  std::vector<int> face_side;
  for (int a = 0; a < 3; ++a)
    for (int level : {0, n}) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      std::map<std::array<int, 2>, int> id;
      for (std::size_t v = 0; v < cube.grid.size(); ++v)
        if (cube.grid[v][static_cast<std::size_t>(a)] == level) id[{cube.grid[v][static_cast<std::size_t>(b)], cube.grid[v][static_cast<std::size_t>(c)]}] = static_cast<int>(v);
      Side side{natural_end_patch([&](int i, int j) { return cube.cage.points[static_cast<std::size_t>(id.at({i, j}))]; }, n, n, false), {}};
      for (const auto& [g, v] : id) side.at[v] = {static_cast<double>(g[0]), static_cast<double>(g[1])};
      for (int f = 0; f < n * n; ++f) face_side.push_back(static_cast<int>(sides.size()));
      sides.push_back(std::move(side));
    }
  const double dev = deviation(s, face_side, sides);
  EXPECT_LT(dev, 1e-12);
  // At the crease vertices, from every face there: the crease rule along the cube edge, corners interpolated.
  double crease_rule = 0;
  int vertices_checked = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    for (int k = 0; k < 4; ++k) {
      const int v = source_vertex(s, s.corners(f)[static_cast<std::size_t>(k)]);
      std::vector<int> along;
      for (std::size_t w = 0; w < cube.grid.size(); ++w) {
        int diff = 0;
        for (int a = 0; a < 3; ++a) diff += std::abs(cube.grid[w][static_cast<std::size_t>(a)] - cube.grid[static_cast<std::size_t>(v)][static_cast<std::size_t>(a)]);
        if (diff == 1 && on_cube_edge(cube, n, v, static_cast<int>(w))) along.push_back(static_cast<int>(w));
      }
      if (along.empty()) continue;
      const Point3& p = cube.cage.points[static_cast<std::size_t>(v)];
      Point3 expect = p;
      if (along.size() == 2)
        for (int a = 0; a < 3; ++a)
          expect[static_cast<std::size_t>(a)] = (cube.cage.points[static_cast<std::size_t>(along[0])][static_cast<std::size_t>(a)] + 4 * p[static_cast<std::size_t>(a)] +
                                                 cube.cage.points[static_cast<std::size_t>(along[1])][static_cast<std::size_t>(a)]) / 6;
      double o[9];
      s.eval(f, k == 1 || k == 2 ? 1 : 0, k >= 2 ? 1 : 0, o);
      for (int a = 0; a < 3; ++a) crease_rule = std::max(crease_rule, std::abs(o[a] - expect[static_cast<std::size_t>(a)]));
      ++vertices_checked;
    }
  EXPECT_EQ(vertices_checked, 6 * (4 + 8 * 2));  // per side: its 4 corners in one face, 8 edge vertices in two
  EXPECT_LT(crease_rule, 1e-13);
  const TSplineTriangulation t = tessellate(s, 1e-3);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  std::printf("creased cube 3 x 3 per side: max deviation from the six natural-end patches %.2e, crease rule at %d face "
              "corners %.2e, %zu triangles closed\n", dev, vertices_checked, crease_rule, t.triangles.size());
}


// The grid cage's vertex (i, j) (grid_cage: j * (nx + 1) + i) and a side of it: the natural-end bicubic of the
// points i0 .. i1 x j0 .. j1, at (s, t) = (i - i0, j - j0).
Side grid_side(const test::QuadMesh& cage, int nx, int i0, int i1, int j0, int j1) {
  const auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  Side side{natural_end_patch([&](int i, int j) { return cage.points[static_cast<std::size_t>(id(i0 + i, j0 + j))]; }, i1 - i0, j1 - j0, false), {}};
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) side.at[id(i, j)] = {static_cast<double>(i - i0), static_cast<double>(j - j0)};
  return side;
}

// A crease along the grid line i = 4 of a 7 x 4 grid, boundary to boundary (points out of the plane): the two
// halves are the natural-end bicubics of their own points; across the crease the surface is C0, not C1.
TEST(SharpCrease, StraightCreaseSplitsAGridIntoTwoNaturalEndHalves) {
  const int nx = 7, ny = 4, c = 4;
  const test::QuadMesh cage = test::grid_cage(nx, ny);
  const auto i_of = [&](int v) { return v % (nx + 1); };
  int count = 0;
  const io::TsmModel model = io::parse_tsm(creased_text(cage, [&](int a, int b) { return i_of(a) == c && i_of(b) == c; }, &count), "grid.tsm");
  EXPECT_EQ(count, ny);
  EXPECT_EQ(model.report.crease_edges, ny);
  const TMeshSurface s(model.mesh, 1);
  std::vector<int> face_side;
  for (int f = 0; f < nx * ny; ++f) face_side.push_back(f % nx < c ? 0 : 1);
  const double dev = deviation(s, face_side, {grid_side(cage, nx, 0, c, 0, ny), grid_side(cage, nx, c, nx, 0, ny)});
  EXPECT_LT(dev, 1e-12);
  // Along the crease: the same points from both sides, the crease rule at its inner vertices, a kink across.
  double gap = 0, rule = 0, kink = 1e300;
  for (int j = 0; j < ny; ++j) {
    const int left = j * nx + c - 1, right = j * nx + c;
    for (double v : {0.0, 0.3, 0.5, 0.9, 1.0}) {
      double a[9], b[9];
      s.eval(left, 1, v, a);
      s.eval(right, 0, v, b);
      double jump = 0;
      for (int k = 0; k < 3; ++k) {
        gap = std::max(gap, std::abs(a[k] - b[k]));
        jump = std::max(jump, std::abs(a[3 + k] - b[3 + k]));
      }
      kink = std::min(kink, jump);
    }
    if (j == 0) continue;
    double a[9];
    s.eval(right, 0, 0, a);
    for (int k = 0; k < 3; ++k) {
      const auto p = [&](int jj) { return cage.points[static_cast<std::size_t>(jj * (nx + 1) + c)][static_cast<std::size_t>(k)]; };
      rule = std::max(rule, std::abs(a[k] - (p(j - 1) + 4 * p(j) + p(j + 1)) / 6));
    }
  }
  EXPECT_LT(gap, 1e-13);
  EXPECT_LT(rule, 1e-13);
  EXPECT_GT(kink, 1e-2);
  // The tessellation shares the crease's points: an open grid, one boundary loop (Euler characteristic 1).
  const TSplineTriangulation t = tessellate(s, 1e-3);
  std::map<std::array<int, 2>, int> edges;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = tri[static_cast<std::size_t>(k)], b = tri[static_cast<std::size_t>((k + 1) % 3)];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  EXPECT_EQ(static_cast<long>(t.points.size()) - static_cast<long>(edges.size()) + static_cast<long>(t.triangles.size()), 1);
  std::printf("grid 7 x 4 with a straight crease: max deviation from the two natural-end halves %.2e, gap along the crease "
              "%.2e, crease rule %.2e, smallest jump of d/du across %.2f\n", dev, gap, rule, kink);
}

// Two creases crossing (the grid lines i = 3 and j = 2 of a 6 x 4 grid): the crossing vertex has four crease
// edges and the creases' ends on the boundary three sharp edges; each is a corner of every side, the four
// quarters natural-end bicubics of their points.
TEST(SharpCrease, CrossingCreasesMakeFourCornerPatches) {
  const int nx = 6, ny = 4, ci = 3, cj = 2;
  const test::QuadMesh cage = test::grid_cage(nx, ny);
  const auto i_of = [&](int v) { return v % (nx + 1); };
  const auto j_of = [&](int v) { return v / (nx + 1); };
  const io::TsmModel model = io::parse_tsm(
      creased_text(cage, [&](int a, int b) { return (i_of(a) == ci && i_of(b) == ci) || (j_of(a) == cj && j_of(b) == cj); }), "cross.tsm");
  EXPECT_EQ(model.report.crease_edges, nx + ny);
  const TMeshSurface s(model.mesh, 1);
  std::vector<int> face_side;
  for (int f = 0; f < nx * ny; ++f) face_side.push_back((f % nx < ci ? 0 : 1) + (f / nx < cj ? 0 : 2));
  const double dev = deviation(s, face_side,
                               {grid_side(cage, nx, 0, ci, 0, cj), grid_side(cage, nx, ci, nx, 0, cj), grid_side(cage, nx, 0, ci, cj, ny),
                                grid_side(cage, nx, ci, nx, cj, ny)});
  EXPECT_LT(dev, 1e-12);
  // The crossing is interpolated from all four faces there.
  double corner = 0;
  for (const auto& [f, uv] : std::vector<std::pair<int, std::array<double, 2>>>{
           {(cj - 1) * nx + ci - 1, {1, 1}}, {(cj - 1) * nx + ci, {0, 1}}, {cj * nx + ci - 1, {1, 0}}, {cj * nx + ci, {0, 0}}}) {
    double o[9];
    s.eval(f, uv[0], uv[1], o);
    for (int k = 0; k < 3; ++k) corner = std::max(corner, std::abs(o[k] - cage.points[static_cast<std::size_t>(cj * (nx + 1) + ci)][static_cast<std::size_t>(k)]));
  }
  EXPECT_LT(corner, 1e-14);
  std::printf("grid 6 x 4 with two crossing creases: max deviation from the four natural-end quarters %.2e, crossing "
              "interpolated to %.2e\n", dev, corner);
}

// A closed crease loop round the tube of a torus cage (12 x 8 faces): the torus opens into a tube whose ends are
// the crease, the natural-end bicubic along the torus and periodic round the tube; its triangulation stays a
// closed torus (Euler characteristic 0).
TEST(SharpCrease, CreaseLoopRoundATorus) {
  const int nu = 12, nv = 8;
  const test::QuadMesh cage = test::torus_cage(nu, nv);
  const io::TsmModel model = io::parse_tsm(creased_text(cage, [&](int a, int b) { return a / nv == 0 && b / nv == 0; }), "torus.tsm");
  EXPECT_EQ(model.report.crease_edges, nv);
  const TMeshSurface s(model.mesh, 1);
  Side tube{natural_end_patch([&](int i, int j) { return cage.points[static_cast<std::size_t>((i % nu) * nv + j)]; }, nu, nv, true), {}, {nu, nv}};
  for (int v = 0; v < nu * nv; ++v) tube.at[v] = {static_cast<double>(v / nv), static_cast<double>(v % nv)};
  const double dev = deviation(s, std::vector<int>(static_cast<std::size_t>(nu * nv), 0), {tube});
  EXPECT_LT(dev, 1e-11);
  const TSplineTriangulation t = tessellate(s, 5e-2);
  EXPECT_EQ(test::closed_euler_characteristic(t), 0);
  std::printf("torus 12 x 8 with a crease loop: max deviation from the natural-end x periodic bicubic %.2e, %zu triangles "
              "closed\n", dev, t.triangles.size());
}

// Unequal knot intervals, across and along the crease: each side is that side alone as a crease-boundary mesh
// (crease_ends_test.cpp checks those against the natural-end B-spline), and both give one crease curve.
TEST(SharpCrease, UnequalIntervalsEachSideIsThatSideAlone) {
  const std::vector<double> s{0, 0.7, 1.9, 2.4, 3.6, 4.1, 5.5}, t{0, 1.2, 1.7, 3.0, 3.4};
  const int c = 3, ns = static_cast<int>(s.size()) - 1, nt = static_cast<int>(t.size()) - 1;
  const test::Grid full = test::grid(s, t);
  TMesh m = test::crease_mesh(full.quads);
  const auto column = [&](int v) { return v % (ns + 1); };
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const TMeshLink& k = m.links[l];
    if (static_cast<int>(l) < k.opp && column(k.vertex) == c && column(m.links[static_cast<std::size_t>(k.opp)].vertex) == c &&
        k.face >= 0 && m.links[static_cast<std::size_t>(k.opp)].face >= 0)
      m.conditions.push_back({k.edge, 1});
  }
  ASSERT_EQ(crease_edges(m).size(), static_cast<std::size_t>(nt));
  const TMeshSurface whole(m, 1);
  const TMeshSurface left(test::crease_mesh(test::grid({s.begin(), s.begin() + c + 1}, t).quads), 1);
  const TMeshSurface right(test::crease_mesh(test::grid({s.begin() + c, s.end()}, t).quads), 1);
  double dev = 0, gap = 0;
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < ns; ++i)
      for (double u : {0.0, 0.4, 1.0})
        for (double v : {0.0, 0.55, 1.0}) {
          double a[9], b[9];
          whole.eval(j * ns + i, u, v, a);
          if (i < c) left.eval(j * c + i, u, v, b);
          else right.eval(j * (ns - c) + i - c, u, v, b);
          for (int d = 0; d < 9; ++d) dev = std::max(dev, std::abs(a[d] - b[d]));
          if (i == c && u == 0) {
            whole.eval(j * ns + i - 1, 1, v, b);
            for (int d = 0; d < 3; ++d) gap = std::max(gap, std::abs(a[d] - b[d]));
          }
        }
  EXPECT_LT(dev, 1e-12);
  EXPECT_LT(gap, 1e-13);
  std::printf("grid 6 x 4 with unequal intervals and a crease: max deviation from its sides alone %.2e, gap along the "
              "crease %.2e\n", dev, gap);
}

// OpenSubdiv's limit surface of the cage with the crease edges infinitely sharp (and its boundary a crease with
// sharp corners, as SUBD_CREASES): the largest difference (value, d/du, d/dv) at 5 x 5 points per face (Bfr's
// quadrilateral parametrisation is the face's (u, v)), leaving out face corners at vertices of three or five and
// more faces, where Bfr approximates within 2^-level of the vertex.
double osd_deviation(const TMeshSurface& s, const test::QuadMesh& cage, const std::function<bool(int, int)>& crease) {
  test::PolyMesh poly;
  poly.points = cage.points;
  std::vector<int> faces_at(cage.points.size(), 0);
  std::set<std::array<int, 2>> sharp;
  for (const auto& q : cage.quads) {
    poly.faces.push_back({q.begin(), q.end()});
    for (int k = 0; k < 4; ++k) {
      const int a = q[static_cast<std::size_t>(k)], b = q[static_cast<std::size_t>((k + 1) % 4)];
      ++faces_at[static_cast<std::size_t>(a)];
      if (crease(a, b)) sharp.insert({std::min(a, b), std::max(a, b)});
    }
  }
  poly.sharp_edges.assign(sharp.begin(), sharp.end());
  const test::OsdLimitSurface ref(poly);
  double worst = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    for (double u : {0.0, 0.25, 0.5, 0.75, 1.0})
      for (double v : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        if ((u == 0 || u == 1) && (v == 0 || v == 1)) {
          const int corner = u == 0 ? (v == 0 ? 0 : 3) : (v == 0 ? 1 : 2);
          const int n = faces_at[static_cast<std::size_t>(cage.quads[static_cast<std::size_t>(f)][static_cast<std::size_t>(corner)])];
          if (n == 3 || n >= 5) continue;
        }
        double a[9];
        s.eval(f, u, v, a);
        const test::LimitSample b = ref.eval(f, u, v);
        for (int k = 0; k < 3; ++k) {
          const auto ku = static_cast<std::size_t>(k);
          worst = std::max({worst, std::abs(a[k] - b.p[ku]), std::abs(a[3 + k] - b.du[ku]), std::abs(a[6 + k] - b.dv[ku])});
        }
      }
  return worst;
}

// The creased cages above against OpenSubdiv's infinitely sharp creases.
TEST(SharpCrease, OpenSubdivInfinitelySharpCreases) {
  const Cube cube = moved_cube(3);
  const auto cube_edges = [&](int a, int b) { return on_cube_edge(cube, 3, a, b); };
  const double d_cube = osd_deviation(TMeshSurface(io::parse_tsm(creased_text(cube.cage, cube_edges), "c.tsm").mesh, 1), cube.cage, cube_edges);
  const test::QuadMesh grid = test::grid_cage(7, 4);
  const auto column = [](int a, int b) { return a % 8 == 4 && b % 8 == 4; };
  const double d_grid = osd_deviation(TMeshSurface(io::parse_tsm(creased_text(grid, column), "g.tsm").mesh, 1), grid, column);
  const test::QuadMesh cross = test::grid_cage(6, 4);
  const auto crossing = [](int a, int b) { return (a % 7 == 3 && b % 7 == 3) || (a / 7 == 2 && b / 7 == 2); };
  const double d_cross = osd_deviation(TMeshSurface(io::parse_tsm(creased_text(cross, crossing), "x.tsm").mesh, 1), cross, crossing);
  const test::QuadMesh torus = test::torus_cage(12, 8);
  const auto loop = [](int a, int b) { return a / 8 == 0 && b / 8 == 0; };
  const double d_torus = osd_deviation(TMeshSurface(io::parse_tsm(creased_text(torus, loop), "t.tsm").mesh, 1), torus, loop);
  EXPECT_LT(d_cube, 1e-12);
  EXPECT_LT(d_grid, 1e-12);
  EXPECT_LT(d_cross, 1e-12);
  EXPECT_LT(d_torus, 1e-11);
  std::printf("against OpenSubdiv's infinitely sharp creases (value, d/du, d/dv): creased cube %.2e, grid with a crease "
              "%.2e, crossing creases %.2e, torus crease loop %.2e\n", d_cube, d_grid, d_cross, d_torus);
}

// A crease loop round a cube cage of 14 x 14 faces per side, half way between its star points (7 faces from them):
// each half is an open box with four valence-3 star points, evaluated with Stam's patches, against OpenSubdiv. At
// 6 faces (a cage of 12) the star points' faces are too close to the crease for those and are evaluated by local
// subdivision (crease_face).
TEST(SharpCrease, CreaseLoopBetweenStarPoints) {
  for (int n : {12, 14}) {
    const Cube cube = moved_cube(n);
    const auto meridian = [&](int a, int b) { return cube.grid[static_cast<std::size_t>(a)][0] == n / 2 && cube.grid[static_cast<std::size_t>(b)][0] == n / 2; };
    const io::TsmModel model = io::parse_tsm(creased_text(cube.cage, meridian), "m.tsm");
    EXPECT_EQ(model.report.crease_edges, 4 * n);
    const TMeshSurface s(model.mesh, 1);
    EXPECT_EQ(s.stars().size(), 8u);
    EXPECT_EQ(s.count(FaceMethod::star), 24);
    EXPECT_EQ(s.count(FaceMethod::crease) > 0, n == 12);
    const double dev = osd_deviation(s, cube.cage, meridian);
    EXPECT_LT(dev, 1e-12);
    std::printf("cube %d x %d per side with a crease loop between its star points: %d faces exact, %d bicubic, %d at star "
                "points, %d by local subdivision; against OpenSubdiv %.2e\n", n, n, s.count(FaceMethod::exact), s.count(FaceMethod::bicubic),
                s.count(FaceMethod::star), s.count(FaceMethod::crease), dev);
  }
}

// The analysis space of the creased cube (iga/t_mesh_space): the patches' sides along a crease are identified by
// their control points (both sides carry the crease curve), so the C0 space is closed and counts as the cube's
// without creases: 9 functions inside each face, 3 inside each edge, one per vertex for 2 x 2 elements per face.
TEST(SharpCrease, AnalysisSpaceIsConformingAcrossTheCreases) {
  const Cube cube = moved_cube(3);
  const TMeshSurface s(io::parse_tsm(creased_text(cube.cage, [&](int a, int b) { return on_cube_edge(cube, 3, a, b); }), "c.tsm").mesh, 1);
  TMeshSpaceReport rep;
  const TMeshSurfaceSpace space = t_mesh_surface_space(s, 2, &rep);
  EXPECT_EQ(rep.faces, 54);
  EXPECT_EQ(rep.corner_patches, 0);
  EXPECT_TRUE(space.space.boundary.empty());
  EXPECT_EQ(space.space.num_basis, 9 * 54 + 3 * 108 + 56);
}

// A Rhino file keeps its edge conditions between faces as they were (no crease rule: the global T-spline).
TEST(SharpCrease, RhinoEdgeConditionsStayConditions) {
  const test::QuadMesh grid = test::grid_cage(3, 3);
  std::string text = test::tsm_text(grid);
  const TMesh plain = io::parse_tsm(text, "r.tsm").mesh;
  const std::string ec = ec_records(plain, [](int a, int b) { return a % 4 == 1 && b % 4 == 1; });
  text.insert(text.find("\ntol "), "\n" + ec);
  const io::TsmModel m = io::parse_tsm(text, "r.tsm");
  EXPECT_EQ(m.mesh.conditions.size(), 12u + 3u);  // tsm_text's on the boundary, and three inside
  EXPECT_EQ(m.report.crease_edges, 0);
  EXPECT_FALSE(m.spline.image.faces.empty());
  EXPECT_TRUE(crease_edges(m.mesh).empty());
}

// Read, written back from source_mesh (as convert does), read again: the ec records and the surface bit for bit.
TEST(SharpCrease, ReadWriteReadKeepsTheCreases) {
  const Cube cube = moved_cube(3);
  const std::string text = creased_text(cube.cage, [&](int a, int b) { return on_cube_edge(cube, 3, a, b); });
  const io::TsmModel a = io::parse_tsm(text, "a.tsm");
  const TMeshSurface sa(a.mesh, 1);
  std::ostringstream os;
  io::write_tsm(os, sa.source_mesh(), a.report);
  const io::TsmModel b = io::parse_tsm(os.str(), "b.tsm");
  EXPECT_EQ(b.mesh.conditions, a.mesh.conditions);
  EXPECT_EQ(b.report.crease_edges, 36);
  const TMeshSurface sb(b.mesh, 1);
  ASSERT_EQ(sb.num_faces(), sa.num_faces());
  for (int f = 0; f < sa.num_faces(); ++f)
    for (double u : {0.0, 0.3, 1.0})
      for (double v : {0.0, 0.8}) {
        double x[9], y[9];
        sa.eval(f, u, v, x);
        sb.eval(f, u, v, y);
        for (int d = 0; d < 9; ++d) EXPECT_EQ(x[d], y[d]);
      }
}

// The command line: info counts the crease edges, convert writes a closed triangle mesh, STEP patches and the TSM
// back.
TEST(SharpCrease, CommandLine) {
  const test::TempDir dir;
  const std::string box = dir.file("box.tsm");
  const Cube cube = moved_cube(3);
  std::ofstream(box) << creased_text(cube.cage, [&](int a, int b) { return on_cube_edge(cube, 3, a, b); });
  const auto run = [&](const std::string& args) { return test::run_cli(dir, args); };
  const std::string info = run("info " + box);
  EXPECT_NE(info.find("T-spline surface with sharp creases"), std::string::npos) << info;
  EXPECT_NE(info.find("54 faces, 36 sharp crease edges"), std::string::npos) << info;
  EXPECT_NE(run("info " + box + " --json").find("\"crease_edges\": 36"), std::string::npos);
  run("convert " + box + " " + dir.file("t.obj"));
  EXPECT_EQ(test::closed_euler_characteristic(test::obj_triangles(dir.file("t.obj"))), 2);
  EXPECT_NE(run("convert " + box + " " + dir.file("box.stp")).find("54 Bezier patches (54 exact"), std::string::npos);
  run("convert " + box + " " + dir.file("back.tsm"));
  EXPECT_EQ(io::read_tsm(dir.file("back.tsm")).report.crease_edges, 36);
}

}  // namespace
}  // namespace trivar::sharp_crease_test
