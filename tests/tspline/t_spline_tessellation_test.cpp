#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/local_knots.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

namespace trivar {
namespace {

TSpline wavy_t_mesh() {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 6.0}});
  }
  g.push_back({{0.0, 4.5}, {2.0, 4.5}});  // a second T-junction, small elements beside big ones
  return t_spline_from_segments({3, 3}, g, [](double s, double t, int a, int b) {
    return RationalPoint{{s + 0.2 * a, t + 0.2 * b, std::sin(s) * std::cos(t)}, 1.0 + 0.1 * s};
  });
}

// A flat T-spline on [0, 10]^2 (points at their Greville points: the parameter plane itself) with the nodes on
// its diagonal lifted (a ridge along s = t from (1, 1) to (9, 9), curved within about two elements of it), a T-junction at (8, 5) and a
// knot line t = 2.5 from s = 6 that the global grid carries through the ridge.
TSpline flat_t_mesh_with_ridge() {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 10; ++i) {
    g.push_back({{0.0, double(i)}, {10.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 8 ? 5.0 : 10.0}});
  }
  g.push_back({{6.0, 2.5}, {10.0, 2.5}});
  TSpline ts = t_spline_from_segments({3, 3}, g, [](double, double, int, int) { return RationalPoint{}; });
  place_at_greville_points(ts);
  for (RationalPoint& p : ts.pointset.points)
    if (p.xyz[0] == p.xyz[1] && p.xyz[0] >= 1 && p.xyz[0] <= 9) p.xyz[2] = 1.5;
  return ts;
}

// One bicubic Bezier element over [0, 1]^2 with z = a s^2 (a parabolic cylinder): the cubic Bernstein
// coefficients of s^2 are g (3 g - 1) / 2 at the Greville abscissae g = 0, 1/3, 2/3, 1.
TSpline parabolic_cylinder(double a) {
  const std::vector<KnotSegment> g{{{0, 0}, {1, 0}}, {{1, 0}, {1, 1}}, {{1, 1}, {0, 1}}, {{0, 1}, {0, 0}}};
  TSpline ts = t_spline_from_segments({3, 3}, g, [](double, double, int, int) { return RationalPoint{}; });
  place_at_greville_points(ts);
  for (RationalPoint& p : ts.pointset.points) p.xyz[2] = a * p.xyz[0] * (3 * p.xyz[0] - 1) / 2;
  return ts;
}

double triangle_area(const TSplineTriangulation& m, const std::array<int, 3>& t) {
  const auto& a = m.params[static_cast<std::size_t>(t[0])];
  const auto& b = m.params[static_cast<std::size_t>(t[1])];
  const auto& c = m.params[static_cast<std::size_t>(t[2])];
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

// The largest distance between the surface at a point of a triangle's parameters and the triangle's point with
// the same barycentric coordinates, over the centroid, the edge midpoints and six more points per triangle.
double chordal_deviation(const TSplineSurface& surf, const TSplineTriangulation& m) {
  static constexpr double kBary[10][3] = {{1 / 3.0, 1 / 3.0, 1 / 3.0}, {0.5, 0.5, 0},     {0, 0.5, 0.5},
                                          {0.5, 0, 0.5},               {2 / 3.0, 1 / 6.0, 1 / 6.0},
                                          {1 / 6.0, 2 / 3.0, 1 / 6.0}, {1 / 6.0, 1 / 6.0, 2 / 3.0},
                                          {0.1, 0.45, 0.45},           {0.45, 0.1, 0.45}, {0.45, 0.45, 0.1}};
  double worst = 0;
  for (const auto& t : m.triangles)
    for (const auto& l : kBary) {
      Param<2> u{0, 0};
      double x[3] = {0, 0, 0}, s[3];
      for (int k = 0; k < 3; ++k) {
        const std::size_t v = static_cast<std::size_t>(t[static_cast<std::size_t>(k)]);
        for (int d = 0; d < 2; ++d) u[static_cast<std::size_t>(d)] += l[k] * m.params[v][static_cast<std::size_t>(d)];
        for (int d = 0; d < 3; ++d) x[d] += l[k] * m.points[v][static_cast<std::size_t>(d)];
      }
      surf.eval(u, s);
      worst = std::max(worst, std::hypot(s[0] - x[0], s[1] - x[1], s[2] - x[2]));
    }
  return worst;
}

// A triangulation of the whole domain (no holes) without cracks: points on the surface; triangles
// counter-clockwise with positive area, covering the domain's area; every edge inside used once each way, every
// other edge on the domain's boundary; no vertex inside another triangle's edge (no T-vertex).
void expect_watertight_cover(const TSplineSurface& surf, const TSplineTriangulation& m) {
  ASSERT_EQ(m.points.size(), m.params.size());
  const Box<2> dom = surf.domain();
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    double x[3];
    surf.eval({m.params[i][0], m.params[i][1]}, x);
    ASSERT_LT(std::hypot(x[0] - m.points[i][0], x[1] - m.points[i][1], x[2] - m.points[i][2]), 1e-12 * (1 + std::hypot(x[0], x[1], x[2])));
  }
  double area = 0;
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles) {
    const double a = triangle_area(m, t);
    ASSERT_GT(a, 0) << t[0] << " " << t[1] << " " << t[2];
    area += a;
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> edge{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]};
      ASSERT_EQ(++directed[edge], 1) << "edge used twice in one direction";
    }
  }
  EXPECT_NEAR(area, dom.extent(0) * dom.extent(1), 1e-12 * dom.extent(0) * dom.extent(1));
  for (const auto& [e, n] : directed) {
    if (directed.count({e.second, e.first})) continue;
    const auto& a = m.params[static_cast<std::size_t>(e.first)];
    const auto& b = m.params[static_cast<std::size_t>(e.second)];
    bool on_side = false;
    for (int k = 0; k < 2; ++k)
      for (double side : {dom.lo[k], dom.hi[k]}) on_side = on_side || (a[static_cast<std::size_t>(k)] == side && b[static_cast<std::size_t>(k)] == side);
    ASSERT_TRUE(on_side) << a[0] << "," << a[1] << " - " << b[0] << "," << b[1];
  }
  // T-vertices: vertices in buckets of a 64 x 64 grid, every edge against the vertices of the buckets it crosses.
  constexpr int kBuckets = 64;
  const auto bucket = [&](double x, int k) {
    return std::clamp(static_cast<int>((x - dom.lo[k]) / dom.extent(k) * kBuckets), 0, kBuckets - 1);
  };
  std::vector<std::vector<int>> buckets(kBuckets * kBuckets);
  for (std::size_t i = 0; i < m.params.size(); ++i)
    buckets[static_cast<std::size_t>(bucket(m.params[i][0], 0) + kBuckets * bucket(m.params[i][1], 1))].push_back(static_cast<int>(i));
  for (const auto& [e, n] : directed) {
    if (e.first > e.second && directed.count({e.second, e.first})) continue;
    const auto& a = m.params[static_cast<std::size_t>(e.first)];
    const auto& b = m.params[static_cast<std::size_t>(e.second)];
    const double len2 = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
    for (int j = bucket(std::min(a[1], b[1]), 1); j <= bucket(std::max(a[1], b[1]), 1); ++j)
      for (int i = bucket(std::min(a[0], b[0]), 0); i <= bucket(std::max(a[0], b[0]), 0); ++i)
        for (int v : buckets[static_cast<std::size_t>(i + kBuckets * j)]) {
          if (v == e.first || v == e.second) continue;
          const auto& c = m.params[static_cast<std::size_t>(v)];
          const double cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
          const double along = (b[0] - a[0]) * (c[0] - a[0]) + (b[1] - a[1]) * (c[1] - a[1]);
          ASSERT_FALSE(std::abs(cross) <= 1e-12 * len2 && along > 0 && along < len2)
              << "T-vertex " << c[0] << "," << c[1] << " on " << a[0] << "," << a[1] << " - " << b[0] << "," << b[1];
        }
  }
}

TEST(TSplineTessellation, CrackFreeAtTJunctionsAndWithinTheTolerance) {
  const TSplineSurface surf(wavy_t_mesh());
  for (double tol : {1e-2, 1e-3}) {
    const TSplineTriangulation m = tessellate(surf, tol);
    expect_watertight_cover(surf, m);
    EXPECT_LE(chordal_deviation(surf, m), tol) << tol;
  }
  EXPECT_GT(tessellate(surf, 1e-4).triangles.size(), 4 * tessellate(surf, 1e-2).triangles.size());
  // Counts capped at 1 to 5 per element side (every mix of ring and lattice elements, 1 x n lattices raised to
  // 2 x n inside rings): still watertight and counter-clockwise.
  for (int cap = 1; cap <= 5; ++cap) expect_watertight_cover(surf, tessellate(surf, 1e-3, cap));
}

// Strongly rational patches: the bound covers the weights' own curvature (not only the control net's).
TEST(TSplineTessellation, RationalPatchesStayWithinTheTolerance) {
  const TSplineSurface patch(io::read_tsm(std::string(TRIVAR_TEST_DATA) + "/tsm/bezier_patch.tsm").spline);  // one weight 2
  TSpline wavy = wavy_t_mesh();
  for (std::size_t i = 0; i < wavy.pointset.points.size(); ++i) wavy.pointset.points[i].w = 0.4 + 0.4 * static_cast<double>((i * 7) % 5);
  const TSplineSurface heavy(wavy);
  for (const TSplineSurface* s : {&patch, &heavy})
    for (double tol : {3e-2, 3e-3}) {
      const TSplineTriangulation m = tessellate(*s, tol);
      expect_watertight_cover(*s, m);
      EXPECT_LE(chordal_deviation(*s, m), tol) << tol;
    }
}

// z = a s^2 on one element: D_uu = 2 a, D_uv = D_vv = 0, and the chord of a parabola over h deviates by exactly
// a h^2 / 4, so the fewest sub-cells are n_u = ceil(sqrt(a / (4 tol))) by 1 (the former third of the tolerance
// per term gave ceil(sqrt(3 a / (4 tol)))).
TEST(TSplineTessellation, ParabolicCylinderGetsTheFewestStrips) {
  const double a = 1, tol = 1e-3;
  const TSplineSurface surf(parabolic_cylinder(a));
  const TSplineTriangulation m = tessellate(surf, tol);
  const int n = static_cast<int>(std::ceil(std::sqrt(a / (4 * tol))));
  EXPECT_EQ(m.triangles.size(), 2u * static_cast<std::size_t>(n));
  const double deviation = chordal_deviation(surf, m);
  EXPECT_LE(deviation, tol);
  EXPECT_GT(deviation, 0.7 * tol);  // the centres of the strips' chords come close
  expect_watertight_cover(surf, m);
}

// Per-element subdivision: a ridge on a flat T-spline refines its own elements only (their neighbours' sides
// follow, stitched to their own lattices); elements away from it keep one cell (two triangles). The global
// column/row scheme with the same element counts (a column as fine as its finest element) needs far more: the
// ridge crosses every column and row.
TEST(TSplineTessellation, FlatElementsAwayFromARidgeStayCoarse) {
  const TSplineSurface surf(flat_t_mesh_with_ridge());
  const double tol = 1e-3;
  const TSplineTriangulation m = tessellate(surf, tol);
  expect_watertight_cover(surf, m);
  EXPECT_LE(chordal_deviation(surf, m), tol);
  const auto elements = surf.elements();
  std::vector<int> per_element(elements.size(), 0);
  for (const auto& t : m.triangles) {
    Param<2> c{0, 0};
    for (int v : t)
      for (int d = 0; d < 2; ++d) c[static_cast<std::size_t>(d)] += m.params[static_cast<std::size_t>(v)][static_cast<std::size_t>(d)] / 3;
    ++per_element[static_cast<std::size_t>(surf.locate(c))];
  }
  // Elements whose neighbourhood (the box one unit larger: all neighbours) is flat, z = 0 at 8 points per unit
  // and direction (a cubic vanishing at more than 4 points per element is zero; x, y are s, t), keep one cell.
  const auto flat_around = [&](const Box<2>& e) {
    const Box<2> dom = surf.domain();
    const double s0 = std::max(e.lo[0] - 1, dom.lo[0]), s1 = std::min(e.hi[0] + 1, dom.hi[0]);
    const double t0 = std::max(e.lo[1] - 1, dom.lo[1]), t1 = std::min(e.hi[1] + 1, dom.hi[1]);
    for (int j = 0; j <= 24; ++j)
      for (int i = 0; i <= 24; ++i) {
        double x[3];
        surf.eval({s0 + (s1 - s0) * i / 24, t0 + (t1 - t0) * j / 24}, x);
        if (std::abs(x[2]) > 1e-12) return false;
      }
    return true;
  };
  int far = 0;
  for (std::size_t e = 0; e < elements.size(); ++e)
    if (flat_around(elements[e])) {
      EXPECT_EQ(per_element[e], 2) << elements[e].lo[0] << "," << elements[e].lo[1];
      ++far;
    }
  EXPECT_GT(far, 20);
  // The column/row scheme: the segments on each element side give the element's counts (a side has those of the
  // finer element on it, so a column's largest side count is its finest element's).
  std::map<double, std::vector<double>> on_t, on_s;  // t = const: the s of its vertices; s = const: the t
  for (const auto& p : m.params) {
    on_t[p[1]].push_back(p[0]);
    on_s[p[0]].push_back(p[1]);
  }
  const auto segments = [](const std::vector<double>& line, double lo, double hi) {
    return static_cast<int>(std::count_if(line.begin(), line.end(), [&](double x) { return x >= lo && x <= hi; })) - 1;
  };
  std::map<double, int> column, row;
  for (const Box<2>& e : elements) {
    int& c = column[e.lo[0]];
    c = std::max({c, segments(on_t[e.lo[1]], e.lo[0], e.hi[0]), segments(on_t[e.hi[1]], e.lo[0], e.hi[0])});
    int& r = row[e.lo[1]];
    r = std::max({r, segments(on_s[e.lo[0]], e.lo[1], e.hi[1]), segments(on_s[e.hi[0]], e.lo[1], e.hi[1])});
  }
  std::size_t lattice = 0;
  for (const Box<2>& e : elements) lattice += 2 * static_cast<std::size_t>(column[e.lo[0]] * row[e.lo[1]]);
  EXPECT_LT(2 * m.triangles.size(), lattice) << m.triangles.size() << " vs " << lattice;  // 39,015 vs 99,360
}

}  // namespace
}  // namespace trivar
