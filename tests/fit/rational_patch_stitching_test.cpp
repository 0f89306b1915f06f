// C1 stitching of two rational surfaces: pieces of one NURBS with non-constant weights (C1 weights across the
// seam). The derivative jump of the rational map is measured by one-sided finite differences on each stitched
// patch's own evaluation; weights and the control points beyond the first two rows must keep their values bit for
// bit; an unbent split is reproduced, and the merged LR spline is the original NURBS.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "trivar/core/number_format.hpp"
#include "trivar/fit/patch_stitching.hpp"
#include "trivar/spline/split.hpp"
#include "fit/one_sided_stencil.hpp"

namespace trivar {
namespace {

// A rational bicubic over [0, 1]^2 (interior knots u 0.25, 0.5, 0.75 and v 0.5, all simple, so the surface is C2
// at u = 0.5): control points over a grid with random heights, random weights in [0.8, 1.25].
TensorSpline<2> rational_bicubic(unsigned seed) {
  std::array<KnotVector, 2> kv{KnotVector(3, {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}),
                               KnotVector(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1})};
  const int nu = kv[0].size(), nv = kv[1].size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> height(-0.2, 0.2), weight(0.8, 1.25);
  std::vector<double> h;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double w = weight(rng);
      h.insert(h.end(), {w * i / (nu - 1), w * j / (nv - 1), w * height(rng), w});
    }
  return TensorSpline<2>(kv, 3, true, std::move(h));
}

// The part's control points of column `col` moved by random Cartesian offsets, weights kept.
TensorSpline<2> bent_column(TensorSpline<2> s, int col, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-0.05, 0.05);
  for (int j = 0; j < s.count(1); ++j) {
    double* c = s.coefs().data() + 4 * s.linear_index({col, j});
    for (int k = 0; k < 3; ++k) c[k] += c[3] * offset(rng);
  }
  return s;
}

// Largest jump of the rational map's derivative across u = seam (first's side u = hi, second's u = lo), from
// one-sided 8-point differences on each patch alone, relative to the largest derivative. With step 0.002 this
// measures 4e-11 on the unsplit surface (the measurement's own floor: rounding against the rational map's high
// derivatives).
double rational_seam_jump(const LRSpline<2>& first, const LRSpline<2>& second, double seam) {
  constexpr double h = 0.002;
  const Eigen::VectorXd down = stencil_weights(h, -1), up = stencil_weights(h, 1);
  double worst = 0, size = 0;
  for (int i = 0; i <= 40; ++i) {
    const double v = i / 40.0;
    double a[3] = {0, 0, 0}, b[3] = {0, 0, 0}, x[3];
    for (int q = 0; q < 8; ++q) {
      first.eval({seam - q * h, v}, x);
      for (int c = 0; c < 3; ++c) a[c] += down[q] * x[c];
      second.eval({seam + q * h, v}, x);
      for (int c = 0; c < 3; ++c) b[c] += up[q] * x[c];
    }
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(a[c] - b[c]));
      size = std::max({size, std::abs(a[c]), std::abs(b[c])});
    }
  }
  return worst / size;
}

// Ids of the B-splines of rows 0 and 1 next to a side.
std::set<int> first_two_rows(const LRSpline<2>& s, DomainSide side) {
  std::set<int> ids;
  for (int r = 0; r < 2; ++r)
    for (int id : side_row(s, side, r)) ids.insert(id);
  return ids;
}

// Weights equal bit for bit; the other coordinates too away from the first two rows of `side`.
void expect_kept(const LRSpline<2>& after, const LRSpline<2>& before, DomainSide side) {
  ASSERT_EQ(after.num_basis(), before.num_basis());
  const std::set<int> rows = first_two_rows(after, side);
  EXPECT_FALSE(rows.empty());
  for (int i = 0; i < after.num_basis(); ++i) {
    const LRBSpline<2>& f = after.basis_function(i);
    const LRBSpline<2>& g = before.basis_function(i);
    EXPECT_EQ(f.gamma * f.coef[3], g.gamma * g.coef[3]) << "weight of B-spline " << i;
    if (rows.count(i) != 0) continue;
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(f.coef[static_cast<std::size_t>(c)], g.coef[static_cast<std::size_t>(c)]) << i;
    }
  }
}

TEST(RationalPatchStitching, BentNurbsPieceMadeC1KeepingTheWeights) {
  const auto [left, right] = split_at(rational_bicubic(5), 0, 0.5);
  const TensorSpline<2> bent = bent_column(right, 1, 9);
  const LRSpline<2> a(left), b(bent);
  const double before = rational_seam_jump(a, b, 0.5);
  EXPECT_GT(before, 1e-3);  // the bend broke C1
  const Stitched<2> s = stitch(a, b, {Continuity::C1});
  EXPECT_EQ(s.seam.dir, 0);
  EXPECT_EQ(s.seam.end, 1);
  // The weights fix the second's speed across the seam: the split's own (its domain kept up to rounding).
  EXPECT_NEAR(s.second.domain().hi[0], 1.0, 1e-12);
  const double after = rational_seam_jump(s.first, s.second, 0.5);
  RecordProperty("jump_before", format_number(before));
  RecordProperty("jump_after", format_number(after));
  RecordProperty("moved", format_number(s.moved));
  EXPECT_LE(after, 1e-10);
  EXPECT_GT(s.moved, 1e-4);
  expect_kept(s.first, a, {0, 1});
  expect_kept(s.second, b, {0, 0});
  // The merged LR spline is both patches.
  const LRSpline<2> m = merge(s);
  double worst = 0;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const Param<2> u{i / 20.0, j / 20.0};
      double x[3], y[3];
      m.eval(u, x);
      (u[0] <= 0.5 ? s.first : s.second).eval(u, y);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[c] - y[c]));
    }
  EXPECT_LE(worst, 1e-12);
}

TEST(RationalPatchStitching, SplitNurbsIsReproducedAndMergesBack) {
  const TensorSpline<2> whole = rational_bicubic(17);
  const auto [left, right] = split_at(whole, 0, 0.5);
  const Stitched<2> s = stitch(LRSpline<2>(left), LRSpline<2>(right), {Continuity::C1});
  RecordProperty("moved", format_number(s.moved));
  EXPECT_LE(s.moved, 1e-12);
  const LRSpline<2> m = merge(s);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> r(0.0, 1.0);
  double worst = 0;
  for (int i = 0; i < 400; ++i) {
    const Param<2> u{r(rng), r(rng)};
    double x[3], y[3];
    m.eval(u, x);
    whole.eval(u, y);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[c] - y[c]));
  }
  RecordProperty("merged_vs_original", format_number(worst));
  EXPECT_LE(worst, 1e-12);
  EXPECT_LE(rational_seam_jump(s.first, s.second, 0.5), 1e-10);
}

// A rational triquadratic volume over [0, 1]^3 with weights varying in every direction (knots u 0.25, 0.5, 0.75,
// simple), split at u = 0.5; the second half's row next to the seam bent. Made C1 with the weights kept; the
// derivative across the face, from each half's own evaluation at the face (one-sided, each on its own domain),
// agrees on an 11 x 11 grid.
TEST(RationalPatchStitching, BentNurbsVolumeHalfMadeC1) {
  std::array<KnotVector, 3> kv{KnotVector(2, {0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1}), KnotVector(2, {0, 0, 0, 1, 1, 1}),
                               KnotVector(2, {0, 0, 0, 1, 1, 1})};
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> weight(0.8, 1.25), offset(-0.05, 0.05);
  std::vector<double> h;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < kv[0].size(); ++i) {
        const double w = weight(rng);
        h.insert(h.end(), {w * i / (kv[0].size() - 1.0), w * j / 2.0, w * k / 2.0, w});
      }
  const auto [left, right] = split_at(TensorSpline<3>(kv, 3, true, std::move(h)), 0, 0.5);
  TensorSpline<3> bent = right;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) {
      double* c = bent.coefs().data() + 4 * bent.linear_index({1, j, k});
      for (int d = 0; d < 3; ++d) c[d] += c[3] * offset(rng);
    }
  const LRSpline<3> a(left), b(bent);
  const auto jump = [](const LRSpline<3>& x, const LRSpline<3>& y) {
    double worst = 0, size = 0, dx[12], dy[12];
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j <= 10; ++j) {
        x.eval_first_derivatives({0.5, i / 10.0, j / 10.0}, dx);
        y.eval_first_derivatives({0.5, i / 10.0, j / 10.0}, dy);
        for (int c = 3; c < 6; ++c) {
          worst = std::max(worst, std::abs(dx[c] - dy[c]));
          size = std::max(size, std::abs(dx[c]));
        }
      }
    return worst / size;
  };
  EXPECT_GT(jump(a, b), 1e-3);
  const Stitched<3> s = stitch(a, b, {Continuity::C1});
  EXPECT_NEAR(s.second.domain().hi[0], 1.0, 1e-12);
  EXPECT_LE(jump(s.first, s.second), 1e-12);
  RecordProperty("volume_jump_after", format_number(jump(s.first, s.second)));
  ASSERT_EQ(s.second.num_basis(), b.num_basis());
  for (int i = 0; i < b.num_basis(); ++i)
    EXPECT_EQ(s.second.basis_function(i).coef[3], b.basis_function(i).coef[3]) << "weight of B-spline " << i;
}

}  // namespace
}  // namespace trivar
