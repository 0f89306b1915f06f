// Seed 004: vertex insertions in the T-spline vertex grid as LR refinements in the u-extended box mesh. A cubic
// tensor mesh on [0, 8]^2 (unit knot intervals, open ends) is refined by a sequence of insertions; after each,
// the T-spline blending functions (rays in the refined T-mesh) and the LR B-splines (the tensor spline refined
// by the mesh lines lr_refinement gives) are computed by unrelated code and compared by their local knots.
#include <gtest/gtest.h>

#include <set>

#include "trivar/core/error.hpp"
#include "trivar/lr/lr_spline.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/local_knots.hpp"
#include "trivar/tspline/vertex_insertion.hpp"

namespace trivar {
namespace {

using Knots = std::array<std::vector<double>, 2>;

std::vector<KnotSegment> tensor_grid() {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 8; ++i) {
    g.push_back({{0.0, double(i)}, {8.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), 8.0}});
  }
  return g;
}

LRSpline<2> tensor_lr() {
  const KnotVector k(3, {0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 8, 8, 8});
  return LRSpline<2>(TensorSpline<2>({k, k}, 1, false, std::vector<double>(121, 0.0)));
}

TSpline t_spline(const std::vector<KnotSegment>& g) {
  return t_spline_from_segments({3, 3}, g, [](double, double, int, int) { return RationalPoint{}; });
}

struct Comparison {
  std::size_t t_functions = 0, lr_functions = 0, common = 0;
};

Comparison compare(const TSpline& ts, const LRSpline<2>& lr) {
  std::set<Knots> a, b;
  for (auto& k : local_knot_vectors(ts)) a.insert(k);
  for (const auto& f : lr.basis_functions()) b.insert(f.knots);
  Comparison c{a.size(), b.size(), 0};
  for (const auto& k : a) c.common += b.count(k);
  return c;
}

TEST(VertexInsertion, JointKindsAndTheirLRLines) {
  auto g = tensor_grid();
  EXPECT_EQ(insert_vertex(g, {4.5, 4.0, {}}), Joint::single);
  EXPECT_EQ(insert_vertex(g, {2.5, 3.0, {true, false, false, false}}), Joint::t);
  EXPECT_EQ(insert_vertex(g, {5.5, 5.5, {true, false, true, false}}), Joint::i);
  const TSpline ts = t_spline(g);
  // The single vertex on the line t = 4 adds the knot s = 4.5 over its function's t-support [2, 6].
  const auto single = lr_refinement(ts, {4.5, 4.0, {}});
  ASSERT_EQ(single.size(), 1u);
  EXPECT_EQ(single[0].dir, 0);
  EXPECT_EQ(single[0].value, 4.5);
  EXPECT_EQ(single[0].extent.lo[1], 2.0);
  EXPECT_EQ(single[0].extent.hi[1], 6.0);
  // The I-joint's vertical line s = 5.5 through (5.5, 5.5): t-knots 4 5 5.5 6 7.
  const auto i = lr_refinement(ts, {5.5, 5.5, {true, false, true, false}});
  ASSERT_EQ(i.size(), 1u);
  EXPECT_EQ(i[0].extent.lo[1], 4.0);
  EXPECT_EQ(i[0].extent.hi[1], 7.0);
  // Malformed insertions.
  auto h = tensor_grid();
  EXPECT_THROW(insert_vertex(h, {4.0, 4.0, {}}), Error);                              // already a vertex
  EXPECT_THROW(insert_vertex(h, {4.5, 4.5, {}}), Error);                              // single vertex in a face
  EXPECT_THROW(insert_vertex(h, {4.5, 4.5, {true, false, false, false}}), Error);     // dangling arm
  EXPECT_THROW(insert_vertex(h, {4.5, 4.5, {true, false, false, true}}), Error);      // L-joint in a face
  EXPECT_THROW(insert_vertex(h, {4.5, 4.0, {false, true, false, false}}), Error);     // arm along the edge
}

// Insertions one after another; after each the T-spline and the LR spline of the same refinements, counted by
// distinct local knot vectors. Measured (T, LR, common):
//   T-joint from the boundary, one interval long: 124, 123, 119. The boundary vertex brings two T-nodes (its
//     Bezier layer) and the T-junction at (3.5, 1) a third; the LR line s = 3.5 over the new functions' support
//     t in [0, 2] splits two B-splines, and the functions near the T-junction have other knots in the two.
//   the same line continued by T-joints up to t = 4: the two coincide (125, 126, 127 functions, all common):
//     LR's u-extended lines reach the T-junction's face extension, the case seed 004 reports as the usual one.
//   a single vertex on the line t = 4: both 128, 124 common (the T-spline's new function has the knot s = 4.5
//     only on its own, LR's split B-splines carry it on the line over t in [2, 6]).
//   I-joints, lines of one interval: the T-spline gains three functions each (131, 134) and stays
//     analysis-suitable and linearly independent, LR's line over the new support (3 intervals) splits no
//     B-spline (seed 004: segments shorter than p + 1 add no dimension) or one (128, 131).
// The T-spline functions with knots off LR's lines are where the two differ; lines reaching the extensions
// make them coincide.
TEST(VertexInsertion, TSplineAndLRBasesOnTheSameRefinements) {
  struct Step {
    VertexInsertion v;
    std::size_t t, lr, common;
  };
  auto g = tensor_grid();
  LRSpline<2> lr = tensor_lr();
  const std::vector<Step> steps{
      {{3.5, 0.0, {true, false, false, false}}, 124, 123, 119},  // T-joint on the boundary
      {{3.5, 2.0, {false, false, true, false}}, 125, 125, 125},  // T-joints continuing s = 3.5
      {{3.5, 3.0, {false, false, true, false}}, 126, 126, 126},
      {{3.5, 4.0, {false, false, true, false}}, 127, 127, 127},
      {{4.5, 4.0, {}}, 128, 128, 124},                           // single vertex
      {{5.5, 5.5, {true, false, true, false}}, 131, 128, 116},   // I-joint
      {{6.5, 2.5, {false, true, false, true}}, 134, 131, 106},   // I-joint across
  };
  for (const Step& s : steps) {
    insert_vertex(g, s.v);
    const TSpline ts = t_spline(g);
    const auto lines = lr_refinement(ts, s.v);
    lr.insert(std::span<const MeshRectangle<2>>(lines));
    const Comparison c = compare(ts, lr);
    EXPECT_EQ(c.t_functions, s.t) << s.v.s << " " << s.v.t;
    EXPECT_EQ(c.lr_functions, s.lr) << s.v.s << " " << s.v.t;
    EXPECT_EQ(c.common, s.common) << s.v.s << " " << s.v.t;
    EXPECT_EQ(c.t_functions, ts.connect.nodes.size());  // no two T-nodes with the same knots
    const TSplineClass cls = classify(ts, TSplineSurface(ts));
    EXPECT_TRUE(cls.analysis_suitable);
    EXPECT_EQ(cls.independence, Independence::independent);
  }
}

}  // namespace
}  // namespace trivar
