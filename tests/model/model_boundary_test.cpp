#include "trivar/model/model_boundary.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <Eigen/Geometry>

#include "trivar/model/attribute_blend.hpp"
#include "trivar/model/block.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/reparametrization.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;

namespace {

// 2 x 2 x 2 blocks; cell 5 with a left-handed parametrisation (u reversed) and cell 6 with v, w swapped.
VModel blocks(bool mixed) {
  VModel m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        TensorSpline<3> b = test::block_at(i, j, k);
        const int c = i + 2 * j + 4 * k;
        if (mixed && c == 5) b = reverse(b, 0);
        if (mixed && c == 6) b = swap_directions(b, 1, 2);
        m.add_cell(VCell(b));
      }
  m.glue();
  return m;
}

}  // namespace

TEST(ModelBoundary, BlocksGiveAClosedBoundaryWithOutwardFlags) {
  for (bool mixed : {false, true}) {
    const VModel m = blocks(mixed);
    const ModelBoundary b = model_boundary(m);
    // 24 boundary faces; 48 boundary edges (the valence-1 and valence-2 curves), each used twice.
    EXPECT_EQ(b.faces.size(), 24u);
    EXPECT_EQ(b.edges.size(), 48u);
    EXPECT_TRUE(b.closed());
    for (const auto& f : b.faces) {
      // Independent normal: central differences of the face at its centre; outward points away from (1,1,1).
      const Box<2> d = f.geometry.domain();
      const Param<2> c = d.center();
      const double h = 1e-4;
      Eigen::Vector3d p, ps0, ps1, pt0, pt1;
      f.geometry.eval(c, p.data());
      f.geometry.eval({c[0] - h, c[1]}, ps0.data());
      f.geometry.eval({c[0] + h, c[1]}, ps1.data());
      f.geometry.eval({c[0], c[1] - h}, pt0.data());
      f.geometry.eval({c[0], c[1] + h}, pt1.data());
      const Eigen::Vector3d n = (ps1 - ps0).cross(pt1 - pt0);
      const bool points_in = n.dot(p - Eigen::Vector3d(1, 1, 1)) < 0;
      EXPECT_EQ(f.inward, points_in) << "cell " << f.cell << " face " << f.face;
    }
  }
}

TEST(ModelBoundary, EdgeContactIsNotAClosedManifold) {
  // Two blocks touching along one edge only: every edge is used exactly twice except the contact edge, which
  // four boundary faces use, so the boundary is not a closed 2-manifold.
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  m.add_cell(VCell(test::block_at(1, 1, 0)));
  m.glue();
  const ModelBoundary b = model_boundary(m);
  EXPECT_EQ(b.faces.size(), 12u);
  EXPECT_FALSE(b.closed());
  int four = 0;
  for (const auto& e : b.edges) four += e.uses.size() == 4 ? 1 : 0;
  EXPECT_EQ(four, 1);
  VModel unglued;
  unglued.add_cell(VCell(test::block_at(0, 0, 0)));
  EXPECT_THROW(model_boundary(unglued), Error);
}

TEST(ModelBoundary, DistanceToBoundary) {
  const VModel m = blocks(true);
  const ModelBoundary b = model_boundary(m);
  const double inside[3] = {0.5, 1.0, 1.2}, outside[3] = {3.0, 1.0, 1.0}, centre[3] = {1, 1, 1};
  EXPECT_NEAR(distance_to_boundary(b, inside), 0.5, 1e-12);
  EXPECT_NEAR(distance_to_boundary(b, outside), 1.0, 1e-12);
  EXPECT_NEAR(distance_to_boundary(b, centre), 1.0, 1e-12);  // internal faces are not boundary
}

TEST(AttributeBlend, UnionFormulaOfSeed001) {
  const double a1[2] = {1, 0}, a2[2] = {0, 1};
  double out[2];
  blend_union(a1, a2, true, true, 3.0, 1.0, out);  // (3 A1 + 1 A2) / 4
  EXPECT_DOUBLE_EQ(out[0], 0.75);
  EXPECT_DOUBLE_EQ(out[1], 0.25);
  blend_union(a1, a2, true, false, 3.0, 1.0, out);
  EXPECT_EQ(out[0], 1.0);
  EXPECT_EQ(out[1], 0.0);
  blend_union(a1, a2, false, true, 0.0, 0.0, out);
  EXPECT_EQ(out[1], 1.0);
  blend_union(a1, a2, true, true, 0.0, 0.0, out);
  EXPECT_EQ(out[0], 0.5);
  EXPECT_THROW(blend_union(a1, a2, false, false, 1, 1, out), Error);
}

TEST(AttributeBlend, OverlappingBlocksBlendByBoundaryDistances) {
  // V1 = [0, 2] x [0, 1]^2 with A1 = 1, V2 = [1, 3] x [0, 1]^2 with A2 = 0. At x = (1.25, 0.5, 0.5): distance to
  // the boundary of V1 is min(0.75, 0.5) = 0.5 and to V2's 0.25, so A = 0.5 / 0.75 = 2/3.
  VModel m1, m2;
  m1.add_cell(VCell(test::block_at(0, 0, 0, {2, 1, 1})));
  m2.add_cell(VCell(test::block_at(1, 0, 0, {2, 1, 1})));
  m1.cell(0).set_attribute("c", Attribute::constant({1}));
  m2.cell(0).set_attribute("c", Attribute::constant({0}));
  m1.glue();
  m2.glue();
  const UnionBlender blend(m1, m2, "c");
  double out;
  const double both[3] = {1.25, 0.5, 0.5}, only1[3] = {0.5, 0.5, 0.5}, only2[3] = {2.5, 0.5, 0.5}, none[3] = {5, 5, 5};
  ASSERT_TRUE(blend.eval(both, &out));
  EXPECT_NEAR(out, 2.0 / 3.0, 1e-9);
  ASSERT_TRUE(blend.eval(only1, &out));
  EXPECT_EQ(out, 1.0);
  ASSERT_TRUE(blend.eval(only2, &out));
  EXPECT_EQ(out, 0.0);
  EXPECT_FALSE(blend.eval(none, &out));
}
