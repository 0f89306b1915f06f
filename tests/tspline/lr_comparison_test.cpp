// Seed 004 ("T-spline vertex grid as interface to LR B-splines"): the same refinement done as a T-mesh and as
// an LR mesh. A cubic tensor mesh on [0, 6]^2 without the line s = 3 gets the segment s = 3, t in [0, 3]; as a
// T-mesh it ends in a T-junction at (3, 3), as an LR refinement it is one mesh line (long enough to split the
// B-splines whose support it traverses). The two bases are computed by unrelated code (rays in the T-image;
// LR splitting and merging) and compared function by function: they differ for the same segment and coincide
// when the LR line is the T-junction's extension.
#include <gtest/gtest.h>

#include <set>

#include "trivar/lr/lr_spline.hpp"
#include "trivar/tspline/local_knots.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"

namespace trivar {
namespace {

using Knots = std::array<std::vector<double>, 2>;

std::set<Knots> lr_basis(double stop) {
  const KnotVector s(3, {0, 0, 0, 0, 1, 2, 4, 5, 6, 6, 6, 6}), t(3, {0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6, 6});
  std::vector<double> c(static_cast<std::size_t>(s.size() * t.size()), 0.0);
  LRSpline<2> lr(TensorSpline<2>({s, t}, 1, false, c));
  lr.insert(MeshRectangle<2>::make(0, 3.0, {3.0, 0.0}, {3.0, stop}));
  std::set<Knots> out;
  for (const auto& b : lr.basis_functions()) {
    EXPECT_EQ(b.gamma, 1.0);
    out.insert(b.knots);
  }
  return out;
}

std::set<Knots> t_basis(double stop) {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? stop : 6.0}});
  }
  const TSpline ts = t_spline_from_segments({3, 3}, g, [](double, double, int, int) { return RationalPoint{}; });
  std::set<Knots> out;
  for (const auto& k : local_knot_vectors(ts)) out.insert(k);
  return out;
}

TEST(TSplineVersusLR, SameSegmentGivesDifferentBases) {
  // The LR line s = 3, t in [0, 3] splits fewer B-splines than the T-junction's rays produce: the T-node at
  // (3, 3) has t-knots 1 2 3 4 5, which no LR B-spline of that mesh has.
  const auto lr = lr_basis(3.0), ts = t_basis(3.0);
  EXPECT_EQ(lr.size(), 75u);
  EXPECT_EQ(ts.size(), 77u);
  EXPECT_TRUE(ts.count(Knots{{{1, 2, 3, 4, 5}, {1, 2, 3, 4, 5}}}));
  EXPECT_FALSE(lr.count(Knots{{{1, 2, 3, 4, 5}, {1, 2, 3, 4, 5}}}));
}

TEST(TSplineVersusLR, TJunctionExtensionGivesTheLRBasis) {
  // Seed 004: the T-spline of a vertex grid is the LR spline of the mesh extended by the T-junction's face
  // extension (here t up to 5): the same 77 functions.
  const auto lr = lr_basis(5.0), ts = t_basis(3.0);
  EXPECT_EQ(ts.size(), lr.size());
  EXPECT_EQ(ts, lr);
}

}  // namespace
}  // namespace trivar
