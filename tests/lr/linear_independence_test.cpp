#include "trivar/lr/linear_independence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/lr/dimension_formula.hpp"
#include "trivar/lr/mesh_rectangle.hpp"

using namespace trivar;

namespace {

// True when the mesh lines at (dir, value) with multiplicity >= m cover the box b across dir.
bool covers(const std::vector<MeshRectangle<2>>& rects, int dir, double value, const Box<2>& b, int m) {
  std::vector<std::pair<double, double>> iv;
  for (const auto& r : rects)
    if (r.dir == dir && r.value == value && r.multiplicity >= m) iv.emplace_back(r.extent.lo[1 - dir], r.extent.hi[1 - dir]);
  std::sort(iv.begin(), iv.end());
  double reach = b.lo[1 - dir];
  for (const auto& [lo, hi] : iv)
    if (lo <= reach) reach = std::max(reach, hi);
  return reach >= b.hi[1 - dir];
}

// Test-side LR refinement for surfaces (independent of LRSpline): mesh lines, minimal-support splitting with the
// Oslo weights of seed 004 (alpha1, alpha2 into gamma) and merging of identical B-splines.
struct LR2 {
  Ints<2> p{};
  std::vector<MeshRectangle<2>> rects;
  std::map<std::vector<double>, LRBSpline<2>> basis;
  static std::vector<double> key(const LRBSpline<2>& b) {
    std::vector<double> k(b.knots[0]);
    k.insert(k.end(), b.knots[1].begin(), b.knots[1].end());
    return k;
  }
  void add(LRBSpline<2> b) {
    auto [it, fresh] = basis.try_emplace(key(b), b);
    if (!fresh) {
      auto& a = it->second;
      for (std::size_t s = 0; s < a.coef.size(); ++s) a.coef[s] = (a.gamma * a.coef[s] + b.gamma * b.coef[s]) / (a.gamma + b.gamma);
      a.gamma += b.gamma;
    }
  }
  // Tensor mesh and B-splines of the global knot vectors t; coefficient of B-spline (i, j) is (i, j, i j).
  LR2(Ints<2> deg, std::array<std::vector<double>, 2> t) : p(deg) {
    for (int k = 0; k < 2; ++k) {
      const auto& v = t[k];
      for (std::size_t i = 0; i < v.size();) {
        std::size_t j = i;
        while (j < v.size() && v[j] == v[i]) ++j;
        Param<2> lo{t[0].front(), t[1].front()}, hi{t[0].back(), t[1].back()};
        rects.push_back(MeshRectangle<2>::make(k, v[i], lo, hi, int(j - i)));
        i = j;
      }
    }
    const int n0 = int(t[0].size()) - p[0] - 1, n1 = int(t[1].size()) - p[1] - 1;
    for (int j = 0; j < n1; ++j)
      for (int i = 0; i < n0; ++i) {
        LRBSpline<2> b;
        b.knots[0].assign(t[0].begin() + i, t[0].begin() + i + p[0] + 2);
        b.knots[1].assign(t[1].begin() + j, t[1].begin() + j + p[1] + 2);
        b.coef = {double(i), double(j), double(i * j)};
        add(b);
      }
  }
  // Splits one B-spline whose support a mesh line traverses beyond its knots; false when all are minimal.
  bool split_one() {
    for (auto it = basis.begin(); it != basis.end(); ++it) {
      const LRBSpline<2> b = it->second;
      const Box<2> s = b.support();
      for (int k = 0; k < 2; ++k)
        for (const auto& r : rects) {
          if (r.dir != k || !(r.value > s.lo[k] && r.value < s.hi[k])) continue;
          const int have = int(std::count(b.knots[k].begin(), b.knots[k].end(), r.value));
          if (have >= r.multiplicity) continue;
          if (!covers(rects, k, r.value, s, have + 1)) continue;
          basis.erase(it);
          const auto& y = b.knots[k];
          const int pk = p[k];
          const double z = r.value;
          std::vector<double> K(y);
          K.insert(std::upper_bound(K.begin(), K.end(), z), z);
          const double a1 = z >= y[pk] ? 1.0 : (z - y[0]) / (y[pk] - y[0]);
          const double a2 = z <= y[1] ? 1.0 : (y[pk + 1] - z) / (y[pk + 1] - y[1]);
          LRBSpline<2> b1 = b, b2 = b;
          b1.knots[k].assign(K.begin(), K.begin() + pk + 2);
          b2.knots[k].assign(K.begin() + 1, K.end());
          b1.gamma = b.gamma * a1;
          b2.gamma = b.gamma * a2;
          add(b1);
          add(b2);
          return true;
        }
    }
    return false;
  }
  // Inserts r when it splits at least one support, then refines to minimal supports.
  bool insert(const MeshRectangle<2>& r) {
    bool any = false;
    for (const auto& [k, b] : basis) {
      const Box<2> s = b.support();
      if (r.value > s.lo[r.dir] && r.value < s.hi[r.dir] && r.contains_across(s) &&
          int(std::count(b.knots[r.dir].begin(), b.knots[r.dir].end(), r.value)) < r.multiplicity) any = true;
    }
    if (!any) return false;
    rects.push_back(r);
    while (split_one()) {}
    return true;
  }
  std::vector<LRBSpline<2>> functions() const {
    std::vector<LRBSpline<2>> v;
    for (const auto& [k, b] : basis) v.push_back(b);
    return v;
  }
  // Elements: cells of the grid of line values merged where no mesh line separates them.
  std::vector<Box<2>> elements() const {
    std::array<std::vector<double>, 2> g;
    for (const auto& r : rects) {
      g[r.dir].push_back(r.value);
      g[1 - r.dir].push_back(r.extent.lo[1 - r.dir]);
      g[1 - r.dir].push_back(r.extent.hi[1 - r.dir]);
    }
    for (auto& v : g) { std::sort(v.begin(), v.end()); v.erase(std::unique(v.begin(), v.end()), v.end()); }
    auto line = [&](int k, double val, double a, double b) {
      Box<2> bx; bx.lo[1 - k] = a; bx.hi[1 - k] = b; bx.lo[k] = bx.hi[k] = val;
      return covers(rects, k, val, bx, 1);
    };
    std::vector<Box<2>> out;
    const int nx = int(g[0].size()), ny = int(g[1].size());
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        if (i > 0 && !line(0, g[0][i], g[1][j], g[1][j + 1])) continue;
        if (j > 0 && !line(1, g[1][j], g[0][i], g[0][i + 1])) continue;
        int i1 = i + 1, j1 = j + 1;
        while (i1 < nx - 1 && !line(0, g[0][i1], g[1][j], g[1][j + 1])) ++i1;
        while (j1 < ny - 1 && !line(1, g[1][j1], g[0][i], g[0][i + 1])) ++j1;
        Box<2> e;
        e.lo = {g[0][i], g[1][j]};
        e.hi = {g[0][i1], g[1][j1]};
        out.push_back(e);
      }
    return out;
  }
};

MeshRectangle<2> knot_line(int dir, double value, double a, double b) {
  Param<2> lo{}, hi{};
  lo[1 - dir] = a;
  hi[1 - dir] = b;
  return MeshRectangle<2>::make(dir, value, lo, hi);
}

// Seed 004 (lecture 4, example by K. F. Pettersen): biquadratic LR refinement ending in a linear relation of
// eight B-splines, knot value = knot position:
//   108 (5678)x(2346) + 135 (2356)x(2456) + 108 (3567)x(3456) + 268 (3456)x(2345) + 324 (4567)x(2345)
//   + 360 (2346)x(1245) + 384 (3468)x(1234) = 720 (2368)x(1246).
// The seed's initial tensor mesh (x 1 2 3 6 8 9, y 1 2 4 6 7) is embedded in a clamped one so that every
// element sees 9 B-splines; the refinement inserts the knot lines of every B-spline the seed's steps show.
struct SeedExample {
  std::vector<std::pair<std::vector<double>, std::vector<double>>> relation = {
      {{5, 6, 7, 8}, {2, 3, 4, 6}}, {{2, 3, 5, 6}, {2, 4, 5, 6}}, {{3, 5, 6, 7}, {3, 4, 5, 6}},
      {{3, 4, 5, 6}, {2, 3, 4, 5}}, {{4, 5, 6, 7}, {2, 3, 4, 5}}, {{2, 3, 4, 6}, {1, 2, 4, 5}},
      {{3, 4, 6, 8}, {1, 2, 3, 4}}, {{2, 3, 6, 8}, {1, 2, 4, 6}}};
  std::vector<double> weights = {108, 135, 108, 268, 324, 360, 384, -720};
  LR2 lr{{2, 2},
         {std::vector<double>{0, 0, 0, 1, 2, 3, 6, 8, 9, 10, 10, 10}, std::vector<double>{0, 0, 0, 1, 2, 4, 6, 7, 8, 8, 8}}};

  SeedExample() {
    std::vector<std::pair<std::vector<double>, std::vector<double>>> shown = relation;
    for (const char* t : {"1235x2467", "5689x2467", "2356x2467", "3568x2467", "3568x2346", "3568x3467", "3567x2346",
                          "5678x2346", "1235x2456", "1235x4567", "1236x1246", "1236x1245", "2356x2456", "2356x4567",
                          "3567x2345", "3567x3456", "3456x2345", "4567x2345", "3689x1234", "5689x2346", "5689x3467",
                          "6789x2346", "1234x1245", "2346x1245", "3468x1234", "4689x1234"}) {
      std::vector<double> x, y;
      for (int i = 0; i < 4; ++i) {
        x.push_back(t[i] - '0');
        y.push_back(t[5 + i] - '0');
      }
      shown.emplace_back(x, y);
    }
    std::vector<MeshRectangle<2>> todo;
    for (const auto& [x, y] : shown) {
      for (double v : x) todo.push_back(knot_line(0, v, y.front(), y.back()));
      for (double v : y) todo.push_back(knot_line(1, v, x.front(), x.back()));
    }
    // A line that splits nothing yet may split something after others; lines already in the mesh are dropped.
    for (int round = 0; round < 10 && !todo.empty(); ++round) {
      std::vector<MeshRectangle<2>> later;
      for (const auto& r : todo)
        if (!lr.insert(r) && !covers(lr.rects, r.dir, r.value, r.extent, 1)) later.push_back(r);
      todo = later;
    }
    EXPECT_TRUE(todo.empty());
  }
};

template <int D>
std::vector<LRBSpline<D>> tensor_basis(const Ints<D>& p, const std::array<std::vector<double>, D>& t) {
  std::vector<LRBSpline<D>> out;
  std::array<int, D> n{}, i{};
  int total = 1;
  for (int k = 0; k < D; ++k) total *= (n[k] = static_cast<int>(t[k].size()) - p[k] - 1);
  for (int l = 0; l < total; ++l) {
    LRBSpline<D> b;
    for (int k = 0; k < D; ++k) b.knots[k].assign(t[k].begin() + i[k], t[k].begin() + i[k] + p[k] + 2);
    out.push_back(b);
    for (int k = 0; k < D; ++k) {
      if (++i[k] < n[k]) break;
      i[k] = 0;
    }
  }
  return out;
}

template <int D>
std::vector<Box<D>> tensor_elements(const std::array<std::vector<double>, D>& t) {
  std::array<std::vector<double>, D> bp;
  int total = 1;
  for (int k = 0; k < D; ++k) {
    bp[k] = t[k];
    bp[k].erase(std::unique(bp[k].begin(), bp[k].end()), bp[k].end());
    total *= static_cast<int>(bp[k].size()) - 1;
  }
  std::vector<Box<D>> out;
  for (int e = 0; e < total; ++e) {
    Box<D> b;
    int r = e;
    for (int k = 0; k < D; ++k) {
      const int n = static_cast<int>(bp[k].size()) - 1;
      b.lo[k] = bp[k][r % n];
      b.hi[k] = bp[k][r % n + 1];
      r /= n;
    }
    out.push_back(b);
  }
  return out;
}

}  // namespace

TEST(LinearIndependence, StatusStrings) {
  EXPECT_STREQ(to_string(Independence::independent), "independent");
  EXPECT_STREQ(to_string(Independence::not_independent), "not_independent");
  EXPECT_STREQ(to_string(Independence::not_tested), "not_tested");
}

TEST(LinearIndependence, SeedRelationHoldsForTheUnscaledBSplines) {
  // The literature's coefficients, checked by Cox-de Boor (independently of the code under test).
  const SeedExample ex;
  std::mt19937 rng(3);
  double worst = 0.0, scale = 0.0;
  for (int q = 0; q < 400; ++q) {
    const double x = std::uniform_real_distribution<double>(2, 8)(rng), y = std::uniform_real_distribution<double>(1, 6)(rng);
    double s = 0.0;
    for (std::size_t i = 0; i < ex.relation.size(); ++i) {
      const auto& [kx, ky] = ex.relation[i];
      const double b = test::cox_de_boor(kx, 0, 2, x, kx.back()) * test::cox_de_boor(ky, 0, 2, y, ky.back());
      s += ex.weights[i] * b;
      scale = std::max(scale, 720 * b);
    }
    worst = std::max(worst, std::abs(s));
  }
  EXPECT_GT(scale, 100.0);
  EXPECT_LE(worst, 1e-10);
}

TEST(LinearIndependence, SeedDependentConfigurationIsFound) {
  const SeedExample ex;
  const auto basis = ex.lr.functions();
  const auto elements = ex.lr.elements();
  for (const auto& [x, y] : ex.relation)
    EXPECT_TRUE(std::any_of(basis.begin(), basis.end(), [&](const auto& b) { return b.knots[0] == x && b.knots[1] == y; }));
  // Peeling is inconclusive and leaves exactly the eight B-splines of the relation.
  const auto peeled = peeling_test<2>({2, 2}, basis, elements);
  EXPECT_EQ(peeled.status, Independence::not_tested);
  ASSERT_EQ(peeled.unresolved.size(), 8u);
  for (int b : peeled.unresolved) {
    const auto& f = basis[static_cast<std::size_t>(b)];
    EXPECT_TRUE(std::any_of(ex.relation.begin(), ex.relation.end(),
                            [&](const auto& r) { return r.first == f.knots[0] && r.second == f.knots[1]; }));
  }
  // The exact test finds the one relation.
  const auto exact = exact_test<2>({2, 2}, basis, elements);
  EXPECT_EQ(exact.status, Independence::not_independent);
  EXPECT_EQ(exact.tested, 8);
  EXPECT_EQ(exact.nullity(), 1);
  // One B-spline more than the dimension of the spline space: the hand-in-hand check sees it too.
  const auto h = hand_in_hand(static_cast<int>(basis.size()), ex.lr.rects, {2, 2});
  EXPECT_EQ(h.basis_count, h.dimension + 1);
  EXPECT_EQ(h.status, Independence::not_independent);
}

// The seed's relation times each univariate B-spline of a third direction: a trivariate collection with one
// relation per B-spline in w (quadratic on 0 0 0 1 2 2 2: 4 of them), so nullity 4 (the rank of a tensor
// product of collections is the product of the ranks). Peeling leaves at least the 8 x 4 B-splines of the
// relations.
TEST(LinearIndependence, SeedRelationExtrudedIsDependentInThreeDimensions) {
  const SeedExample ex;
  const std::vector<double> tw{0, 0, 0, 1, 2, 2, 2};
  std::vector<LRBSpline<3>> basis;
  for (const auto& b : ex.lr.functions())
    for (std::size_t j = 0; j + 3 < tw.size(); ++j) {
      LRBSpline<3> c;
      c.knots[0] = b.knots[0];
      c.knots[1] = b.knots[1];
      c.knots[2].assign(tw.begin() + static_cast<std::ptrdiff_t>(j), tw.begin() + static_cast<std::ptrdiff_t>(j) + 4);
      basis.push_back(c);
    }
  std::vector<Box<3>> elements;
  for (const auto& e : ex.lr.elements())
    for (double w : {0.0, 1.0}) elements.push_back(Box<3>{{e.lo[0], e.lo[1], w}, {e.hi[0], e.hi[1], w + 1}});
  const auto peeled = peeling_test<3>({2, 2, 2}, basis, elements);
  EXPECT_EQ(peeled.status, Independence::not_tested);
  EXPECT_GE(peeled.unresolved.size(), 32u);
  const auto exact = exact_test<3>({2, 2, 2}, basis, elements);
  EXPECT_EQ(exact.status, Independence::not_independent);
  EXPECT_EQ(exact.tested, static_cast<int>(peeled.unresolved.size()));
  EXPECT_EQ(exact.nullity(), 4);
}

TEST(LinearIndependence, TensorCollectionsAreIndependentByBothTests) {
  const std::array<std::vector<double>, 2> t2 = {std::vector<double>{0, 0, 0, 0, 1, 2, 2, 3, 4, 4, 4, 4},
                                                 std::vector<double>{0, 0, 0, 0.5, 1, 1.5, 2, 2, 2}};
  const auto b2 = tensor_basis<2>({3, 2}, t2);
  const auto e2 = tensor_elements<2>(t2);
  const auto p2 = peeling_test<2>({3, 2}, b2, e2);
  EXPECT_EQ(p2.status, Independence::independent);
  EXPECT_EQ(p2.overloaded_elements, 0);
  EXPECT_EQ(exact_test<2>({3, 2}, b2, e2).status, Independence::independent);
  const std::array<std::vector<double>, 3> t3 = {std::vector<double>{0, 0, 0, 1, 2, 3, 3, 3},
                                                 std::vector<double>{0, 0, 1, 2, 2}, std::vector<double>{0, 0, 0, 0, 1, 1, 1, 1}};
  const auto b3 = tensor_basis<3>({2, 1, 3}, t3);
  const auto e3 = tensor_elements<3>(t3);
  EXPECT_EQ(peeling_test<3>({2, 1, 3}, b3, e3).status, Independence::independent);
  EXPECT_EQ(exact_test<3>({2, 1, 3}, b3, e3).status, Independence::independent);
}

namespace {

// Bicubic on 6 x 6 uniform elements with two crossing pairs of lines spanning B-spline supports: linearly
// independent, with overloaded elements that peeling alone cannot clear.
LR2 refined_bicubic() {
  const std::vector<double> t{0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6, 6};
  LR2 lr{{3, 3}, {t, t}};
  for (const auto& m :
       {knot_line(0, 2.5, 0, 5), knot_line(1, 2.5, 0, 5), knot_line(0, 3.5, 1, 6), knot_line(1, 3.5, 1, 6)})
    EXPECT_TRUE(lr.insert(m));
  return lr;
}

}  // namespace

TEST(LinearIndependence, RefinedIndependentConfigurationPasses) {
  // Bicubic, 6 x 6 uniform elements; a few LR refinements (lines spanning B-spline supports), including a
  // crossing pair, which leaves overloaded elements for the exact test to resolve.
  LR2 lr = refined_bicubic();
  const auto basis = lr.functions();
  const auto elements = lr.elements();
  const auto peeled = peeling_test<2>({3, 3}, basis, elements);
  EXPECT_GT(peeled.overloaded_elements, 0);
  const auto exact = exact_test<2>({3, 3}, basis, elements);
  EXPECT_EQ(exact.status, Independence::independent);
  EXPECT_EQ(exact.rank, exact.tested);
  if (peeled.status == Independence::independent) {
    EXPECT_EQ(exact.tested, 0);
  }
  // Independent, and the count equals the dimension of the spline space.
  const auto h = hand_in_hand(static_cast<int>(basis.size()), lr.rects, {3, 3});
  EXPECT_EQ(h.status, Independence::independent);
}

TEST(LinearIndependence, DuplicatedBSplineIsDependentAndPeelingCannotClearIt) {
  const std::array<std::vector<double>, 2> t = {std::vector<double>{0, 0, 0, 1, 2, 3, 3, 3},
                                                std::vector<double>{0, 0, 0, 1, 2, 2, 2}};
  auto basis = tensor_basis<2>({2, 2}, t);
  basis.push_back(basis[7]);
  const auto elements = tensor_elements<2>(t);
  EXPECT_EQ(peeling_test<2>({2, 2}, basis, elements).status, Independence::not_tested);
  const auto exact = exact_test<2>({2, 2}, basis, elements);
  EXPECT_EQ(exact.status, Independence::not_independent);
  EXPECT_EQ(exact.nullity(), 1);
}

// Exactly independent, numerically nearly dependent: the biquadratic tensor basis plus the B-spline
// B[1, 2 + d, 3, 4] x B[0, 0, 0, 1], d = 2^-40, next to the tensor B-spline B[1, 2, 3, 4] x B[0, 0, 0, 1]. The
// extra B-spline has a breakpoint at 2 + d that no tensor B-spline has, so it is not in their span: the
// collection is independent (nullity 0) although the two rows differ by about d. A floating-point rank with a
// relative threshold above d calls it dependent; the exact rank must not. With d = 0 it is a duplicate.
TEST(LinearIndependence, NearlyDependentButIndependentCollection) {
  for (const double d : {std::ldexp(1.0, -40), std::ldexp(1.0, -50), 0.0}) {
    const std::array<std::vector<double>, 2> t = {std::vector<double>{0, 0, 0, 1, 2, 3, 4, 4, 4},
                                                  std::vector<double>{0, 0, 0, 1, 1, 1}};
    auto basis = tensor_basis<2>({2, 2}, t);
    LRBSpline<2> extra;
    extra.knots[0] = {1, 2 + d, 3, 4};
    extra.knots[1] = {0, 0, 0, 1};
    basis.push_back(extra);
    auto cut = t;
    if (d > 0) cut[0].insert(cut[0].begin() + 5, 2 + d);
    const auto elements = tensor_elements<2>(cut);
    EXPECT_EQ(peeling_test<2>({2, 2}, basis, elements).status, Independence::not_tested);
    const auto exact = exact_test<2>({2, 2}, basis, elements);
    EXPECT_EQ(exact.status, d > 0 ? Independence::independent : Independence::not_independent) << d;
    EXPECT_EQ(exact.nullity(), d > 0 ? 0 : 1) << d;
  }
}

TEST(LinearIndependence, CollectionNotSpanningPolynomialsIsRejected) {
  const std::array<std::vector<double>, 2> t = {std::vector<double>{0, 0, 0, 1, 2, 2, 2},
                                                std::vector<double>{0, 0, 0, 1, 1, 1}};
  auto basis = tensor_basis<2>({2, 2}, t);
  basis.pop_back();
  EXPECT_THROW(peeling_test<2>({2, 2}, basis, tensor_elements<2>(t)), Error);
}

TEST(LinearIndependence, BezierExtractionOfRefinedCollectionReproducesTheSpline) {
  // LR refinement keeps sum gamma_i c_i B_i equal to the tensor spline it started from (coefficients
  // (i, j, i j) on the tensor grid); the element Bezier nets must evaluate to it.
  const std::vector<double> tu{0, 0, 0, 1, 2, 3, 4, 4, 4}, tv{0, 0, 0, 0, 1, 2, 3, 3, 3, 3};
  LR2 lr{{2, 3}, {tu, tv}};
  ASSERT_TRUE(lr.insert(knot_line(0, 1.5, 0, 2)));
  ASSERT_TRUE(lr.insert(knot_line(1, 1.5, 0, 3)));
  ASSERT_TRUE(lr.insert(knot_line(0, 2.5, 1, 3)));
  const auto basis = lr.functions();
  const auto elements = lr.elements();
  const auto nets = bezier_elements<2>({2, 3}, basis, elements, 3, false);
  std::mt19937 rng(8);
  double worst = 0.0;
  for (std::size_t e = 0; e < elements.size(); ++e)
    for (int q = 0; q < 5; ++q) {
      Param<2> u;
      for (int k = 0; k < 2; ++k) u[k] = std::uniform_real_distribution<double>(elements[e].lo[k], elements[e].hi[k])(rng);
      double x[3];
      eval_bezier(nets[e], u, x);
      double ref[3] = {0, 0, 0};
      for (int j = 0; j + 4 < static_cast<int>(tv.size()); ++j)
        for (int i = 0; i + 3 < static_cast<int>(tu.size()); ++i) {
          const double b = test::cox_de_boor(tu, i, 2, u[0], 4) * test::cox_de_boor(tv, j, 3, u[1], 3);
          ref[0] += b * i;
          ref[1] += b * j;
          ref[2] += b * i * j;
        }
      for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(x[d] - ref[d]));
    }
  EXPECT_LE(worst, 1e-13);
}

// The LRSpline overloads run on the spline's own support lists and must agree with the search-based tests.
TEST(LinearIndependence, SplineOverloadsAgreeWithCollectionTests) {
  const auto check = [](const LR2& src, int expect_nullity) {
    const LRSpline<2> lr(src.p, 3, false, src.functions(), src.rects);
    const auto basis = lr.basis_functions();
    const auto elements = lr.elements();
    const auto a = peeling_test<2>(src.p, basis, elements);
    const auto b = peeling_test(lr);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.overloaded_elements, b.overloaded_elements);
    EXPECT_EQ(a.overloaded_basis, b.overloaded_basis);
    EXPECT_EQ(a.unresolved, b.unresolved);
    const auto x = exact_test<2>(src.p, basis, elements);
    const auto y = exact_test(lr);
    EXPECT_EQ(x.status, y.status);
    EXPECT_EQ(x.tested, y.tested);
    EXPECT_EQ(x.rank, y.rank);
    EXPECT_EQ(y.nullity(), expect_nullity);
  };
  check(SeedExample{}.lr, 1);
  check(refined_bicubic(), 0);
}
