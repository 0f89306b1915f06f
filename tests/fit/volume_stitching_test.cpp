// C0/C1 stitching of two volumes sharing a face: the derivative jump across the face measured by evaluating the
// two stitched volumes independently at random points on it, control points away from the two face rows kept bit
// for bit, the merged LR volume equal to both, and the halves of one C2 volume merging back into it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/fit/patch_stitching.hpp"
#include "trivar/spline/knot_insertion.hpp"
#include "trivar/spline/split.hpp"

namespace trivar {
namespace {

constexpr int kVolumeDegree = 3;

// A cubic volume whose direction `across` runs over x in [x0, x1] and the two others, cyclically after it, over
// y and z in [0, 1]; control points on that grid moved randomly by up to 0.04. With `face` given, the layer at
// x0 takes face[(b, c)] instead (b, c the grid indices along the two other directions).
TensorSpline<3> grid_volume(std::array<std::vector<double>, 3> knots, int across, double x0, double x1, unsigned seed,
                            const std::map<std::array<int, 2>, std::array<double, 3>>& face = {}) {
  std::array<KnotVector, 3> kv;
  for (int k = 0; k < 3; ++k) kv[static_cast<std::size_t>(k)] = KnotVector(kVolumeDegree, knots[static_cast<std::size_t>(k)]);
  std::array<int, 3> n{};
  for (int k = 0; k < 3; ++k) n[static_cast<std::size_t>(k)] = kv[static_cast<std::size_t>(k)].size();
  const auto d1 = static_cast<std::size_t>((across + 1) % 3), d2 = static_cast<std::size_t>((across + 2) % 3),
             d0 = static_cast<std::size_t>(across);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  std::vector<double> pts;
  std::array<int, 3> i{};
  for (i[2] = 0; i[2] < n[2]; ++i[2])
    for (i[1] = 0; i[1] < n[1]; ++i[1])
      for (i[0] = 0; i[0] < n[0]; ++i[0]) {
        const std::array<double, 3> p{x0 + (x1 - x0) * i[d0] / (n[d0] - 1) + jitter(rng),
                                      static_cast<double>(i[d1]) / (n[d1] - 1) + jitter(rng),
                                      static_cast<double>(i[d2]) / (n[d2] - 1) + jitter(rng)};
        if (i[d0] == 0 && !face.empty()) {
          const auto& f = face.at({i[d1], i[d2]});
          pts.insert(pts.end(), f.begin(), f.end());
        } else {
          pts.insert(pts.end(), p.begin(), p.end());
        }
      }
  return TensorSpline<3>::from_cartesian(kv, 3, pts);
}

// The control points of the layer u = hi of a volume built with across = 0, keyed by (j, k).
std::map<std::array<int, 2>, std::array<double, 3>> last_layer(const TensorSpline<3>& s) {
  std::map<std::array<int, 2>, std::array<double, 3>> out;
  for (int k = 0; k < s.count(2); ++k)
    for (int j = 0; j < s.count(1); ++j) {
      const auto at = static_cast<std::size_t>(3 * s.linear_index({s.count(0) - 1, j, k}));
      out[{j, k}] = {s.coefs()[at], s.coefs()[at + 1], s.coefs()[at + 2]};
    }
  return out;
}

struct VolumePair {
  TensorSpline<3> a, b;
};

// a on [0, 1]^3; b beyond its face u = 1, given with its directions turned (b's w crosses the face, b's (u, v)
// run along a's (v, w)), both refined along the face differently so the knot planes must be adapted.
VolumePair volume_pair() {
  const std::vector<double> t{0, 0, 0, 0, 0.5, 1, 1, 1, 1};
  TensorSpline<3> a = grid_volume({std::vector<double>{0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1}, t, t}, 0, 0.0, 1.0, 5);
  TensorSpline<3> b = grid_volume({t, t, std::vector<double>{0, 0, 0, 0, 0.5, 1, 1, 1, 1}}, 2, 1.0, 1.7, 9, last_layer(a));
  a = insert_knot(a, 1, 0.25);
  a = insert_knot(a, 2, 0.8);
  b = insert_knot(b, 0, 0.6);
  b = insert_knot(b, 1, 0.35);
  return {a, b};
}

// Largest difference of value (order 0) or derivative d/du_k (order k + 1) between the two stitched volumes at
// random points of the face u = 1.
double face_jump(const Stitched<3>& s, int order) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> t(0.0, 1.0);
  double jump = 0, x[12], y[12];
  for (int i = 0; i < 60; ++i) {
    const Param<3> u{1.0, t(rng), t(rng)};
    s.first.eval_first_derivatives(u, x);
    s.second.eval_first_derivatives(u, y);
    for (int c = 0; c < 3; ++c) jump = std::max(jump, std::abs(x[3 * order + c] - y[3 * order + c]));
  }
  return jump;
}

std::map<std::array<std::vector<double>, 3>, std::vector<double>> coefs_by_knots(const LRSpline<3>& lr) {
  std::map<std::array<std::vector<double>, 3>, std::vector<double>> m;
  for (const auto& b : lr.basis_functions()) m[b.knots] = b.coef;
  return m;
}

void expect_merged_is_pair(const Stitched<3>& s, const LRSpline<3>& merged) {
  double x[3], y[3];
  for (double u : {0.1, 0.8, 0.999, 1.0, 1.001, 1.4, s.second.domain().hi[0]})
    for (double v : {0.0, 0.3, 1.0})
      for (double w : {0.2, 0.65}) {
        (u < 1.0 ? s.first : s.second).eval({u, v, w}, x);
        merged.eval({u, v, w}, y);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12) << u << " " << v << " " << w;
      }
}

void expect_kept_away_from_face(const TensorSpline<3>& original, const LRSpline<3>& stitched, const LRSpline<3>& merged,
                                int rows) {
  const auto before = coefs_by_knots(LRSpline<3>(original));
  const auto after = coefs_by_knots(stitched), joined = coefs_by_knots(merged);
  int kept = 0;
  for (const auto& [knots, coef] : before) {
    if (std::count(knots[0].begin(), knots[0].end(), 1.0) > kVolumeDegree + 1 - rows) continue;  // one of the face rows
    ASSERT_TRUE(after.count(knots));
    EXPECT_EQ(after.at(knots), coef);  // bit for bit
    ASSERT_TRUE(joined.count(knots));
    EXPECT_EQ(joined.at(knots), coef);
    ++kept;
  }
  EXPECT_EQ(kept, original.count(1) * original.count(2) * (original.count(0) - rows));
}

TEST(VolumeStitching, C1AcrossTheFaceAndUnchangedElsewhere) {
  const VolumePair in = volume_pair();
  const Stitched<3> s = stitch(LRSpline<3>(in.a), LRSpline<3>(in.b), {Continuity::C1});
  EXPECT_EQ(s.seam.dir, 0);
  EXPECT_EQ(s.seam.end, 1);
  EXPECT_LT(s.seam_gap, 1e-14);
  EXPECT_GT(s.moved, 1e-3);  // the random volumes were not C1
  for (int order = 0; order < 4; ++order) EXPECT_LT(face_jump(s, order), 1e-10) << order;
  const LRSpline<3> merged = merge(s);
  expect_kept_away_from_face(in.a, s.first, merged, 2);
  expect_merged_is_pair(s, merged);
}

TEST(VolumeStitching, C0AcrossTheFace) {
  const VolumePair in = volume_pair();
  const Stitched<3> s = stitch(LRSpline<3>(in.a), LRSpline<3>(in.b), {Continuity::C0});
  EXPECT_LT(face_jump(s, 0), 1e-12);
  EXPECT_LT(face_jump(s, 2), 1e-10);  // derivatives along the face follow from C0
  EXPECT_LT(face_jump(s, 3), 1e-10);
  EXPECT_GT(face_jump(s, 1), 1e-3);  // but not across it
  const LRSpline<3> merged = merge(s);
  expect_kept_away_from_face(in.a, s.first, merged, 1);
  expect_merged_is_pair(s, merged);
}

// The halves of one C2 volume, refined along the face differently, stitched from the right half (its face at
// u = lo, so the canonical map negates two directions) merge back into the original.
TEST(VolumeStitching, HalvesOfOneVolumeMergeBackIntoIt) {
  const std::vector<double> t{0, 0, 0, 0, 0.4, 1, 1, 1, 1};
  const TensorSpline<3> whole =
      grid_volume({std::vector<double>{0, 0, 0, 0, 0.5, 1, 1.5, 2, 2, 2, 2}, t, t}, 0, 0.0, 2.0, 3);
  auto [left, right] = split_at(whole, 0, 1.0);
  left = insert_knot(left, 1, 0.7);
  right = insert_knot(right, 2, 0.2);
  const Stitched<3> s = stitch(LRSpline<3>(right), LRSpline<3>(left), {Continuity::C1});
  EXPECT_EQ(s.seam.dir, 0);
  EXPECT_EQ(s.seam.end, 0);
  EXPECT_LT(s.moved, 1e-13);
  const LRSpline<3> merged = merge(s);
  EXPECT_NEAR(merged.domain().lo[0], 0.0, 1e-14);
  EXPECT_EQ(merged.domain().hi[0], 2.0);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> r(0.0, 1.0);
  double x[3], y[3];
  for (int i = 0; i < 200; ++i) {
    const Param<3> u{std::max(2 * r(rng), merged.domain().lo[0]), r(rng), r(rng)};
    whole.eval(u, x);
    merged.eval(u, y);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-12);
  }
}

TEST(VolumeStitching, VolumesWithoutACommonFaceAreRefused) {
  const VolumePair in = volume_pair();
  const std::vector<double> t{0, 0, 0, 0, 1, 1, 1, 1};
  const TensorSpline<3> far = grid_volume({t, t, t}, 0, 3.0, 4.0, 2);
  try {
    stitch(LRSpline<3>(in.a), LRSpline<3>(far));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("share no side"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace trivar
