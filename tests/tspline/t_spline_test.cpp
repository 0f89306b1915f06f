#include <gtest/gtest.h>

#include <random>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/local_knots.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"
#include "trivar/tspline/t_spline_surface.hpp"
#include "trivar/tspline/tensor_t_spline.hpp"

namespace trivar {
namespace {

TensorSpline<2> random_tensor(int p, int q, bool rational, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1), W(0.5, 2);
  const std::vector<double> bs{0.0, 0.7, 1.5, 2.0, 3.2}, bt{-1.0, 0.0, 0.25, 2.0};
  KnotVector ks = KnotVector::from_breakpoints(p, bs), kt = KnotVector::from_breakpoints(q, bt);
  const int n = ks.size() * kt.size();
  const int st = rational ? 4 : 3;
  std::vector<double> c(static_cast<std::size_t>(n * st));
  for (int i = 0; i < n; ++i) {
    const double w = rational ? W(rng) : 1.0;
    for (int d = 0; d < 3; ++d) c[static_cast<std::size_t>(i * st + d)] = U(rng) * (rational ? w : 1.0);
    if (rational) c[static_cast<std::size_t>(i * st + 3)] = w;
  }
  return TensorSpline<2>({ks, kt}, 3, rational, c);
}

// The T-spline by its definition, sum w_i P_i B_i / sum w_i B_i with every B_i evaluated on its local knots by
// Cox-de Boor (spline/basis), independent of the Bezier extraction the evaluator uses.
std::array<double, 9> direct_sum(const TSpline& ts, double s, double t) {
  const auto basis = blending_functions(ts);
  double num[3][3] = {}, den[3] = {};
  for (const auto& b : basis) {
    double v[2][2];
    bool inside = true;
    for (int k = 0; k < 2; ++k) {
      const auto& kv = b.knots[k];
      const double u = k == 0 ? s : t;
      const int p = ts.degrees[k];
      if (u < kv.front() || u > kv.back() || (u == kv.back() && kv.back() != ts.image.domain().hi[k])) {
        inside = false;
        break;
      }
      // The one function of degree p on the p + 2 local knots: pad with p copies on both sides and take the
      // middle function of the extended sequence.
      std::vector<double> ext(static_cast<std::size_t>(3 * p + 2));
      for (int i = 0; i < p; ++i) ext[static_cast<std::size_t>(i)] = kv.front() - 1.0 - (p - i);
      for (int i = 0; i < p + 2; ++i) ext[static_cast<std::size_t>(p + i)] = kv[static_cast<std::size_t>(i)];
      for (int i = 0; i < p; ++i) ext[static_cast<std::size_t>(2 * p + 2 + i)] = kv.back() + 1.0 + i;
      int span = p;
      while (span + 1 < 2 * p + 1 && ext[static_cast<std::size_t>(span + 1)] <= u) ++span;
      while (ext[static_cast<std::size_t>(span)] == ext[static_cast<std::size_t>(span + 1)]) --span;
      double ders[2 * (kMaxDegree + 1)];
      basis_derivatives(ext.data(), p, span, u, 1, ders);
      const int idx = p - (span - p);  // function p of the extended sequence is the local one
      if (idx < 0 || idx > p) {
        v[k][0] = v[k][1] = 0;
      } else {
        v[k][0] = ders[idx];
        v[k][1] = ders[p + 1 + idx];
      }
    }
    if (!inside) continue;
    const double w = b.coef[3];
    const double B[3] = {v[0][0] * v[1][0], v[0][1] * v[1][0], v[0][0] * v[1][1]};
    for (int j = 0; j < 3; ++j) {
      den[j] += w * B[j];
      for (int d = 0; d < 3; ++d) num[j][d] += b.coef[static_cast<std::size_t>(d)] * B[j];
    }
  }
  std::array<double, 9> out{};
  for (int d = 0; d < 3; ++d) {
    out[static_cast<std::size_t>(d)] = num[0][d] / den[0];
    out[static_cast<std::size_t>(3 + d)] = (num[1][d] - out[static_cast<std::size_t>(d)] * den[1]) / den[0];
    out[static_cast<std::size_t>(6 + d)] = (num[2][d] - out[static_cast<std::size_t>(d)] * den[2]) / den[0];
  }
  return out;
}

class TensorReproduction : public ::testing::TestWithParam<std::tuple<int, int, bool>> {};

TEST_P(TensorReproduction, TensorMeshGivesTheTensorSpline) {
  const auto [p, q, rational] = GetParam();
  const TensorSpline<2> s = random_tensor(p, q, rational, 7u + static_cast<unsigned>(p * 10 + q));
  const TSpline ts = t_spline_from_tensor(s);
  const TSplineSurface surf(ts);
  EXPECT_EQ(static_cast<int>(surf.basis().size()), s.num_coefs());
  EXPECT_LT(surf.partition_of_unity().max_defect, 1e-13);
  // Local knot vectors are the tensor B-splines' knot windows.
  const auto knots = local_knot_vectors(ts);
  for (int b = 0; b < s.count(1); ++b)
    for (int a = 0; a < s.count(0); ++a) {
      const auto& kv = knots[static_cast<std::size_t>(a + s.count(0) * b)];
      for (int i = 0; i < p + 2; ++i) ASSERT_EQ(kv[0][static_cast<std::size_t>(i)], s.knots(0)[a + i]) << a << " " << b;
      for (int i = 0; i < q + 2; ++i) ASSERT_EQ(kv[1][static_cast<std::size_t>(i)], s.knots(1)[b + i]) << a << " " << b;
    }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> us(0.0, 3.2), ut(-1.0, 2.0);
  for (int i = 0; i < 300; ++i) {
    const Param<2> u{i == 0 ? 3.2 : us(rng), i == 0 ? 2.0 : ut(rng)};
    double a[9], b[9];
    surf.eval_first_derivatives(u, a);
    s.eval_derivs(u, 1, b);
    for (int d = 0; d < 9; ++d) ASSERT_NEAR(a[d], b[d], 1e-11 * (1 + std::abs(b[d]))) << d << " at " << u[0] << "," << u[1];
  }
}

INSTANTIATE_TEST_SUITE_P(Degrees, TensorReproduction,
                         ::testing::Values(std::tuple{3, 3, false}, std::tuple{3, 3, true}, std::tuple{2, 2, false},
                                           std::tuple{2, 2, true}, std::tuple{1, 1, false}, std::tuple{5, 3, true},
                                           std::tuple{4, 2, false}, std::tuple{3, 2, true}, std::tuple{2, 5, true}));

// A 6 x 6 cubic grid on [0, 6]^2 whose line s = 3 stops at t = 3: one T-junction at (3, 3) pointing up.
std::vector<KnotSegment> one_t_junction() {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 6.0}});
  }
  return g;
}

RationalPoint bump(double s, double t, int a, int b) {
  return {{s + 0.1 * a, t + 0.1 * b, std::sin(s) * std::cos(0.5 * t) + 0.05 * (a + b)}, 1.0 + 0.1 * std::sin(s + 2 * t)};
}

TEST(TJunction, LocalKnotVectorsFollowTheRaysOfSederberg2003) {
  const auto g = one_t_junction();
  const TSpline ts = t_spline_from_segments({3, 3}, g, bump);
  // 7 x 7 vertices less (3,4), (3,5), (3,6); the boundary adds one layer per side.
  const auto knots = local_knot_vectors(ts);
  const auto node_at = [&](double s, double t) {
    for (std::size_t i = 0; i < ts.connect.nodes.size(); ++i) {
      const TVertex& v = ts.image.vertices[static_cast<std::size_t>(ts.connect.nodes[i].anchor)];
      if (v.s == s && v.t == t) return i;
    }
    return std::size_t(-1);
  };
  using V = std::vector<double>;
  // Hand-derived: the ray along t = 4 from (2, 4) passes s = 3 (no edge there above t = 3).
  EXPECT_EQ(knots[node_at(2, 4)][0], (V{0, 1, 2, 4, 5}));
  EXPECT_EQ(knots[node_at(2, 4)][1], (V{2, 3, 4, 5, 6}));
  EXPECT_EQ(knots[node_at(4, 5)][0], (V{1, 2, 4, 5, 6}));
  // The T-junction itself: along t = 3 the full line; along s = 3 up through the edges t = 4, 5.
  EXPECT_EQ(knots[node_at(3, 3)][0], (V{1, 2, 3, 4, 5}));
  EXPECT_EQ(knots[node_at(3, 3)][1], (V{1, 2, 3, 4, 5}));
  EXPECT_EQ(knots[node_at(3, 2)][1], (V{0, 1, 2, 3, 4}));
  // The ray along t = 3 from (2, 3) meets the T-junction's stem end (counts).
  EXPECT_EQ(knots[node_at(2, 3)][0], (V{0, 1, 2, 3, 4}));
  // Corner blocks: the outer node has the full end multiplicity.
  EXPECT_EQ(knots[node_at(0, 0)][0], (V{0, 0, 0, 0, 1}));
}

TEST(TJunction, AnalysisSuitableMeshIsAPartitionOfUnityAndMatchesTheDefinition) {
  const auto g = one_t_junction();
  const TSpline ts = t_spline_from_segments({3, 3}, g, bump);
  const TSplineSurface surf(ts);
  // A single T-junction's extensions cannot cross: analysis-suitable, so the blending functions sum to one
  // (Li, Zheng, Sederberg, Hughes, Scott 2012).
  EXPECT_LT(surf.partition_of_unity().max_defect, 1e-13);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0.0, 6.0);
  for (int i = 0; i < 200; ++i) {
    const Param<2> u{U(rng), U(rng)};
    double a[9];
    surf.eval_first_derivatives(u, a);
    const auto b = direct_sum(ts, u[0], u[1]);
    for (int d = 0; d < 9; ++d) ASSERT_NEAR(a[d], b[static_cast<std::size_t>(d)], 1e-11 * (1 + std::abs(b[static_cast<std::size_t>(d)])));
  }
}

TEST(TJunction, DerivativesMatchFiniteDifferences) {
  // Two T-junctions whose extensions cross (not analysis-suitable) and a rational surface: the quotient rule.
  auto g = one_t_junction();
  g.push_back({{0.0, 2.5}, {4.0, 2.5}});
  g.push_back({{3.5, 0.0}, {3.5, 6.0}});
  const TSpline ts = t_spline_from_segments({3, 3}, g, bump);
  const TSplineSurface surf(ts);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0.2, 5.8);
  const double h = 1e-6;
  for (int i = 0; i < 100; ++i) {
    const Param<2> u{U(rng), U(rng)};
    double a[9], p[3], m[3];
    surf.eval_first_derivatives(u, a);
    for (int k = 0; k < 2; ++k) {
      Param<2> up = u, um = u;
      up[k] += h;
      um[k] -= h;
      surf.eval(up, p);
      surf.eval(um, m);
      for (int d = 0; d < 3; ++d) ASSERT_NEAR(a[3 + 3 * k + d], (p[d] - m[d]) / (2 * h), 1e-6);
    }
  }
}

TEST(TJunction, QuinticHasThreeOpenEndLayers) {
  const auto g = one_t_junction();
  const TSpline ts = t_spline_from_segments({5, 3}, g, bump);
  const TSplineSurface surf(ts);
  const auto knots = local_knot_vectors(ts);
  EXPECT_EQ(knots[0][0], (std::vector<double>{0, 0, 0, 0, 0, 0, 1}));
  double a[9];
  surf.eval_first_derivatives({1.3, 4.7}, a);
  const auto b = direct_sum(ts, 1.3, 4.7);
  for (int d = 0; d < 9; ++d) EXPECT_NEAR(a[d], b[static_cast<std::size_t>(d)], 1e-11);
}

TEST(TSplineValidation, BrokenLayersGiveOneLineErrors) {
  TSpline ts = t_spline_from_tensor(random_tensor(3, 3, false, 1));
  TSpline bad = ts;
  bad.connect.nodes[3].point = 10000;
  EXPECT_THROW(validate(bad), Error);
  bad = ts;
  bad.connect.nodes[3].neighbours[0] = 100000;  // no such node
  EXPECT_THROW(validate(bad), Error);
  bad = ts;
  std::swap(bad.image.faces[0].loop[0], bad.image.faces[0].loop[2]);
  EXPECT_THROW(validate(bad), Error);
  bad = ts;
  bad.pointset.points[0].w = -1;
  EXPECT_THROW(validate(bad), Error);
  try {
    validate(bad);
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace trivar
