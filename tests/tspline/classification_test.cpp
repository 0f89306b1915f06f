#include <gtest/gtest.h>

#include "star_mesh_tsm.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"
#include "trivar/tspline/tensor_t_spline.hpp"

namespace trivar {
namespace {

std::vector<KnotSegment> grid_with_stub() {  // 6 x 6 cells on [0, 6]^2, the line s = 3 stops at t = 3
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 6.0}});
  }
  return g;
}

RationalPoint plane(double s, double t, int a, int b) { return {{s + 0.01 * a, t + 0.01 * b, 0.0}, 1.0}; }

TEST(Classification, OneTJunctionIsAnalysisSuitableIndependentAndStandard) {
  const TSpline ts = t_spline_from_segments({3, 3}, grid_with_stub(), plane);
  const auto ext = t_junction_extensions(ts);
  ASSERT_EQ(ext.size(), 1u);
  // Hand-derived: missing edge north at (3, 3); the face extension crosses t = 4, 5, the edge extension t = 2.
  EXPECT_EQ(ext[0].direction, 0);
  EXPECT_EQ(ext[0].axis, 1);
  EXPECT_EQ(ext[0].line, 3.0);
  EXPECT_EQ(ext[0].lo, 2.0);
  EXPECT_EQ(ext[0].hi, 5.0);
  const TSplineSurface surf(ts);
  const TSplineClass c = classify(ts, surf);
  EXPECT_TRUE(c.analysis_suitable);
  EXPECT_TRUE(c.standard);       // AS T-splines form a partition of unity (Li et al. 2012)
  EXPECT_TRUE(c.semi_standard);  // all weights 1
  EXPECT_EQ(c.independence, Independence::independent);  // and are linearly independent
  EXPECT_EQ(c.part42_type(), "ANALYSIS_SUITABLE_T_SPLINE");
  EXPECT_TRUE(c.dual.compatible);  // AS <=> dual-compatible (Beirao da Veiga, Buffa, Sangalli, Vazquez 2013)
}

TEST(Classification, CrossingExtensionsAreNotAnalysisSuitable) {
  auto g = grid_with_stub();
  g.push_back({{0.0, 3.5}, {2.0, 3.5}});  // a T-junction at (2, 3.5) missing east: extension s in [1, 4]
  g.push_back({{3.5, 0.0}, {3.5, 6.0}});
  const TSpline ts = t_spline_from_segments({3, 3}, g, plane);
  const auto ext = t_junction_extensions(ts);
  ASSERT_EQ(ext.size(), 2u);
  const TSplineSurface surf(ts);
  const TSplineClass c = classify(ts, surf);
  EXPECT_FALSE(c.analysis_suitable);
  EXPECT_EQ(c.crossing_extensions, 1);
  EXPECT_NE(c.part42_type(), "ANALYSIS_SUITABLE_T_SPLINE");
  EXPECT_FALSE(c.dual.compatible);
  EXPECT_GT(c.dual.failing_pairs, 0);
}

// Rhino's fan model in small: on a 6 x 6 grid the line s = 3 misses t in (1, 2) and (4, 5), the line t = 3
// misses s in (2, 3) and (4, 5). Eight T-junctions face each other in pairs; their closed extensions all meet at
// the vertex (3, 3), yet no ray crosses a gap (no anchor strictly inside one), so every local knot vector is
// the full grid's: the blending functions are the tensor-product B-splines, dual-compatible and independent.
// The gaps are recognised and the mesh is analysis-suitable. With one more line t = 1.5 a ray crosses the first
// gap: its two T-junctions count again, and their extensions cross.
TEST(Classification, TJunctionsFacingAcrossAGapNoRayCrossesAreLeftOut) {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    if (i == 3) {
      for (const auto& [a, b] : {std::pair{0.0, 2.0}, {3.0, 4.0}, {5.0, 6.0}}) g.push_back({{a, 3.0}, {b, 3.0}});
      for (const auto& [a, b] : {std::pair{0.0, 1.0}, {2.0, 4.0}, {5.0, 6.0}}) g.push_back({{3.0, a}, {3.0, b}});
      continue;
    }
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), 6.0}});
  }
  const TSpline ts = t_spline_from_segments({3, 3}, g, plane);
  int gaps = 0;
  EXPECT_TRUE(t_junction_extensions(ts, &gaps).empty());
  EXPECT_EQ(gaps, 8);
  const TSplineSurface surf(ts);
  const TSplineClass c = classify(ts, surf);
  EXPECT_EQ(c.t_junctions, 8);
  EXPECT_EQ(c.gap_junctions, 8);
  EXPECT_EQ(c.crossing_extensions, 0);
  EXPECT_TRUE(c.analysis_suitable);
  EXPECT_TRUE(c.dual.compatible);
  // The blending functions are those of the full 6 x 6 grid.
  std::vector<KnotSegment> full;
  for (int i = 0; i <= 6; ++i) {
    full.push_back({{0.0, double(i)}, {6.0, double(i)}});
    full.push_back({{double(i), 0.0}, {double(i), 6.0}});
  }
  const TSplineSurface tensor(t_spline_from_segments({3, 3}, full, plane));
  ASSERT_EQ(surf.basis().size(), tensor.basis().size());
  std::vector<std::array<std::vector<double>, 2>> a, b;
  for (const auto& f : surf.basis()) a.push_back(f.knots);
  for (const auto& f : tensor.basis()) b.push_back(f.knots);
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  // A line t = 1.5 crossing s = 3 from the left boundary to s = 4: rays at t = 1.5 cross the gap (1, 2).
  g.push_back({{0.0, 1.5}, {4.0, 1.5}});
  const TSpline crossed = t_spline_from_segments({3, 3}, g, plane);
  const TSplineClass cc = classify(crossed, TSplineSurface(crossed));
  EXPECT_LT(cc.gap_junctions, 8);
  EXPECT_GT(cc.crossing_extensions, 0);
  EXPECT_FALSE(cc.analysis_suitable);
}

// Any degree (Beirao da Veiga, Buffa, Sangalli, Vazquez 2013): extensions cross ceil(p / 2) knot lines on the
// missing edge's side and floor(p / 2) on the other, and a T-mesh on a rectangle is analysis-suitable exactly
// when it is dual-compatible, which is tested here from the blending functions' local knot vectors alone. The
// stub mesh plus a horizontal T-junction at (1, 3.5) missing east (the line s = 3.5 runs through): for p_s = 2
// the horizontal extension is s in [0, 2] (face: s = 2; edge: s = 0), short of the vertical one at s = 3 (t in
// [3 - floor(p_t / 2), 3 + ceil(p_t / 2)]); for p_s = 3 and 4 it reaches s = 3.5 past s = 3 (the stub does not
// reach t = 3.5): they cross, whatever p_t.
TEST(Classification, AnyDegreeExtensionsAgreeWithDualCompatibility) {
  auto g = grid_with_stub();
  g.push_back({{0.0, 3.5}, {1.0, 3.5}});
  g.push_back({{3.5, 0.0}, {3.5, 6.0}});
  for (const auto& [p, expect_as] : std::vector<std::pair<Ints<2>, bool>>{
           {{2, 2}, true}, {{3, 3}, false}, {{4, 4}, false}, {{2, 3}, true}, {{3, 2}, false}, {{2, 4}, true}}) {
    const TSpline ts = t_spline_from_segments(p, g, plane);
    const auto ext = t_junction_extensions(ts);
    ASSERT_EQ(ext.size(), 2u);
    for (const auto& e : ext) {
      if (e.axis == 0) {  // the horizontal one, at t = 3.5, degree p_s
        EXPECT_EQ(e.lo, 0.0);
        EXPECT_EQ(e.hi, p[0] == 2 ? 2.0 : 3.5) << p[0];
      } else {  // the vertical one, at s = 3, degree p_t: [3 - floor(p_t / 2), 3 + ceil(p_t / 2)]
        EXPECT_EQ(e.lo, 3.0 - p[1] / 2) << p[1];
        EXPECT_EQ(e.hi, 3.0 + (p[1] + 1) / 2) << p[1];
      }
    }
    const TSplineSurface surf(ts);
    const TSplineClass c = classify(ts, surf);
    EXPECT_EQ(c.analysis_suitable, expect_as) << p[0] << ' ' << p[1];
    EXPECT_EQ(c.dual.compatible, expect_as) << p[0] << ' ' << p[1];
    if (expect_as) {
      EXPECT_TRUE(c.standard);
      EXPECT_EQ(c.independence, Independence::independent);
    }
  }
}

TEST(Classification, TensorMeshHasNoTJunction) {
  const KnotVector k = KnotVector::from_breakpoints(2, std::vector<double>{0, 1, 2, 3});
  std::vector<double> c(static_cast<std::size_t>(k.size() * k.size() * 3), 0.5);
  const TSpline ts = t_spline_from_tensor(TensorSpline<2>({k, k}, 3, false, c));
  const TSplineSurface surf(ts);
  const TSplineClass cl = classify(ts, surf);
  EXPECT_EQ(cl.t_junctions, 0);
  EXPECT_TRUE(cl.analysis_suitable);
  EXPECT_TRUE(cl.dual.compatible);
  EXPECT_TRUE(cl.standard);
  EXPECT_EQ(cl.independence, Independence::independent);
}

}  // namespace
}  // namespace trivar

namespace trivar {
namespace {

// Extensions that only touch: an 8 x 8 grid whose line s = 4 has a gap for t in (2, 4) and whose line t = 5 has a
// gap for s in (2, 4). The extension of (4, 4) (missing south) is t in [2, 5] at s = 4; those of (2, 5) and (4, 5)
// on t = 5 are s in [1, 4] and [2, 5]: the vertical one ends on the horizontal ones. Extensions are closed
// segments, so these cross, and indeed the blending functions are neither dual-compatible nor a partition of
// unity.
TEST(Classification, ExtensionsThatTouchCross) {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 8; ++i) {
    const double x = i;
    if (i == 4) {
      g.push_back({{x, 0.0}, {x, 2.0}});
      g.push_back({{x, 4.0}, {x, 8.0}});
    } else {
      g.push_back({{x, 0.0}, {x, 8.0}});
    }
    if (i == 5) {
      g.push_back({{0.0, x}, {2.0, x}});
      g.push_back({{4.0, x}, {8.0, x}});
    } else {
      g.push_back({{0.0, x}, {8.0, x}});
    }
  }
  const TSpline ts = t_spline_from_segments({3, 3}, g, plane);
  const auto ext = t_junction_extensions(ts);
  EXPECT_EQ(ext.size(), 4u);
  const TSplineSurface surf(ts);
  const TSplineClass c = classify(ts, surf);
  EXPECT_GT(c.crossing_extensions, 0);
  EXPECT_FALSE(c.analysis_suitable);
  EXPECT_FALSE(c.dual.compatible);
  EXPECT_FALSE(c.standard);
}

}  // namespace
}  // namespace trivar

namespace trivar {
namespace {

// The B-spline on local knots t_0 .. t_(p+1) at x, by the Cox-de Boor recursion (x not on a knot).
double local_bspline(const std::vector<double>& t, double x) {
  const std::size_t p = t.size() - 2;
  std::vector<double> n(p + 1);
  for (std::size_t i = 0; i <= p; ++i) n[i] = t[i] <= x && x < t[i + 1] ? 1.0 : 0.0;
  for (std::size_t k = 1; k <= p; ++k)
    for (std::size_t i = 0; i + k <= p; ++i) {
      const double a = t[i + k] > t[i] ? (x - t[i]) / (t[i + k] - t[i]) * n[i] : 0.0;
      const double b = t[i + k + 1] > t[i + 1] ? (t[i + k + 1] - x) / (t[i + k + 1] - t[i + 1]) * n[i + 1] : 0.0;
      n[i] = a + b;
    }
  return n[0];
}

// A 6 x 6 grid of faces with the centre-left face deleted (a hole, TSM `f` without a link): a domain that is not
// a rectangle, no T-junction. Analysis-suitability there needs the blending functions to be dual-compatible and
// to sum to one; the sum is checked here point by point from the blending functions themselves.
TEST(Classification, AHoleNeedsDualCompatibilityAndAPartitionOfUnity) {
  test::QuadMesh m;
  for (int j = 0; j <= 6; ++j)
    for (int i = 0; i <= 6; ++i) m.points.push_back({double(i), double(j), 0.1 * i * j});
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i)
      if (!(i == 2 && j == 2)) m.quads.push_back({i + 7 * j, i + 1 + 7 * j, i + 1 + 7 * (j + 1), i + 7 * (j + 1)});
  const io::TsmModel model = io::parse_tsm(test::tsm_text(m), "hole.tsm");
  ASSERT_EQ(model.report.star_points, 0);
  const TSplineSurface surf(model.spline);
  const TSplineClass c = classify(model.spline, surf);
  EXPECT_FALSE(c.rectangular_domain);
  EXPECT_EQ(c.t_junctions, 0);
  EXPECT_EQ(c.crossing_extensions, 0);
  double defect = 0;
  for (const Box<2>& e : surf.elements())
    for (double a : {0.1, 0.5, 0.9})
      for (double b : {0.3, 0.7}) {
        const double x[2] = {e.lo[0] + a * e.extent(0), e.lo[1] + b * e.extent(1)};
        double sum = 0;
        for (const auto& f : surf.basis()) sum += local_bspline(f.knots[0], x[0]) * local_bspline(f.knots[1], x[1]);
        defect = std::max(defect, std::abs(sum - 1));
      }
  EXPECT_EQ(c.standard, defect < 1e-12) << defect;
  EXPECT_EQ(c.analysis_suitable, c.dual.compatible && defect < 1e-12);
  std::printf("hole: sum of blending functions off 1 by up to %.3g, dual-compatible %s, analysis-suitable %s\n", defect,
              c.dual.compatible ? "yes" : "no", c.analysis_suitable ? "yes" : "no");
}

}  // namespace
}  // namespace trivar
