// Distributed isogeometric analysis (iga_petsc/): the sine-cube Poisson problem assembled and solved on the MPI
// ranks, run as `mpirun -np N bench_petsc [--sizes=p:n,...] [benchmark flags]`. Two benchmarks per size:
// assembly (stiffness, load, Dirichlet projection and elimination, insertion into the distributed matrix) with
// its processor time per element, and the CG solve with block Jacobi/ICC(0) blocks (one per rank) with its
// iterations. Every rank runs the same fixed number of iterations (collective calls must match), the times are
// the slowest rank's (manual time) and rank 0 alone reports.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"
#include "trivar/iga_petsc/petsc_session.hpp"

using namespace trivar;

namespace {

// The phases of one distributed solve of sine-cube at degree p on n^3 elements.
struct SolveRun {
  SolveResult result;
  PhaseCpuSeconds cpu;
  double peak_mb = 0;  // the largest rank's peak resident memory
};

SolveRun solve_sine_cube(int p, int n) {
  const PoissonBenchmark<3> b = sine_box<3>(p, n);
  PetscSolverOptions o;
  o.preconditioner = "bjacobi";
  o.tolerance = 1e-10;
  SolveRun r;
  r.result = petsc_solve_poisson(single_patch_space(b.space), b.problem, o);
  r.cpu = last_phase_cpu_seconds();
  for (double bytes : peak_memory_per_rank()) r.peak_mb = std::max(r.peak_mb, bytes / 1e6);
  return r;
}

void report(benchmark::State& state, const SolveRun& r, int n) {
  const double elements = static_cast<double>(n) * n * n;
  state.counters["ranks"] = rank_partition().parts;
  state.counters["dofs"] = r.result.dofs;
  state.counters["assembly_cpu_s"] = r.cpu.assembly;
  // Per element and rank: the processor time all ranks spend together, divided by the elements.
  state.counters["assembly_cpu_us_per_element"] = 1e6 * r.cpu.assembly * rank_partition().parts / elements;
  state.counters["solve_cpu_s"] = r.cpu.solve;
  state.counters["cg_iterations"] = r.result.stats.iterations;
  state.counters["peak_MB_per_rank"] = r.peak_mb;
}

// The manual time of one phase (SolveResult::assembly_seconds or ::solve_seconds); range(0): degree, range(1):
// elements per direction.
template <double SolveResult::*phase>
void BM_PetscPhase(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  SolveRun r;
  for (auto _ : state) {
    r = solve_sine_cube(p, n);
    state.SetIterationTime(r.result.*phase);
  }
  report(state, r, n);
}

// Discards every report: ranks other than 0 run the benchmarks for their share of the collective work only.
class Silent : public benchmark::BenchmarkReporter {
public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>&) override {}
};

// "--sizes=3:16,3:32" (degree:elements); the default keeps a run under a minute on two cores.
std::vector<std::pair<int, int>> sizes_from(int& argc, char** argv) {
  std::vector<std::pair<int, int>> sizes{{3, 16}, {3, 32}};
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--sizes=", 8) != 0) continue;
    sizes.clear();
    std::string list = argv[i] + 8;
    for (std::size_t at = 0; at < list.size();) {
      const std::size_t end = std::min(list.find(',', at), list.size());
      int p = 0, n = 0;
      if (std::sscanf(list.substr(at, end - at).c_str(), "%d:%d", &p, &n) == 2 && p >= 1 && n >= 1) sizes.emplace_back(p, n);
      at = end + 1;
    }
    for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
    --argc;
    break;
  }
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  PetscSession mpi;
  for (const auto& [p, n] : sizes_from(argc, argv)) {
    // Fixed iteration counts: Google Benchmark's own choice depends on each rank's timing and would differ.
    benchmark::RegisterBenchmark("BM_PetscAssembly", BM_PetscPhase<&SolveResult::assembly_seconds>)->Args({p, n})->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_PetscSolve", BM_PetscPhase<&SolveResult::solve_seconds>)->Args({p, n})->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  Silent silent;
  if (mpi.rank() == 0)
    benchmark::RunSpecifiedBenchmarks();
  else
    benchmark::RunSpecifiedBenchmarks(&silent);
  benchmark::Shutdown();
  return 0;
}
