// Splitting V-models by a plane and by a B-spline surface: the volumes on either side against closed forms,
// the cut shared by the cells on both sides, attributes carried, and the errors.
#include <gtest/gtest.h>

#include <numbers>

#include <Eigen/Core>

#include "trivar/cad/split.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/primitives.hpp"
#include "trivar/model/trimmed_integral.hpp"
#include "trivar/model/trimmed_tessellation.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;

namespace {

using std::numbers::pi;

// Volume of the result cells on the positive side of the plane n.x = d, each cell's side told by the sign of its
// mean n.x - d (every cell of a split lies on one side of the cut): int (n.x - d) dV by the exact-boundary rule,
// with the antiderivative in x of n.x - d.
double volume_on_positive_side(const VModel& m, const std::array<double, 3>& n, double d) {
  double v = 0;
  for (const VCell& c : m.cells()) {
    const double moment = trimmed_integral(c.trim()->boundary(), [&](const std::array<double, 3>& x) {
      return 0.5 * n[0] * x[0] * x[0] + (n[1] * x[1] + n[2] * x[2] - d) * x[0];
    });
    if (moment > 0) v += c.trim()->volume();
  }
  return v;
}

}  // namespace

// The unit ball (7 cells) cut by z = 0.3: the cap above is pi h^2 (3R - h) / 3 with h = 0.7, every cell the
// plane crosses becomes two, and the cut faces are shared by the cells on both sides.
TEST(Split, BallByAPlaneGivesTheSphericalCap) {
  VModel ball = test::glued(make_ball({1.0, Eigen::Vector3d::Zero()}));
  for (int c = 0; c < ball.num_cells(); ++c) ball.cell(c).set_attribute("density", Attribute::constant({2.5}));
  cad::BooleanReport rep;
  const VModel parts = cad::split(ball, cad::SplitPlane{{0, 0, 0.3}, {0, 0, 2}}, {}, &rep);
  const double h = 0.7, cap = pi * h * h * (3 - h) / 3, whole = 4 * pi / 3;
  EXPECT_NEAR(parts.volume(), whole, 1e-8 * whole);
  EXPECT_NEAR(volume_on_positive_side(parts, {0, 0, 1}, 0.3), cap, 1e-8 * cap);
  EXPECT_EQ(rep.cells, rep.pieces_a_only + rep.pieces_both);
  EXPECT_GE(rep.pieces_both, 1);
  EXPECT_GT(rep.cells, 7);
  EXPECT_GT(rep.interior_faces, 0);
  for (const VCell& c : parts.cells()) EXPECT_DOUBLE_EQ(c.attribute("density").values()[0], 2.5);
  const ModelTessellation t = trimmed_boundary_mesh(parts);
  EXPECT_TRUE(is_watertight(t.mesh));
  EXPECT_EQ(euler_characteristic(t.mesh), 2);
  // A tilted plane through the centre halves the ball; its cuts across the rational sphere patches are the
  // kernel's approximations of the intersection curves (not lines of the patches as z = 0.3 is), hence 1e-7.
  const VModel halves = cad::split(ball, cad::SplitPlane{{0, 0, 0}, {1, 1, 1}});
  EXPECT_NEAR(volume_on_positive_side(halves, {1, 1, 1}, 0), whole / 2, 1e-7 * whole);
}

// The unit cube cut by the quadratic graph z = 0.3 + 0.4 x (1 - x) (a Bezier surface over [-0.5, 1.5]^2, its
// normal upwards): the part below is 0.3 + 0.4 / 6.
TEST(Split, CubeByABsplineSurface) {
  const VModel cube = test::glued(make_box({Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Zero()}));
  // Control points by blossoming z(x) at x in {-0.5, 1.5}: f(-.5,-.5) = 0, f(-.5, 1.5) = 0.8, f(1.5, 1.5) = 0.
  std::vector<double> pts;
  for (double y : {-0.5, 1.5})
    for (const auto& [x, z] : {std::pair{-0.5, 0.0}, std::pair{0.5, 0.8}, std::pair{1.5, 0.0}}) pts.insert(pts.end(), {x, y, z});
  const TensorSpline<2> s =
      TensorSpline<2>::from_cartesian({KnotVector::open_uniform(2, 1), KnotVector::open_uniform(1, 1)}, 3, pts);
  cad::BooleanReport rep;
  const VModel parts = cad::split(cube, s, {}, &rep);
  EXPECT_EQ(rep.cells, 2);
  EXPECT_EQ(rep.interior_faces, 1);
  const double below = 0.3 + 0.4 / 6;
  ASSERT_EQ(parts.num_cells(), 2);
  const double v0 = parts.cell(0).trim()->volume(), v1 = parts.cell(1).trim()->volume();
  EXPECT_NEAR(std::min(v0, v1), below, 1e-8);
  EXPECT_NEAR(v0 + v1, 1.0, 1e-9);
}

TEST(Split, BadInputIsOneLineError) {
  const VModel cube = test::glued(make_box({Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Zero()}));
  EXPECT_THROW(cad::split(cube, cad::SplitPlane{{0, 0, 5}, {0, 0, 1}}), Error);  // misses the model
  EXPECT_THROW(cad::split(cube, cad::SplitPlane{{0, 0, 0.5}, {0, 0, 0}}), Error);
  EXPECT_THROW(cad::parse_split_plane("0,0,1"), Error);
  EXPECT_THROW(cad::parse_split_plane("0,0,1,0,0,1,7"), Error);
  const cad::SplitPlane p = cad::parse_split_plane("1,2,3,0,0,-1");
  EXPECT_EQ(p.point[1], 2);
  EXPECT_EQ(p.normal[2], -1);
}
