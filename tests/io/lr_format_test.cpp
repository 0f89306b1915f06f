#include "trivar/io/lr_format.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "support/spline_fixtures.hpp"
#include "support/temp_dir.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/step/step_file.hpp"
#include "io/io_test_support.hpp"

using namespace trivar;

namespace {

using test::as;
using test::mid_knot;
using test::replaced;

// The unit cube as IFEM's unit tests spell it (orders 2, the identity map), written by LRsplines.
constexpr const char* kCube =
    "# LRSPLINE VOLUME\n"
    "#\tp1\tp2\tp3\tNbasis\tNline\tNel\tdim\trat\n"
    "\t2\t2\t2\t8\t6\t1\t3\t0\n"
    "# Basis functions:\n"
    "0: [0 0 1 ] x [0 0 1 ] x [0 0 1 ] 0 0 0 (1)\n"
    "1: [0 1 1 ] x [0 0 1 ] x [0 0 1 ] 1 0 0 (1)\n"
    "2: [0 0 1 ] x [0 1 1 ] x [0 0 1 ] 0 1 0 (1)\n"
    "3: [0 1 1 ] x [0 1 1 ] x [0 0 1 ] 1 1 0 (1)\n"
    "4: [0 0 1 ] x [0 0 1 ] x [0 1 1 ] 0 0 1 (1)\n"
    "5: [0 1 1 ] x [0 0 1 ] x [0 1 1 ] 1 0 1 (1)\n"
    "6: [0 0 1 ] x [0 1 1 ] x [0 1 1 ] 0 1 1 (1)\n"
    "7: [0 1 1 ] x [0 1 1 ] x [0 1 1 ] 1 1 1 (1)\n"
    "# Mesh rectangles:\n"
    "[0, 0] x [0, 1] x [0, 1] (2)\n"
    "[1, 1] x [0, 1] x [0, 1] (2)\n"
    "[0, 1] x [0, 0] x [0, 1] (2)\n"
    "[0, 1] x [1, 1] x [0, 1] (2)\n"
    "[0, 1] x [0, 1] x [0, 0] (2)\n"
    "[0, 1] x [0, 1] x [1, 1] (2)\n"
    "# Elements:\n"
    "0 [3] : (0, 0, 0) x (1, 1, 1)    {0, 1, 2, 3, 4, 5, 6, 7}\n";

// A bilinear square split once at u = 0.5 (by hand: the two u-functions with support [0, 1] become three with
// local knots [0 0 .5], [0 .5 1], [.5 1 1]); the control points make it the map (u, v) -> (2u, v).
constexpr const char* kSplitSquare =
    "# LRSPLINE SURFACE\n"
    "#\tp1\tp2\tNbasis\tNline\tNel\tdim\trat\n"
    "\t2\t2\t6\t5\t2\t2\t0\n"
    "# Basis functions:\n"
    "10: [0 0 0.5 ] x [0 0 1 ] 0 0 (1)\n"
    "11: [0 0.5 1 ] x [0 0 1 ] 1 0 (1)\n"
    "12: [0.5 1 1 ] x [0 0 1 ] 2 0 (1)\n"
    "13: [0 0 0.5 ] x [0 1 1 ] 0 1 (1)\n"
    "14: [0 0.5 1 ] x [0 1 1 ] 1 1 (1)\n"
    "15: [0.5 1 1 ] x [0 1 1 ] 2 1 (1)\n"
    "# Mesh lines:\n"
    "0 x [0, 1] (2)\n"
    "0.5 x [0, 1] (1)\n"
    "1 x [0, 1] (2)\n"
    "[0, 1] x 0 (2)\n"
    "[0, 1] x 1 (2)\n"
    "# Elements:\n"
    "0 [2] : (0, 0) x (0.5, 1)    {10, 11, 13, 14}\n"
    "1 [2] : (0.5, 0) x (1, 1)    {11, 12, 14, 15}\n";

template <int D>
std::vector<Param<D>> grid_params(int n) {
  std::vector<Param<D>> out;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    Param<D> u;
    for (double& x : u) x = U(rng);
    out.push_back(u);
  }
  return out;
}

std::string lr_text(const AnyLRSpline& s) {
  std::ostringstream os;
  io::write_lr(os, s);
  return os.str();
}

// A distinct interior knot of direction k (partial rectangles must end on mesh lines).
// A refined cubic LR volume: a random tensor spline with three local insertions.
LRSpline<3> refined_volume(bool rational) {
  const TensorSpline<3> t = test::random_spline<3>({3, 2, 3}, {3, 2, 2}, 3, rational, 3);
  LRSpline<3> lr(t);
  const Box<3> d = lr.domain();
  const auto at = [&](int k, double f) { return d.lo[k] + f * (d.hi[k] - d.lo[k]); };
  lr.insert(MeshRectangle<3>::make(0, at(0, 0.5), {0, d.lo[1], d.lo[2]}, {0, d.hi[1], mid_knot(t, 2)}));
  lr.insert(MeshRectangle<3>::make(2, at(2, 0.25), {d.lo[0], d.lo[1], 0}, {mid_knot(t, 0), d.hi[1], 0}));
  lr.insert(MeshRectangle<3>::make(1, at(1, 0.6), {d.lo[0], d.lo[1], d.lo[2]}, {d.hi[0], d.hi[1], d.hi[2]}, 2));
  return lr;
}

template <int D>
void expect_identical(const LRSpline<D>& a, const LRSpline<D>& b) {
  ASSERT_EQ(a.num_basis(), b.num_basis());
  ASSERT_EQ(a.num_elements(), b.num_elements());
  ASSERT_EQ(a.mesh().size(), b.mesh().size());
  std::vector<double> x(static_cast<std::size_t>(a.dim())), y(x.size());
  for (const Param<D>& u : grid_params<D>(200)) {
    Param<D> v;
    for (int k = 0; k < D; ++k) v[k] = a.domain().lo[k] + u[k] * (a.domain().hi[k] - a.domain().lo[k]);
    a.eval(v, x.data());
    b.eval(v, y.data());
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(x[i], y[i]);
  }
}

void expect_lr_error(const std::string& text, const std::string& fragment) {
  try {
    io::parse_lr(text, "bad.lr");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("bad.lr:", 0), 0u) << m;
    EXPECT_NE(m.find(fragment), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

}  // namespace

TEST(LrFormat, ReadsLRsplinesCubeAsTheIdentity) {
  const auto objects = io::parse_lr(kCube, "cube.lr");
  ASSERT_EQ(objects.size(), 1u);
  const LRSpline<3>& cube = as<3>(objects[0]);
  EXPECT_EQ(cube.num_basis(), 8);
  EXPECT_EQ(cube.num_elements(), 1);
  EXPECT_EQ(cube.degree(0), 1);
  double x[3];
  for (const Param<3>& u : grid_params<3>(50)) {
    cube.eval(u, x);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], u[k], 1e-15);
  }
}

TEST(LrFormat, ReadsHandSplitSquareWithArbitraryIds) {
  const auto objects = io::parse_lr(kSplitSquare, "square.lr");
  const LRSpline<2>& sq = as<2>(objects.at(0));
  EXPECT_EQ(sq.num_basis(), 6);
  EXPECT_EQ(sq.num_elements(), 2);
  double x[2];
  for (const Param<2>& u : grid_params<2>(50)) {
    sq.eval(u, x);
    EXPECT_NEAR(x[0], 2 * u[0], 1e-15);
    EXPECT_NEAR(x[1], u[1], 1e-15);
  }
}

TEST(LrFormat, SeveralBlocksRoundTripExactly) {
  const LRSpline<3> poly = refined_volume(false), rat = refined_volume(true);
  const AnyLRSpline square = io::parse_lr(kSplitSquare, "square.lr").at(0);
  const std::string text = lr_text(poly) + lr_text(square) + lr_text(rat);
  const auto back = io::parse_lr(text, "three.lr");
  ASSERT_EQ(back.size(), 3u);
  expect_identical(poly, as<3>(back[0]));
  expect_identical(as<2>(square), as<2>(back[1]));
  expect_identical(rat, as<3>(back[2]));
  EXPECT_TRUE(as<3>(back[2]).is_rational());
  // Writing what was read gives the same text: ids, order and reals are reproduced exactly.
  EXPECT_EQ(lr_text(back[0]) + lr_text(back[1]) + lr_text(back[2]), text);
}

TEST(LrFormat, TensorSplineThroughTheFormatEvaluatesAsTheTensorSpline) {
  const TensorSpline<2> t = test::random_spline<2>({3, 2}, {4, 3}, 3, true, 11);
  const auto back = io::parse_lr(lr_text(LRSpline<2>(t)), "t.lr");
  double a[3], b[3];
  for (const Param<2>& u : test::random_params(t, 200, 5)) {
    as<2>(back.at(0)).eval(u, a);
    t.eval(u, b);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], 1e-13);
  }
}

TEST(LrFormat, MalformedInputFailsWithLineAndReason) {
  const std::string cube = kCube;
  expect_lr_error("", "no LR spline");
  // A knot 1e121 times the domain length (found by the fuzzer): the mesh's cell lookup must not overflow int.
  try {
    io::read_lr(TRIVAR_TEST_DATA "/io/malformed/lr_element_far_outside.lr");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(":34: element 0 of the block, (0, 0) x (2.2222222222222223e+121, 0.25), is "
                                         "not an element of the mesh"),
              std::string::npos)
        << e.what();
  }
  expect_lr_error("# LRSPLINE CURVE\n", "unsupported LR spline kind 'CURVE'");
  expect_lr_error("# comment\n1 2 3\n", "7 values for a surface, 8 for a volume");
  expect_lr_error(cube.substr(0, cube.size() / 2), "expected");
  expect_lr_error(replaced(cube, "\t3\t0\n", "\t3\t2\n"), "rational flag");
  expect_lr_error(replaced(cube, "\t2\t2\t2\t8", "\t0\t2\t2\t8"), "order");
  expect_lr_error(replaced(cube, "3: [0 1 1 ]", "3: [0 1 1 1 ]"), "after a local knot vector");
  expect_lr_error(replaced(cube, "5: [0 1 1 ] x [0 0 1 ] x [0 1 1 ] 1 0 1 (1)", "5: [0 1 1 ] x [0 0 1 ] x [0 1 1 ] 1 0 (1)"),
               "expected control value");
  expect_lr_error(replaced(cube, "7: [", "6: ["), "appears twice");
  expect_lr_error(replaced(cube, "{0, 1, 2, 3, 4, 5, 6, 7}", "{0, 1, 2, 3, 4, 5, 6, 9}"), "unknown basis function 9");
  expect_lr_error(replaced(cube, "[0, 1] x [0, 1] x [1, 1] (2)", "[0, 1] x [1, 1] x [1, 1] (2)"), "two directions");
  expect_lr_error(replaced(cube, "[0, 1] x [0, 0] x [0, 1] (2)", "[1, 0] x [0, 0] x [0, 1] (2)"), "reversed");
  expect_lr_error(replaced(cube, "0 0 0 (1)", "0 0 0 (nan)"), "scaling factor");
  expect_lr_error(replaced(cube, "\t8\t6\t1\t3", "\t8\t6\t2\t3"), "expected element id");
  // Semantic errors come from the LRSpline constructor, with the file position in front.
  expect_lr_error(replaced(cube, "0 0 0 (1)", "0 0 0 (0)"), "bad.lr:");
  expect_lr_error(replaced(cube, "0: [0 0 1 ]", "0: [0 0 2 ]"), "bad.lr:");
}

// An LR volume written by the LRsplines library (degrees 2 3 2, 2684 B-splines, 2478 elements, 73 mesh
// rectangles) through STEP, which stores no mesh: the mesh rebuilt from the B-splines' knot lines has planes
// that are unions of several rectangles, and must give back the same B-splines, elements and geometry.
TEST(LrFormat, LRsplinesVolumeSurvivesStep) {
  const auto in = io::read_lr(std::string(TRIVAR_TEST_DATA) + "/io/lr_volume_lrsplines.lr");
  ASSERT_EQ(in.size(), 1u);
  const LRSpline<3>& a = as<3>(in[0]);
  ASSERT_EQ(a.num_basis(), 2684);
  ASSERT_EQ(a.num_elements(), 2478);
  ASSERT_EQ(a.mesh().size(), 73u);
  const test::TempDir dir;
  io::step::write_step(dir.file("v.stp"), {}, in, {}, "2026-01-01T00:00:00");
  const auto back = io::step::read_step(dir.file("v.stp"));
  ASSERT_EQ(back.lr_splines.size(), 1u);
  const LRSpline<3>& b = as<3>(back.lr_splines[0]);
  ASSERT_EQ(b.num_basis(), a.num_basis());
  for (int i = 0; i < a.num_basis(); ++i) {
    EXPECT_EQ(a.basis_function(i).knots, b.basis_function(i).knots);
    EXPECT_EQ(a.basis_function(i).gamma, b.basis_function(i).gamma);
  }
  const auto boxes = [](const LRSpline<3>& s) {
    std::vector<std::pair<Param<3>, Param<3>>> e;
    for (const Box<3>& x : s.elements()) e.emplace_back(x.lo, x.hi);
    std::sort(e.begin(), e.end());
    return e;
  };
  EXPECT_EQ(boxes(a), boxes(b));
  std::vector<double> x(3), y(3);
  for (const Param<3>& u : grid_params<3>(5000)) {
    a.eval(u, x.data());
    b.eval(u, y.data());
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(x[static_cast<std::size_t>(i)], y[static_cast<std::size_t>(i)], 1e-12);
  }
}

// Older LRsplines versions start a block with a bare "# LRSPLINE" (LRsplines' reader skips every comment line):
// the header line's value count tells a surface (7) from a volume (8).
TEST(LrFormat, ReadsTheOlderBareHeader) {
  const auto s = io::parse_lr(replaced(kSplitSquare, "# LRSPLINE SURFACE", "# LRSPLINE"), "old.lr");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(as<2>(s[0]).num_elements(), 2);
  const auto v = io::parse_lr(replaced(kCube, "# LRSPLINE VOLUME", "# LRSPLINE\n# written by hand"), "old.lr");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(as<3>(v[0]).num_basis(), 8);
  // Two blocks, the second with the old header.
  const auto two = io::parse_lr(std::string(kCube) + replaced(kSplitSquare, "# LRSPLINE SURFACE", "# LRSPLINE"), "two.lr");
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(parametric_dimension(two[1]), 2);
}

// Element ids are the positions in the file's element block, and the writer lists elements in id order.
TEST(LrFormat, ElementIdsAreTheBlockOrder) {
  const std::string swapped =
      replaced(replaced(kSplitSquare, "0 [2] : (0, 0) x (0.5, 1)    {10, 11, 13, 14}\n", ""),
               "1 [2] : (0.5, 0) x (1, 1)    {11, 12, 14, 15}\n",
               "1 [2] : (0.5, 0) x (1, 1)    {11, 12, 14, 15}\n0 [2] : (0, 0) x (0.5, 1)    {10, 11, 13, 14}\n");
  const auto s = io::parse_lr(swapped, "swapped.lr");
  const LRSpline<2>& lr = as<2>(s[0]);
  EXPECT_EQ(lr.element(0).lo, (Param<2>{0.5, 0}));
  EXPECT_EQ(lr.element(1).lo, (Param<2>{0, 0}));
  const std::string text = lr_text(s[0]);
  EXPECT_LT(text.find("0 [2] : (0.5, 0) x (1, 1)"), text.find("1 [2] : (0, 0) x (0.5, 1)")) << text;
  EXPECT_EQ(lr_text(io::parse_lr(text, "again.lr")[0]), text);
}

// The literature's cross (cubic, 10 x 10 B-splines, lines u = 3.5 and v = 3.5 over [1, 5]): a block that lists
// the mesh's 58 elements is read; one that lists the 49 elements of the mesh without the cross names the first
// listed element the cross cuts.
TEST(LrFormat, ElementBlockMustListTheMeshElements) {
  const auto kv = KnotVector::open_uniform(3, 7, 0.0, 7.0);
  LRSpline<2> cross(TensorSpline<2>({kv, kv}, 1, false, std::vector<double>(100, 1.0)));
  const std::string tensor = lr_text(cross);
  cross.insert(MeshRectangle<2>::make(0, 3.5, {0, 1}, {0, 5}));
  cross.insert(MeshRectangle<2>::make(1, 3.5, {1, 0}, {5, 0}));
  const std::string text = lr_text(cross);
  const auto objects = io::parse_lr(text, "cross.lr");
  const LRSpline<2>& back = as<2>(objects[0]);
  EXPECT_EQ(back.num_basis(), 103);
  EXPECT_EQ(back.num_elements(), 58);
  // The cross's mesh and B-splines with the tensor mesh's element block.
  const std::string stale = text.substr(0, text.find("# Elements:")) + tensor.substr(tensor.find("# Elements:"));
  expect_lr_error(replaced(stale, "\t103\t18\t58\t", "\t103\t18\t49\t"),
               "of the block, (3, 1) x (4, 2), is not an element of the mesh (the mesh has 58 elements, the block "
               "lists 49");
}

TEST(LrFormat, DeletedBasisFunctionIsRefused) {
  std::string text = replaced(kSplitSquare, "14: [0 0.5 1 ] x [0 1 1 ] 1 1 (1)\n", "");
  text = replaced(replaced(text, "{10, 11, 13, 14}", "{10, 11, 13}"), "{11, 12, 14, 15}", "{11, 12, 15}");
  expect_lr_error(replaced(text, "\t6\t5\t2", "\t5\t5\t2"), "do not sum to one on element [0, 0.5] x [0, 1]");
}
