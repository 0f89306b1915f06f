// Stitching and multi-block matching. BM_StitchC1: two bicubic patches of n x n B-splines with different knot
// lines along their common side (the second rotated by 180 degrees), stitched C1 (side search, re-parametrisation,
// knot line segments, continuity on the two seam rows) and merged into one LR spline. BM_MultiblockTJoint: three
// biquadratic blocks with a T-joint made conforming and turned into the analysis space; the residual indicator and
// an adaptive round on them. BM_MultiblockStitchC1: the same blocks stitched C1 (matching over two rows, the
// conditions at every seam, their minimum-norm solution). Figures in bench/README.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "trivar/fit/multiblock_adaptive.hpp"
#include "trivar/fit/multiblock_space.hpp"
#include "trivar/fit/multiblock_stitching.hpp"
#include "trivar/fit/patch_stitching.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/solver.hpp"

using namespace trivar;

namespace {

// Degree-p patch over [x0, x0 + 1] x [0, 1]: n x n B-splines, interior knots shifted by `shift` along v; the
// heights a smooth function of x, y (so the side u = 0 of one patch and u = 1 of the previous are one curve only
// up to their knots: the test uses the same curve by sharing v knots where it matters).
LRSpline<2> patch(int n, int p, double x0, double shift, bool rotated, int dim) {
  std::vector<double> u(static_cast<std::size_t>(p), 0.0), v = u;
  for (int i = 0; i <= n - p; ++i) {
    u.push_back(static_cast<double>(i) / (n - p));
    const double t = static_cast<double>(i) / (n - p);
    v.push_back(i == 0 || i == n - p ? t : t + shift / (n - p));
  }
  u.insert(u.end(), static_cast<std::size_t>(p), 1.0);
  v.insert(v.end(), static_cast<std::size_t>(p), 1.0);
  const KnotVector ku(p, u), kv(p, v);
  std::vector<double> pts;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double g[2] = {0, 0};
      for (int k = 1; k <= p; ++k) {
        g[0] += u[static_cast<std::size_t>(i + k)] / p;
        g[1] += v[static_cast<std::size_t>(j + k)] / p;
      }
      const double x = rotated ? x0 + 1 - g[0] : x0 + g[0], y = rotated ? 1 - g[1] : g[1];
      pts.push_back(x);
      pts.push_back(y);
      if (dim == 3) pts.push_back(0.0);
    }
  return LRSpline<2>(TensorSpline<2>::from_cartesian({ku, kv}, dim, pts));
}

void BM_StitchC1(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const LRSpline<2> a = patch(n, 3, 0.0, 0.0, false, 3), b = patch(n, 3, 1.0, 0.3, true, 3);
  int coefs = 0;
  for (auto _ : state) {
    const Stitched s = stitch(a, b, {Continuity::C1});
    const LRSpline<2> m = merge(s);
    coefs = m.num_basis();
    benchmark::DoNotOptimize(coefs);
  }
  state.counters["coefficients"] = coefs;
}
BENCHMARK(BM_StitchC1)->Arg(16)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

// Long block [0, 2] x [0, 1] (2n x n), two blocks [0, 1] x [1, 2] and [1, 2] x [1, 2] above it, interior knots
// shifted so no interface matches.
std::vector<LRSpline<2>> t_joint_model(int n) {
  auto block = [&](double x0, double y0, double w, int nu, double shift) {
    std::vector<double> u(2, 0.0), v(2, 0.0);
    for (int i = 0; i <= nu - 2; ++i) u.push_back(i == 0 || i == nu - 2 ? double(i) / (nu - 2) : (i + shift) / (nu - 2));
    for (int i = 0; i <= n - 2; ++i) v.push_back(static_cast<double>(i) / (n - 2));
    u.insert(u.end(), 2, 1.0);
    v.insert(v.end(), 2, 1.0);
    std::vector<double> pts;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < nu; ++i) {
        pts.push_back(x0 + w * (u[static_cast<std::size_t>(i + 1)] + u[static_cast<std::size_t>(i + 2)]) / 2);
        pts.push_back(y0 + (v[static_cast<std::size_t>(j + 1)] + v[static_cast<std::size_t>(j + 2)]) / 2);
      }
    return LRSpline<2>(TensorSpline<2>::from_cartesian({KnotVector(2, u), KnotVector(2, v)}, 2, pts));
  };
  return {block(0, 0, 2, 2 * n + 1, 0.5), block(0, 1, 1, n, 0.25), block(1, 1, 1, n, 0.7)};
}

// Matching the blocks and building their conforming space, timed per iteration.
template <int D>
void time_matching(benchmark::State& state, const std::vector<LRSpline<D>>& blocks) {
  int functions = 0;
  for (auto _ : state) {
    const MultiblockSpace<D> m = multiblock_space(blocks);
    functions = m.space.num_basis;
    benchmark::DoNotOptimize(functions);
  }
  state.counters["functions"] = functions;
}

void BM_MultiblockTJoint(benchmark::State& state) {
  const std::vector<LRSpline<2>> blocks = t_joint_model(static_cast<int>(state.range(0)));
  time_matching(state, blocks);
}
BENCHMARK(BM_MultiblockTJoint)->Arg(16)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);

void BM_MultiblockStitchC1(benchmark::State& state) {
  const std::vector<LRSpline<2>> blocks = t_joint_model(static_cast<int>(state.range(0)));
  int conditions = 0, unknowns = 0;
  for (auto _ : state) {
    // The long block is parametrised with twice the scale along its top as across it: fitted speeds.
    const StitchedBlocks<2> s = stitch_blocks(blocks, {}, CrossSpeed::fitted);
    conditions = s.conditions;
    unknowns = s.unknowns;
    benchmark::DoNotOptimize(s.jump);
  }
  state.counters["conditions"] = conditions;
  state.counters["unknowns"] = unknowns;
}
BENCHMARK(BM_MultiblockStitchC1)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_MultiblockPoisson(benchmark::State& state) {
  const MultiblockSpace<2> m = multiblock_space(t_joint_model(static_cast<int>(state.range(0))));
  PoissonProblem<2> problem;
  problem.source = [](const double*) { return 1.0; };
  problem.dirichlet = {DirichletCondition<2>{boundary_faces(m), {}, nullptr}};
  int dofs = 0;
  for (auto _ : state) {
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_poisson(m.space, problem, *solver, 1);
    dofs = r.dofs;
    benchmark::DoNotOptimize(r.coefs.data());
  }
  state.counters["dofs"] = dofs;
}
BENCHMARK(BM_MultiblockPoisson)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

// A triquadratic block origin + [0, 1]^3 scaled by `size`, n_k uniform spans per direction.
LRSpline<3> volume_block(std::array<int, 3> n, std::array<double, 3> origin, std::array<double, 3> size) {
  std::array<KnotVector, 3> kv;
  for (std::size_t k = 0; k < 3; ++k) {
    std::vector<double> t(3, 0.0);
    for (int i = 1; i < n[k]; ++i) t.push_back(static_cast<double>(i) / n[k]);
    t.insert(t.end(), 3, 1.0);
    kv[k] = KnotVector(2, t);
  }
  std::vector<double> pts;
  for (double w : kv[2].greville())
    for (double v : kv[1].greville())
      for (double u : kv[0].greville()) pts.insert(pts.end(), {origin[0] + u * size[0], origin[1] + v * size[1], origin[2] + w * size[2]});
  return LRSpline<3>(TensorSpline<3>::from_cartesian(kv, 3, pts));
}

void BM_MultiblockVolumes(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  // A slab [0, 2] x [0, 1] x [0, 1] (2n x n x n) and two blocks [0, 1] x [0, 1] x [1, 2] and [1, 2] x [0, 1] x [1, 2]
  // with n - 1 and n + 1 spans along y: every knot plane of one is new to the other.
  const std::vector<LRSpline<3>> blocks{volume_block({2 * n, n, n}, {0, 0, 0}, {2, 1, 1}),
                                        volume_block({n, n - 1, n}, {0, 0, 1}, {1, 1, 1}),
                                        volume_block({n, n + 1, n}, {1, 0, 1}, {1, 1, 1})};
  time_matching(state, blocks);
}
BENCHMARK(BM_MultiblockVolumes)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);

// The residual indicator on the T-joint model (one thread): interior jumps through each block's element locator,
// interface jumps through the neighbour block at the mapped parameter.
void BM_MultiblockEstimate(benchmark::State& state) {
  const MultiblockSpace<2> m = multiblock_space(t_joint_model(static_cast<int>(state.range(0))));
  PoissonProblem<2> problem;
  problem.source = [](const double*) { return 1.0; };
  problem.dirichlet = {DirichletCondition<2>{boundary_faces(m), {}, nullptr}};
  auto solver = make_solver("cholmod");
  const SolveResult r = solve_poisson(m.space, problem, *solver, 1);
  const ElementAcross<2> across = multiblock_across(m);
  for (auto _ : state) {
    const std::vector<double> eta = residual_indicators(m.space, problem, r.coefs, 1, across);
    benchmark::DoNotOptimize(eta.data());
  }
  state.counters["elements"] = m.space.num_elements();
}
BENCHMARK(BM_MultiblockEstimate)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

// One adaptive round after the solve on the T-joint model: estimate, Dorfler marking (0.3), FULLSPAN refinement
// inside the blocks and matching again (two solves per iteration: the loop's steps 0 and 1).
void BM_MultiblockAdaptiveStep(benchmark::State& state) {
  const std::vector<LRSpline<2>> blocks = t_joint_model(static_cast<int>(state.range(0)));
  PoissonProblem<2> problem;
  problem.source = [](const double*) { return 1.0; };
  AdaptiveOptions o;
  o.steps = 2;
  int elements = 0;
  for (auto _ : state) {
    MultiblockSpace<2> m = multiblock_space(blocks);
    problem.dirichlet = {DirichletCondition<2>{boundary_faces(m), {}, nullptr}};
    const auto rows = adaptive_poisson(m, problem, nullptr, o, {}, nullptr, 1);
    elements = rows.back().elements;
    benchmark::DoNotOptimize(elements);
  }
  state.counters["elements"] = elements;
}
BENCHMARK(BM_MultiblockAdaptiveStep)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
