#include "trivar/model/multipatch.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "trivar/model/block.hpp"
#include "trivar/model/model_boundary.hpp"
#include "trivar/model/revolve.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/reparametrization.hpp"
#include "trivar/spline/split.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;

namespace {

using std::numbers::pi;

// The disk r <= 1, z in [0, 1], revolved and cut into `pieces` wedges of equal angle: each wedge has its v0
// face collapsed onto the axis.
VModel wedges(int pieces) {
  TensorSpline<3> rest = revolve<3>(make_rectangle_profile({0, 1}, {0, 1}), Eigen::Vector3d::Zero(),
                                    Eigen::Vector3d::UnitZ(), 2 * pi);
  VModel m;
  for (int k = 1; k < pieces; ++k) {
    auto [piece, tail] = split_at(rest, 2, static_cast<double>(k) / pieces);
    m.add_cell(VCell(piece));
    rest = tail;
  }
  m.add_cell(VCell(rest));
  m.glue();
  return m;
}

}  // namespace

TEST(Multipatch, BlocksHaveRegularValencesAndOrientedLinks) {
  VModel m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        TensorSpline<3> b = test::block_at(i, j, k);
        if (i + 2 * j + 4 * k == 1) b = swap_directions(reverse(b, 0), 1, 2);
        m.add_cell(VCell(b));
      }
  m.glue();
  const MultipatchView v = multipatch_view(m);
  EXPECT_TRUE(v.singular_edges.empty());
  ASSERT_EQ(v.edge_valence.size(), 54u);
  // Cell 0's face u1 meets cell 1's face u1 (u reversed), with (s, t) -> (t, s) (see glue_test).
  EXPECT_EQ(v.links[0][1].cell, 1);
  EXPECT_EQ(v.links[0][1].face, 1);
  EXPECT_EQ(v.links[0][1].orientation, (FaceOrientation{true, false, false}));
  EXPECT_EQ(v.links[0][0].cell, -1);
  int shared = 0;
  for (const auto& l : v.links)
    for (const auto& f : l) shared += f.cell >= 0 ? 1 : 0;
  EXPECT_EQ(shared, 24);
  const WatertightReport w = check_watertight(m);
  EXPECT_TRUE(w.watertight);
  EXPECT_LT(w.max_gap, 1e-14);
}

TEST(Multipatch, WedgesAroundAnAxisHaveCollapsedAndSingularEdges) {
  // Three wedges: the axis edge has valence 3 and is interior (all three cut faces around it are shared), so
  // it is singular; the two ends of the axis, where each wedge's w-edges collapse to a point, are collapsed
  // V-curves. The v0 faces are degenerate (segments) and are not V-surfaces.
  const VModel m3 = wedges(3);
  const MultipatchView v = multipatch_view(m3);
  int collapsed = 0, interior = 0;
  for (const auto& s : v.singular_edges) {
    if (s.kind == SingularEdge::Kind::collapsed) ++collapsed;
    if (s.kind == SingularEdge::Kind::interior_valence) {
      ++interior;
      EXPECT_EQ(s.valence, 3);
    }
  }
  EXPECT_EQ(collapsed, 2);
  EXPECT_EQ(interior, 1);
  EXPECT_TRUE(v.links[0][2].degenerate);
  EXPECT_EQ(m3.topology().num_shared_surfaces(), 3);
  EXPECT_EQ(m3.topology().num_boundary_surfaces(), 9);  // outer, top, bottom per wedge
  EXPECT_TRUE(model_boundary(m3).closed());
  EXPECT_TRUE(check_watertight(m3).watertight);
  EXPECT_NEAR(m3.volume(), pi, 1e-12 * pi);
  // Four wedges: the axis has valence 4, regular; only the collapsed ends remain singular.
  const MultipatchView v4 = multipatch_view(wedges(4));
  EXPECT_EQ(v4.singular_edges.size(), 2u);
}

TEST(Multipatch, WatertightnessReportsParametricGapsOfNonConformingFaces) {
  // Same face geometry but the neighbour's y is parametrised quadratically (a degree-2 reparametrisation of
  // y via moved control points): glued as non-conforming, and the parametric gap is reported.
  const KnotVector k1 = KnotVector::open_uniform(1, 1), k2 = KnotVector::open_uniform(2, 1);
  std::vector<double> pts;
  for (double z : {0.0, 1.0})
    for (double y : {0.0, 0.0, 1.0})  // y(v) = v^2
      for (double x : {1.0, 2.0}) pts.insert(pts.end(), {x, y, z});
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  m.add_cell(VCell(TensorSpline<3>::from_cartesian({k1, k2, k1}, 3, pts)));
  m.glue();
  ASSERT_EQ(m.topology().num_shared_surfaces(), 1);
  ASSERT_EQ(m.topology().non_conforming.size(), 1u);
  const WatertightReport w = check_watertight(m, 0, 9);
  EXPECT_FALSE(w.watertight);
  // Largest |v - v^2| on the 9-point grid: at v = 0.5, 0.25.
  EXPECT_NEAR(w.max_gap, 0.25, 1e-14);
  ASSERT_EQ(w.open_surfaces.size(), 1u);
  EXPECT_THROW(check_watertight(m, 0, 1), Error);
}
