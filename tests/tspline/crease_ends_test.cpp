// T-mesh boundaries as subdivision creases (EndConditions::subd_creases), evaluated through their Bezier end
// conditions (crease_ends). Known answers, built independently with TensorSpline: on a regular grid the surface is
// the uniform bicubic B-spline of the control points extended by the natural ghost rows 2 P0 - P1 (corner ghosts
// 4 P00 - 2 P10 - 2 P01 + P11), polynomial and rational; with unequal knot intervals whose first two at each end are
// equal it is the B-spline on the unclamped knots with ghost intervals equal to the first; with any intervals the
// second derivative across the boundary vanishes (four values of the cubic across the first face), the boundary
// curve interpolates the corners and the faces two rings in are the B-spline of the points. A star point and a
// T-junction keep those references on the faces they do not reach, the tessellation is watertight, and a mesh
// with Bezier end conditions is left as it is.
#include <gtest/gtest.h>

#include <map>
#include <numbers>
#include <random>
#include <string>

#include "face_continuity.hpp"
#include "knot_grid.hpp"
#include "star_mesh_tsm.hpp"
#include "triangulation_loops.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/crease_ends.hpp"
#include "trivar/tspline/sharp_creases.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar::crease_ends_test {

using test::crease_mesh;
using test::Grid;
using test::grid;
using test::wave;

std::vector<double> uniform(int n, double d) {
  std::vector<double> k;
  for (int i = 0; i <= n; ++i) k.push_back(i * d);
  return k;
}

// Knots of the B-spline of nodes at x[0..n] and one ghost node beyond each end, node-centred (node i has the knots
// x[i - 2 .. i + 2]), the missing knots beyond the ends spaced as the first and last intervals.
KnotVector ghost_knots(const std::vector<double>& x) {
  const double a = x[1] - x[0], b = x[x.size() - 1] - x[x.size() - 2];
  std::vector<double> k{x[0] - 3 * a, x[0] - 2 * a, x[0] - a};
  k.insert(k.end(), x.begin(), x.end());
  for (int i = 1; i <= 3; ++i) k.push_back(x.back() + i * b);
  return KnotVector(3, k);
}

// The natural-end tensor B-spline of a grid of homogeneous points (rows of ns): ghost rows 2 P0 - P1 in both
// directions (the corner ghost is then 4 P00 - 2 P10 - 2 P01 + P11), on ghost_knots.
SplineSurface natural_reference(const std::vector<double>& s, const std::vector<double>& t, const std::vector<std::array<double, 4>>& h) {
  const int ns = static_cast<int>(s.size()), nt = static_cast<int>(t.size());
  const auto ghost_index = [](int i, int n) -> std::array<int, 2> {  // extended index -> (index, index reflected through)
    if (i < 0) return {0, 1};
    if (i >= n) return {n - 1, n - 2};
    return {i, -1};
  };
  std::vector<double> coefs;
  for (int j = -1; j <= nt; ++j)
    for (int i = -1; i <= ns; ++i) {
      const auto gi = ghost_index(i, ns), gj = ghost_index(j, nt);
      std::array<double, 4> c{};
      // The product of the 1-D rules: (2, -1) on the ghost side, 1 inside.
      for (int a = 0; a < (gi[1] < 0 ? 1 : 2); ++a)
        for (int b = 0; b < (gj[1] < 0 ? 1 : 2); ++b) {
          const double w = (gi[1] < 0 ? 1.0 : (a == 0 ? 2.0 : -1.0)) * (gj[1] < 0 ? 1.0 : (b == 0 ? 2.0 : -1.0));
          const auto& p = h[static_cast<std::size_t>(gi[static_cast<std::size_t>(a)] + ns * gj[static_cast<std::size_t>(b)])];
          for (std::size_t k = 0; k < 4; ++k) c[k] += w * p[k];
        }
      coefs.insert(coefs.end(), c.begin(), c.end());
    }
  return SplineSurface({ghost_knots(s), ghost_knots(t)}, 3, true, coefs);
}

std::vector<std::array<double, 4>> homogeneous_points(const TMesh& m, int count) {
  std::vector<std::array<double, 4>> h;
  for (int v = 0; v < count; ++v) {
    const RationalPoint& p = m.points[static_cast<std::size_t>(m.vertices[static_cast<std::size_t>(v)].primary)];
    h.push_back({p.w * p.xyz[0], p.w * p.xyz[1], p.w * p.xyz[2], p.w});
  }
  return h;
}

// The surface at the parameter (x, y) of the mesh's layout: the face whose corners' parameters hold it, in its
// own (u, v). param: per vertex its (s, t).
struct Located {
  int face = -1;
  double u = 0, v = 0;
};
Located locate(const TMeshSurface& s, const std::vector<std::array<double, 2>>& param, double x, double y) {
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) == FaceMethod::none) continue;
    const auto c = s.corners(f);
    const auto& p0 = param[static_cast<std::size_t>(c[0])];
    const auto& p1 = param[static_cast<std::size_t>(c[1])];
    const auto& p3 = param[static_cast<std::size_t>(c[3])];
    const std::array<double, 2> a{p1[0] - p0[0], p1[1] - p0[1]}, b{p3[0] - p0[0], p3[1] - p0[1]};
    const double u = ((x - p0[0]) * a[0] + (y - p0[1]) * a[1]) / (a[0] * a[0] + a[1] * a[1]);
    const double v = ((x - p0[0]) * b[0] + (y - p0[1]) * b[1]) / (b[0] * b[0] + b[1] * b[1]);
    if (u >= -1e-12 && u <= 1 + 1e-12 && v >= -1e-12 && v <= 1 + 1e-12) return {f, std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0)};
  }
  return {};
}

std::array<double, 3> value_at(const TMeshSurface& s, const std::vector<std::array<double, 2>>& param, double x, double y) {
  const Located l = locate(s, param, x, y);
  EXPECT_GE(l.face, 0) << x << ' ' << y;
  double o[9];
  s.eval(l.face, l.u, l.v, o);
  return {o[0], o[1], o[2]};
}

std::vector<std::array<double, 2>> grid_params(const Grid& g) {
  std::vector<std::array<double, 2>> p;
  for (double y : g.t)
    for (double x : g.s) p.push_back({x, y});
  return p;
}

double distance(const std::array<double, 3>& a, const double* b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

// Largest distance between the surface and the reference at 5 x 5 parameters per face of the cells
// [s[i], s[i + 1]] x [t[j], t[j + 1]] that `compare(i, j)` selects.
template <class Select>
double max_deviation(const TMeshSurface& surface, const std::vector<std::array<double, 2>>& param, const SplineSurface& ref,
                     const std::vector<double>& s, const std::vector<double>& t, Select compare, int* cells = nullptr) {
  double worst = 0;
  for (std::size_t j = 0; j + 1 < t.size(); ++j)
    for (std::size_t i = 0; i + 1 < s.size(); ++i) {
      if (!compare(static_cast<int>(i), static_cast<int>(j))) continue;
      if (cells) ++*cells;
      for (int b = 0; b <= 4; ++b)
        for (int a = 0; a <= 4; ++a) {
          const double x = s[i] + (s[i + 1] - s[i]) * a / 4, y = t[j] + (t[j + 1] - t[j]) * b / 4;
          double r[3];
          ref.eval({x, y}, r);
          worst = std::max(worst, distance(value_at(surface, param, x, y), r));
        }
    }
  return worst;
}

// Second derivative across the boundary side of the first face, in the direction `dir` (0: along s, 1: along t)
// from the boundary value `edge` inwards by `d` (signed), from four values of the cubic across the face (exact for
// cubics): f'' = (2 f0 - 5 f1 + 4 f2 - f3) / h^2.
double second_derivative_across(const TMeshSurface& s, const std::vector<std::array<double, 2>>& param, int dir, double edge,
                                double along, double d) {
  const double h = d / 3;
  std::array<std::array<double, 3>, 4> f;
  for (int k = 0; k < 4; ++k) {
    const double c = edge + k * h;
    f[static_cast<std::size_t>(k)] = dir == 0 ? value_at(s, param, c, along) : value_at(s, param, along, c);
  }
  double n = 0;
  for (std::size_t c = 0; c < 3; ++c) n = std::max(n, std::abs(2 * f[0][c] - 5 * f[1][c] + 4 * f[2][c] - f[3][c]) / (h * h));
  return n;
}

TEST(CreaseEnds, RegularGridIsTheNaturalEndUniformBicubic) {
  for (const bool rational : {false, true}) {
    const double d = rational ? 0.5 : 1.0;
    const Grid g = grid(uniform(6, d), uniform(5, d));
    TMesh m = crease_mesh(g.quads);
    if (rational) {
      std::mt19937 gen(7);
      std::uniform_real_distribution<double> w(0.8, 1.25);
      for (std::size_t v = 0; v < g.quads.points.size(); ++v)
        m.points[static_cast<std::size_t>(m.vertices[v].primary)].w = w(gen);
    }
    const TMeshSurface surface(m, 1);
    EXPECT_EQ(surface.count(FaceMethod::exact), 30);
    const auto param = grid_params(g);
    const SplineSurface ref = natural_reference(g.s, g.t, homogeneous_points(m, static_cast<int>(g.quads.points.size())));
    const double dev = max_deviation(surface, param, ref, g.s, g.t, [](int, int) { return true; });
    EXPECT_LT(dev, 1e-12) << (rational ? "rational" : "polynomial");
    // The corners are interpolated.
    double corner = 0;
    for (int j : {0, 5})
      for (int i : {0, 6}) {
        const RationalPoint& p = m.points[static_cast<std::size_t>(g.id(i, j))];
        corner = std::max(corner, distance(value_at(surface, param, g.s[static_cast<std::size_t>(i)], g.t[static_cast<std::size_t>(j)]), p.xyz.data()));
      }
    EXPECT_LT(corner, 1e-13);
    std::printf("crease grid 6 x 5 (%s): %zu x 25 points, max deviation from the natural-end B-spline %.2e, corners %.2e\n",
                rational ? "rational, weights 0.8..1.25" : "polynomial", std::size_t{30}, dev, corner);
  }
}

TEST(CreaseEnds, UnequalIntervalsWithEqualEndPairsAreTheGhostIntervalSpline) {
  // The first two intervals at each end equal: the ghost row 2 P0 - P1 one first interval beyond the boundary
  // gives both the boundary value P0 and the zero second derivative, so that unclamped spline is the reference.
  const Grid g = grid({0, 0.7, 1.4, 3.4, 3.9, 5.4, 6.2, 7.0}, {0, 1.3, 2.6, 3.1, 4.9, 6.1, 7.3});
  const TMesh m = crease_mesh(g.quads);
  const TMeshSurface surface(m, 1);
  const auto param = grid_params(g);
  const SplineSurface ref = natural_reference(g.s, g.t, homogeneous_points(m, static_cast<int>(g.quads.points.size())));
  const double dev = max_deviation(surface, param, ref, g.s, g.t, [](int, int) { return true; });
  EXPECT_LT(dev, 1e-12);
  std::printf("crease grid with unequal intervals (equal end pairs): max deviation %.2e\n", dev);
}

TEST(CreaseEnds, UnequalEndIntervalsHaveZeroSecondDerivativeAcrossTheBoundary) {
  const Grid g = grid({0, 0.5, 2.0, 3.0, 5.0, 5.7, 6.9}, {0, 1.4, 1.9, 3.1, 3.6, 5.4});
  const TMesh m = crease_mesh(g.quads);
  const TMeshSurface surface(m, 1);
  const auto param = grid_params(g);
  // Across each side, at sample points along it (corners included), and for scale inside (the second face).
  double across = 0, inside = 0;
  const double s0 = g.s.front(), s1 = g.s.back(), t0 = g.t.front(), t1 = g.t.back();
  const double ds0 = g.s[1] - g.s[0], ds1 = g.s[g.s.size() - 1] - g.s[g.s.size() - 2];
  const double dt0 = g.t[1] - g.t[0], dt1 = g.t[g.t.size() - 1] - g.t[g.t.size() - 2];
  for (int k = 0; k <= 20; ++k) {
    const double x = s0 + (s1 - s0) * k / 20, y = t0 + (t1 - t0) * k / 20;
    across = std::max({across, second_derivative_across(surface, param, 1, t0, x, dt0), second_derivative_across(surface, param, 1, t1, x, -dt1),
                       second_derivative_across(surface, param, 0, s0, y, ds0), second_derivative_across(surface, param, 0, s1, y, -ds1)});
    inside = std::max({inside, second_derivative_across(surface, param, 1, g.t[1], x, g.t[2] - g.t[1]),
                       second_derivative_across(surface, param, 0, g.s[1], y, g.s[2] - g.s[1])});
  }
  EXPECT_GT(inside, 0.05);
  EXPECT_LT(across, 1e-10 * inside);
  // The corners are interpolated.
  double corner = 0;
  for (std::size_t j : {std::size_t{0}, g.t.size() - 1})
    for (std::size_t i : {std::size_t{0}, g.s.size() - 1})
      corner = std::max(corner, distance(value_at(surface, param, g.s[i], g.t[j]), m.points[static_cast<std::size_t>(g.id(static_cast<int>(i), static_cast<int>(j)))].xyz.data()));
  EXPECT_LT(corner, 1e-13);
  // Faces two rings in from every side depend on the points alone (any extension beyond the boundary): the
  // B-spline of the points there; so does the boundary curve two faces from the corners.
  const SplineSurface ref = natural_reference(g.s, g.t, homogeneous_points(m, static_cast<int>(g.quads.points.size())));
  const int ns = static_cast<int>(g.s.size()) - 1, nt = static_cast<int>(g.t.size()) - 1;
  int cells = 0;
  const double dev = max_deviation(surface, param, ref, g.s, g.t, [&](int i, int j) { return i >= 2 && i < ns - 2 && j >= 2 && j < nt - 2; }, &cells);
  EXPECT_EQ(cells, 2);
  EXPECT_LT(dev, 1e-12);
  // The boundary t = t0: the cubic B-spline of its points on the knots s (ghosts 2 P0 - P1, not reached there).
  std::vector<double> row;
  const auto push = [&](const std::array<double, 3>& p) { row.insert(row.end(), p.begin(), p.end()); };
  const auto& pts = g.quads.points;
  std::array<double, 3> ghost{};
  for (std::size_t c = 0; c < 3; ++c) ghost[c] = 2 * pts[0][c] - pts[1][c];
  push(ghost);
  for (int i = 0; i <= ns; ++i) push(pts[static_cast<std::size_t>(i)]);
  for (std::size_t c = 0; c < 3; ++c) ghost[c] = 2 * pts[static_cast<std::size_t>(ns)][c] - pts[static_cast<std::size_t>(ns - 1)][c];
  push(ghost);
  const SplineCurve boundary = SplineCurve::from_cartesian({ghost_knots(g.s)}, 3, row);
  double curve = 0;
  for (int k = 0; k <= 20; ++k) {
    const double x = g.s[2] + (g.s[static_cast<std::size_t>(ns - 2)] - g.s[2]) * k / 20;
    double r[3];
    boundary.eval({x}, r);
    curve = std::max(curve, distance(value_at(surface, param, x, t0), r));
  }
  EXPECT_LT(curve, 1e-12);
  std::printf("crease grid with unequal end intervals: second derivative across the boundary %.2e (inside up to %.2f), "
              "corners %.2e, inner faces %.2e, boundary curve %.2e\n", across, inside, corner, dev, curve);
}

// The parameters of a fan's vertices in the plane (valence 4: the grid [-m, m]^2, points over it).
std::vector<std::array<double, 2>> planar_params(const test::QuadMesh& q) {
  std::vector<std::array<double, 2>> p;
  for (const auto& x : q.points) p.push_back({x[0], x[1]});
  return p;
}

TEST(CreaseEnds, TJunctionNextToTheBoundary) {
  // The grid [-6, 6]^2 with the faces [1, 5] x [4, 5] split at t = 4.5: the boundary vertices (1..5, 6) have
  // the knots 5, 4.5 inwards (d1 = 1, d2 = 1/2).
  const int m = 6;
  const test::QuadMesh q = test::fan_mesh_with_t_junctions(4, m, 4, 1, 5, wave);
  const TMesh mesh = crease_mesh(q);
  const TMeshSurface surface(mesh, 1);
  const auto param = planar_params(q);
  // The reference: the natural-end B-spline of the grid without the split (its vertices at integer (x, y)).
  std::vector<double> knots = uniform(2 * m, 1.0);
  for (double& k : knots) k -= m;
  std::vector<std::array<double, 4>> h;
  for (double y : knots)
    for (double x : knots) {
      int v = -1;
      for (int i = 0; i < static_cast<int>(q.points.size()) && v < 0; ++i)
        if (std::abs(param[static_cast<std::size_t>(i)][0] - x) + std::abs(param[static_cast<std::size_t>(i)][1] - y) < 1e-12) v = i;
      ASSERT_GE(v, 0);
      const auto& p = q.points[static_cast<std::size_t>(v)];
      h.push_back({p[0], p[1], p[2], 1});
    }
  const SplineSurface ref = natural_reference(knots, knots, h);
  // Faces beyond the supports of the nodes on and across the split (x <= -1): the reference.
  int cells = 0;
  const double dev = max_deviation(surface, param, ref, knots, knots, [&](int i, int) { return i + 1 - m <= -1; }, &cells);
  EXPECT_EQ(cells, 5 * 12);
  EXPECT_LT(dev, 1e-12);
  // The boundary curve is the B-spline of the boundary points everywhere, also along the split's columns.
  double curve = 0;
  for (int k = 0; k <= 96; ++k) {
    const double a = -m + 2.0 * m * k / 96;
    for (const std::array<double, 2> at : {std::array<double, 2>{a, -m}, {a, double(m)}, {-m, a}, {double(m), a}}) {
      double r[3];
      ref.eval({at[0], at[1]}, r);
      curve = std::max(curve, distance(value_at(surface, param, at[0], at[1]), r));
    }
  }
  EXPECT_LT(curve, 1e-12);
  // Zero second derivative across the boundary at x in [2, 4], where the blending functions of the rows 6, 5,
  // 4.5 are tensor products of their rows (columns 1..5 all have the split's vertex).
  double across = 0, inside = 0;
  for (int k = 0; k <= 8; ++k) {
    const double x = 2 + 2.0 * k / 8;
    across = std::max(across, second_derivative_across(surface, param, 1, m, x, -1.0));
    inside = std::max(inside, second_derivative_across(surface, param, 1, m - 1, x, -0.5));
  }
  EXPECT_GT(inside, 0.05);
  EXPECT_LT(across, 1e-10 * inside);
  const TSplineTriangulation t = tessellate(surface, 1e-3);
  EXPECT_EQ(test::boundary_loops(t), 1);
  std::printf("crease grid with a T-junction row: %d faces as the reference (%.2e), boundary curve %.2e, second derivative "
              "across %.2e (inside %.2f); %zu triangles\n", cells, dev, curve, across, inside, t.triangles.size());
}

TEST(CreaseEnds, TJunctionStemsFromTheBoundary) {
  // Columns 0..6 and rows 0, 1, 2, 4, 5; the top row's faces [1, 4] x [4, 5] split at the half columns, whose
  // edges end in T-junctions on the top sides of the faces [1, 4] x [2, 4]. The boundary vertices (i + 1/2, 5)
  // take d2 = 2 from the depth of the face below their T-junction, the others from the edge after (x, 4).
  test::QuadMesh q;
  std::vector<std::array<double, 2>> param;
  std::map<std::array<double, 2>, int> id;
  const auto vertex = [&](double x, double y) {
    const auto [it, fresh] = id.emplace(std::array<double, 2>{x, y}, static_cast<int>(param.size()));
    if (fresh) {
      param.push_back({x, y});
      const double px = x + 0.1 * y, py = y - 0.05 * x;
      q.points.push_back({px, py, wave(px, py)});
    }
    return it->second;
  };
  const auto face = [&](std::vector<std::array<double, 2>> corners, std::vector<char> straight) {
    std::vector<int> loop;
    for (const auto& c : corners) loop.push_back(vertex(c[0], c[1]));
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const auto& a = param[static_cast<std::size_t>(loop[k])];
      const auto& b = param[static_cast<std::size_t>(loop[(k + 1) % loop.size()])];
      q.intervals[{loop[k], loop[(k + 1) % loop.size()]}] = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]);
    }
    if (loop.size() == 4)
      q.quads.push_back({loop[0], loop[1], loop[2], loop[3]});
    else
      q.t_faces.push_back({loop, straight});
  };
  const std::vector<double> rows{0, 1, 2, 4, 5};
  for (std::size_t j = 0; j + 1 < rows.size(); ++j)
    for (int i = 0; i < 6; ++i) {
      const double y0 = rows[j], y1 = rows[j + 1], x0 = i, x1 = i + 1;
      const bool split = i >= 1 && i <= 3;
      if (split && y0 == 4) {
        face({{x0, y0}, {x0 + 0.5, y0}, {x0 + 0.5, y1}, {x0, y1}}, {});
        face({{x0 + 0.5, y0}, {x1, y0}, {x1, y1}, {x0 + 0.5, y1}}, {});
      } else if (split && y1 == 4) {
        face({{x0, y0}, {x1, y0}, {x1, y1}, {x0 + 0.5, y1}, {x0, y1}}, {0, 0, 0, 1, 0});
      } else {
        face({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {});
      }
    }
  const TMesh mesh = crease_mesh(q);
  const TMeshSurface surface(mesh, 1);
  EXPECT_EQ(surface.count(FaceMethod::exact), surface.num_faces());
  // The section across the top boundary at every x is the clamped cubic of one column of rows (5, 5, 4) with
  // d1 = 1, d2 = 2, so the second derivative across vanishes everywhere along it.
  double across = 0, inside = 0;
  for (int k = 0; k <= 24; ++k) {
    const double x = 6.0 * k / 24;
    across = std::max(across, second_derivative_across(surface, param, 1, 5, x, -1.0));
    inside = std::max(inside, second_derivative_across(surface, param, 1, 4, x, -2.0));
  }
  EXPECT_GT(inside, 0.05);
  EXPECT_LT(across, 1e-10 * inside);
  // The top boundary curve two spans from its ends: the B-spline of its points on their knots 0, 1, 1.5, ..., 6.
  const std::vector<double> top{0, 1, 1.5, 2, 2.5, 3, 3.5, 4, 5, 6};
  std::vector<double> row;
  const auto at = [&](double x) -> const std::array<double, 3>& { return q.points[static_cast<std::size_t>(id.at({x, 5.0}))]; };
  for (std::size_t c = 0; c < 3; ++c) row.push_back(2 * at(0)[c] - at(1)[c]);
  for (double x : top) row.insert(row.end(), at(x).begin(), at(x).end());
  for (std::size_t c = 0; c < 3; ++c) row.push_back(2 * at(6)[c] - at(5)[c]);
  const SplineCurve boundary = SplineCurve::from_cartesian({ghost_knots(top)}, 3, row);
  double curve = 0;
  for (int k = 0; k <= 20; ++k) {
    const double x = 1.5 + 2.5 * k / 20;
    double r[3];
    boundary.eval({x}, r);
    curve = std::max(curve, distance(value_at(surface, param, x, 5), r));
  }
  EXPECT_LT(curve, 1e-12);
  const TSplineTriangulation t = tessellate(surface, 1e-3);
  EXPECT_EQ(test::boundary_loops(t), 1);
  std::printf("crease grid with T-junction stems from the boundary: second derivative across %.2e (inside %.2f), boundary "
              "curve %.2e\n", across, inside, curve);
}

// The fans' sectors as grids: sector k's vertex (i, j) at i e(k) + j e(k + 1), e(k) the unit vector at angle
// k * step. Per sector the cells whose 4 x 4 points avoid the star point and lie in the sector, or reach beyond
// a boundary spoke (`spokes_on_boundary`: spokes 0 and `sectors`, the half fan), where the natural ghost row is
// the crease: the natural-end B-spline of the sector's points there. Returns the largest deviation.
double sector_deviation(const TMeshSurface& surface, const test::QuadMesh& q, int sectors, int m, double step, bool spokes_on_boundary,
                        int* cells) {
  double worst = 0;
  const std::vector<double> knots = uniform(m, 1.0);
  for (int k = 0; k < sectors; ++k) {
    std::vector<std::array<double, 2>> param(q.points.size(), {std::nan(""), std::nan("")});
    std::vector<std::array<double, 4>> h;
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i <= m; ++i) {
        const double x = i * std::cos(k * step) + j * std::cos((k + 1) * step), y = i * std::sin(k * step) + j * std::sin((k + 1) * step);
        int v = -1;
        for (int w = 0; w < static_cast<int>(q.points.size()) && v < 0; ++w)
          if (std::abs(q.points[static_cast<std::size_t>(w)][0] - x) + std::abs(q.points[static_cast<std::size_t>(w)][1] - y) < 1e-9) v = w;
        EXPECT_GE(v, 0);
        param[static_cast<std::size_t>(v)] = {double(i), double(j)};
        const auto& p = q.points[static_cast<std::size_t>(v)];
        h.push_back({p[0], p[1], p[2], 1});
      }
    const SplineSurface ref = natural_reference(knots, knots, h);
    const bool low_j_boundary = spokes_on_boundary && k == 0, low_i_boundary = spokes_on_boundary && k == sectors - 1;
    worst = std::max(worst, max_deviation(surface, param, ref, knots, knots, [&](int i, int j) {
      if (i <= 1 && j <= 1) return false;  // the star point among the face's points
      return (i >= 1 || low_i_boundary) && (j >= 1 || low_j_boundary);
    }, cells));
  }
  return worst;
}

TEST(CreaseEnds, InteriorStarPointWithACreaseBoundary) {
  const int m = 7;
  const test::QuadMesh q = test::fan_mesh(5, m, wave);
  const TMesh mesh = crease_mesh(q);
  const TMeshSurface surface(mesh, 1);
  EXPECT_EQ(surface.count(FaceMethod::star), 5);
  int cells = 0;
  const double dev = sector_deviation(surface, q, 5, m, 2 * std::numbers::pi / 5, false, &cells);
  EXPECT_EQ(cells, 5 * (m * m - 2 * m));
  EXPECT_LT(dev, 1e-12);
  // Across every interior edge (also those at the star point, away from it): positions, normals, C1.
  const test::Continuity c = test::continuity(mesh, [&](int f, double u, double v, double* o) { surface.eval(f, u, v, o); });
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-10);
  EXPECT_LT(c.c1, 1e-10);
  const TSplineTriangulation t = tessellate(surface, 1e-2);
  EXPECT_EQ(test::boundary_loops(t), 1);
  std::printf("crease fan of valence 5 (%d faces): %d faces as the sectors' natural-end B-splines (%.2e); %d edges: gap %.2e, "
              "normal defect (sin) %.2e, C1 defect %.2e; %zu triangles\n",
              surface.num_faces(), cells, dev, c.edges, c.gap, c.normal_angle, c.c1, t.triangles.size());
}

TEST(CreaseEnds, BoundaryStarPointIsLeftToLocalSubdivision) {
  // Four sectors around a star point on the straight boundary (the x axis): a crease vertex of four faces, which
  // has no Bezier form. The conversion leaves its point and gives it no block; its faces are evaluated by local
  // subdivision (crease_face, checked against OpenSubdiv in crease_face_test), and the faces whose points avoid
  // it are the sectors' natural-end B-splines, also the boundary faces along the x axis (the crease there).
  const int m = 7;
  const test::QuadMesh q = test::half_fan_mesh(4, m, wave);
  const TMesh mesh = crease_mesh(q);
  const TMeshSurface surface(mesh, 1);
  EXPECT_EQ(surface.boundary_star_faces(), 0);
  EXPECT_GT(surface.count(FaceMethod::crease), 0);
  int cells = 0;
  const double dev = sector_deviation(surface, q, 4, m, std::numbers::pi / 4, true, &cells);
  EXPECT_EQ(cells, 4 * (m * m - 2 * m) + 2 * (m - 2));
  EXPECT_LT(dev, 1e-12);
  const int star = surface.stars()[0];
  const TMesh x = bezier_equivalent(mesh);
  const TMeshVertex& sv = x.vertices[static_cast<std::size_t>(star)];
  EXPECT_TRUE(sv.block.empty());
  EXPECT_LT(distance(x.points[static_cast<std::size_t>(sv.primary)].xyz, q.points[static_cast<std::size_t>(star)].data()), 1e-15);
  const TSplineTriangulation t = tessellate(surface, 1e-2);
  EXPECT_EQ(test::boundary_loops(t), 1);
  std::printf("crease half fan of 4 sectors: %d faces as the sectors' natural-end B-splines (%.2e)\n", cells, dev);
}

TEST(CreaseEnds, BezierEndConditionsAreKept) {
  const TMesh m = io::parse_tsm(test::tsm_text(test::half_fan_mesh(2, 3, wave)), "bezier.tsm").mesh;
  ASSERT_EQ(m.end_conditions, EndConditions::bezier);
  const TMesh x = bezier_equivalent(m);
  ASSERT_EQ(x.points.size(), m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    EXPECT_EQ(x.points[i].xyz, m.points[i].xyz);
    EXPECT_EQ(x.points[i].w, m.points[i].w);
  }
  ASSERT_EQ(x.vertices.size(), m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    EXPECT_EQ(x.vertices[v].primary, m.vertices[v].primary);
    EXPECT_EQ(x.vertices[v].block, m.vertices[v].block);
    EXPECT_EQ(x.vertices[v].block_dims, m.vertices[v].block_dims);
  }
  // The crease mesh given to the conversion keeps its flag and points.
  const TMesh crease = crease_mesh(test::half_fan_mesh(2, 3, wave));
  const TMesh converted = bezier_equivalent(crease);
  EXPECT_EQ(crease.end_conditions, EndConditions::subd_creases);
  EXPECT_EQ(converted.end_conditions, EndConditions::bezier);
  EXPECT_GT(converted.points.size(), crease.points.size());
}

TEST(CreaseEnds, LeavesConcaveCornersAndRefusesOtherDegrees) {
  // An L-shaped grid: the inner corner has 270 degrees of faces.
  Grid g = grid(uniform(4, 1.0), uniform(4, 1.0));
  std::vector<std::array<int, 4>> kept;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      if (i < 2 || j < 2) kept.push_back(g.quads.quads[static_cast<std::size_t>(i + 4 * j)]);
  // Only the vertices the kept faces use, renumbered.
  std::map<int, int> renumber;
  test::QuadMesh l;
  for (auto& f : kept)
    for (int& v : f) {
      const auto [it, fresh] = renumber.emplace(v, static_cast<int>(l.points.size()));
      if (fresh) l.points.push_back(g.quads.points[static_cast<std::size_t>(v)]);
      v = it->second;
    }
  l.quads = kept;
  // Its inner corner is a crease vertex of three faces: no Bezier form, left to local subdivision (its point kept,
  // no block).
  const TMesh m = crease_mesh(l);
  const std::vector<int> irregular = irregular_crease_vertices(m);
  ASSERT_EQ(irregular.size(), 1u);
  const TMesh converted = bezier_equivalent(m);
  const TMeshVertex& corner = converted.vertices[static_cast<std::size_t>(irregular[0])];
  EXPECT_TRUE(corner.block.empty());
  EXPECT_EQ(corner.primary, m.vertices[static_cast<std::size_t>(irregular[0])].primary);
  TMesh even = crease_mesh(grid(uniform(3, 1.0), uniform(3, 1.0)).quads);
  even.degree = 5;
  EXPECT_THROW(bezier_equivalent(even), Error);
}

}  // namespace trivar::crease_ends_test
