// The evaluation kernels compiled for each instruction set (generic x86-64, AVX2 + FMA, AVX-512) agree with
// each other to rounding and with the Cox-de Boor recursion, on every path (single point, batch, first
// derivatives), for every degree (and mixed degree) and stride that has a kernel. Paths the CPU lacks are skipped.
#include "trivar/spline/simd_level.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/spline_fixtures.hpp"
#include "trivar/spline/tensor_spline.hpp"

using namespace trivar;

namespace {

// Rebuilt from its data so the constructor picks the kernels of the current level (a copy keeps the old ones).
template <int D>
TensorSpline<D> rebuilt(const TensorSpline<D>& s) {
  return TensorSpline<D>(s.knot_vectors(), s.dim(), s.is_rational(), {s.coefs().begin(), s.coefs().end()});
}

// Open uniform knots (the O(1) span search) with random control values and weights.
template <int D>
TensorSpline<D> uniform_spline(int p, int dim, bool rational, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::array<KnotVector, D> kv;
  int n = 1;
  for (int k = 0; k < D; ++k) {
    kv[k] = KnotVector::open_uniform(p, 3 + k, -0.5, 2.0);
    n *= kv[k].size();
  }
  std::vector<double> pts(static_cast<std::size_t>(n * dim)), w;
  for (double& x : pts) x = U(rng);
  if (rational)
    for (int i = 0; i < n; ++i) w.push_back(1.0 + 0.5 * U(rng));
  return TensorSpline<D>::from_cartesian(kv, dim, pts, w);
}

struct Results {
  std::vector<double> value, first, batch;
};

template <int D>
Results evaluate(const TensorSpline<D>& s, const std::vector<Param<D>>& u) {
  const std::size_t dim = static_cast<std::size_t>(s.dim());
  Results r;
  r.value.resize(u.size() * dim);
  r.first.resize(u.size() * (D + 1) * dim);
  r.batch.resize(u.size() * dim);
  for (std::size_t i = 0; i < u.size(); ++i) {
    s.eval(u[i], r.value.data() + i * dim);
    s.eval_derivs(u[i], 1, r.first.data() + i * (D + 1) * dim);
  }
  s.eval_batch(u, r.batch, 1);
  return r;
}

void expect_close(const std::vector<double>& a, const std::vector<double>& b, double tol, const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_NEAR(a[i], b[i], tol * (1.0 + std::abs(b[i]))) << what << " entry " << i;
}

template <int D>
void check_all_levels(const TensorSpline<D>& original, const std::string& name) {
  auto u = test::random_params(original, 300, 7);
  // The domain's corners and the right end (closed) too.
  Param<D> lo, hi;
  for (int k = 0; k < D; ++k) {
    lo[k] = original.knots(k).start();
    hi[k] = original.knots(k).end();
  }
  u.push_back(lo);
  u.push_back(hi);
  limit_simd_level(SimdLevel::generic);
  const Results generic = evaluate(rebuilt(original), u);
  // The generic path against the recursion.
  for (std::size_t i = 0; i < u.size(); ++i) {
    const auto ref = test::reference_eval(original, u[i]);
    for (int d = 0; d < original.dim(); ++d)
      ASSERT_NEAR(generic.value[i * original.dim() + d], ref[d], 1e-12 * (1.0 + std::abs(ref[d]))) << name;
  }
  expect_close(generic.batch, generic.value, 0.0, name + " generic batch");
  for (int l = 1; l <= static_cast<int>(supported_simd_level()); ++l) {
    const auto level = static_cast<SimdLevel>(l);
    limit_simd_level(level);
    ASSERT_EQ(simd_level(), level);
    const Results r = evaluate(rebuilt(original), u);
    const std::string what = name + " " + simd_level_name(level);
    expect_close(r.value, generic.value, 1e-14, what + " value");
    expect_close(r.batch, generic.value, 1e-14, what + " batch");
    expect_close(r.first, generic.first, 1e-13, what + " first derivatives");
  }
  limit_simd_level(supported_simd_level());
}

template <int D>
void check_dimension() {
  for (int p = 1; p <= 4; ++p)
    for (auto [dim, rational] : {std::pair{1, false}, std::pair{3, false}, std::pair{3, true}}) {
      const std::string name = std::to_string(D) + "-D degree " + std::to_string(p) + " dim " +
                               std::to_string(dim) + (rational ? " rational" : "");
      Ints<D> deg, el;
      for (int k = 0; k < D; ++k) {
        deg[k] = p;
        el[k] = 3 + k;
      }
      check_all_levels(test::random_spline<D>(deg, el, dim, rational, 11u * static_cast<unsigned>(p)),
                       name + " non-uniform");
      check_all_levels(uniform_spline<D>(p, dim, rational, 5u * static_cast<unsigned>(p)), name + " uniform");
    }
  if constexpr (D > 1)
    // A lower degree in the last direction (the kernels of sphere and torus shells).
    for (auto [p, q] : {std::pair{2, 1}, std::pair{3, 1}, std::pair{3, 2}, std::pair{4, 1}, std::pair{4, 2}})
      for (bool rational : {false, true}) {
        Ints<D> deg, el;
        for (int k = 0; k < D; ++k) {
          deg[k] = k + 1 == D ? q : p;
          el[k] = 2 + k;
        }
        check_all_levels(test::random_spline<D>(deg, el, 3, rational, 7u * static_cast<unsigned>(p + q)),
                         std::to_string(D) + "-D degrees " + std::to_string(p) + "/" + std::to_string(q) +
                             (rational ? " rational" : ""));
      }
}

}  // namespace

TEST(SimdDispatch, LevelsAreOrderedAndCapped) {
  const SimdLevel best = supported_simd_level();
  limit_simd_level(SimdLevel::generic);
  EXPECT_EQ(simd_level(), SimdLevel::generic);
  limit_simd_level(SimdLevel::avx512);
  EXPECT_EQ(simd_level(), best);  // a cap above the supported level has no effect
  EXPECT_STREQ(simd_level_name(SimdLevel::avx2), "avx2");
}

TEST(SimdDispatch, CurvesAgreeOnEveryPath) { check_dimension<1>(); }
TEST(SimdDispatch, SurfacesAgreeOnEveryPath) { check_dimension<2>(); }
TEST(SimdDispatch, VolumesAgreeOnEveryPath) { check_dimension<3>(); }

// The kernels find spans of uniform knots by one multiplication; at the knots of a long uniform curve (300
// spans, where the product's rounding is largest) and one unit in the last place either side, every level
// agrees with the recursion, as on knots graded by 10^3 from span to span.
TEST(SimdDispatch, SpanLookupAtKnotsOfLongUniformAndGradedCurves) {
  std::vector<double> graded(4, 0.0);
  for (int i = 0; i < 4; ++i) graded.push_back(graded.back() + std::pow(1e3, i - 2));
  graded.insert(graded.end(), 3, graded.back());
  for (const KnotVector& kv : {KnotVector::open_uniform(3, 300, -0.3, 7.0), KnotVector(3, graded)}) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<double> pts(static_cast<std::size_t>(kv.size()) * 3);
    for (double& x : pts) x = U(rng);
    const auto curve = SplineCurve::from_cartesian({kv}, 3, pts);
    std::vector<Param<1>> u;
    for (int s = kv.first_span(); s <= kv.last_span() + 1; ++s)
      for (double v : {std::nextafter(kv[s], -1e9), kv[s], std::nextafter(kv[s], 1e9)})
        if (v >= kv.start() && v <= kv.end()) u.push_back({v});
    for (int l = 0; l <= static_cast<int>(supported_simd_level()); ++l) {
      limit_simd_level(static_cast<SimdLevel>(l));
      const Results r = evaluate(rebuilt(curve), u);
      for (std::size_t i = 0; i < u.size(); ++i) {
        const auto ref = test::reference_eval(curve, u[i]);
        for (int d = 0; d < 3; ++d)
          ASSERT_NEAR(r.value[i * 3 + d], ref[d], 1e-13)
              << simd_level_name(static_cast<SimdLevel>(l)) << " u " << u[i][0];
      }
    }
    limit_simd_level(supported_simd_level());
  }
}
