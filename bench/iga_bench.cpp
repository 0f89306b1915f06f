// Isogeometric analysis: sum-factorised assembly of the sine-cube Poisson system (stiffness + load +
// Dirichlet projection, the "assembly" time of `trivar solve`), the same on a multipatch model of 2 x 2 x 2
// cells (the cost of renumbering and summing the patch matrices), and elastic free vibration.
#include <benchmark/benchmark.h>

#include <omp.h>

#include "trivar/iga/assembler.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/dirichlet.hpp"
#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/multipatch_assembly.hpp"
#include "trivar/model/vmodel.hpp"

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

// The unit cube as 2 x 2 x 2 glued cells.
VModel eight_cells() {
  VModel m;
  for (int c = 0; c < 8; ++c) {
    const Param<3> lo{0.5 * (c & 1), 0.5 * ((c >> 1) & 1), 0.5 * ((c >> 2) & 1)};
    m.add_cell(VCell(box_geometry<3>(lo, {lo[0] + 0.5, lo[1] + 0.5, lo[2] + 0.5}, 1, 1)));
  }
  m.glue();
  return m;
}

// range(0): degree, range(1): elements per direction of the whole cube, range(2): threads (0 = all).
void BM_AssembleSineCubeEightCells(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  const int threads = set_threads(state, 2);
  const MultipatchSpace<3> space = multipatch_space(eight_cells(), p, n / 2);
  BilinearForm<3> form;
  form.coefficients = [](const double*, double* P) {
    for (int a = 0; a < 16; ++a) P[a] = 0.0;
    P[5] = P[10] = P[15] = 1.0;
  };
  const PoissonBenchmark<3> b = sine_box<3>(1, 1);
  const std::vector<DirichletCondition<3>> dirichlet{{space.boundary, {}, nullptr}};
  for (auto _ : state) {
    SparseMatrix A = assemble_matrix<3>(space, [&](int) { return form; }, threads);
    Eigen::VectorXd rhs = assemble_load<3>(space, 1, [&](const double* x, double* f) { f[0] = b.problem.source(x); },
                                           threads);
    apply_dirichlet(A, rhs, project_dirichlet(space, 1, dirichlet));
    benchmark::DoNotOptimize(A.valuePtr());
  }
  state.counters["threads"] = threads;
  state.counters["dofs"] = space.num_basis;
  state.counters["elements/s"] = benchmark::Counter(
      static_cast<double>(n) * n * n * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AssembleSineCubeEightCells)
    ->Args({3, 16, 0})
    ->Args({3, 32, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The 8 lowest free-vibration modes of the roller cube (elastic-cube-modes): assembly of K and M, CHOLMOD
// factorisation of the shifted matrix and the Lanczos iteration. range(0): degree, range(1): elements.
void BM_ElasticCubeModes(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  const int threads = set_threads(state, 2);
  const MultipatchSpace<3> space = single_patch_space(TensorSpace<3>{box_geometry<3>({0, 0, 0}, {1, 1, 1}, p, n)});
  ElasticityProblem<3> pb;
  pb.material = {200, 0.3, 7.8};
  for (const Face& f : space.boundary) pb.displacement.push_back({{f}, {f.dir}, nullptr});
  const std::vector<double> exact = roller_cube_eigenvalues(pb.material, 8);
  double worst = 0;
  for (auto _ : state) {
    const ModesResult r = elastic_modes(space, pb, 8, threads);
    for (int i = 0; i < 8; ++i) worst = std::max(worst, std::abs(r.values[i] / exact[static_cast<std::size_t>(i)] - 1));
  }
  state.counters["threads"] = threads;
  state.counters["dofs"] = 3.0 * space.num_basis;
  state.counters["max_rel_error"] = worst;
}
BENCHMARK(BM_ElasticCubeModes)->Args({3, 8, 0})->Args({2, 12, 0})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
