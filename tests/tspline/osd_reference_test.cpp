// The OpenSubdiv reference (osd_reference) against closed forms, before it is trusted as a reference for trivar:
// a regular grid is the uniform bicubic B-spline of its points (inside) and of its points extended by the natural
// ghost rows 2 P0 - P1 (at the boundary, with sharp corners), a chain of sharp edges is the cubic B-spline of its
// vertices, the limit point of an interior vertex of valence n is the Catmull-Clark limit mask, and the face
// parametrisations of quadrilaterals and N-gons are as documented.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "osd_reference.hpp"
#include "star_mesh_tsm.hpp"

namespace trivar::osd_reference_test {

using P3 = std::array<double, 3>;
using test::LimitSample;
using test::OsdLimitSurface;
using test::PolyMesh;

double gap(const P3& a, const P3& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

// The uniform cubic B-spline basis on [0, 1] and its derivative (the closed form, node-centred: B_k has its
// knots at k - 3 .. k + 1 relative to the interval's start).
std::array<double, 4> bspline_basis(double t) {
  const double s = 1 - t;
  return {s * s * s / 6, (3 * t * t * t - 6 * t * t + 4) / 6, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
}
std::array<double, 4> bspline_derivative(double t) {
  return {-(1 - t) * (1 - t) / 2, (3 * t * t - 4 * t) / 2, (-3 * t * t + 2 * t + 1) / 2, t * t / 2};
}

// The bicubic patch of 4 x 4 points p(i, j) (i along u) at (u, v): value, d/du, d/dv.
template <class Points>
LimitSample bicubic(const Points& p, double u, double v) {
  const auto bu = bspline_basis(u), bv = bspline_basis(v), du = bspline_derivative(u), dv = bspline_derivative(v);
  LimitSample s;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const P3 x = p(i, j);
      for (int k = 0; k < 3; ++k) {
        s.p[k] += bu[i] * bv[j] * x[k];
        s.du[k] += du[i] * bv[j] * x[k];
        s.dv[k] += bu[i] * dv[j] * x[k];
      }
    }
  return s;
}

// A grid of nx x ny faces with random heights over a sheared lattice.
struct GridMesh {
  int nx, ny;
  PolyMesh mesh;
  int id(int i, int j) const { return i + j * (nx + 1); }
};
GridMesh grid_mesh(int nx, int ny, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> d(-0.3, 0.3);
  GridMesh m{nx, ny, {}};
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.mesh.points.push_back({i + 0.2 * j + 0.5 * d(g), j + 0.5 * d(g), d(g)});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) m.mesh.faces.push_back({m.id(i, j), m.id(i + 1, j), m.id(i + 1, j + 1), m.id(i, j + 1)});
  return m;
}

TEST(OsdReference, RegularGridIsTheUniformBicubicBSpline) {
  const GridMesh g = grid_mesh(6, 5, 3);
  const OsdLimitSurface osd(g.mesh);
  // The point of lattice index (i, j), extended beyond the grid by the natural ghost rows 2 P0 - P1 (the corner
  // ghost is then 4 P00 - 2 P10 - 2 P01 + P11): the surface of infinitely sharp boundary edges and corners.
  const auto point = [&](int i, int j) {
    const auto axis = [](int k, int n) -> std::array<std::array<double, 2>, 2> {  // (index, weight) pairs
      if (k < 0) return {{{0, 2}, {1, -1}}};
      if (k > n) return {{{double(n), 2}, {double(n - 1), -1}}};
      return {{{double(k), 1}, {double(k), 0}}};
    };
    P3 x{};
    for (const auto& a : axis(i, g.nx))
      for (const auto& b : axis(j, g.ny))
        for (int k = 0; k < 3; ++k) x[k] += a[1] * b[1] * g.mesh.points[static_cast<std::size_t>(g.id(int(a[0]), int(b[0])))][k];
    return x;
  };
  double worst_inner = 0, worst_boundary = 0;
  for (int fj = 0; fj < g.ny; ++fj)
    for (int fi = 0; fi < g.nx; ++fi)
      for (double u : {0.0, 0.3, 0.71, 1.0})
        for (double v : {0.0, 0.45, 0.9}) {
          const LimitSample a = osd.eval(fi + fj * g.nx, u, v);
          const LimitSample b = bicubic([&](int i, int j) { return point(fi - 1 + i, fj - 1 + j); }, u, v);
          const double d = std::max({gap(a.p, b.p), gap(a.du, b.du), gap(a.dv, b.dv)});
          const bool inner = fi > 0 && fj > 0 && fi + 1 < g.nx && fj + 1 < g.ny;
          (inner ? worst_inner : worst_boundary) = std::max(inner ? worst_inner : worst_boundary, d);
        }
  EXPECT_LT(worst_inner, 1e-13);
  EXPECT_LT(worst_boundary, 1e-13);
}

TEST(OsdReference, SharpEdgeChainIsTheCubicBSplineOfItsVertices) {
  // A chain of infinitely sharp edges across a grid along row 2: on both sides its limit curve is the uniform
  // cubic B-spline of the chain's vertices (the crease rules (1, 6, 1) / 8 and midpoints), whatever the rows off it.
  GridMesh g = grid_mesh(6, 5, 5);
  for (int i = 0; i < g.nx; ++i) g.mesh.sharp_edges.push_back({g.id(i, 2), g.id(i + 1, 2)});
  const OsdLimitSurface osd(g.mesh);
  const OsdLimitSurface smooth(grid_mesh(6, 5, 5).mesh);
  double worst = 0, off = 0;
  for (int i = 1; i + 1 < g.nx; ++i)
    for (double t : {0.0, 0.35, 0.8}) {
      const auto w = bspline_basis(t);
      P3 x{};
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) x[c] += w[k] * g.mesh.points[static_cast<std::size_t>(g.id(i - 1 + k, 2))][c];
      for (const auto& [face, v] : {std::pair{i + 1 * g.nx, 1.0}, std::pair{i + 2 * g.nx, 0.0}}) {
        worst = std::max(worst, gap(osd.eval(face, t, v).p, x));
        off = std::max(off, gap(smooth.eval(face, t, v).p, x));
      }
    }
  EXPECT_LT(worst, 1e-14);
  EXPECT_GT(off, 1e-3);  // without the crease the rows beside it pull the surface off the curve
}

TEST(OsdReference, LimitPointOfAnInteriorVertexIsTheCatmullClarkMask) {
  for (int n : {3, 4, 5, 6, 8}) {
    std::mt19937 g(static_cast<unsigned>(n));
    std::uniform_real_distribution<double> d(-0.2, 0.2);
    const test::QuadMesh q = test::fan_mesh(n, 2, [&](double, double) { return d(g); });
    PolyMesh mesh;
    mesh.points = q.points;
    for (auto& p : mesh.points) p[0] += d(g);
    for (const auto& f : q.quads) mesh.faces.push_back({f.begin(), f.end()});
    const int star = 0;  // fan_mesh's first vertex
    // (n^2 P + 4 sum E_i + sum F_i) / (n (n + 5)): each face at the star point gives the next edge neighbour
    // E and the diagonal neighbour F.
    P3 mask{};
    int faces = 0;
    for (const auto& f : q.quads)
      for (int c = 0; c < 4; ++c)
        if (f[c] == star) {
          ++faces;
          for (int k = 0; k < 3; ++k)
            mask[k] += 4 * mesh.points[static_cast<std::size_t>(f[(c + 1) % 4])][k] + mesh.points[static_cast<std::size_t>(f[(c + 2) % 4])][k];
        }
    ASSERT_EQ(faces, n);
    for (int k = 0; k < 3; ++k) mask[k] = (mask[k] + n * n * mesh.points[star][k]) / (n * (n + 5));

    const OsdLimitSurface osd(mesh);
    const LimitSample limit = osd.vertex_limits()[star];
    EXPECT_LT(gap(limit.p, mask), 1e-15) << n;
    const P3 normal{limit.du[1] * limit.dv[2] - limit.du[2] * limit.dv[1], limit.du[2] * limit.dv[0] - limit.du[0] * limit.dv[2],
                    limit.du[0] * limit.dv[1] - limit.du[1] * limit.dv[0]};
    // Every face's patch starts at the limit point with its tangents in the limit tangent plane, to Bfr's
    // approximation at the extraordinary vertex (documented in osd_reference.hpp; none at valence 4).
    for (int f = 0; f < static_cast<int>(q.quads.size()); ++f) {
      const int c = static_cast<int>(std::find(q.quads[f].begin(), q.quads[f].end(), star) - q.quads[f].begin());
      if (c == 4) continue;
      const std::array<std::array<double, 2>, 4> corner{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
      const LimitSample s = osd.eval(f, corner[c][0], corner[c][1]);
      EXPECT_LT(gap(s.p, mask), 1e-14) << n << ' ' << f;
      for (const P3& t : {s.du, s.dv}) {
        const double dot = normal[0] * t[0] + normal[1] * t[1] + normal[2] * t[2];
        EXPECT_LT(std::abs(dot), (n == 3 ? 2e-6 : 1e-9) * gap(normal, {}) * gap(t, {})) << n << ' ' << f;
      }
    }
  }
}

TEST(OsdReference, FaceParametrisationOfQuadsAndNGons) {
  // A quadrilateral grid with two faces merged into a hexagon and one split into two triangles (its vertices
  // then of valence 3 and 5).
  GridMesh g = grid_mesh(6, 6, 11);
  PolyMesh& m = g.mesh;
  const auto face = [&](int i, int j) { return i + j * g.nx; };
  m.faces[static_cast<std::size_t>(face(2, 2))] = {g.id(2, 2), g.id(3, 2), g.id(4, 2), g.id(4, 3), g.id(3, 3), g.id(2, 3)};
  m.faces[static_cast<std::size_t>(face(3, 2))] = {g.id(3, 4), g.id(4, 4), g.id(3, 5)};
  m.faces[static_cast<std::size_t>(face(3, 4))] = {g.id(4, 4), g.id(4, 5), g.id(3, 5)};
  const OsdLimitSurface osd(m);
  const auto limits = osd.vertex_limits();
  for (int f : {face(2, 2), face(3, 2), face(3, 4)}) {
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    const int n = static_cast<int>(loop.size());
    for (int c = 0; c < n; ++c) {
      EXPECT_LT(gap(osd.eval_ngon_corner(f, c, 0, 0).p, limits[static_cast<std::size_t>(loop[c])].p), 1e-13) << f << ' ' << c;
      // s runs to the midpoint of the edge to the next corner, where the next sub-face's t ends.
      EXPECT_LT(gap(osd.eval_ngon_corner(f, c, 1, 0).p, osd.eval_ngon_corner(f, (c + 1) % n, 0, 1).p), 1e-13) << f << ' ' << c;
      EXPECT_GT(gap(osd.eval_ngon_corner(f, c, 1, 0).p, osd.eval_ngon_corner(f, (c + n - 1) % n, 1, 0).p), 1e-3) << f << ' ' << c;
    }
  }
  // A quadrilateral's corners in the order of its loop: (0, 0), (1, 0), (1, 1), (0, 1), also next to the hexagon.
  const std::array<std::array<double, 2>, 4> corner{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  for (int f : {face(1, 1), face(2, 3), face(4, 2)})
    for (int c = 0; c < 4; ++c)
      EXPECT_LT(gap(osd.eval(f, corner[c][0], corner[c][1]).p, limits[static_cast<std::size_t>(m.faces[static_cast<std::size_t>(f)][c])].p), 1e-13) << f << ' ' << c;
}

}  // namespace trivar::osd_reference_test
