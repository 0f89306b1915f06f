#include "trivar/model/model_tessellation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "trivar/core/error.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/torus.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;

namespace {

// Every vertex is the cell's geometry at the recorded parameters.
void expect_traceable(const VModel& m, const ModelTessellation& t) {
  ASSERT_EQ(t.cell.size(), t.mesh.vertices.size());
  double x[3];
  for (std::size_t v = 0; v < t.cell.size(); ++v) {
    m.cell(t.cell[v]).geometry().eval(t.param[v], x);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], t.mesh.vertices[v][k], 1e-13);
  }
}

}  // namespace

TEST(ModelTessellation, BallBoundaryIsTheExactSphereAndClosed) {
  const double R = 1.5;
  const VModel ball = test::glued(make_ball({.radius = R}));
  const double exact = 4.0 / 3.0 * std::numbers::pi * R * R * R;
  double previous = 1.0;
  for (double tol : {1e-2, 1e-3}) {
    const ModelTessellation t = tessellate_boundary(ball, {.chordal_tolerance = tol});
    EXPECT_TRUE(is_watertight(t.mesh));
    for (const auto& x : t.mesh.vertices) EXPECT_NEAR(std::hypot(x[0], x[1], x[2]), R, 1e-12);
    expect_traceable(ball, t);
    // Inscribed polyhedron: a little less volume than the ball, converging with the tolerance.
    const double v = enclosed_volume(t.mesh);
    EXPECT_LT(v, exact);
    EXPECT_LT(exact - v, previous);
    EXPECT_LT((exact - v) / exact, 3 * tol / R);
    previous = exact - v;
  }
}

TEST(ModelTessellation, TorusVerticesLieOnTheTube) {
  const double R = 2.0, r = 0.5;
  const VModel torus = test::glued(make_torus({.major_radius = R, .minor_radius = r}));
  const ModelTessellation t = tessellate_boundary(torus, {.chordal_tolerance = 1e-3});
  EXPECT_TRUE(is_watertight(t.mesh));
  for (const auto& x : t.mesh.vertices) EXPECT_NEAR(std::hypot(std::hypot(x[0], x[1]) - R, x[2]), r, 1e-12);
  expect_traceable(torus, t);
  const double exact = 2 * std::numbers::pi * std::numbers::pi * R * r * r;
  EXPECT_NEAR(enclosed_volume(t.mesh), exact, 1e-2 * exact);
}

TEST(ModelTessellation, NeedsAGluedClosedModel) {
  VModel m;
  for (const auto& c : make_ball({})) m.add_cell(VCell(c));
  EXPECT_THROW(tessellate_boundary(m), Error);
}
