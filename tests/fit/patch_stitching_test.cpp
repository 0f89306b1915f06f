// C0/C1 stitching of two surfaces: continuity measured by evaluating the two stitched patches independently at
// the seam, geometry elsewhere unchanged (control points bit for bit, values to 1e-12), the merged LR spline equal
// to both, the halves of one C2 surface merging back into it, and one-line errors for bad pairs.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/fit/patch_stitching.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/knot_insertion.hpp"
#include "trivar/spline/split.hpp"

namespace trivar {
namespace {

constexpr int kDegree = 3;

// A cubic surface over the knots, control points over a grid in x in [x0, x1], y in [0, 1] with random heights;
// column `fixed` (if >= 0) takes the given edge points instead.
TensorSpline<2> surface(std::vector<double> u, std::vector<double> v, double x0, double x1, unsigned seed,
                        const std::vector<double>& edge = {}, int fixed = -1) {
  std::array<KnotVector, 2> kv{KnotVector(kDegree, std::move(u)), KnotVector(kDegree, std::move(v))};
  const int nu = kv[0].size(), nv = kv[1].size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> h(-0.2, 0.2);
  std::vector<double> pts;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      if (i == fixed) {
        pts.insert(pts.end(), edge.begin() + 3 * j, edge.begin() + 3 * j + 3);
        continue;
      }
      pts.push_back(x0 + (x1 - x0) * i / (nu - 1));
      pts.push_back(static_cast<double>(j) / (nv - 1));
      pts.push_back(h(rng));
    }
  return TensorSpline<2>::from_cartesian(kv, 3, pts);
}

// The points of column i of a surface.
std::vector<double> column(const TensorSpline<2>& s, int i) {
  std::vector<double> out;
  for (int j = 0; j < s.count(1); ++j)
    for (int c = 0; c < 3; ++c) out.push_back(s.coefs()[static_cast<std::size_t>(3 * s.linear_index({i, j}) + c)]);
  return out;
}

// s re-parametrised by (u, v) -> (1 - u, 1 - v) mapped onto [u0, u1] x [v0, v1]: the same surface, the first
// side now last.
TensorSpline<2> rotated(const TensorSpline<2>& s, double u0, double u1, double v0, double v1, bool flip_v = true) {
  std::array<KnotVector, 2> kv;
  const double lo[2] = {u0, v0}, hi[2] = {u1, v1};
  for (int k = 0; k < 2; ++k) {
    const auto& t = s.knots(k).knots();
    const bool flip = k == 0 || flip_v;
    std::vector<double> n;
    for (double x : t) {
      const double x01 = (x - t.front()) / (t.back() - t.front());
      n.push_back(lo[k] + (hi[k] - lo[k]) * (flip ? 1 - x01 : x01));
    }
    if (flip) std::reverse(n.begin(), n.end());
    kv[static_cast<std::size_t>(k)] = KnotVector(kDegree, n);
  }
  std::vector<double> pts;
  for (int j = 0; j < s.count(1); ++j)
    for (int i = 0; i < s.count(0); ++i) {
      const int si = s.count(0) - 1 - i, sj = flip_v ? s.count(1) - 1 - j : j;
      for (int c = 0; c < 3; ++c) pts.push_back(s.coefs()[static_cast<std::size_t>(3 * s.linear_index({si, sj}) + c)]);
    }
  return TensorSpline<2>::from_cartesian(kv, 3, pts);
}

// s with its parameter directions swapped and the new v reversed: (u, v) -> (v, 1 - u), a quarter turn (the
// orientation is kept).
TensorSpline<2> quarter_turn(const TensorSpline<2>& s) {
  const auto& tu = s.knots(0).knots();
  std::vector<double> nv;
  for (auto it = tu.rbegin(); it != tu.rend(); ++it) nv.push_back(tu.front() + tu.back() - *it);
  std::array<KnotVector, 2> kv{s.knots(1), KnotVector(kDegree, nv)};
  std::vector<double> pts;
  const int nu = s.count(0), nw = s.count(1);
  for (int j = 0; j < nu; ++j)
    for (int i = 0; i < nw; ++i)
      for (int c = 0; c < 3; ++c) pts.push_back(s.coefs()[static_cast<std::size_t>(3 * s.linear_index({nu - 1 - j, i}) + c)]);
  return TensorSpline<2>::from_cartesian(kv, 3, pts);
}

struct Pair {
  TensorSpline<2> a, b;  // a on [0, 1]^2; b continues it beyond u = 1 but is given rotated onto [2, 5] x [-1, 1]
};

// Two independent patches sharing the side u = 1 of a as one curve, with knot lines the other lacks on that
// side (a: v = 0.3; b: v = 0.7, 0.8) and unrelated derivatives across it.
Pair make_pair_() {
  const std::vector<double> v0{0, 0, 0, 0, 0.5, 1, 1, 1, 1};
  TensorSpline<2> a = surface({0, 0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1}, v0, 0.0, 1.0, 7);
  TensorSpline<2> b = surface({0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}, v0, 1.0, 1.8, 11, column(a, a.count(0) - 1), 0);
  a = insert_knot(a, 1, 0.3);
  const std::vector<double> extra{0.7, 0.8};
  b = insert_knots(b, 1, extra);
  return {a, rotated(b, 2.0, 5.0, -1.0, 1.0)};
}

double max_jump(const Stitched<2>& s, int order, int samples = 101) {
  double jump = 0;
  double x[9], y[9];
  for (int i = 0; i < samples; ++i) {
    const double v = static_cast<double>(i) / (samples - 1);
    s.first.eval_first_derivatives({1.0, v}, x);
    s.second.eval_first_derivatives({1.0, v}, y);
    for (int c = 0; c < 3; ++c) jump = std::max(jump, std::abs(x[3 * order + c] - y[3 * order + c]));
  }
  return jump;
}

// Control points of the B-splines of `lr` keyed by their knots.
std::map<std::array<std::vector<double>, 2>, std::vector<double>> by_knots(const LRSpline<2>& lr) {
  std::map<std::array<std::vector<double>, 2>, std::vector<double>> m;
  for (const auto& b : lr.basis_functions()) m[b.knots] = b.coef;
  return m;
}

TEST(PatchStitching, C1AcrossTheSeamAndUnchangedElsewhere) {
  const Pair in = make_pair_();
  const Stitched<2> s = stitch(LRSpline<2>(in.a), LRSpline<2>(in.b), {Continuity::C1});
  EXPECT_EQ(s.seam.dir, 0);
  EXPECT_EQ(s.seam.end, 1);
  EXPECT_LT(s.seam_gap, 1e-14);
  EXPECT_EQ(s.second.domain().lo[0], 1.0);
  EXPECT_EQ(s.second.domain().lo[1], 0.0);
  EXPECT_EQ(s.second.domain().hi[1], 1.0);
  EXPECT_GT(s.moved, 1e-3);  // the random patches were not C1
  EXPECT_LT(max_jump(s, 0), 1e-12);
  EXPECT_LT(max_jump(s, 1), 1e-10);  // d/du
  EXPECT_LT(max_jump(s, 2), 1e-12);  // d/dv along the seam

  // B-splines of a outside the two rows next to the seam: same knots, bit-identical control points.
  const auto before = by_knots(LRSpline<2>(in.a));
  const auto after = by_knots(s.first);
  const LRSpline<2> merged = merge(s);
  const auto joined = by_knots(merged);
  int kept = 0;
  for (const auto& [knots, coef] : before) {
    if (std::count(knots[0].begin(), knots[0].end(), 1.0) >= kDegree) continue;
    ASSERT_TRUE(after.count(knots));
    EXPECT_EQ(after.at(knots), coef);
    ASSERT_TRUE(joined.count(knots));
    EXPECT_EQ(joined.at(knots), coef);
    ++kept;
  }
  EXPECT_EQ(kept, in.a.count(1) * (in.a.count(0) - 2));
  // Values where the two rows do not reach (u <= 0.6) are a's own.
  double x[3], y[3];
  for (double u : {0.0, 0.17, 0.45, 0.6})
    for (double v : {0.0, 0.3, 0.55, 1.0}) {
      in.a.eval({u, v}, x);
      s.first.eval({u, v}, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12);
    }
  // The merged LR spline is the pair: one domain, the same values on both sides.
  EXPECT_EQ(merged.domain().lo[0], 0.0);
  EXPECT_EQ(merged.domain().hi[0], s.second.domain().hi[0]);
  for (double u : {0.1, 0.7, 0.999, 1.0, 1.001, 1.3, s.second.domain().hi[0]})
    for (double v : {0.0, 0.25, 0.75, 1.0}) {
      (u < 1.0 ? s.first : s.second).eval({u, v}, x);
      merged.eval({u, v}, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12) << u << " " << v;
    }
}

// The second patch given with its directions swapped (a quarter turn) stitches to the same result.
TEST(PatchStitching, QuarterTurnedSecondPatch) {
  const Pair in = make_pair_();
  const Stitched<2> s = stitch(LRSpline<2>(in.a), LRSpline<2>(quarter_turn(in.b)), {Continuity::C1});
  const Stitched<2> r = stitch(LRSpline<2>(in.a), LRSpline<2>(in.b), {Continuity::C1});
  EXPECT_LT(max_jump(s, 1), 1e-10);
  EXPECT_NEAR(s.second.domain().hi[0], r.second.domain().hi[0], 1e-12);
  double x[3], y[3];
  for (double u : {1.0, 1.2, 1.5, s.second.domain().hi[0]})
    for (double v : {0.0, 0.4, 1.0}) {
      s.second.eval({u, v}, x);
      r.second.eval({u, v}, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12);
    }
}

TEST(PatchStitching, C0KeepsTheDerivativeJump) {
  const Pair in = make_pair_();
  const Stitched<2> s = stitch(LRSpline<2>(in.a), LRSpline<2>(in.b), {Continuity::C0});
  EXPECT_LT(max_jump(s, 0), 1e-12);
  EXPECT_GT(max_jump(s, 1), 1e-2);  // nothing made the random patches tangent
  const LRSpline<2> merged = merge(s);
  double x[3], y[3];
  for (double u : {0.5, 0.95, 1.05, 1.5})
    for (double v : {0.1, 0.9}) {
      (u < 1.0 ? s.first : s.second).eval({u, v}, x);
      merged.eval({u, v}, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12);
    }
}

// The two halves of one C2 surface, each refined along the seam differently and the second given rotated and
// shifted, stitch C1 with rounding-size changes and merge back into the original surface.
TEST(PatchStitching, HalvesOfOneSurfaceMergeBackIntoIt) {
  const TensorSpline<2> whole = surface({0, 0, 0, 0, 0.5, 1, 1.5, 2, 2, 2, 2}, {0, 0, 0, 0, 0.4, 1, 1, 1, 1}, 0, 2, 3);
  auto [left, right] = split_at(whole, 0, 1.0);
  left = insert_knot(left, 1, 0.7);
  right = insert_knot(right, 1, 0.2);
  const Stitched<2> s = stitch(LRSpline<2>(rotated(right, 0, 1, 0, 1)), LRSpline<2>(left), {Continuity::C1});
  EXPECT_LT(s.moved, 1e-13);
  const LRSpline<2> merged = merge(s);
  // right was rotated by 180 degrees, so merged(u, v) = whole(2 - u, 1 - v) on [0, 2] x [0, 1].
  EXPECT_DOUBLE_EQ(merged.domain().lo[0], 0.0);
  EXPECT_NEAR(merged.domain().hi[0], 2.0, 1e-14);
  double x[3], y[3];
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 10; ++j) {
      const double u = 0.1 * i, v = 0.1 * j;
      whole.eval({2.0 - u, 1.0 - v}, x);
      merged.eval({std::min(u, merged.domain().hi[0]), v}, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12);
    }
}

// An LR patch refined locally inside (away from the seam rows) stitches the same way; its refinement stays.
TEST(PatchStitching, LocallyRefinedPatch) {
  const Pair in = make_pair_();
  LRSpline<2> a(in.a);
  ASSERT_TRUE(a.insert(MeshRectangle<2>::make(0, 0.3, {0.3, 0.0}, {0.3, 0.5})));
  ASSERT_TRUE(a.insert(MeshRectangle<2>::make(1, 0.4, {0.0, 0.4}, {0.6, 0.4})));
  const Stitched<2> s = stitch(a, LRSpline<2>(in.b), {Continuity::C1});
  EXPECT_LT(max_jump(s, 0), 1e-12);
  EXPECT_LT(max_jump(s, 1), 1e-10);
  const LRSpline<2> merged = merge(s);
  double x[3], y[3];
  for (double u : {0.25, 0.35, 0.5, 1.2})
    for (double v : {0.3, 0.45}) {
      (u < 1.0 ? s.first : s.second).eval({u, v}, x);
      merged.eval({u, v}, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12);
      if (u < 0.6) {
        a.eval({u, v}, y);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12);
      }
    }
  EXPECT_GT(merged.num_elements(), s.first.num_elements());
}

void expect_error(const LRSpline<2>& a, const LRSpline<2>& b, const std::string& part) {
  try {
    stitch(a, b);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(part), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

TEST(PatchStitching, BadPairsGiveOneLineErrors) {
  const Pair in = make_pair_();
  TensorSpline<2> far = in.b;
  for (std::size_t i = 0; i < far.coefs().size(); i += 3) far.coefs()[i] += 10.0;
  expect_error(LRSpline<2>(in.a), LRSpline<2>(far), "share no side");
  expect_error(LRSpline<2>(in.a), LRSpline<2>(elevate_degree(in.b, 0, 1)), "degrees differ");
  // b mirrored along the seam: the same surface with its normal reversed.
  const TensorSpline<2> b = rotated(in.b, 0, 1, 0, 1, false);
  expect_error(LRSpline<2>(in.a), LRSpline<2>(b), "opposite orientation");
}

// Quarter cylinders x^2 + y^2 = 1, z in [0, 1]: the exact rational quadratic arc (weights 1, sqrt(2)/2, 1) across,
// linear in z along. The second spans 90..180 degrees with every weight tripled (the same surface) and other knots
// in z, so C0 stitching must scale its weights to meet the first's and exchange knot lines along the seam; the
// stitched and merged surface is still exactly the half cylinder.
TensorSpline<2> quarter_cylinder(double angle0, double weight_scale, std::vector<double> z_knots) {
  std::array<KnotVector, 2> kv{KnotVector(2, {0, 0, 0, 1, 1, 1}), KnotVector(1, std::move(z_knots))};
  const double a1 = angle0 + std::numbers::pi / 2, w1 = std::sqrt(0.5);
  const std::array<std::array<double, 3>, 3> arc = {{{std::cos(angle0), std::sin(angle0), 1.0},
                                                     {std::cos(angle0) + std::cos(a1), std::sin(angle0) + std::sin(a1), w1},
                                                     {std::cos(a1), std::sin(a1), 1.0}}};
  const std::vector<double> g = kv[1].greville();
  std::vector<double> h;
  for (double z : g)
    for (const auto& q : arc) {
      const double w = q[2] * weight_scale;
      h.insert(h.end(), {w * q[0], w * q[1], w * z, w});
    }
  return TensorSpline<2>(kv, 3, true, std::move(h));
}

TEST(PatchStitching, RationalCylinderPiecesStayExact) {
  const TensorSpline<2> a = quarter_cylinder(0.0, 1.0, {0, 0, 0.5, 1, 1});
  const TensorSpline<2> b = quarter_cylinder(std::numbers::pi / 2, 3.0, {0, 0, 0.3, 1, 1});
  const Stitched<2> s = stitch(LRSpline<2>(a), LRSpline<2>(b), {Continuity::C0});
  EXPECT_TRUE(s.first.is_rational() && s.second.is_rational());
  EXPECT_LT(s.moved, 1e-13);  // the seam points were equal once the weights were scaled
  const LRSpline<2> merged = merge(s);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> r(0.0, 1.0);
  const Box<2> dom = merged.domain();
  double worst_radius = 0, worst_jump = 0, worst_first = 0;
  for (int i = 0; i < 300; ++i) {
    const Param<2> u{dom.lo[0] + r(rng) * (dom.hi[0] - dom.lo[0]), r(rng)};
    double x[3];
    merged.eval(u, x);
    worst_radius = std::max(worst_radius, std::abs(std::hypot(x[0], x[1]) - 1.0));
    EXPECT_GE(x[2], -1e-14);
    EXPECT_LE(x[2], 1 + 1e-14);
  }
  for (int i = 0; i < 100; ++i) {  // the first patch unchanged (its parametrisation is kept)
    const Param<2> u{r(rng), r(rng)};
    double x[3], y[3];
    s.first.eval(u, x);
    a.eval(u, y);
    for (int k = 0; k < 3; ++k) worst_first = std::max(worst_first, std::abs(x[k] - y[k]));
  }
  // The arcs meet tangentially with equal speeds at 90 degrees, and the stitch keeps both: the derivative across
  // the seam from either side (each patch on its own domain) agrees.
  const double seam = s.seam.value(s.first);
  for (int i = 0; i <= 50; ++i) {
    double da[9], db[9];
    s.first.eval_first_derivatives({seam, i / 50.0}, da);
    s.second.eval_first_derivatives({seam, i / 50.0}, db);
    for (int k = 0; k < 3; ++k) worst_jump = std::max(worst_jump, std::abs(da[3 + k] - db[3 + k]));
  }
  EXPECT_LT(worst_radius, 1e-14);
  EXPECT_LT(worst_first, 1e-14);
  EXPECT_LT(worst_jump, 1e-10);
  // C1 keeps the weights, and the two arcs' weights are not C1 across the seam: with weights (1, s, 1), s =
  // sqrt(2)/2, on [0, 1] each, the weight's derivative is 2 (1 - s) leaving the first and 2 (s - 1) entering the
  // second (both arcs run at the same speed there), a jump of 4 - 2 sqrt(2). Refused, naming it.
  try {
    stitch(LRSpline<2>(a), LRSpline<2>(b), {Continuity::C1});
    ADD_FAILURE() << "C1 with weights that are not C1 accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    const std::string key = "weight-derivative jump ";
    const std::size_t at = what.find(key);
    ASSERT_NE(at, std::string::npos) << what;
    EXPECT_NEAR(std::stod(what.substr(at + key.size())), 4 - 2 * std::sqrt(2.0), 1e-12) << what;
    EXPECT_NE(what.find("not C1 across the shared side"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  // A rational patch and a polynomial one: refused.
  TensorSpline<2> flat = surface({0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 0, 0, 1, 1, 1, 1}, 0, 1, 3);
  expect_error(LRSpline<2>(a), LRSpline<2>(flat), "one patch is rational");
}

}  // namespace
}  // namespace trivar
