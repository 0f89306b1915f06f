#include "trivar/hier/hierarchical_space.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "hier/hier_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/lr/linear_independence.hpp"
#include "trivar/spline/derivative_index.hpp"

using namespace trivar;
using namespace trivar::test;

namespace {

template <int D>
HierarchicalSpace<D> uniform_space(int p, int elements, HierarchicalBasis b) {
  std::array<KnotVector, D> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(p, elements);
  return HierarchicalSpace<D>(TensorHierarchy<D>(kv), b);
}

// The cells of level l inside [0, x]^D.
template <int D>
std::vector<Ints<D>> corner_cells(const HierarchicalSpace<D>& s, int level, double x) {
  std::vector<Ints<D>> out;
  const int n = s.hierarchy().axis(level, 0).num_cells();
  int m = 0;
  while (m < n && s.hierarchy().axis(level, 0).brk(m + 1) <= x) ++m;
  Ints<D> c{};
  while (true) {
    out.push_back(c);
    int k = 0;
    while (k < D && ++c[k] == m) c[k] = 0, ++k;
    if (k == D) break;
  }
  return out;
}

// HB functions as scaled B-splines (gamma 1): the input of the LR layer's exact independence test.
template <int D>
std::vector<LRBSpline<D>> as_bsplines(const HierarchicalSpace<D>& s) {
  std::vector<LRBSpline<D>> out;
  for (int id = 0; id < s.num_basis(); ++id) {
    const auto f = s.function(id);
    LRBSpline<D> b;
    for (int k = 0; k < D; ++k) {
      const KnotVector& kv = s.hierarchy().knots(f.level, k);
      b.knots[k].assign(kv.data() + f.index[k], kv.data() + f.index[k] + s.degree(k) + 2);
    }
    b.coef = {0.0};
    out.push_back(b);
  }
  return out;
}

// Smallest eigenvalue of the Gram matrix of the functions' Bernstein coefficients over all elements, relative
// to the largest: zero (to rounding) exactly when the functions are linearly dependent.
template <int D>
double gram_condition(const HierarchicalSpace<D>& s) {
  const int N = s.num_basis();
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(N, N);
  for (int e = 0; e < s.num_elements(); ++e) {
    const auto el = s.element_operator(e);
    const Eigen::MatrixXd g = el.C * el.C.transpose();
    for (std::size_t a = 0; a < el.ids.size(); ++a)
      for (std::size_t b = 0; b < el.ids.size(); ++b)
        G(el.ids[a], el.ids[b]) += g(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
  }
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(G).eigenvalues();
  return ev.minCoeff() / ev.maxCoeff();
}

}  // namespace

// Biquadratic, 4 x 4 cells, [0, 1/2]^2 refined: 36 - 4 level-0 B-splines inside the refined square + 16
// level-1 B-splines in it (t_{i+3} <= 1/2 on both levels); 16 - 4 + 16 elements.
TEST(HierarchicalSpace, HandCountedSurface) {
  for (auto b : {HierarchicalBasis::hb, HierarchicalBasis::thb}) {
    auto s = uniform_space<2>(2, 4, b);
    EXPECT_EQ(s.num_basis(), 36);
    EXPECT_EQ(s.refine_cells(0, corner_cells(s, 0, 0.5)), 4);
    EXPECT_EQ(s.num_levels(), 2);
    EXPECT_EQ(s.num_basis(0), 32);
    EXPECT_EQ(s.num_basis(1), 16);
    EXPECT_EQ(s.num_elements(), 28);
  }
}

// Tricubic, 4^3 cells, [0, 1/2]^3 refined: 343 - 8 + 64 functions; 64 - 8 + 64 elements. Then the level-1
// cells in [0, 1/4]^3 (8 cells): at the clamped corner the level-2 B-splines with t_{i+4} <= 1/4 (i <= 3, 4 per
// direction) fit, and the level-1 ones with t_{i+4} <= 1/4 (i <= 1) leave: 399 - 8 + 64.
TEST(HierarchicalSpace, HandCountedVolume) {
  auto s = uniform_space<3>(3, 4, HierarchicalBasis::thb);
  s.refine_cells(0, corner_cells(s, 0, 0.5));
  EXPECT_EQ(s.num_basis(), 399);
  EXPECT_EQ(s.num_elements(), 120);
  s.refine_cells(1, corner_cells(s, 1, 0.25));
  EXPECT_EQ(s.num_basis(), 455);
  EXPECT_EQ(s.num_elements(), 120 - 8 + 64);
  EXPECT_EQ(s.num_levels(), 3);
  EXPECT_EQ(s.num_basis(2), 64);
  // One interior level-0 cell: no level-1 tricubic fits into its 2 x 2 x 2 children, no level-0 one leaves.
  const int before = s.num_basis();
  s.refine_cells(0, std::vector<Ints<3>>{{2, 2, 2}});
  EXPECT_EQ(s.num_basis(), before);
  EXPECT_EQ(s.num_elements(), 176 - 1 + 8);
}

TEST(HierarchicalSpace, RefinementByFunctions) {
  auto s = uniform_space<2>(2, 4, HierarchicalBasis::hb);
  // Function (0, 0) has support [0, 1/4]^2 (one cell): it leaves, and the level-1 B-splines with
  // t_{i+3} <= 1/4 (i <= 1) join: 36 - 1 + 4.
  const int id = s.find_function(0, {0, 0});
  EXPECT_EQ(s.refine_functions(std::vector<int>{id}), 1);
  EXPECT_EQ(s.num_basis(), 39);
  // Function (1, 1): support [0, 1/2]^2, 4 cells, 3 of them new: the hierarchy of HandCountedSurface.
  EXPECT_EQ(s.refine_functions(std::vector<int>{s.find_function(0, {1, 1})}), 3);
  EXPECT_EQ(s.num_basis(), 48);
}

template <int D>
void check_partition_and_independence(int p, int elements, int steps) {
  auto thb = HierarchicalSpline<D>(generic_spline<D>(p, elements, 1, false), HierarchicalBasis::thb);
  refine_randomly(thb, steps);
  const HierarchicalSpace<D>& s = thb.space();
  ASSERT_GE(s.num_levels(), steps);
  // THB: non-negative, sum to one at random points and on every element (Bernstein rows sum to ones).
  std::vector<int> ids;
  std::vector<double> v;
  for (const auto& u : random_points<D>(200)) {
    s.eval_basis(u, 0, ids, v);
    double sum = 0;
    for (double x : v) {
      EXPECT_GE(x, -1e-14);
      sum += x;
    }
    EXPECT_NEAR(sum, 1.0, 1e-13);
  }
  for (int e = 0; e < s.num_elements(); ++e) {
    const Eigen::VectorXd colsum = s.element_operator(e).C.colwise().sum().transpose();
    EXPECT_LT((colsum.array() - 1.0).abs().maxCoeff(), 1e-13) << "element " << e;
  }
  // HB of the same hierarchy: independent, exactly (the HB functions are B-splines with dyadic knots).
  const HierarchicalSpace<D> hb = s.with_basis(HierarchicalBasis::hb);
  const auto boxes = hb.element_boxes();
  const auto basis = as_bsplines(hb);
  const ExactResult exact = exact_test<D>(hb.degrees(), basis, boxes, 1);
  EXPECT_EQ(exact.status, Independence::independent);
  EXPECT_EQ(exact.nullity(), 0);
  // Both bases numerically: the Gram matrix of the Bernstein coefficients is regular.
  EXPECT_GT(gram_condition(hb), 1e-10);
  EXPECT_GT(gram_condition(s), 1e-10);
  // The test can fail: a level-0 B-spline that left the active set lies inside Omega^1, so it is a combination
  // of active functions; added to the HB functions it makes them dependent.
  auto more = basis;
  Ints<D> f{};
  while (hb.find_function(0, f) >= 0) {
    int k = 0;
    while (k < D && ++f[k] == hb.hierarchy().axis(0, k).num_functions()) f[k] = 0, ++k;
    ASSERT_LT(k, D) << "no level-0 function was deactivated";
  }
  LRBSpline<D> extra;
  for (int k = 0; k < D; ++k) {
    const KnotVector& kv = hb.hierarchy().knots(0, k);
    extra.knots[k].assign(kv.data() + f[k], kv.data() + f[k] + p + 2);
  }
  extra.coef = {0.0};
  more.push_back(extra);
  const ExactResult dep = exact_test<D>(hb.degrees(), more, boxes, 1);
  EXPECT_EQ(dep.status, Independence::not_independent);
  EXPECT_EQ(dep.nullity(), 1);
}

TEST(HierarchicalSpace, PartitionOfUnityAndIndependenceSurface) { check_partition_and_independence<2>(2, 4, 4); }
TEST(HierarchicalSpace, PartitionOfUnityAndIndependenceSurfaceCubic) { check_partition_and_independence<2>(3, 5, 4); }
TEST(HierarchicalSpace, PartitionOfUnityAndIndependenceVolume) { check_partition_and_independence<3>(2, 3, 3); }

TEST(HierarchicalSpace, BasisDerivativesMatchFiniteDifferences) {
  auto thb = HierarchicalSpline<2>(generic_spline<2>(3, 4, 1, false), HierarchicalBasis::thb);
  refine_randomly(thb, 3);
  const auto& s = thb.space();
  std::vector<int> ids, ip, im;
  std::vector<double> v, vp, vm;
  const double h = 1e-6;
  const int nd = derivative_count(2, 2);
  for (const auto& u : random_points<2>(50, 11)) {
    s.eval_basis(u, 2, ids, v);
    for (int a = 0; a < 2; ++a) {
      Param<2> up = u, um = u;
      up[a] += h;
      um[a] -= h;
      if (s.find_element(up) != s.find_element(u) || s.find_element(um) != s.find_element(u)) continue;
      s.eval_basis(up, 1, ip, vp);
      s.eval_basis(um, 1, im, vm);
      ASSERT_EQ(ip, ids);
      for (std::size_t r = 0; r < ids.size(); ++r) {
        const double fd = (vp[r * 3] - vm[r * 3]) / (2 * h);
        EXPECT_NEAR(v[r * nd + 1 + a], fd, 1e-6 * (1 + std::abs(fd)));
        for (int b = 0; b < 2; ++b) {
          const double fd2 = (vp[r * 3 + 1 + b] - vm[r * 3 + 1 + b]) / (2 * h);
          const int pos = derivative_position<2>(a == b ? Ints<2>{a == 0 ? 2 : 0, a == 1 ? 2 : 0} : Ints<2>{1, 1});
          EXPECT_NEAR(v[r * nd + pos], fd2, 1e-4 * (1 + std::abs(fd2)));
        }
      }
    }
  }
}

TEST(HierarchicalSpace, ExplicitNestedLevels) {
  // Level 1 adds knots at 1/3 and 0.8 only (not dyadic), level 2 is dyadic from it.
  const KnotVector k0 = KnotVector::open_uniform(2, 2);
  const KnotVector k1(2, {0, 0, 0, 1.0 / 3, 0.5, 0.8, 1, 1, 1});
  std::vector<std::array<KnotVector, 2>> levels{{k0, k0}, {k1, k1}};
  HierarchicalSpace<2> s(TensorHierarchy<2>(levels), HierarchicalBasis::thb);
  EXPECT_EQ(s.num_basis(), 16);
  s.refine_cells(0, std::vector<Ints<2>>{{0, 0}, {1, 0}, {0, 1}, {1, 1}});  // the whole domain: level 1 only
  EXPECT_EQ(s.num_basis(), 36);
  EXPECT_EQ(s.num_elements(), 16);
  const KnotVector bad(2, {0, 0, 0, 0.4, 1, 1, 1});  // lacks 0.5
  std::vector<std::array<KnotVector, 2>> wrong{{k0, k0}, {bad, k1}};
  EXPECT_THROW(TensorHierarchy<2>{wrong}, Error);
}

TEST(HierarchicalSpace, RefiningOutsideTheDomainThrows) {
  auto s = uniform_space<2>(2, 4, HierarchicalBasis::thb);
  EXPECT_THROW(s.refine_cells(1, std::vector<Ints<2>>{{0, 0}}), Error);  // level 1 does not exist yet
  s.refine_cells(0, std::vector<Ints<2>>{{0, 0}});
  EXPECT_THROW(s.refine_cells(1, std::vector<Ints<2>>{{5, 5}}), Error);  // not inside Omega^1
  EXPECT_THROW(s.refine_cells(0, std::vector<Ints<2>>{{4, 0}}), Error);  // no such cell
  EXPECT_THROW(s.refine_elements(std::vector<int>{1000}), Error);
}

// Domains given as arbitrary cell sets (G+Smo's boxes): Omega^1 = level-1 cells [3, 8)^3 cuts level-0 cells,
// Omega^2 = level-2 cells [7, 12)^3 cuts level-1 cells. HB functions stay independent, THB ones a partition of
// unity on every element, and the mesh holds exactly the domain.
TEST(HierarchicalSpace, DomainsCuttingCoarserCells) {
  auto box = [](int lo, int hi) {
    std::vector<Ints<3>> out;
    for (int k = lo; k < hi; ++k)
      for (int j = lo; j < hi; ++j)
        for (int i = lo; i < hi; ++i) out.push_back({i, j, k});
    return out;
  };
  for (auto b : {HierarchicalBasis::hb, HierarchicalBasis::thb}) {
    auto s = uniform_space<3>(2, 4, b);
    EXPECT_EQ(s.extend_domains({{}, box(3, 8), box(7, 12)}), 125 + 125);
    EXPECT_EQ(s.num_levels(), 3);
    EXPECT_TRUE(s.is_refined(1, {4, 4, 4}));
    EXPECT_TRUE(s.is_split(1, {3, 3, 3}));
    EXPECT_FALSE(s.is_refined(1, {3, 3, 3}));
    // Elements tile the domain: volumes sum to one, and the element found at a point contains it.
    double volume = 0;
    for (int e = 0; e < s.num_elements(); ++e) {
      const Box<3> q = s.element_box(e);
      volume += q.extent(0) * q.extent(1) * q.extent(2);
    }
    EXPECT_NEAR(volume, 1.0, 1e-14);
    for (const auto& u : random_points<3>(100)) {
      const Box<3> q = s.element_box(s.find_element(u));
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(q.lo[k] <= u[k] && u[k] <= q.hi[k]);
    }
    EXPECT_GT(gram_condition(s), 1e-10);
    if (b == HierarchicalBasis::thb)
      for (int e = 0; e < s.num_elements(); ++e) {
        const auto el = s.element_operator(e);
        for (int q = 0; q < s.local_size(); ++q) EXPECT_NEAR(el.C.col(q).sum(), 1.0, 1e-13);
      }
  }
  // Level-2 cells covering whole level-1 cells make those level-1 domain cells: the aligned hierarchy.
  auto given = uniform_space<2>(1, 4, HierarchicalBasis::thb);
  std::vector<Ints<2>> corner;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) corner.push_back({i, j});
  given.extend_domains({{}, {}, corner});
  auto refined = uniform_space<2>(1, 4, HierarchicalBasis::thb);
  refined.refine_cells(0, std::vector<Ints<2>>{{0, 0}});
  refined.refine_cells(1, std::vector<Ints<2>>{{0, 0}, {1, 0}, {0, 1}, {1, 1}});
  EXPECT_EQ(given.num_basis(), refined.num_basis());
  EXPECT_EQ(given.num_elements(), refined.num_elements());
  EXPECT_TRUE(given.is_refined(0, {0, 0}));
  EXPECT_THROW(given.extend_domains({{}, {{8, 0}}}), Error);
}

namespace {

// Refines `steps` times the leaf at (x, x) and 16 random leaves, admissibly of class m or (m = 0) plainly.
template <int D>
void refine_towards_corner(HierarchicalSpace<D>& s, int steps, int m, double x) {
  std::mt19937 rng(9);
  for (int i = 0; i < steps; ++i) {
    Param<D> u;
    u.fill(x);
    std::vector<int> marked{s.find_element(u)};
    std::uniform_int_distribution<int> pick(0, s.num_elements() - 1);
    for (int j = 0; j < 16; ++j) marked.push_back(pick(rng));
    if (m) s.refine_elements_admissible(marked, m);
    else s.refine_elements(marked);
  }
}

}  // namespace

// Class-m admissible meshes: at most m levels and m (p + 1)^D functions act on any element. Refining the same
// marks without the closure breaks the bound (so the check can fail).
TEST(HierarchicalSpace, AdmissibleRefinementBoundsTheLevelsPerElement) {
  for (auto b : {HierarchicalBasis::thb, HierarchicalBasis::hb})
    for (int m : {2, 3}) {
      auto s = uniform_space<2>(2, 4, b);
      refine_towards_corner(s, 8, m, 0.3);
      EXPECT_GE(s.num_levels(), 8);
      const auto [levels, functions] = levels_and_functions_per_element(s);
      EXPECT_LE(levels, m) << to_string(b) << " m = " << m;
      EXPECT_LE(functions, m * 9) << to_string(b) << " m = " << m;
    }
  auto plain = uniform_space<2>(2, 4, HierarchicalBasis::thb);
  refine_towards_corner(plain, 8, 0, 0.3);
  EXPECT_GT(levels_and_functions_per_element(plain).first, 2);
  // A volume, class 2.
  auto v = uniform_space<3>(2, 2, HierarchicalBasis::thb);
  refine_towards_corner(v, 4, 2, 0.3);
  const auto [levels, functions] = levels_and_functions_per_element(v);
  EXPECT_LE(levels, 2);
  EXPECT_LE(functions, 2 * 27);
}
