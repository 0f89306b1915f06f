#include "trivar/model/vmodel.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "trivar/model/block.hpp"
#include "trivar/model/revolve.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/split.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;

namespace {

using std::numbers::pi;

// The field u * v * w on [0, 1]^3 with its own knots (degree 2, 3 elements): coefficients at the Greville
// abscissae reproduce the trilinear product exactly.
TensorSpline<3> uvw_field() {
  const KnotVector kv = KnotVector::open_uniform(2, 3);
  const auto g = kv.greville();
  std::vector<double> c;
  for (double w : g)
    for (double v : g)
      for (double u : g) c.push_back(u * v * w);
  return TensorSpline<3>::from_cartesian({kv, kv, kv}, 1, c);
}

}  // namespace

TEST(VModel, VolumeMassAndBoxOfBlocks) {
  VModel m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) m.add_cell(VCell(test::block_at(i, j, k, {1, 1, 1}, {2, 1, 3}, {1, 2, 2})));
  EXPECT_NEAR(m.volume(), 8.0, 1e-13);
  // Density 1 + x over [0, 2]^3: 8 + 4 * (integral of x over [0, 2]) = 8 + 4 * 2 = 16.
  for (int c = 0; c < 8; ++c) m.cell(c).set_attribute("density", Attribute::expression({"1 + x"}, Attribute::Space::model));
  EXPECT_NEAR(m.mass("density"), 16.0, 1e-12);
  const Box<3> b = m.bounding_box();
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(b.lo[k], 0.0);
    EXPECT_DOUBLE_EQ(b.hi[k], 2.0);
  }
  m.cell(3).set_attribute("density", Attribute::constant({1, 2}));
  EXPECT_THROW(m.mass("density"), Error);
  EXPECT_THROW(m.mass("missing"), Error);
  EXPECT_THROW(m.cell(8), Error);
}

TEST(VModel, MassWithASplineDensityFieldOnItsOwnKnots) {
  // Cell x = 2u, y = v, z = w (det J = 2) with density u v w: mass = 2 / 8. The stretched cell has 2 elements
  // in u, the field 3: the quadrature uses the union of the spans.
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0, {2, 1, 1}, {1, 1, 1}, {2, 1, 1})));
  m.cell(0).set_attribute("rho", Attribute::field(uvw_field()));
  EXPECT_NEAR(m.mass("rho"), 0.25, 1e-14);
}

TEST(VModel, RingVolumeAndMassAreExact) {
  // Annulus r in [1, 2], height 1: volume pi (4 - 1) = 3 pi, in four rational cells.
  const auto full = revolve<3>(make_rectangle_profile({0, 1}, {1, 2}, {2, 1}, {1, 2}), Eigen::Vector3d::Zero(),
                               Eigen::Vector3d::UnitZ(), 2 * pi);
  auto [a, rest] = split_at(full, 2, 0.25);
  auto [b, rest2] = split_at(rest, 2, 0.5);
  auto [c, d] = split_at(rest2, 2, 0.75);
  VModel m;
  for (const auto* s : {&a, &b, &c, &d}) m.add_cell(VCell(*s));
  EXPECT_NEAR(m.volume(), 3 * pi, 1e-12 * 3 * pi);
  // Density r^2 = x^2 + y^2: integral of r^3 dr dtheta dz = 2 pi (16 - 1) / 4.
  for (int k = 0; k < 4; ++k)
    m.cell(k).set_attribute("rho", Attribute::expression({"x^2 + y^2"}, Attribute::Space::model));
  EXPECT_NEAR(m.mass("rho"), 2 * pi * 15 / 4, 1e-11);
  // The control box contains the ring [-2, 2]^2 x [0, 1].
  const Box<3> box = m.bounding_box();
  EXPECT_LE(box.lo[0], -2.0);
  EXPECT_GE(box.hi[1], 2.0);
  EXPECT_DOUBLE_EQ(box.lo[2], 0.0);
  EXPECT_DOUBLE_EQ(box.hi[2], 1.0);
}

TEST(VModel, AddingACellDropsTheTopology) {
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  m.glue();
  EXPECT_TRUE(m.is_glued());
  m.add_cell(VCell(test::block_at(1, 0, 0)));
  EXPECT_FALSE(m.is_glued());
  EXPECT_THROW(m.relation(0, 1), Error);
  m.glue();
  EXPECT_EQ(m.relation(0, 1), CellRelation::face);
}
