#include "trivar/io/g2_format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/io_test_support.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

TEST(G2Format, PolynomialAndRationalRoundTripsAreBitExact) {
  test::TempDir dir;
  for (bool rational : {false, true}) {
    const auto objects = test::random_objects(rational, rational ? 21 : 22);
    io::write_g2(dir.file("o.g2"), objects);
    const auto back = io::read_g2(dir.file("o.g2"));
    ASSERT_EQ(back.size(), objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) test::expect_identical(objects[i], back[i]);
  }
}

TEST(G2Format, AwkwardNumbersRoundTrip) {
  test::TempDir dir;
  // Three homogeneous points (x, y, z, w) with weights 1.5, 1e8 and 1e-3 (within the accepted ratio 1e12).
  const std::vector<double> h = {1.0 / 3,
                                 -0.0,
                                 0.1,
                                 1.5,
                                 1e-300,
                                 std::numeric_limits<double>::max(),
                                 std::numeric_limits<double>::denorm_min(),
                                 1e8,
                                 0.5,
                                 std::nextafter(1.0, 0.0),
                                 -1e22,
                                 1e-3};
  const SplineCurve c({KnotVector(1, {-1.0 / 7, -1.0 / 7, 0.1 + 0.2, 0.7, 0.7})}, 3, true, h);
  io::write_g2(dir.file("a.g2"), {c});
  test::expect_identical(c, io::read_g2(dir.file("a.g2")).at(0));
}

// GoTools layout: header, "dim rational", per direction "ncoef order" and the knots, then homogeneous
// coefficients (w*x, w*y, w), one per line.
TEST(G2Format, WritesGoToolsLayout) {
  test::TempDir dir;
  const SplineCurve c = SplineCurve::from_cartesian({KnotVector(1, {0, 0, 1, 1})}, 2, std::vector<double>{1, 2, 3, 4},
                                                    std::vector<double>{1, 0.5});
  io::write_g2(dir.file("c.g2"), {c});
  std::ifstream in(dir.file("c.g2"));
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "100 1 0 0\n2 1\n2 2\n0 0 1 1\n1 2 1\n1.5 2 0.5\n");
}

TEST(G2Format, ReadsHandWrittenSurfaceAndQuarterCircle) {
  const auto objects = io::read_g2(TRIVAR_TEST_DATA "/io/curve_surface.g2");
  ASSERT_EQ(objects.size(), 2u);

  // Bilinear patch on [0,1] x [0,2] through (0,0,0), (1,0,0), (0,1,1), (1,1,-1).
  const auto& s = std::get<SplineSurface>(objects[0]);
  EXPECT_FALSE(s.is_rational());
  double x[3];
  for (const Param<2>& u : {Param<2>{0.25, 1.5}, Param<2>{0.8, 0.3}, Param<2>{1, 2}, Param<2>{0, 0}}) {
    s.eval(u, x);
    const double a = u[0], b = u[1] / 2;
    EXPECT_NEAR(x[0], a, 1e-15);
    EXPECT_NEAR(x[1], b, 1e-15);
    EXPECT_NEAR(x[2], (1 - a) * b - a * b, 1e-15);
  }

  // Rational quadratic quarter of the unit circle in the xy plane, weights 1, 1/sqrt(2), 1.
  const auto& c = std::get<SplineCurve>(objects[1]);
  ASSERT_TRUE(c.is_rational());
  EXPECT_EQ(c.weight(1), 0.7071067811865476);
  c.control_point(1, x);
  EXPECT_EQ(x[0], 1.0);
  EXPECT_EQ(x[1], 1.0);
  for (int i = 0; i <= 20; ++i) {
    c.eval({i / 20.0}, x);
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0, 1e-15);
    EXPECT_EQ(x[2], 0.0);
  }
  c.eval({0.5}, x);  // symmetric weights: the parameter midpoint is the 45 degree point
  EXPECT_NEAR(x[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(x[1], std::sqrt(0.5), 1e-15);
}

TEST(G2Format, EmptySplineCannotBeWritten) {
  test::TempDir dir;
  EXPECT_THROW(
      io::write_g2(dir.file("e.g2"), {test::random_spline<3>({1, 1, 1}, {1, 1, 1}, 3, false, 23), AnySpline{}}), Error);
  EXPECT_EQ(dir.entries(), 0);
}

// The g2 reader goes through the same knot validation as every other reader and names line and direction.
TEST(G2Format, SubnormalKnotSpansAreRejectedWithTheirDirection) {
  test::TempDir dir;
  const std::string path = dir.file("s.g2");
  std::ofstream(path) << "100 1 0 0\n2 0\n4 3\n0 0 0 1e-320 1 1 1\n0 0\n1 0\n2 1\n3 1\n";
  try {
    io::read_g2(path);
    FAIL() << "expected trivar::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ":4: invalid knot vector in direction u: knot vector: span [t_2, t_3] = "
                                            "[0, 1e-320] is non-zero but shorter than 1e-12 (1e-12 of the domain length)");
  }
}
