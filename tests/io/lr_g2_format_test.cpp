#include "trivar/io/lr_g2_format.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "io_test_support.hpp"
#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

using test::as;
using test::mid_knot;
using test::replaced;

// A biquadratic-by-linear LR surface on [0, 3] x [0, 2] written by hand in GoTools' LRSplineSurface stream
// format: u-knots 0 1 2 3 (degree 2, clamped), v-knots 0 1 2 (degree 1), and the mesh line u = 1.5 for v in
// [0, 1] only (a T-junction at (1.5, 1)). The line splits the three u-functions crossing 1.5 times the
// v-function [0 0 1] into four (gammas merge to 1). Coefficients are the Greville abscissae (u: mean of the
// interior local knots, v: the middle knot), so the surface is the identity (u, v) -> (u, v) by linear
// precision. Knot indices refer to the distinct knots u: 0 1 1.5 2 3, v: 0 1 2.
constexpr const char* kTSurface =
    "293 1 0 0\n"
    "0 1e-08\n"
    "5 0 1 1.5 2 3\n"
    "3 0 1 2\n"
    "5\n"
    "1 0 3\n"
    "1 0 1\n"
    "2 0 1 1 0\n"
    "1 0 1\n"
    "1 0 3\n"
    "3\n"
    "1 0 2\n"
    "1 0 1\n"
    "1 0 2\n"
    "16\n"
    // unsplit: A = [0 0 0 1] x {a, b, c}
    "2 0\n0 0 1 1\n4 0 0 0 1\n3 0 0 1\n"
    "2 0\n0 1 1 1\n4 0 0 0 1\n3 0 1 2\n"
    "2 0\n0 2 1 1\n4 0 0 0 1\n3 1 2 2\n"
    // B = [0 0 1 2], C = [0 1 2 3], D = [1 2 3 3] times b = [0 1 2] and c = [1 2 2]
    "2 0\n0.5 1 1 1\n4 0 0 1 3\n3 0 1 2\n"
    "2 0\n0.5 2 1 1\n4 0 0 1 3\n3 1 2 2\n"
    "2 0\n1.5 1 1 1\n4 0 1 3 4\n3 0 1 2\n"
    "2 0\n1.5 2 1 1\n4 0 1 3 4\n3 1 2 2\n"
    "2 0\n2.5 1 1 1\n4 1 3 4 4\n3 0 1 2\n"
    "2 0\n2.5 2 1 1\n4 1 3 4 4\n3 1 2 2\n"
    // E = [2 3 3 3] x {a, b, c}
    "2 0\n3 0 1 1\n4 3 4 4 4\n3 0 0 1\n"
    "2 0\n3 1 1 1\n4 3 4 4 4\n3 0 1 2\n"
    "2 0\n3 2 1 1\n4 3 4 4 4\n3 1 2 2\n"
    // the children of the split, times a = [0 0 1]
    "2 0\n0.5 0 1 1\n4 0 0 1 2\n3 0 0 1\n"
    "2 0\n1.25 0 1 1\n4 0 1 2 3\n3 0 0 1\n"
    "2 0\n1.75 0 1 1\n4 1 2 3 4\n3 0 0 1\n"
    "2 0\n2.5 0 1 1\n4 2 3 4 4\n3 0 0 1\n";

// The unit cube as a trilinear LRSplineVolume (one element), identity map; GoTools' 3D mesh rectangles are
// index boxes in the cyclic direction pairs (v, w), (w, u), (u, v). Written with two auxiliary header values.
constexpr const char* kG2Cube =
    "793 1 0 2 0 0\n"
    "0 1e-08\n"
    "2 0 1\n2 0 1\n2 0 1\n"
    "2\n1 0 0 1 1 2\n1 0 0 1 1 2\n"
    "2\n1 0 0 1 1 2\n1 0 0 1 1 2\n"
    "2\n1 0 0 1 1 2\n1 0 0 1 1 2\n"
    "8\n"
    "3 0\n0 0 0 1 1\n3 0 0 1\n3 0 0 1\n3 0 0 1\n"
    "3 0\n1 0 0 1 1\n3 0 1 1\n3 0 0 1\n3 0 0 1\n"
    "3 0\n0 1 0 1 1\n3 0 0 1\n3 0 1 1\n3 0 0 1\n"
    "3 0\n1 1 0 1 1\n3 0 1 1\n3 0 1 1\n3 0 0 1\n"
    "3 0\n0 0 1 1 1\n3 0 0 1\n3 0 0 1\n3 0 1 1\n"
    "3 0\n1 0 1 1 1\n3 0 1 1\n3 0 0 1\n3 0 1 1\n"
    "3 0\n0 1 1 1 1\n3 0 0 1\n3 0 1 1\n3 0 1 1\n"
    "3 0\n1 1 1 1 1\n3 0 1 1\n3 0 1 1\n3 0 1 1\n";

template <int D>
std::vector<Param<D>> params_in(const Box<D>& box, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Param<D>> out(static_cast<std::size_t>(n));
  for (auto& u : out)
    for (int k = 0; k < D; ++k) u[k] = std::uniform_real_distribution<double>(box.lo[k], box.hi[k])(rng);
  return out;
}

std::string g2_text(const AnyLRSpline& s) {
  std::ostringstream os;
  io::write_lr_g2(os, s);
  return os.str();
}

// A distinct interior knot of direction k (partial rectangles must end on mesh lines).
template <int D>
LRSpline<D> refined_g2_case(bool rational, unsigned seed) {
  Ints<D> degrees, elements;
  for (int k = 0; k < D; ++k) {
    degrees[k] = 2 + (k % 2);
    elements[k] = 3;
  }
  const TensorSpline<D> t = test::random_spline<D>(degrees, elements, 3, rational, seed);
  LRSpline<D> lr(t);
  const Box<D> d = lr.domain();
  const auto at = [&](int k, double f) { return d.lo[k] + f * (d.hi[k] - d.lo[k]); };
  Param<D> lo = d.lo, hi = d.hi;
  hi[1] = mid_knot(t, 1);
  lr.insert(MeshRectangle<D>::make(0, at(0, 0.4), lo, hi));
  lo = d.lo;
  hi = d.hi;
  hi[0] = mid_knot(t, 0);
  lr.insert(MeshRectangle<D>::make(1, at(1, 0.25), lo, hi));
  lr.insert(MeshRectangle<D>::make(D - 1, at(D - 1, 0.8), d.lo, d.hi, 2));
  return lr;
}

// GoTools stores gamma * c (polynomial) or the Cartesian point with a weight that includes gamma (rational),
// so control values come back through one multiplication and one division: to a few ulps, not bit for bit.
// Knots, scaling factors and the mesh are stored as they are and must match exactly.
template <int D>
void expect_equivalent(const LRSpline<D>& a, const LRSpline<D>& b) {
  ASSERT_EQ(a.num_basis(), b.num_basis());
  ASSERT_EQ(a.num_elements(), b.num_elements());
  EXPECT_EQ(a.dim(), b.dim());
  EXPECT_EQ(a.is_rational(), b.is_rational());
  for (int i = 0; i < a.num_basis(); ++i) {
    const auto &x = a.basis_function(i), &y = b.basis_function(i);
    for (int k = 0; k < D; ++k) EXPECT_EQ(x.knots[k], y.knots[k]) << "B-spline " << i;
    EXPECT_EQ(x.gamma, y.gamma) << "B-spline " << i;
    ASSERT_EQ(x.coef.size(), y.coef.size());
    for (std::size_t j = 0; j < x.coef.size(); ++j)
      EXPECT_NEAR(x.coef[j], y.coef[j], 4 * std::numeric_limits<double>::epsilon() * std::abs(x.coef[j]))
          << "B-spline " << i << " value " << j;
  }
  std::vector<double> p(static_cast<std::size_t>(a.dim())), q(p.size());
  for (const Param<D>& u : params_in(a.domain(), 100, 9)) {
    a.eval(u, p.data());
    b.eval(u, q.data());
    for (std::size_t j = 0; j < p.size(); ++j) EXPECT_NEAR(p[j], q[j], 1e-14 * (1 + std::abs(p[j])));
  }
}

void expect_g2_error(const std::string& text, const std::string& fragment) {
  try {
    io::parse_lr_g2(text, "bad.g2");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("bad.g2:", 0), 0u) << m;
    EXPECT_NE(m.find(fragment), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

}  // namespace

TEST(LrG2Format, HandWrittenTJunctionSurfaceIsTheIdentity) {
  const auto objects = io::parse_lr_g2(kTSurface, "t.g2");
  ASSERT_EQ(objects.size(), 1u);
  const LRSpline<2>& s = as<2>(objects[0]);
  EXPECT_EQ(s.num_basis(), 16);
  EXPECT_EQ(s.num_elements(), 7);
  EXPECT_EQ(s.degree(0), 2);
  EXPECT_EQ(s.degree(1), 1);
  double x[2];
  for (const Param<2>& u : params_in(s.domain(), 300, 1)) {
    s.eval(u, x);
    EXPECT_NEAR(x[0], u[0], 1e-14);
    EXPECT_NEAR(x[1], u[1], 1e-14);
  }
}

TEST(LrG2Format, HandWrittenCubeWithAuxiliaryHeaderValues) {
  const auto objects = io::parse_lr_g2(kG2Cube, "cube.g2");
  const LRSpline<3>& cube = as<3>(objects.at(0));
  EXPECT_EQ(cube.num_basis(), 8);
  EXPECT_EQ(cube.num_elements(), 1);
  double x[3];
  for (const Param<3>& u : params_in(cube.domain(), 50, 2))
    for (cube.eval(u, x); const int k : {0, 1, 2}) EXPECT_NEAR(x[k], u[k], 1e-15);
}

TEST(LrG2Format, RationalConventionWeightIncludesGamma) {
  // A rational bilinear square: GoTools stores the Cartesian point and the weight; the value is
  // sum c_i w_i B_i / sum w_i B_i. With weights 1, 2, 2, 4 (w_u * w_v for w_u = 1, 2) the u-parameter
  // maps are x = 2u / (1 + u) and y = 2v / (1 + v) for the control points 0, 1.
  const std::string text =
      "293 1 0 0\n1 1e-08\n2 0 1\n2 0 1\n2\n1 0 2\n1 0 2\n2\n1 0 2\n1 0 2\n4\n"
      "2 1\n0 0 1 1\n3 0 0 1\n3 0 0 1\n"
      "2 1\n1 0 1 2\n3 0 1 1\n3 0 0 1\n"
      "2 1\n0 1 1 2\n3 0 0 1\n3 0 1 1\n"
      "2 1\n1 1 1 4\n3 0 1 1\n3 0 1 1\n";
  const auto objects = io::parse_lr_g2(text, "r.g2");
  const LRSpline<2>& s = as<2>(objects.at(0));
  ASSERT_TRUE(s.is_rational());
  double x[2];
  for (const Param<2>& u : params_in(s.domain(), 50, 3)) {
    s.eval(u, x);
    EXPECT_NEAR(x[0], 2 * u[0] / (1 + u[0]), 1e-15);
    EXPECT_NEAR(x[1], 2 * u[1] / (1 + u[1]), 1e-15);
  }
  // Written back, the weights and points are GoTools' again.
  EXPECT_EQ(g2_text(objects[0]).substr(text.find("\n4\n")), text.substr(text.find("\n4\n")));
}

TEST(LrG2Format, RefinedSplinesRoundTripToRounding) {
  for (bool rational : {false, true}) {
    const LRSpline<2> s = refined_g2_case<2>(rational, 4);
    const LRSpline<3> v = refined_g2_case<3>(rational, 5);
    const auto back = io::parse_lr_g2(g2_text(s) + g2_text(v), "two.g2");
    ASSERT_EQ(back.size(), 2u);
    expect_equivalent(s, as<2>(back[0]));
    expect_equivalent(v, as<3>(back[1]));
    bool scaled = false;
    for (const auto& b : v.basis_functions()) scaled |= b.gamma != 1.0;
    EXPECT_TRUE(scaled) << "the refinement should produce scaled B-splines";
  }
}

TEST(LrG2Format, FileRoundTripAndAtomicFailure) {
  test::TempDir dir;
  const std::vector<AnyLRSpline> objects = {refined_g2_case<3>(true, 6), io::parse_lr_g2(kTSurface, "t.g2").at(0)};
  io::write_lr_g2(dir.file("a.g2"), objects);
  const auto back = io::read_lr_g2(dir.file("a.g2"));
  ASSERT_EQ(back.size(), 2u);
  expect_equivalent(as<3>(objects[0]), as<3>(back[0]));
  EXPECT_THROW(io::write_lr_g2(dir.file("b.g2"), std::vector<AnyLRSpline>{}), Error);
  EXPECT_EQ(dir.entries(), 1);
  EXPECT_THROW(io::read_lr_g2(dir.file("missing.g2")), Error);
}

TEST(LrG2Format, MalformedInputFailsWithLineAndReason) {
  const std::string t = kTSurface;
  expect_g2_error("", "no LR spline");
  expect_g2_error("200 1 0 0\n", "unsupported class type 200");
  expect_g2_error(replaced(t, "293 1 0 0", "293 2 0 0"), "major version");
  expect_g2_error(t.substr(0, t.size() / 2), "end of file");
  expect_g2_error(replaced(t, "5 0 1 1.5 2 3", "5 0 1 1.5 1.5 3"), "increase strictly");
  expect_g2_error(replaced(t, "2 0 1 1 0", "2 0 1 5 0"), "out of range");
  expect_g2_error(replaced(t, "2 0\n0 1 1 1\n", "2 1\n0 1 1 1\n"), "rational flag");
  expect_g2_error(replaced(t, "2 0\n0 1 1 1\n", "3 0\n0 1 0 1 1\n"), "dimension 3");
  expect_g2_error(replaced(t, "4 0 0 1 3\n3 0 1 2\n", "3 0 0 1\n3 0 1 2\n"), "degree 1");
  expect_g2_error(replaced(t, "0.5 1 1 1", "0.5 1 0 1"), "gamma must be positive");
  expect_g2_error(replaced(t, "0.5 1 1 1", "0.5 1 1 x"), "expected weight");
  expect_g2_error(replaced(t, "4 0 0 0 1\n3 0 0 1", "4 0 0 0 9\n3 0 0 1"), "knot index 9");
  // The LRSpline constructor's verdict comes with the position of the object's header.
  expect_g2_error(replaced(t, "2 0 1 1 0", "1 0 0"), "bad.g2:1:");
}
