// Rebuilding an LR mesh from the B-splines alone (what a STEP reader must do) and the constructor's cutting of
// elements by planes given as several rectangles. Reference: the spline the B-splines came from (its elements
// and its values).
#include "trivar/lr/knot_line_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/lr/lr_spline.hpp"

using namespace trivar;

namespace {

template <int D>
std::vector<Box<D>> sorted_elements(const LRSpline<D>& s) {
  std::vector<Box<D>> e(s.elements().begin(), s.elements().end());
  std::sort(e.begin(), e.end(), [](const Box<D>& a, const Box<D>& b) {
    return std::tie(a.lo, a.hi) < std::tie(b.lo, b.hi);
  });
  return e;
}

template <int D>
void expect_same_spline(const LRSpline<D>& a, const LRSpline<D>& b) {
  ASSERT_EQ(a.num_basis(), b.num_basis());
  for (int i = 0; i < a.num_basis(); ++i) EXPECT_EQ(a.basis_function(i).knots, b.basis_function(i).knots);
  const auto ea = sorted_elements(a), eb = sorted_elements(b);
  ASSERT_EQ(ea.size(), eb.size());
  for (std::size_t i = 0; i < ea.size(); ++i) {
    EXPECT_EQ(ea[i].lo, eb[i].lo);
    EXPECT_EQ(ea[i].hi, eb[i].hi);
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<double> x(static_cast<std::size_t>(a.dim())), y(x.size());
  for (int n = 0; n < 500; ++n) {
    Param<D> u;
    for (int k = 0; k < D; ++k) u[k] = a.domain().lo[k] + U(rng) * a.domain().extent(k);
    a.eval(u, x.data());
    b.eval(u, y.data());
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], y[i], 1e-12);
  }
}

}  // namespace

// The plane v = 1 as two pieces meeting at u = 1.5: neither crosses the element [1, 2] x [0, 2] alone, their
// union does, so it is cut (and no piece "ends inside" it).
TEST(KnotLineMesh, APlaneOfSeveralRectanglesCutsWhereTheirUnionCrosses) {
  const KnotVector kv(1, {0, 0, 1, 2, 2});
  const LRSpline<2> tensor(TensorSpline<2>({kv, kv}, 1, false, std::vector<double>(9, 1.0)));
  std::vector<MeshRectangle<2>> mesh;
  for (const auto& r : tensor.mesh())
    if (!(r.dir == 1 && r.value == 1.0)) mesh.push_back(r);
  mesh.push_back(MeshRectangle<2>::make(1, 1.0, {0, 0}, {1.5, 0}));
  mesh.push_back(MeshRectangle<2>::make(1, 1.0, {1.5, 0}, {2, 0}));
  const std::vector<LRBSpline<2>> basis(tensor.basis_functions().begin(), tensor.basis_functions().end());
  const LRSpline<2> pieces({1, 1}, 1, false, basis, mesh);
  EXPECT_EQ(pieces.num_elements(), 4);
  expect_same_spline(tensor, pieces);
}

// A refined volume whose planes are unions of differently sized pieces (L-shapes): the mesh of its knot lines
// gives back its B-splines, elements and values.
TEST(KnotLineMesh, RebuildsTheMeshOfARefinedVolume) {
  const TensorSpline<3> t = test::random_spline<3>({2, 3, 2}, {4, 4, 4}, 3, false, 11);
  LRSpline<3> lr(t);
  const Box<3> d = lr.domain();
  const auto at = [&](int k, double f) { return d.lo[k] + f * d.extent(k); };
  // Rectangles on element boundaries of the random knots are not known here: refine by FULLSPAN-like planes
  // through element midpoints, spanning the supports on the element, on a few corner elements.
  for (int round = 0; round < 3; ++round)
    for (int e = 0; e < lr.num_elements(); ++e) {
      const Box<3> el = lr.element(e);
      if (!(el.lo[0] < at(0, 0.5) && el.lo[1] < at(1, 0.4 + 0.1 * round) && el.lo[2] < at(2, 0.6))) continue;
      Box<3> span = Box<3>::empty();
      for (int b : lr.element_support(e)) {
        const Box<3> s = lr.basis_function(b).support();
        span.extend(s.lo.data());
        span.extend(s.hi.data());
      }
      const int k = (e + round) % 3;
      lr.insert(MeshRectangle<3>::make(k, el.center()[k], span.lo, span.hi));
      break;
    }
  ASSERT_GT(lr.num_elements(), 64);
  const std::vector<LRBSpline<3>> basis(lr.basis_functions().begin(), lr.basis_functions().end());
  const LRSpline<3> rebuilt(lr.degrees(), lr.dim(), false, basis, knot_line_mesh<3>(basis));
  expect_same_spline(lr, rebuilt);
}

// Partition of unity on read: a deleted B-spline or a wrong scaling factor is named by the element it breaks.
TEST(KnotLineMesh, ConstructionChecksPartitionOfUnity) {
  const auto kv = KnotVector::open_uniform(2, 3, 0.0, 3.0);
  LRSpline<2> lr(TensorSpline<2>({kv, kv}, 1, false, std::vector<double>(25, 1.0)));
  lr.insert(MeshRectangle<2>::make(0, 1.5, {0, 0}, {0, 3}));
  std::vector<LRBSpline<2>> basis(lr.basis_functions().begin(), lr.basis_functions().end());
  const auto expect_error = [&](std::vector<LRBSpline<2>> b) {
    try {
      LRSpline<2> bad({2, 2}, 1, false, std::move(b), lr.mesh());
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("do not sum to one on element ["), std::string::npos) << e.what();
    }
  };
  auto deleted = basis;
  deleted.erase(deleted.begin() + 7);
  expect_error(deleted);
  auto scaled = basis;
  scaled[3].gamma *= 0.5;
  expect_error(scaled);
  EXPECT_NO_THROW(LRSpline<2>({2, 2}, 1, false, basis, lr.mesh()));
}

TEST(KnotLineMesh, ReorderElementsKeepsSupportsAndValues) {
  const auto kv = KnotVector::open_uniform(2, 3, 0.0, 3.0);
  LRSpline<2> lr(TensorSpline<2>({kv, kv}, 2, false, std::vector<double>(50, 1.0)));
  lr.insert(MeshRectangle<2>::make(0, 1.5, {0, 0}, {0, 3}));
  const LRSpline<2> before = lr;
  std::vector<int> order(static_cast<std::size_t>(lr.num_elements()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(order.size() - 1 - i);
  lr.reorder_elements(order);
  for (int i = 0; i < lr.num_elements(); ++i) {
    const int old = order[static_cast<std::size_t>(i)];
    EXPECT_EQ(lr.element(i).lo, before.element(old).lo);
    const auto a = lr.element_support(i), b = before.element_support(old);
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
  }
  for (int b = 0; b < lr.num_basis(); ++b)
    for (int e : lr.basis_elements(b)) {
      const auto s = lr.element_support(e);
      EXPECT_TRUE(std::find(s.begin(), s.end(), b) != s.end());
    }
  expect_same_spline(before, lr);
  order[0] = order[1];
  EXPECT_THROW(lr.reorder_elements(order), Error);
}
