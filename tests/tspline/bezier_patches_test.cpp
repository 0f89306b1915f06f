#include <gtest/gtest.h>

#include <cmath>

#include "trivar/tspline/bezier_patches.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"

namespace trivar {
namespace {

// The per-element Bezier patches evaluate as the T-spline inside and on the sides of their elements (exact
// form, here of a T-spline whose blending functions do not sum to one).
TEST(BezierPatches, EveryPatchIsTheTSplineOnItsElement) {
  auto g = std::vector<KnotSegment>{};
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 6.0}});
  }
  g.push_back({{0.0, 3.5}, {2.0, 3.5}});
  g.push_back({{3.5, 0.0}, {3.5, 6.0}});
  const TSpline ts = t_spline_from_segments({3, 3}, g, [](double s, double t, int a, int b) {
    return RationalPoint{{s + 0.2 * a, t - 0.1 * b, std::sin(s) * std::cos(t)}, 1.0 + 0.25 * std::cos(s * t)};
  });
  const TSplineSurface surf(ts);
  EXPECT_GT(surf.partition_of_unity().max_defect, 1e-3);  // crossing extensions: not a partition of unity
  const auto patches = bezier_patches(surf);
  ASSERT_EQ(patches.size(), surf.elements().size());
  for (std::size_t e = 0; e < patches.size(); ++e) {
    const Box<2>& b = surf.elements()[e];
    for (double x : {0.0, 0.3, 1.0})
      for (double y : {0.0, 0.8, 1.0}) {
        const Param<2> u{b.lo[0] + x * b.extent(0), b.lo[1] + y * b.extent(1)};
        double a[3], c[3];
        surf.eval_on_element(static_cast<int>(e), u, a);
        patches[e].eval(u, c);
        for (int d = 0; d < 3; ++d) ASSERT_NEAR(a[d], c[d], 1e-13 * (1 + std::abs(a[d])));
      }
  }
}

}  // namespace
}  // namespace trivar
