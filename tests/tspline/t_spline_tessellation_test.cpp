#include <gtest/gtest.h>

#include <map>

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

TEST(TSplineTessellation, CrackFreeAtTJunctionsAndWithinTheTolerance) {
  const TSplineSurface surf(wavy_t_mesh());
  for (double tol : {1e-2, 1e-3}) {
    const TSplineTriangulation m = tessellate(surf, tol);
    // Every edge is used twice (once each way) except on the domain's boundary: no crack.
    std::map<std::pair<int, int>, int> use;
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k) ++use[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
    for (const auto& [e, n] : use) {
      ASSERT_LE(n, 2);
      if (n == 1) {
        const auto& a = m.params[static_cast<std::size_t>(e.first)];
        const auto& b = m.params[static_cast<std::size_t>(e.second)];
        const bool on_boundary = (a[0] == b[0] && (a[0] == 0 || a[0] == 6)) || (a[1] == b[1] && (a[1] == 0 || a[1] == 6));
        ASSERT_TRUE(on_boundary) << a[0] << "," << a[1] << " - " << b[0] << "," << b[1];
      }
    }
    // Chordal deviation at the triangles' parameter centroids.
    double worst = 0;
    for (const auto& t : m.triangles) {
      Param<2> c{0, 0};
      std::array<double, 3> mid{0, 0, 0};
      for (int v : t)
        for (int k = 0; k < 3; ++k) {
          if (k < 2) c[static_cast<std::size_t>(k)] += m.params[static_cast<std::size_t>(v)][static_cast<std::size_t>(k)] / 3;
          mid[static_cast<std::size_t>(k)] += m.points[static_cast<std::size_t>(v)][static_cast<std::size_t>(k)] / 3;
        }
      double x[3];
      surf.eval(c, x);
      worst = std::max(worst, std::hypot(x[0] - mid[0], x[1] - mid[1], x[2] - mid[2]));
    }
    EXPECT_LT(worst, tol) << tol;
  }
  EXPECT_GT(tessellate(surf, 1e-4).triangles.size(), 4 * tessellate(surf, 1e-2).triangles.size());
}

}  // namespace
}  // namespace trivar
