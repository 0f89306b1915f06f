// Linear-independence checks on a large collection: cubic tensor B-splines on [0,1]^3 with n^3 elements
// (n = 44: 47^3 = 103823 B-splines, 1.3e7 element-support pairs), the size of the 3D n = 16 FULLSPAN level-5
// benchmark of issue 3. Reports the incidence build (k-d tree), peeling and the exact test (peeling first); then
// peeling and the exact test of the real 3D n = 16 level-5 FULLSPAN result on the spline's own support lists.
#include <benchmark/benchmark.h>

#include <vector>

#include "lr_diagonal.hpp"
#include "trivar/lr/linear_independence.hpp"

namespace {

using namespace trivar;

struct Collection {
  std::vector<LRBSpline<3>> basis;
  std::vector<Box<3>> elements;
};

const Collection& tensor_collection() {
  static const Collection c = [] {
    constexpr int n = 44, p = 3;
    std::vector<double> t;
    for (int i = 0; i < p; ++i) t.push_back(0.0);
    for (int i = 0; i <= n; ++i) t.push_back(static_cast<double>(i) / n);
    for (int i = 0; i < p; ++i) t.push_back(1.0);
    const int nb = n + p;
    Collection out;
    for (int k = 0; k < nb; ++k)
      for (int j = 0; j < nb; ++j)
        for (int i = 0; i < nb; ++i) {
          LRBSpline<3> b;
          for (auto [d, s] : {std::pair{0, i}, std::pair{1, j}, std::pair{2, k}})
            b.knots[static_cast<std::size_t>(d)].assign(t.begin() + s, t.begin() + s + p + 2);
          out.basis.push_back(std::move(b));
        }
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          Box<3> e;
          e.lo = {static_cast<double>(i) / n, static_cast<double>(j) / n, static_cast<double>(k) / n};
          e.hi = {static_cast<double>(i + 1) / n, static_cast<double>(j + 1) / n, static_cast<double>(k + 1) / n};
          out.elements.push_back(e);
        }
    return out;
  }();
  return c;
}

void BM_ElementSupports(benchmark::State& state) {
  const auto& c = tensor_collection();
  for (auto _ : state) benchmark::DoNotOptimize(element_supports<3>(c.basis, c.elements).ids.size());
  state.counters["basis"] = static_cast<double>(c.basis.size());
}

void BM_Peeling(benchmark::State& state) {
  const auto& c = tensor_collection();
  for (auto _ : state) benchmark::DoNotOptimize(peeling_test<3>({3, 3, 3}, c.basis, c.elements).status);
  state.counters["basis"] = static_cast<double>(c.basis.size());
}

void BM_Exact(benchmark::State& state) {
  const auto& c = tensor_collection();
  for (auto _ : state) benchmark::DoNotOptimize(exact_test<3>({3, 3, 3}, c.basis, c.elements).status);
}

const LRSpline<3>& fullspan_level5() {
  static const LRSpline<3> lr = [] {
    auto s = bench::unit_lr<3>(16);
    for (int level = 0; level < 5; ++level) bench::refine_diagonal(s, Strategy::fullspan);
    return s;
  }();
  return lr;
}

void BM_PeelingRefined(benchmark::State& state) {
  const auto& lr = fullspan_level5();
  PeelingResult r;
  for (auto _ : state) r = peeling_test(lr);
  state.counters["basis"] = lr.num_basis();
  state.counters["unresolved"] = static_cast<double>(r.unresolved.size());
  state.counters["independent"] = r.status == Independence::independent;
}

void BM_ExactRefined(benchmark::State& state) {
  const auto& lr = fullspan_level5();
  ExactResult r;
  for (auto _ : state) r = exact_test(lr);
  state.counters["tested"] = r.tested;
  state.counters["independent"] = r.status == Independence::independent;
}

}  // namespace

BENCHMARK(BM_PeelingRefined)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExactRefined)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ElementSupports)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Peeling)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Exact)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
