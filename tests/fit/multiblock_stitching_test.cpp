// C1 stitching of multi-block surfaces with T-joints: one bicubic polynomial surface in space (a single Bezier
// patch, polynomial or rational) cut into four blocks, two below v = 0.9 cut at u = 1.3 and two above cut at
// u = 0.7, so each horizontal seam has a T-joint, and each block refined with its own knots (the interfaces do not
// match). The blocks keep the surface's parameters, so the seams are collinear-parametrised with speed 1 and
// the derivative jump across a seam is measured by one-sided finite differences on each block's own evaluation
// (an 8-point stencil, exact for the cubic pieces), independently of the stitching code.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/fit/multiblock_stitching.hpp"
#include "trivar/spline/knot_insertion.hpp"
#include "trivar/spline/split.hpp"
#include "fit/one_sided_stencil.hpp"

namespace trivar {
namespace {

// A bicubic Bezier patch over [0, 2]^2: x and y on a regular grid (with a little random shift), z random; with
// `rational` random weights in [0.8, 1.25].
TensorSpline<2> bezier_surface(bool rational, unsigned seed) {
  const KnotVector k(3, {0, 0, 0, 0, 2, 2, 2, 2});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-0.1, 0.1), height(-0.5, 0.5), weight(0.8, 1.25);
  std::vector<double> pts, w;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      pts.insert(pts.end(), {2.0 * i / 3 + shift(rng), 2.0 * j / 3 + shift(rng), height(rng)});
      if (rational) w.push_back(weight(rng));
    }
  return TensorSpline<2>::from_cartesian({k, k}, 3, pts, w);
}

// The four blocks with T-joints at (1.3, 0.9) and (0.7, 0.9), each refined with its own knots.
std::vector<LRSpline<2>> split_t_joint_blocks(const TensorSpline<2>& s) {
  const auto [below, above] = split_at(s, 1, 0.9);
  const auto [b0, b1] = split_at(below, 0, 1.3);
  const auto [b2, b3] = split_at(above, 0, 0.7);
  const auto refine = [](const TensorSpline<2>& t, std::vector<double> u, std::vector<double> v) {
    return LRSpline<2>(insert_knots(insert_knots(t, 0, u), 1, v));
  };
  return {refine(b0, {0.4, 0.85}, {0.3, 0.6}), refine(b1, {1.5, 1.6, 1.8}, {0.2, 0.45}),
          refine(b2, {0.2, 0.35, 0.5}, {1.2, 1.5, 1.8}), refine(b3, {1.0, 1.5}, {1.2, 1.4, 1.7})};
}

// The block holding (u, v), taken on the given side of a seam: below/left (`before`) or above/right.
const LRSpline<2>& block_holding(const std::vector<LRSpline<2>>& blocks, double u, double v, int dir, bool before) {
  for (const LRSpline<2>& b : blocks) {
    const Box<2>& d = b.domain();
    const double x[2] = {u, v};
    bool in = true;
    for (int k = 0; k < 2; ++k)
      in = in && (k == dir ? (before ? d.lo[k] < x[k] && x[k] <= d.hi[k] : d.lo[k] <= x[k] && x[k] < d.hi[k])
                           : d.lo[k] <= x[k] && x[k] <= d.hi[k]);
    if (in) return b;
  }
  throw Error("no block holds the point");
}

// Largest jump of the derivative across the seams (v = 0.9 for u in [0, 2]; u = 1.3 below, u = 0.7 above), by
// one-sided finite differences on each side, at n points per seam.
double seam_derivative_jump(const std::vector<LRSpline<2>>& blocks, int n = 41) {
  constexpr double h = 0.004;
  const Eigen::VectorXd down = stencil_weights(h, -1), up = stencil_weights(h, 1);
  double worst = 0;
  const auto jump_at = [&](double u, double v, int dir) {
    double a[3] = {0, 0, 0}, b[3] = {0, 0, 0}, x[3];
    for (int k = 0; k < 8; ++k) {
      Param<2> p{u, v}, q{u, v};
      p[static_cast<std::size_t>(dir)] -= k * h;
      q[static_cast<std::size_t>(dir)] += k * h;
      block_holding(blocks, p[0], p[1], dir, true).eval(p, x);
      for (int c = 0; c < 3; ++c) a[c] += down[k] * x[c];
      block_holding(blocks, q[0], q[1], dir, false).eval(q, x);
      for (int c = 0; c < 3; ++c) b[c] += up[k] * x[c];
    }
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[c] - b[c]));
  };
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) / n;
    jump_at(2 * t, 0.9, 1);
    jump_at(1.3, 0.9 * t, 0);
    jump_at(0.7, 0.9 + 1.1 * t, 0);
  }
  return worst;
}

// Moves the control points of the B-splines of row 1 next to the given side whose support lies inside the side
// (not at the block's corners) by random offsets: the seam stays C0, the derivative across it jumps.
void bend_row(LRSpline<2>& s, int dir, int end, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-0.05, 0.05);
  std::vector<LRBSpline<2>> basis(s.basis_functions().begin(), s.basis_functions().end());
  const double side = end ? s.domain().hi[dir] : s.domain().lo[dir];
  const int along = 1 - dir;
  int bent = 0;
  for (LRBSpline<2>& f : basis) {
    const auto& t = f.knots[static_cast<std::size_t>(dir)];
    const auto& a = f.knots[static_cast<std::size_t>(along)];
    const bool row1 = std::count(t.begin(), t.end(), side) == 3 && (end ? t.back() == side : t.front() == side);
    // Not the corners (rows 0 and 1 of the sides across): those stay as they are.
    const bool corner = std::count(a.begin(), a.end(), s.domain().lo[along]) >= 3 || std::count(a.begin(), a.end(), s.domain().hi[along]) >= 3;
    if (!row1 || corner) continue;
    for (std::size_t c = 0; c < f.coef.size() && c < 3; ++c) f.coef[c] += offset(rng);
    ++bent;
  }
  ASSERT_GT(bent, 0);
  s = LRSpline<2>(s.degrees(), s.dim(), s.is_rational(), std::move(basis), s.mesh());
}

// Largest jump |lambda d0 - d1| of the derivatives across every interface of r (block 0's out of it, block 1's
// into it), by one-sided finite differences in each block's own parameters, at n points along each common part.
double interface_derivative_jump(const StitchedBlocks<2>& r, int n = 21) {
  constexpr double h = 0.004;
  double worst = 0;
  for (std::size_t k = 0; k < r.interfaces.size(); ++k) {
    const BlockInterface<2>& f = r.interfaces[k];
    const int a = f.side[0].along();
    std::array<double, 3> d[2];
    for (int i = 0; i < n; ++i) {
      Param<2> u = f.lo[0];
      u[static_cast<std::size_t>(a)] += (f.hi[0][a] - f.lo[0][a]) * (i + 0.5) / n;
      const Param<2> at[2] = {u, interface_param(f, 0, u)};
      for (int s = 0; s < 2; ++s) {
        const DomainSide side = f.side[static_cast<std::size_t>(s)];
        // Samples into the block; the derivative out of block 0 and into block 1.
        const double into = side.end == 1 ? -1.0 : 1.0;
        const Eigen::VectorXd w = stencil_weights(h, into);
        d[s] = {0, 0, 0};
        for (int q = 0; q < 8; ++q) {
          Param<2> p = at[s];
          p[static_cast<std::size_t>(side.dir)] += into * q * h;
          double x[3];
          r.blocks[static_cast<std::size_t>(f.block[static_cast<std::size_t>(s)])].eval(p, x);
          for (int c = 0; c < 3; ++c) d[s][static_cast<std::size_t>(c)] += w[q] * x[c];
        }
      }
      for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(r.speed[k] * d[0][c] - d[1][c]));
    }
  }
  return worst;
}

TEST(MultiblockStitching, SplitPolynomialSurfaceIsReproduced) {
  const TensorSpline<2> s = bezier_surface(false, 3);
  const StitchedBlocks<2> r = stitch_blocks(split_t_joint_blocks(s));
  ASSERT_EQ(r.interfaces.size(), 5u);  // two vertical seams, three parts of the horizontal one
  for (double lambda : r.speed) EXPECT_NEAR(lambda, 1.0, 1e-12);
  EXPECT_LE(r.moved, 1e-12);
  EXPECT_LE(r.jump, 1e-12);
  EXPECT_LE(seam_derivative_jump(r.blocks), 1e-10);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  double worst = 0, x[3], y[3];
  for (const LRSpline<2>& b : r.blocks)
    for (int i = 0; i < 50; ++i) {
      const Param<2> u{b.domain().lo[0] + U(rng) * b.domain().extent(0), b.domain().lo[1] + U(rng) * b.domain().extent(1)};
      b.eval(u, x);
      s.eval(u, y);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[c] - y[c]));
    }
  EXPECT_LE(worst, 1e-12);
}

TEST(MultiblockStitching, BentBlocksBecomeC1AndKeepTheirGeometryAwayFromTheSeams) {
  std::vector<LRSpline<2>> blocks = split_t_joint_blocks(bezier_surface(false, 4));
  bend_row(blocks[0], 1, 1, 10);  // below the horizontal seam, across the T-joint at u = 0.7
  bend_row(blocks[3], 1, 0, 11);  // above it, across the T-joint at u = 1.3
  bend_row(blocks[1], 0, 0, 12);  // right of the lower vertical seam
  EXPECT_GT(seam_derivative_jump(blocks), 1e-3);
  const StitchedBlocks<2> r = stitch_blocks(blocks);
  EXPECT_GT(r.moved, 1e-3);
  EXPECT_LE(r.jump, 1e-12);
  const double jump = seam_derivative_jump(r.blocks);
  EXPECT_LE(jump, 1e-10);
  EXPECT_LE(interface_derivative_jump(r), 1e-10);
  RecordProperty("seam_derivative_jump", format_number(jump));
  RecordProperty("conditions", r.conditions);
  RecordProperty("unknowns", r.unknowns);

  // Only B-splines of the first two rows of interface sides move: compared with the same blocks matched alone.
  std::vector<LRSpline<2>> matched = blocks;
  match_blocks(matched, {}, 2);
  int kept = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    ASSERT_EQ(matched[b].num_basis(), r.blocks[b].num_basis());
    for (int id = 0; id < matched[b].num_basis(); ++id) {
      const LRBSpline<2>& before = matched[b].basis_function(id);
      const LRBSpline<2>& after = r.blocks[b].basis_function(id);
      ASSERT_EQ(before.knots, after.knots);
      if (before.coef == after.coef) {
        ++kept;
        continue;
      }
      bool first_rows = false;
      for (const BlockInterface<2>& f : r.interfaces)
        for (int k = 0; k < 2; ++k) {
          if (f.block[static_cast<std::size_t>(k)] != static_cast<int>(b)) continue;
          const DomainSide side = f.side[static_cast<std::size_t>(k)];
          const auto& t = after.knots[static_cast<std::size_t>(side.dir)];
          first_rows = first_rows || std::count(t.begin(), t.end(), side.value(r.blocks[b])) >= 3;
        }
      EXPECT_TRUE(first_rows) << "block " << b << " B-spline " << id;
    }
  }
  EXPECT_GT(kept, 20);
  // Beyond the supports of the first rows the surface is the bent input's (one point per block).
  double worst = 0, x[3], y[3];
  for (const Param<2>& u : {Param<2>{0.1, 0.1}, Param<2>{1.9, 0.1}, Param<2>{0.1, 1.9}, Param<2>{1.9, 1.9}}) {
    block_holding(r.blocks, u[0], u[1], 0, true).eval(u, x);
    block_holding(blocks, u[0], u[1], 0, true).eval(u, y);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[c] - y[c]));
  }
  EXPECT_LE(worst, 1e-13);
}

// Blocks parametrised with different scales across and along a seam (block 1 and 3 stretched to twice their
// length in v): the parametric speed ratio would call the split surface kinked, the fitted one finds lambda from
// the input, reproduces the unbent surface and makes the bent one C1 with the same lambdas.
TEST(MultiblockStitching, FittedSpeedsForAnisotropicParametrisations) {
  const auto stretch = [](const LRSpline<2>& s) {
    std::vector<LRBSpline<2>> basis(s.basis_functions().begin(), s.basis_functions().end());
    std::vector<MeshRectangle<2>> mesh = s.mesh();
    const double v0 = s.domain().lo[1];
    for (LRBSpline<2>& f : basis)
      for (double& t : f.knots[1]) t = v0 + 2 * (t - v0);
    for (MeshRectangle<2>& r : mesh) {
      if (r.dir == 1) r.value = v0 + 2 * (r.value - v0);
      r.extent.lo[1] = v0 + 2 * (r.extent.lo[1] - v0);
      r.extent.hi[1] = v0 + 2 * (r.extent.hi[1] - v0);
    }
    return LRSpline<2>(s.degrees(), s.dim(), s.is_rational(), std::move(basis), std::move(mesh));
  };
  std::vector<LRSpline<2>> blocks = split_t_joint_blocks(bezier_surface(false, 9));
  blocks[1] = stretch(blocks[1]);
  blocks[3] = stretch(blocks[3]);
  const StitchedBlocks<2> exact = stitch_blocks(blocks, {}, CrossSpeed::fitted);
  EXPECT_LE(exact.moved, 1e-12);
  bend_row(blocks[0], 1, 1, 16);
  bend_row(blocks[3], 1, 0, 17);
  const StitchedBlocks<2> r = stitch_blocks(blocks, {}, CrossSpeed::fitted);
  EXPECT_LE(r.jump, 1e-12);
  EXPECT_LE(interface_derivative_jump(r), 1e-10);
  EXPECT_GT(r.moved, 1e-3);
}

TEST(MultiblockStitching, RationalBlocksStitchC1WithTheirWeights) {
  const TensorSpline<2> s = bezier_surface(true, 6);
  const StitchedBlocks<2> exact = stitch_blocks(split_t_joint_blocks(s));
  EXPECT_LE(exact.moved, 1e-12);
  std::vector<LRSpline<2>> blocks = split_t_joint_blocks(s);
  bend_row(blocks[2], 0, 1, 13);
  bend_row(blocks[0], 1, 1, 14);
  EXPECT_GT(seam_derivative_jump(blocks), 1e-3);
  const StitchedBlocks<2> r = stitch_blocks(blocks);
  const double jump = seam_derivative_jump(r.blocks);
  EXPECT_LE(jump, 1e-10);
  RecordProperty("rational_seam_derivative_jump", format_number(jump));
  // The weights are kept.
  std::vector<LRSpline<2>> matched = blocks;
  match_blocks(matched, {}, 2);
  for (std::size_t b = 0; b < blocks.size(); ++b)
    for (int id = 0; id < matched[b].num_basis(); ++id)
      EXPECT_EQ(matched[b].basis_function(id).coef[3], r.blocks[b].basis_function(id).coef[3]);
}

TEST(MultiblockStitching, C0ClosesGapsAndKeepsTheKinks) {
  std::vector<LRSpline<2>> blocks = split_t_joint_blocks(bezier_surface(false, 7));
  bend_row(blocks[1], 0, 0, 15);
  const double kink = seam_derivative_jump(blocks);
  StitchOptions c0;
  c0.continuity = Continuity::C0;
  const StitchedBlocks<2> r = stitch_blocks(blocks, c0);
  EXPECT_LE(r.jump, 1e-12);
  EXPECT_NEAR(seam_derivative_jump(r.blocks), kink, 1e-9);
}

TEST(MultiblockStitching, WeightsThatJumpAreRefusedNamingTheBlocks) {
  std::vector<LRSpline<2>> blocks = split_t_joint_blocks(bezier_surface(true, 8));
  // All of block 3's homogeneous values doubled: the same geometry, but weights twice the neighbours'.
  std::vector<LRBSpline<2>> basis(blocks[3].basis_functions().begin(), blocks[3].basis_functions().end());
  for (LRBSpline<2>& f : basis)
    for (double& c : f.coef) c *= 2;
  blocks[3] = LRSpline<2>(blocks[3].degrees(), 3, true, std::move(basis), blocks[3].mesh());
  try {
    stitch_blocks(blocks);
    FAIL() << "weights that jump accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("weights differ"), std::string::npos) << m;
    EXPECT_NE(m.find(" and 3"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
}

// One triquadratic Bezier volume cut into three blocks with a T-joint (z < 0.8; above it cut at x = 0.6), each
// refined with its own knots: stitched C1 with nothing moved and every block still the volume; with the upper
// blocks' first rows bent, C1 again (jumps through finite differences across the two seams z = 0.8 and x = 0.6).
TEST(MultiblockStitching, SplitVolumeIsReproducedAndBentVolumeMadeC1) {
  const KnotVector k(2, {0, 0, 0, 1.5, 1.5, 1.5});
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> shift(-0.1, 0.1);
  std::vector<double> pts;
  for (int l = 0; l < 3; ++l)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) pts.insert(pts.end(), {0.75 * i + shift(rng), 0.75 * j + shift(rng), 0.75 * l + shift(rng)});
  const TensorSpline<3> s = TensorSpline<3>::from_cartesian({k, k, k}, 3, pts);
  const auto [below, above] = split_at(s, 2, 0.8);
  const auto [left, right] = split_at(above, 0, 0.6);
  std::vector<LRSpline<3>> blocks{LRSpline<3>(insert_knots(below, 0, std::vector<double>{0.4, 1.1})),
                                  LRSpline<3>(insert_knots(left, 1, std::vector<double>{0.5})),
                                  LRSpline<3>(insert_knots(insert_knots(insert_knots(right, 2, std::vector<double>{1.1}), 0,
                                                                        std::vector<double>{0.9, 1.2}),
                                                           1, std::vector<double>{0.5, 1.0}))};
  const StitchedBlocks<3> r = stitch_blocks(blocks);
  EXPECT_EQ(r.interfaces.size(), 3u);
  EXPECT_LE(r.moved, 1e-12);
  EXPECT_LE(r.jump, 1e-12);
  double worst = 0, x[3], y[3];
  for (const LRSpline<3>& b : r.blocks)
    for (int i = 0; i < 20; ++i) {
      Param<3> u;
      for (int c = 0; c < 3; ++c) u[static_cast<std::size_t>(c)] = b.domain().lo[c] + (0.05 + 0.9 * ((i * (c + 3)) % 20) / 19.0) * b.domain().extent(c);
      b.eval(u, x);
      s.eval(u, y);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[c] - y[c]));
    }
  EXPECT_LE(worst, 1e-12);

  // Bend the upper right block's second layer above the seam z = 0.8 (inside the face, away from its edges).
  std::vector<LRBSpline<3>> basis(blocks[2].basis_functions().begin(), blocks[2].basis_functions().end());
  int bent = 0;
  for (LRBSpline<3>& f : basis)
    if (std::count(f.knots[2].begin(), f.knots[2].end(), 0.8) == 2 && f.knots[0].front() > 0.6 && f.knots[1].front() > 0) {
      f.coef[2] += 0.03 * (1 + bent++ % 3);
    }
  ASSERT_GT(bent, 0);
  blocks[2] = LRSpline<3>(blocks[2].degrees(), 3, false, std::move(basis), blocks[2].mesh());
  const StitchedBlocks<3> c1 = stitch_blocks(blocks);
  EXPECT_GT(c1.moved, 1e-3);
  // One-sided derivatives across z = 0.8 (below: block 0; above: blocks 1, 2) and x = 0.6 (blocks 1, 2): quadratic
  // pieces, so the 8-point stencil is exact up to rounding.
  constexpr double h = 0.004;
  const Eigen::VectorXd down = stencil_weights(h, -1), up = stencil_weights(h, 1);
  double jump = 0;
  const auto derivative = [&](const LRSpline<3>& b, Param<3> u, int dir, const Eigen::VectorXd& w, double sign) {
    std::array<double, 3> d{0, 0, 0};
    for (int q = 0; q < 8; ++q) {
      Param<3> p = u;
      p[static_cast<std::size_t>(dir)] += sign * q * h;
      b.eval(p, x);
      for (int c = 0; c < 3; ++c) d[static_cast<std::size_t>(c)] += w[q] * x[c];
    }
    return d;
  };
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) {
      const double a = 1.5 * (i + 0.5) / 9, b = 1.5 * (j + 0.5) / 9;
      const auto lo = derivative(c1.blocks[0], {a, b, 0.8}, 2, down, -1);
      const auto hi = derivative(c1.blocks[a < 0.6 ? 1 : 2], {a, b, 0.8}, 2, up, 1);
      const double z = 0.8 + 0.7 * (j + 0.5) / 9;
      const auto left_side = derivative(c1.blocks[1], {0.6, b, z}, 0, down, -1);
      const auto right_side = derivative(c1.blocks[2], {0.6, b, z}, 0, up, 1);
      for (std::size_t c = 0; c < 3; ++c)
        jump = std::max({jump, std::abs(lo[c] - hi[c]), std::abs(left_side[c] - right_side[c])});
    }
  EXPECT_LE(jump, 1e-10);
  RecordProperty("volume_seam_derivative_jump", format_number(jump));
}

}  // namespace
}  // namespace trivar
