// Isogeometric analysis: sum-factorised assembly of the sine-cube Poisson system (stiffness + load +
// Dirichlet projection, the "assembly" time of `trivar solve`) and its CG solve.
#include <benchmark/benchmark.h>

#include <omp.h>

#include "trivar/iga/assembler.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/dirichlet.hpp"

using namespace trivar;

namespace {

int set_threads(const benchmark::State& state, int arg) {
  const int threads = state.range(arg) > 0 ? static_cast<int>(state.range(arg)) : omp_get_num_procs();
  omp_set_num_threads(threads);
  return threads;
}

// range(0): degree, range(1): elements per direction, range(2): threads (0 = all).
void BM_AssembleSineCube(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  const int threads = set_threads(state, 2);
  const PoissonBenchmark<3> b = sine_box<3>(p, n);
  BilinearForm<3> form;
  form.coefficients = [](const double*, double* P) {
    for (int a = 0; a < 16; ++a) P[a] = 0.0;
    P[5] = P[10] = P[15] = 1.0;
  };
  long nnz = 0;
  for (auto _ : state) {
    SparseMatrix A = assemble_matrix(b.space, form, threads);
    Eigen::VectorXd rhs = assemble_load<3>(b.space, 1, [&](const double* x, double* f) { f[0] = b.problem.source(x); },
                                           threads);
    const FixedDofs fixed = project_dirichlet(b.space, 1, b.problem.dirichlet);
    apply_dirichlet(A, rhs, fixed);
    nnz = A.nonZeros();
    benchmark::DoNotOptimize(A.valuePtr());
  }
  state.counters["threads"] = threads;
  state.counters["dofs"] = b.space.num_basis();
  state.counters["nnz"] = static_cast<double>(nnz);
  state.counters["elements/s"] = benchmark::Counter(static_cast<double>(n) * n * n * static_cast<double>(state.iterations()),
                                                    benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AssembleSineCube)
    ->Args({2, 32, 0})
    ->Args({3, 16, 1})
    ->Args({3, 32, 1})
    ->Args({3, 32, 0})
    ->Args({4, 16, 0})
    ->Args({4, 32, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
