#include "trivar/spline/jacobian.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/derivative_index.hpp"
#include "trivar/spline/knot_insertion.hpp"

using namespace trivar;

namespace {

// Independent reference: det of the D x D matrix of first derivatives from TensorSpline::eval_derivs.
template <int D>
double det_at(const TensorSpline<D>& s, const Param<D>& u) {
  double d[derivative_count(3, 1) * 3];
  s.eval_derivs(u, 1, d);
  Eigen::Matrix<double, D, D> J;
  for (int k = 0; k < D; ++k)
    for (int r = 0; r < D; ++r) J(r, k) = d[(1 + k) * D + r];
  return J.determinant();
}

// Minimum of det J over a uniform grid of `n` points per direction.
template <int D>
double grid_min(const TensorSpline<D>& s, int n) {
  const auto box = s.domain();
  double m = std::numeric_limits<double>::infinity();
  int total = 1;
  for (int k = 0; k < D; ++k) total *= n;
  for (int q = 0; q < total; ++q) {
    Param<D> u;
    int r = q;
    for (int k = 0; k < D; ++k) {
      u[k] = box.lo[k] + box.extent(k) * (r % n) / (n - 1);
      r /= n;
    }
    m = std::min(m, det_at(s, u));
  }
  return m;
}

// Control points at the Greville abscissae mapped by x = A g + b: by linear precision the spline is exactly
// the affine map u -> A u + b, whatever the degrees and knots.
template <int D>
TensorSpline<D> affine(const std::array<KnotVector, D>& kv, const Eigen::Matrix<double, D, D>& A,
                       const Eigen::Matrix<double, D, 1>& b) {
  std::array<std::vector<double>, D> g;
  int n = 1;
  for (int k = 0; k < D; ++k) {
    g[k] = kv[k].greville();
    n *= kv[k].size();
  }
  std::vector<double> pts;
  for (int q = 0; q < n; ++q) {
    Eigen::Matrix<double, D, 1> u;
    int r = q;
    for (int k = 0; k < D; ++k) {
      u[k] = g[k][r % kv[k].size()];
      r /= kv[k].size();
    }
    const Eigen::Matrix<double, D, 1> x = A * u + b;
    pts.insert(pts.end(), x.data(), x.data() + D);
  }
  return TensorSpline<D>::from_cartesian(kv, D, pts);
}

template <int D>
std::array<KnotVector, D> knots(const Ints<D>& degrees, const Ints<D>& elements, unsigned seed) {
  std::mt19937 rng(seed);
  std::array<KnotVector, D> kv;
  for (int k = 0; k < D; ++k) kv[k] = test::random_knots(degrees[k], elements[k], rng, 0.0, 1.0 + k);
  return kv;
}

// Moves every control point of s by a random vector of length <= amplitude.
template <int D>
TensorSpline<D> perturbed(TensorSpline<D> s, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-amplitude, amplitude);
  for (double& c : s.coefs()) c += U(rng);
  return s;
}

// Quarter annulus 1 <= r <= 2 in the first quadrant: u radial (degree 1), v angular (exact rational
// quadratic, weights 1, sqrt(2)/2, 1); in 3-D extruded in z over [0, h] by w (degree 1).
std::vector<double> annulus_points(std::vector<double>& weights, double z, std::vector<double> pts = {}) {
  const double s = std::sqrt(0.5);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 2; ++i) {
      const double r = 1.0 + i;
      const double xy[3][2] = {{r, 0}, {r, r}, {0, r}};
      pts.insert(pts.end(), {xy[j][0], xy[j][1]});
      if (z >= 0) pts.push_back(z);
      weights.push_back(j == 1 ? s : 1.0);
    }
  return pts;
}

SplineSurface quarter_annulus_2d() {
  std::vector<double> w;
  const auto pts = annulus_points(w, -1);
  return SplineSurface::from_cartesian({KnotVector(1, {0, 0, 1, 1}), KnotVector(2, {0, 0, 0, 1, 1, 1})}, 2, pts, w);
}

SplineVolume quarter_annulus_3d(double h) {
  std::vector<double> w;
  auto pts = annulus_points(w, 0.0);
  pts = annulus_points(w, h, pts);
  return SplineVolume::from_cartesian(
      {KnotVector(1, {0, 0, 1, 1}), KnotVector(2, {0, 0, 0, 1, 1, 1}), KnotVector(1, {0, 0, 1, 1})}, 3, pts, w);
}

}  // namespace

TEST(Jacobian, AffineMapHasConstantDeterminant) {
  Eigen::Matrix3d A;
  A << 1.2, 0.3, -0.2, 0.1, 0.9, 0.4, -0.3, 0.2, 1.5;
  const Eigen::Vector3d b(0.5, -1, 2);
  for (const Ints<3>& p : {Ints<3>{1, 1, 1}, Ints<3>{2, 3, 1}}) {
    const auto s = affine<3>(knots<3>(p, {3, 2, 4}, 301), A, b);
    const auto rep = check_jacobian(s);
    EXPECT_TRUE(rep.valid);
    EXPECT_FALSE(rep.invalid);
    EXPECT_NEAR(rep.min_lower_bound, A.determinant(), 1e-12);
    EXPECT_NEAR(rep.min_value, A.determinant(), 1e-12);
    EXPECT_EQ(rep.elements, 3 * 2 * 4);
    EXPECT_EQ(rep.subdivisions, 0);
  }
  // Orientation reversed: det A < 0 everywhere, certified invalid with the exact value.
  const Eigen::Matrix3d M = A * Eigen::Vector3d(1, -1, 1).asDiagonal();
  const auto rep = check_jacobian(affine<3>(knots<3>({1, 2, 2}, {2, 2, 2}, 302), M, b));
  EXPECT_FALSE(rep.valid);
  EXPECT_TRUE(rep.invalid);
  EXPECT_NEAR(rep.min_value, M.determinant(), 1e-12);
}

TEST(Jacobian, AffinePlanarMap) {
  Eigen::Matrix2d A;
  A << 0.7, -0.4, 0.2, 1.1;
  const auto s = affine<2>(knots<2>({3, 1}, {4, 3}, 303), A, Eigen::Vector2d(1, 1));
  const auto rep = check_jacobian(s);
  EXPECT_TRUE(rep.valid);
  EXPECT_NEAR(rep.min_lower_bound, A.determinant(), 1e-12);
  EXPECT_NEAR(rep.min_value, A.determinant(), 1e-12);
}

TEST(Jacobian, ElevatedAndRefinedAffineVolumeKeepsExactBound) {
  Eigen::Matrix3d A;
  A << 2, 0.5, 0, -0.3, 1, 0.2, 0.1, 0.4, 0.8;
  auto s = affine<3>({KnotVector(1, {0, 0, 1, 1}), KnotVector(1, {0, 0, 1, 1}), KnotVector(1, {0, 0, 1, 1})}, A,
                     Eigen::Vector3d(0, 0, 0));
  s = elevate_degree(s, Ints<3>{2, 2, 2});
  s = insert_knot(s, 0, 0.3);
  s = insert_knot(s, 1, 0.55, 2);
  s = insert_knot(s, 2, 0.8);
  s = insert_knot(s, 2, 0.25);
  ASSERT_EQ(s.degree(0), 3);
  const auto rep = check_jacobian(s);
  EXPECT_TRUE(rep.valid);
  EXPECT_EQ(rep.elements, 2 * 2 * 3);
  EXPECT_NEAR(rep.min_lower_bound, A.determinant(), 1e-10);
  EXPECT_NEAR(rep.min_value, A.determinant(), 1e-10);
}

TEST(Jacobian, PerturbedBoxIsValidWithTightBound) {
  const auto box = affine<3>(knots<3>({3, 2, 3}, {3, 3, 2}, 304), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  const auto s = perturbed(box, 0.04, 305);
  const auto rep = check_jacobian(s);
  const double sampled = grid_min(s, 41);
  ASSERT_GT(sampled, 0.2);
  EXPECT_TRUE(rep.valid);
  EXPECT_FALSE(rep.invalid);
  EXPECT_LE(rep.min_lower_bound, sampled);
  EXPECT_LE(rep.min_lower_bound, rep.min_value);
  EXPECT_GE(rep.min_lower_bound, sampled * (1 - 1e-2));
  EXPECT_NEAR(rep.min_value, sampled, 1e-2 * sampled);
  EXPECT_NEAR(det_at(s, rep.where), rep.min_value, 1e-8);
}

TEST(Jacobian, PerturbedPlanarMapIsValidWithTightBound) {
  const auto sq = affine<2>(knots<2>({2, 3}, {4, 3}, 306), Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero());
  const auto s = perturbed(sq, 0.05, 307);
  const auto rep = check_jacobian(s);
  const double sampled = grid_min(s, 401);
  ASSERT_GT(sampled, 0.2);
  EXPECT_TRUE(rep.valid);
  EXPECT_LE(rep.min_lower_bound, sampled);
  EXPECT_GE(rep.min_lower_bound, sampled * (1 - 1e-2));
  EXPECT_NEAR(rep.min_value, sampled, 1e-2 * sampled);
}

TEST(Jacobian, FoldedVolumeIsInvalidAtAnActualValue) {
  // Tricubic unit cube with 2 elements per direction (C^2, so det J is continuous): a control point of the
  // top face z = 1 pushed through the opposite face z = 0.
  std::array<KnotVector, 3> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(3, 2);
  auto s = affine<3>(kv, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  const int n = kv[0].size();
  s.coefs()[s.linear_index({1, 2, n - 1}) * 3 + 2] = -0.5;
  const auto rep = check_jacobian(s);
  EXPECT_FALSE(rep.valid);
  EXPECT_TRUE(rep.invalid);
  EXPECT_LT(rep.min_value, 0.0);
  EXPECT_LE(rep.min_lower_bound, rep.min_value);
  EXPECT_NEAR(det_at(s, rep.where), rep.min_value, 1e-8);
  EXPECT_LE(rep.min_value, grid_min(s, 21) + 1e-2 * std::abs(rep.min_value));
}

TEST(Jacobian, FoldedPlanarMapIsInvalid) {
  std::array<KnotVector, 2> kv{KnotVector::open_uniform(2, 3), KnotVector::open_uniform(2, 3)};
  auto s = affine<2>(kv, Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero());
  s.coefs()[s.linear_index({2, 2}) * 2 + 1] = -0.2;  // an interior point below the bottom edge y = 0
  const auto rep = check_jacobian(s);
  EXPECT_TRUE(rep.invalid);
  EXPECT_FALSE(rep.valid);
  EXPECT_LT(rep.min_value, 0.0);
  EXPECT_NEAR(det_at(s, rep.where), rep.min_value, 1e-8);
  EXPECT_LE(rep.min_lower_bound, grid_min(s, 301));
}

TEST(Jacobian, RationalQuarterAnnulusIsValid) {
  const auto s = quarter_annulus_3d(0.7);
  // The map is the exact annulus: radius 1 + u at every (u, v).
  double x[3];
  for (double u : {0.0, 0.4, 1.0})
    for (double v : {0.0, 0.3, 0.77, 1.0}) {
      s.eval({u, v, 0.5}, x);
      EXPECT_NEAR(std::hypot(x[0], x[1]), 1 + u, 1e-14);
    }
  for (const auto& vol : {s, insert_knot(elevate_degree(s, Ints<3>{1, 1, 2}), 1, 0.4)}) {
    const auto rep = check_jacobian(vol);
    const double sampled = grid_min(vol, 31);
    EXPECT_TRUE(rep.valid);
    EXPECT_GT(rep.min_lower_bound, 0.0);
    EXPECT_LE(rep.min_lower_bound, sampled);
    EXPECT_GE(rep.min_lower_bound, sampled * (1 - 1e-2));
    EXPECT_NEAR(det_at(vol, rep.where), rep.min_value, 1e-8);
  }
}

TEST(Jacobian, RationalPlanarAnnulusIsValid) {
  const auto s = quarter_annulus_2d();
  const auto rep = check_jacobian(s);
  const double sampled = grid_min(s, 201);
  EXPECT_TRUE(rep.valid);
  EXPECT_LE(rep.min_lower_bound, sampled);
  EXPECT_GE(rep.min_lower_bound, sampled * (1 - 1e-2));
  EXPECT_NEAR(det_at(s, rep.where), rep.min_value, 1e-8);
  // Mirrored (v reversed by swapping x and y): orientation flips, certified invalid.
  auto m = s;
  for (int i = 0; i < m.num_coefs(); ++i) std::swap(m.coefs()[i * 3], m.coefs()[i * 3 + 1]);
  const auto bad = check_jacobian(m);
  EXPECT_TRUE(bad.invalid);
  EXPECT_NEAR(det_at(m, bad.where), bad.min_value, 1e-8);
}

TEST(Jacobian, CollapsedFaceIsNotValid) {
  // Unit cube whose top face is collapsed to its centre: a pyramid, det J = 0 on the top face.
  std::array<KnotVector, 3> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(1, 1);
  auto s = affine<3>(kv, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      double* c = s.coefs().data() + s.linear_index({i, j, 1}) * 3;
      c[0] = c[1] = 0.5;
    }
  for (const auto& vol : {s, refine_uniform(elevate_degree(s, Ints<3>{1, 2, 0}), Ints<3>{2, 2, 2})}) {
    const auto rep = check_jacobian(vol);
    EXPECT_FALSE(rep.valid);
    EXPECT_LE(rep.min_lower_bound, 1e-12);
    EXPECT_NEAR(rep.min_value, 0.0, 1e-12);
    EXPECT_NEAR(rep.where[2], 1.0, 1e-15);
  }
}

TEST(Jacobian, ZeroUpToRoundingIsNotCertifiedValid) {
  // Bi-quadratic square with the middle control point at (1.5, 1): x_u = 2 (0.25 * 0.5 - 0.5 * 0.5 + 0.25 * 0.5)
  // = 0 at (u, v) = (1, 0.5), so det J >= 0 with a zero there; rounding may compute it as a tiny positive.
  std::array<KnotVector, 2> kv{KnotVector::open_uniform(2, 1), KnotVector::open_uniform(2, 1)};
  auto s = affine<2>(kv, Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero());
  double* c = s.coefs().data() + s.linear_index({1, 1}) * 2;
  c[0] = 1.5;
  c[1] = 1.0;
  EXPECT_NEAR(det_at(s, {1.0, 0.5}), 0.0, 1e-15);
  const auto rep = check_jacobian(s);
  EXPECT_FALSE(rep.valid);
  EXPECT_LE(rep.min_lower_bound, 0.0);
  EXPECT_NEAR(rep.min_value, 0.0, 1e-15);
}

TEST(Jacobian, UndecidedWithoutSubdivisionCertifiedWithIt) {
  // A bi-quadratic square whose middle control point is pulled towards a corner: det J > 0 but some Bernstein
  // coefficients are negative, so only subdivision can certify it.
  std::array<KnotVector, 2> kv{KnotVector::open_uniform(2, 1), KnotVector::open_uniform(2, 1)};
  auto s = affine<2>(kv, Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero());
  double* c = s.coefs().data() + s.linear_index({1, 1}) * 2;
  c[0] = 1.3;
  c[1] = 1.0;
  const double sampled = grid_min(s, 401);
  ASSERT_GT(sampled, 0.0);
  JacobianOptions shallow;
  shallow.max_depth = 0;
  const auto r0 = check_jacobian(s, shallow);
  EXPECT_FALSE(r0.valid);
  EXPECT_FALSE(r0.invalid);
  EXPECT_LT(r0.min_lower_bound, 0.0);
  const auto r = check_jacobian(s);
  EXPECT_TRUE(r.valid);
  EXPECT_GT(r.subdivisions, 0);
  EXPECT_LE(r.min_lower_bound, sampled);
}

TEST(Jacobian, CurveDerivativeSign) {
  // x' is piecewise linear with B-spline coefficients p (P_{i+1} - P_i) / (t_{i+p+1} - t_{i+1}) = 2, 1, 4:
  // its minimum 1 is at the knot u = 1.
  const SplineCurve c({KnotVector(2, {0, 0, 0, 1, 2, 2, 2})}, 1, false, {0, 1, 2, 4});
  const auto rep = check_jacobian(c);
  EXPECT_TRUE(rep.valid);
  EXPECT_NEAR(rep.min_value, 1.0, 1e-14);
  EXPECT_LE(rep.min_lower_bound, 1.0);
  EXPECT_GE(rep.min_lower_bound, 1.0 - 1e-12);
  EXPECT_NEAR(rep.where[0], 1.0, 1e-15);
}

TEST(Jacobian, RejectsMismatchedDimensionAndOptions) {
  EXPECT_THROW(check_jacobian(test::random_spline<3>({1, 1, 1}, {1, 1, 1}, 2, false, 308)), Error);
  EXPECT_THROW(check_jacobian(test::random_spline<2>({1, 1}, {1, 1}, 3, false, 309)), Error);
  JacobianOptions bad;
  bad.max_depth = -1;
  EXPECT_THROW(check_jacobian(test::random_spline<2>({1, 1}, {1, 1}, 2, false, 310), bad), Error);
}
