#include "trivar/lr/lr_spline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/knot_insertion.hpp"

using namespace trivar;

namespace {

// max |lr(u) - s(u)| over the parameters, values and (with derivs) first partials against the tensor spline's
// own evaluator.
template <int D>
double deviation(const LRSpline<D>& lr, const TensorSpline<D>& s, const std::vector<Param<D>>& params, bool derivs) {
  const int dim = s.dim();
  std::vector<double> a(static_cast<std::size_t>((D + 1) * dim)), b(a.size());
  double worst = 0.0;
  for (const auto& u : params) {
    if (derivs) {
      lr.eval_first_derivatives(u, a.data());
      s.eval_derivs(u, 1, b.data());  // order 0, then d/du_0 .. d/du_{D-1}: the same layout
    } else {
      lr.eval(u, a.data());
      s.eval(u, b.data());
    }
    const int n = derivs ? (D + 1) * dim : dim;
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return worst;
}

// The same knots with every control value 1 (polynomial, dim 1): its LR form evaluates sum gamma_i B_i.
template <int D>
TensorSpline<D> ones_like(const TensorSpline<D>& s) {
  return TensorSpline<D>(s.knot_vectors(), 1, false, std::vector<double>(static_cast<std::size_t>(s.num_coefs()), 1.0));
}

// FULLSPAN-style rectangle for element e in direction k: through its midpoint, spanning the bounding box of the
// supports of all B-splines whose support contains e.
template <int D>
MeshRectangle<D> fullspan_rectangle(const LRSpline<D>& lr, const Box<D>& e, int k, int multiplicity) {
  Box<D> span = Box<D>::empty();
  for (const auto& b : lr.basis_functions()) {
    const auto s = b.support();
    bool contains = true;
    for (int j = 0; j < D; ++j) contains = contains && s.lo[j] <= e.lo[j] && e.hi[j] <= s.hi[j];
    if (contains) {
      span.extend(s.lo.data());
      span.extend(s.hi.data());
    }
  }
  return MeshRectangle<D>::make(k, 0.5 * (e.lo[k] + e.hi[k]), span.lo, span.hi, multiplicity);
}

template <int D>
void check_random_refinement(const Ints<D>& degrees, const Ints<D>& elements, bool rational, unsigned seed,
                             int refinements) {
  const auto s = test::random_spline<D>(degrees, elements, 3, rational, seed);
  LRSpline<D> lr(s), ones(ones_like(s));
  const auto params = test::random_params(s, 300, seed + 1);
  EXPECT_LE(deviation(lr, s, params, false), 1e-12);
  EXPECT_LE(deviation(lr, s, params, true), 1e-10);
  std::mt19937 rng(seed + 2);
  int done = 0;
  for (int attempt = 0; attempt < 10 * refinements && done < refinements; ++attempt) {
    const auto e = lr.element(std::uniform_int_distribution<int>(0, lr.num_elements() - 1)(rng));
    const int k = std::uniform_int_distribution<int>(0, D - 1)(rng);
    const int m = std::uniform_int_distribution<int>(1, std::min(2, degrees[k] + 1))(rng);
    const auto r = fullspan_rectangle(lr, e, k, m);
    bool inserted = false;
    try {
      inserted = lr.insert(r);
    } catch (const Error&) {
      continue;  // e.g. a rectangle ending inside an element: not an LR refinement, rejected unchanged
    }
    EXPECT_EQ(ones.insert(r), inserted);
    if (inserted) ++done;
  }
  EXPECT_EQ(done, refinements);
  EXPECT_EQ(lr.num_basis(), ones.num_basis());
  EXPECT_GT(lr.num_basis(), s.num_coefs());
  EXPECT_LE(deviation(lr, s, params, false), 1e-12);
  EXPECT_LE(deviation(lr, s, params, true), 1e-9);
  double pou = 0.0;
  for (const auto& u : params) {
    double v = 0.0;
    ones.eval(u, &v);
    pou = std::max(pou, std::abs(v - 1.0));
  }
  EXPECT_LE(pou, 1e-12);
  for (const auto& b : lr.basis_functions()) {
    EXPECT_GT(b.gamma, 0.0);
    EXPECT_LE(b.gamma, 1.0 + 1e-14);
  }
}

}  // namespace

TEST(LRSpline, ConversionFromTensorEvaluatesIdentically) {
  for (bool rational : {false, true}) {
    const auto s2 = test::random_spline<2>({3, 2}, {4, 3}, 3, rational, 11);
    const LRSpline<2> a(s2);
    EXPECT_EQ(a.num_basis(), s2.num_coefs());
    EXPECT_EQ(static_cast<int>(a.elements().size()), s2.knots(0).num_elements() * s2.knots(1).num_elements());
    EXPECT_LE(deviation(a, s2, test::random_params(s2, 500, 12), false), 1e-12);
    EXPECT_LE(deviation(a, s2, test::random_params(s2, 500, 13), true), 1e-10);
    const auto s3 = test::random_spline<3>({2, 1, 3}, {3, 2, 2}, 2, rational, 14);
    const LRSpline<3> b(s3);
    EXPECT_EQ(b.num_basis(), s3.num_coefs());
    EXPECT_LE(deviation(b, s3, test::random_params(s3, 500, 15), false), 1e-12);
    EXPECT_LE(deviation(b, s3, test::random_params(s3, 500, 16), true), 1e-10);
    // Corners and the closed right end of the domain.
    const auto d = s3.domain();
    EXPECT_LE(deviation(b, s3, {d.lo, d.hi, Param<3>{d.hi[0], d.lo[1], d.hi[2]}}, false), 1e-12);
  }
}

TEST(LRSpline, RandomRefinementKeepsGeometryAndPartitionOfUnity) {
  check_random_refinement<2>({2, 3}, {4, 4}, false, 21, 25);
  check_random_refinement<2>({3, 1}, {3, 5}, true, 22, 25);
  check_random_refinement<3>({2, 2, 1}, {3, 2, 3}, false, 23, 20);
  check_random_refinement<3>({1, 3, 2}, {2, 3, 2}, true, 24, 20);
}

// LRsplines regression suite, orders 3x3: lines (is_const_u, value, start, stop, multiplicity).
TEST(LRSpline, RegressionOrder3Counts) {
  const KnotVector ku(2, {0, 0, 0, 2, 4, 6, 6, 6}), kv(2, {0, 0, 0, 2, 3, 5, 5, 5});
  LRSpline<2> lr(TensorSpline<2>({ku, kv}, 1, false, std::vector<double>(25, 1.0)));
  const double lines[5][5] = {{1, 1, 2, 5, 1}, {0, 4, 0, 4, 1}, {1, 5, 0, 3, 1}, {0, 1, 2, 6, 1}, {1, 3, 0, 1, 1}};
  for (const auto& l : lines) {
    const int dir = l[0] == 1 ? 0 : 1;
    Param<2> lo{}, hi{};
    lo[1 - dir] = l[2];
    hi[1 - dir] = l[3];
    EXPECT_TRUE(lr.insert(MeshRectangle<2>::make(dir, l[1], lo, hi, static_cast<int>(l[4]))));
  }
  EXPECT_EQ(lr.num_basis(), 36);
  EXPECT_EQ(lr.mesh().size(), 13u);
  EXPECT_EQ(lr.elements().size(), 20u);
}

TEST(LRSpline, RegressionOrder4CrossCounts) {
  for (int mult : {1, 2}) {
    const auto kv = KnotVector::open_uniform(3, 7, 0.0, 7.0);
    LRSpline<2> lr(TensorSpline<2>({kv, kv}, 1, false, std::vector<double>(100, 1.0)));
    EXPECT_TRUE(lr.insert(MeshRectangle<2>::make(0, 3.5, {0, 1}, {0, 5}, mult)));
    EXPECT_TRUE(lr.insert(MeshRectangle<2>::make(1, 3.5, {1, 0}, {5, 0}, mult)));
    EXPECT_EQ(lr.num_basis(), mult == 1 ? 103 : 108);
    EXPECT_EQ(lr.mesh().size(), 18u);
    EXPECT_EQ(lr.elements().size(), 58u);
  }
}

TEST(LRSpline, FullSpanPlanesOnEveryElementReproduceTensorRefinement) {
  const auto s = test::random_spline<3>({2, 1, 3}, {3, 2, 2}, 3, true, 31);
  LRSpline<3> lr(s);
  auto t = s;
  int expected_inserts = 0;
  const std::vector<Box<3>> cells(lr.elements().begin(), lr.elements().end());
  for (int k = 0; k < 3; ++k) {
    const auto br = s.knots(k).breakpoints();
    std::vector<double> mids;
    for (std::size_t i = 0; i + 1 < br.size(); ++i) mids.push_back(0.5 * (br[i] + br[i + 1]));
    t = insert_knots(t, k, mids);
    expected_inserts += static_cast<int>(mids.size());
  }
  const auto d = s.domain();
  int inserted = 0;
  for (const auto& e : cells)
    for (int k = 0; k < 3; ++k)
      if (lr.insert(MeshRectangle<3>::make(k, 0.5 * (e.lo[k] + e.hi[k]), d.lo, d.hi))) ++inserted;
  EXPECT_EQ(inserted, expected_inserts);
  EXPECT_EQ(lr.num_basis(), t.num_coefs());
  EXPECT_EQ(static_cast<int>(lr.elements().size()),
            t.knots(0).num_elements() * t.knots(1).num_elements() * t.knots(2).num_elements());
  for (const auto& b : lr.basis_functions()) EXPECT_NEAR(b.gamma, 1.0, 1e-13);  // tensor B-splines again
  EXPECT_LE(deviation(lr, t, test::random_params(t, 500, 32), false), 1e-12);
}

TEST(LRSpline, PartialRectanglesMergeAcrossIn3D) {
  // Two halves of a plane, inserted one after the other, merge into one full-span rectangle; the result is
  // the tensor refinement.
  const auto s = test::random_spline<3>({2, 2, 2}, {2, 2, 2}, 1, false, 41);
  LRSpline<3> lr(s);
  const auto d = s.domain();
  const double y_mid = s.knots(1).breakpoints()[1];
  const double x = 0.5 * (s.knots(0).breakpoints()[0] + s.knots(0).breakpoints()[1]);
  const std::size_t before = lr.mesh().size();
  EXPECT_TRUE(lr.insert(MeshRectangle<3>::make(0, x, d.lo, Param<3>{0, y_mid, d.hi[2]})));
  EXPECT_TRUE(lr.insert(MeshRectangle<3>::make(0, x, Param<3>{0, y_mid, d.lo[2]}, d.hi)));
  EXPECT_EQ(lr.mesh().size(), before + 1);
  const auto t = insert_knot(s, 0, x);
  EXPECT_EQ(lr.num_basis(), t.num_coefs());
  EXPECT_LE(deviation(lr, t, test::random_params(t, 300, 42), false), 1e-12);
}

TEST(LRSpline, InvalidOrIneffectiveRectangles) {
  const auto kv = KnotVector::open_uniform(3, 7, 0.0, 7.0);
  LRSpline<2> lr(TensorSpline<2>({kv, kv}, 1, false, std::vector<double>(100, 1.0)));
  // One element long in the interior: no cubic B-spline support is traversed, so it splits nothing.
  EXPECT_THROW(lr.insert(MeshRectangle<2>::make(0, 3.5, {0, 3}, {0, 4})), Error);
  EXPECT_THROW(lr.insert(MeshRectangle<2>::make(0, 3.5, {0, 1.5}, {0, 5})), Error);  // ends inside an element
  EXPECT_THROW(lr.insert(MeshRectangle<2>::make(0, 3.5, {0, 1}, {0, 5}, 5)), Error);  // multiplicity > p+1
  EXPECT_THROW(lr.insert(MeshRectangle<2>::make(0, 3.0, {0, 0.5}, {0, 5}, 2)), Error);  // ends inside a face
  EXPECT_THROW(lr.insert(MeshRectangle<2>::make(0, 7.0, {0, 1}, {0, 5})), Error);     // on the boundary
  EXPECT_THROW(lr.insert(MeshRectangle<2>::make(1, 3.5, {2, 0}, {2, 5})), Error);     // empty extent
  EXPECT_EQ(lr.num_basis(), 100);
  EXPECT_EQ(lr.mesh().size(), 16u);
  EXPECT_EQ(lr.elements().size(), 49u);
  // Already in the mesh: a no-op reported by false.
  EXPECT_FALSE(lr.insert(MeshRectangle<2>::make(0, 3.0, {0, 1}, {0, 5})));
  EXPECT_TRUE(lr.insert(MeshRectangle<2>::make(0, 3.5, {0, 1}, {0, 5})));
  EXPECT_FALSE(lr.insert(MeshRectangle<2>::make(0, 3.5, {0, 2}, {0, 4})));
  // Only the 4 B-splines with v knots 1..5 are traversed; split at 3.5 they become the 5 B-splines of the
  // u knots with 3.5 inserted: one more.
  EXPECT_EQ(lr.num_basis(), 101);
  EXPECT_EQ(lr.elements().size(), 53u);
}

TEST(LRSpline, RaisingMultiplicityOfExistingLines) {
  const auto s = test::random_spline<2>({3, 2}, {4, 3}, 2, true, 51);
  const auto params = test::random_params(s, 300, 52);
  const auto d = s.domain();
  const double u = s.knots(0).breakpoints()[2];
  const int m = s.knots(0).multiplicity(u);
  // Full span: the tensor spline with u inserted once more.
  LRSpline<2> full(s);
  EXPECT_TRUE(full.insert(MeshRectangle<2>::make(0, u, d.lo, d.hi, m + 1)));
  const auto t = insert_knot(s, 0, u);
  EXPECT_EQ(full.num_basis(), t.num_coefs());
  EXPECT_EQ(full.elements().size(), static_cast<std::size_t>(4 * 3));  // no new elements
  EXPECT_LE(deviation(full, t, params, false), 1e-12);
  // Part of the line (between mesh lines, long enough to traverse supports): geometry unchanged.
  LRSpline<2> part(s);
  const auto vb = s.knots(1).breakpoints();
  EXPECT_TRUE(part.insert(MeshRectangle<2>::make(0, u, Param<2>{0, vb[0]}, Param<2>{0, vb[2]}, m + 1)));
  EXPECT_GT(part.num_basis(), s.num_coefs());
  EXPECT_LT(part.num_basis(), t.num_coefs());
  EXPECT_LE(deviation(part, s, params, false), 1e-12);
}

TEST(LRSpline, DerivativesMatchFiniteDifferencesAfterRefinement) {
  const auto s = test::random_spline<3>({3, 2, 2}, {3, 3, 2}, 2, true, 61);
  LRSpline<3> lr(s);
  const auto d = s.domain();
  lr.insert(MeshRectangle<3>::make(0, 0.5 * (d.lo[0] + d.hi[0]), d.lo, d.hi));
  const double h = 1e-6;
  std::mt19937 rng(62);
  for (int t = 0; t < 50; ++t) {
    Param<3> u;
    for (int k = 0; k < 3; ++k)
      u[k] = std::uniform_real_distribution<double>(d.lo[k] + 0.01, d.hi[k] - 0.01)(rng);
    double a[8];
    lr.eval_first_derivatives(u, a);
    for (int k = 0; k < 3; ++k) {
      auto up = u, um = u;
      up[k] += h;
      um[k] -= h;
      double vp[2], vm[2];
      lr.eval(up, vp);
      lr.eval(um, vm);
      for (int i = 0; i < 2; ++i) EXPECT_NEAR(a[2 * (k + 1) + i], (vp[i] - vm[i]) / (2 * h), 1e-5 * (1 + std::abs(a[2 * (k + 1) + i])));
    }
  }
}

// A parameter one ulp below an interior knot whose product with the element locator's grid scale rounds up to the
// next grid cell: it is still found in its element (the lower one) and evaluates as the tensor spline does.
TEST(LRSpline, ParametersJustBelowAKnotFindTheirElement) {
  std::array<std::vector<double>, 3> t;
  const std::array<int, 3> n{6, 7, 4};
  for (int k = 0; k < 3; ++k) {
    t[static_cast<std::size_t>(k)] = {0, 0, 0};
    for (int i = 1; i < n[static_cast<std::size_t>(k)]; ++i) t[static_cast<std::size_t>(k)].push_back(static_cast<double>(i) / n[static_cast<std::size_t>(k)]);
    t[static_cast<std::size_t>(k)].insert(t[static_cast<std::size_t>(k)].end(), {1, 1, 1});
  }
  std::vector<double> c;
  for (int i = 0; i < 8 * 9 * 6 * 3; ++i) c.push_back(std::sin(0.37 * i));
  const TensorSpline<3> s({KnotVector(2, t[0]), KnotVector(2, t[1]), KnotVector(2, t[2])}, 3, false, c);
  const LRSpline<3> lr(s);
  const double below = std::nextafter(5.0 / 6.0, 0.0);  // 168 elements: a 6^3 grid, 6 * below rounds to 5
  ASSERT_EQ(below * 6, 5.0);
  double x[3], y[3];
  for (double w : {0.0, 0.5, 1.0}) {
    lr.eval({below, 1.0 / 3.0, w}, x);
    s.eval({below, 1.0 / 3.0, w}, y);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], y[k], 1e-14);
  }
}

TEST(LRSpline, BatchEvaluationIsThreadCountIndependent) {
  const auto s = test::random_spline<3>({3, 3, 3}, {4, 4, 4}, 3, false, 71);
  LRSpline<3> lr(s);
  const auto d = s.domain();
  lr.insert(MeshRectangle<3>::make(1, 0.5 * (d.lo[1] + d.hi[1]), d.lo, d.hi));
  const auto params = test::random_params(s, 2000, 72);
  std::vector<double> one(params.size() * 3), two(one.size()), ref(one.size());
  lr.eval_many(params, one, 1);
  lr.eval_many(params, two, 2);
  for (std::size_t i = 0; i < params.size(); ++i) lr.eval(params[i], ref.data() + 3 * i);
  EXPECT_EQ(one, two);
  EXPECT_EQ(one, ref);
  std::vector<double> da(params.size() * 12), db(da.size());
  lr.eval_first_derivatives_many(params, da, 1);
  lr.eval_first_derivatives_many(params, db, 2);
  EXPECT_EQ(da, db);
  EXPECT_LE(deviation(lr, s, params, false), 1e-12);
}

TEST(LRSpline, ConstructionFromPartsRoundTripsAndValidates) {
  const auto s = test::random_spline<2>({2, 3}, {4, 3}, 2, true, 81);
  LRSpline<2> lr(s);
  const auto d = s.domain();
  const double x = 0.5 * (s.knots(0).breakpoints()[1] + s.knots(0).breakpoints()[2]);
  lr.insert(MeshRectangle<2>::make(0, x, d.lo, Param<2>{0, s.knots(1).breakpoints()[2]}));
  std::vector<LRBSpline<2>> basis(lr.basis_functions().begin(), lr.basis_functions().end());
  std::reverse(basis.begin(), basis.end());  // any order: the constructor sorts
  LRSpline<2> copy({2, 3}, 2, true, basis, lr.mesh());
  EXPECT_EQ(copy.num_basis(), lr.num_basis());
  EXPECT_EQ(copy.num_elements(), lr.num_elements());
  for (int b = 0; b < lr.num_basis(); ++b) EXPECT_EQ(copy.basis_function(b).knots, lr.basis_function(b).knots);
  EXPECT_LE(deviation(copy, s, test::random_params(s, 300, 82), false), 1e-12);

  const auto expect_error = [&](std::vector<LRBSpline<2>> b, std::vector<MeshRectangle<2>> m, const char* what) {
    try {
      LRSpline<2> bad({2, 3}, 2, true, std::move(b), std::move(m));
      ADD_FAILURE() << "no error for " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  auto b1 = basis;
  b1[0].knots[0].pop_back();
  expect_error(b1, lr.mesh(), "knots in direction 0");
  auto b2 = basis;
  b2[1].gamma = 1.5;
  expect_error(b2, lr.mesh(), "scaling factor");
  auto b3 = basis;
  b3[2].coef.pop_back();
  expect_error(b3, lr.mesh(), "control values");
  auto b4 = basis;
  b4[3].knots[1].back() = d.hi[1] + 1;
  b4[3].knots[1][4] = d.hi[1] + 1;
  expect_error(b4, lr.mesh(), "outside the domain");
  auto m1 = lr.mesh();
  m1.push_back(MeshRectangle<2>::make(1, 0.5 * (d.lo[1] + d.hi[1]), Param<2>{x, 0}, Param<2>{d.hi[0] + 0.5 * (x - d.hi[0]), 0}));
  expect_error(basis, m1, "ends inside an element");
  auto m2 = lr.mesh();
  m2.back().multiplicity = 7;
  expect_error(basis, m2, "multiplicity");
  auto b5 = basis;
  b5.push_back(basis[0]);
  expect_error(b5, lr.mesh(), "same knots");
}
