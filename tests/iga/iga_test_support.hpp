#pragma once
// Shared geometry for the analysis tests: a box whose control points and weights are perturbed, so the map is
// a genuinely curved NURBS with a valid Jacobian, and the identity on its boundary faces' planes is kept; and
// a local refinement of an LR space near a corner, so LR tests run on spaces that are not tensor spaces; the
// the reproduction and convergence-rate checks of the LR tests and of the adaptive loops.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trivar/iga/convergence_table.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/tensor_space.hpp"
#include "trivar/lr/refinement.hpp"

namespace iga_test {

// Unit box, degree p, n elements per direction; interior control points moved by up to 0.15 / n per
// coordinate and every weight drawn from [0.8, 1.25] when rational.
template <int D>
trivar::TensorSpline<D> distorted_box(int p, int n, bool rational, unsigned seed) {
  using namespace trivar;
  Param<D> lo, hi;
  lo.fill(0.0);
  hi.fill(1.0);
  const TensorSpline<D> box = box_geometry<D>(lo, hi, p, n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> move(-0.15 / n, 0.15 / n), weight(0.8, 1.25);
  std::vector<double> pts(box.coefs().begin(), box.coefs().end()), w;
  for (int i = 0; i < box.num_coefs(); ++i) {
    const auto m = box.multi_index(i);
    bool interior = true;
    for (int k = 0; k < D; ++k) interior = interior && m[k] > 0 && m[k] < box.count(k) - 1;
    for (int k = 0; k < D; ++k)
      if (interior) pts[static_cast<std::size_t>(i * D + k)] += move(rng);
    if (rational) w.push_back(weight(rng));
  }
  return TensorSpline<D>::from_cartesian(box.knot_vectors(), D, pts, w);
}

// FULLSPAN refinement of the elements whose centre lies in the parameter box [lo, lo + fraction * extent]
// (per direction): the new mesh lines end inside the domain (T-junctions), so the space is not a tensor one.
template <int D>
void refine_corner(trivar::LRSpline<D>& lr, double fraction) {
  std::vector<int> marked;
  const trivar::Box<D>& dom = lr.domain();
  for (int e = 0; e < lr.num_elements(); ++e) {
    bool inside = true;
    for (int k = 0; k < D; ++k)
      inside = inside && lr.element(e).center()[k] < dom.lo[k] + fraction * dom.extent(k);
    if (inside) marked.push_back(e);
  }
  trivar::refine_elements(lr, std::span<const int>(marked), trivar::RefineOptions{});
}

// True when some mesh rectangle does not span the whole domain across its direction.
template <int D>
bool has_t_junction(const trivar::LRSpline<D>& lr) {
  for (const auto& r : lr.mesh())
    for (int k = 0; k < D; ++k)
      if (k != r.dir && (r.extent.lo[k] > lr.domain().lo[k] || r.extent.hi[k] < lr.domain().hi[k])) return true;
  return false;
}

// The D faces of the unit box at u_k = side.
template <int D>
std::vector<trivar::Face> faces_on_side(int side) {
  std::vector<trivar::Face> f;
  for (int k = 0; k < D; ++k) f.push_back({k, side});
  return f;
}

// On a locally refined space (with T-junctions) that holds the exact solution, the solution returned by
// solve(space, solver) is that solution up to rounding.
template <int D, class Solve>
void expect_reproduced(const trivar::LRSpline<D>& lr, int components, const trivar::ExactSolution<D>& exact,
                       Solve&& solve) {
  ASSERT_TRUE(has_t_junction(lr));
  const auto space = trivar::refined_space(lr);
  auto solver = trivar::make_solver("cholmod");
  const trivar::ErrorNorms e = trivar::error_norms<D>(space, solve(space, *solver).coefs, components, exact);
  EXPECT_LE(e.l2, 1e-10) << D;
  EXPECT_LE(e.h1, 1e-10) << D;
}

// The convergence study of the LR tests: the map (2 elements per direction) at degree p with n = 4, 8, 16, 32
// elements per direction, then the elements in [0, 1/4]^D refined once more (T-junctions; the largest
// elements keep h = 1/n). solve(space, solver) on each space, errors against a smooth exact solution,
// and a-priori rates between successive spaces: L2 ~ h^(p+1), H1 ~ h^p within [-0.15, +0.6] (pre-asymptotic meshes converge
// faster), within 0.2 on the finest pair. Returns the errors per space.
template <int D, class Solve>
std::vector<trivar::ErrorNorms> expect_optimal_convergence(const trivar::TensorSpline<D>& map, int p, int components,
                                                           const trivar::ExactSolution<D>& exact, Solve&& solve) {
  std::vector<trivar::ErrorNorms> errors;
  for (int n : {4, 8, 16, 32}) {
    trivar::LRSpline<D> lr(trivar::make_tensor_space(map, p, n / 2).geometry);
    refine_corner(lr, 0.25);
    EXPECT_TRUE(has_t_junction(lr));
    const auto space = trivar::refined_space(lr);
    auto solver = trivar::make_solver("cholmod");
    errors.push_back(trivar::error_norms<D>(space, solve(space, *solver).coefs, components, exact));
    if (n == 4) continue;
    const trivar::ErrorNorms &coarse = errors[errors.size() - 2], &fine = errors.back();
    const double rl2 = std::log2(coarse.l2 / fine.l2), rh1 = std::log2(coarse.h1 / fine.h1);
    const std::string what = "p " + std::to_string(p) + " n " + std::to_string(n);
    EXPECT_GE(rl2, p + 1 - 0.15) << what;
    EXPECT_LE(rl2, p + 1 + 0.6) << what;
    EXPECT_GE(rh1, p - 0.15) << what;
    EXPECT_LE(rh1, p + 0.6) << what;
    if (n == 32) {
      EXPECT_NEAR(rl2, p + 1, 0.2) << what;
      EXPECT_NEAR(rh1, p, 0.2) << what;
    }
  }
  return errors;
}

// The estimator tracks the true H1 error within a fixed factor on every step.
inline void expect_efficient_estimates(const std::vector<trivar::ConvergenceRow>& rows) {
  for (const auto& r : rows) {
    EXPECT_GT(r.estimate / r.h1, 0.2);
    EXPECT_LT(r.estimate / r.h1, 20.0);
  }
}

// Every step adds dofs and lowers the H1 error, and the estimator tracks the true error.
inline void expect_monotone_and_efficient(const std::vector<trivar::ConvergenceRow>& rows) {
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_GT(rows[i].dofs, rows[i - 1].dofs);
    EXPECT_LT(rows[i].h1, rows[i - 1].h1);
  }
  expect_efficient_estimates(rows);
}

}  // namespace iga_test
