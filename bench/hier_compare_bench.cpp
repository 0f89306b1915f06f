// HB, THB and LR B-splines on the same marked elements (the comparison of seed 000 section 4.2 and seed 004):
// the identity map on [0, 1]^2 as a bicubic spline with 8 x 8 elements, four levels of refinement of the
// elements whose open interior meets the diagonal (0,0)-(1,1), or the open corner square (0, 1/8)^2; and the
// adaptive L-shape loop (biquadratic, 16 steps, Dorfler 0.3). The timed part is the refinement (selection
// included); the counters are the resulting numbers of functions and elements, the non-zeros of the stiffness
// matrix (Laplace) and the 2-norm condition number of the mass matrix (dense eigenvalues). LR uses FULLSPAN on
// the marked elements, the hierarchical kinds refine the marked cells dyadically. Figures in bench/README.md.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>

#include "trivar/hier/hierarchical_spline.hpp"
#include "trivar/iga/adaptive_loop.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/refined_assembly.hpp"
#include "trivar/iga/refined_space.hpp"
#include "trivar/lr/refinement.hpp"
#include "trivar/lr/selection.hpp"

using namespace trivar;

namespace {

constexpr int kLevels = 4;

TensorSpline<2> unit_square(int p, int n) {
  std::array<KnotVector, 2> kv{KnotVector::open_uniform(p, n), KnotVector::open_uniform(p, n)};
  const auto g = kv[0].greville();
  std::vector<double> c;
  for (double y : g)
    for (double x : g) c.insert(c.end(), {x, y});
  return TensorSpline<2>(kv, 2, false, c);
}

bool marked(const Box<2>& b, bool diagonal) {
  if (diagonal) return segment_meets_open<2>({0, 0}, {1, 1}, b);
  return box_meets_open<2>(Box<2>{{0, 0}, {0.125, 0.125}}, b);
}

void refine(LRSpline<2>& lr, bool diagonal) {
  std::vector<int> ids;
  for (int e = 0; e < lr.num_elements(); ++e)
    if (marked(lr.element(e), diagonal)) ids.push_back(e);
  refine_elements(lr, std::span<const int>(ids), RefineOptions{});
}

void refine(HierarchicalSpline<2>& h, bool diagonal) {
  std::vector<int> ids;
  for (int e = 0; e < h.space().num_elements(); ++e)
    if (marked(h.space().element_box(e), diagonal)) ids.push_back(e);
  h.refine_elements(ids);
}

// Stiffness non-zeros and mass condition number of a space.
void matrix_counters(benchmark::State& state, const RefinedSpace<2>& s) {
  auto system = [&](bool mass) {
    return assemble_refined_system<2>(
               s, 1, 1,
               [mass](const RefinedPoint<2>& p, const std::vector<double>& grad, double dV, Eigen::MatrixXd& K,
                      Eigen::VectorXd&) {
                 const Eigen::Index m = static_cast<Eigen::Index>(p.R.size());
                 if (mass) {
                   const Eigen::Map<const Eigen::VectorXd> R(p.R.data(), m);
                   K.noalias() += dV * R * R.transpose();
                 } else {
                   const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>> G(grad.data(), m, 2);
                   K.noalias() += dV * G * G.transpose();
                 }
               },
               [](const RefinedElement<2>&, Eigen::VectorXd&) {})
        .A;
  };
  state.counters["functions"] = s.num_basis;
  state.counters["elements"] = s.num_elements();
  state.counters["stiffness_nnz"] = static_cast<double>(system(false).nonZeros());
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(system(true)),
                                                                            Eigen::EigenvaluesOnly)
                                 .eigenvalues();
  state.counters["mass_cond"] = ev.maxCoeff() / ev.minCoeff();
}

template <class Kind>
void marked_refinement(benchmark::State& state, bool diagonal, HierarchicalBasis basis) {
  const TensorSpline<2> start = unit_square(3, 8);
  auto make = [&] {
    if constexpr (std::is_same_v<Kind, LRSpline<2>>) return LRSpline<2>(start);
    else return HierarchicalSpline<2>(start, basis);
  };
  for (auto _ : state) {
    Kind g = make();
    for (int l = 0; l < kLevels; ++l) refine(g, diagonal);
    benchmark::DoNotOptimize(&g);
  }
  Kind g = make();
  for (int l = 0; l < kLevels; ++l) refine(g, diagonal);
  matrix_counters(state, refined_space(g, 1));
}

template <class Kind>
void l_shape_loop(benchmark::State& state, HierarchicalBasis basis) {
  const PoissonBenchmark<2> b = l_shape(2, 4);
  AdaptiveOptions o;
  o.steps = 16;
  o.solver = "cholmod";
  std::vector<ConvergenceRow> rows;
  auto make = [&] {
    if constexpr (std::is_same_v<Kind, LRSpline<2>>) return LRSpline<2>(b.space.geometry);
    else return HierarchicalSpline<2>(b.space.geometry, basis);
  };
  Kind g = make();
  for (auto _ : state) {
    g = make();
    rows = adaptive_poisson(g, b.problem, b.exact, o, {}, nullptr, 1);
  }
  matrix_counters(state, refined_space(g, 1));
  state.counters["h1_error"] = rows.back().h1;
}

using HSpline = HierarchicalSpline<2>;
constexpr auto kHB = HierarchicalBasis::hb;
constexpr auto kTHB = HierarchicalBasis::thb;
void diagonal_hb(benchmark::State& s) { marked_refinement<HSpline>(s, true, kHB); }
void diagonal_thb(benchmark::State& s) { marked_refinement<HSpline>(s, true, kTHB); }
void diagonal_lr(benchmark::State& s) { marked_refinement<LRSpline<2>>(s, true, kTHB); }
void corner_hb(benchmark::State& s) { marked_refinement<HSpline>(s, false, kHB); }
void corner_thb(benchmark::State& s) { marked_refinement<HSpline>(s, false, kTHB); }
void corner_lr(benchmark::State& s) { marked_refinement<LRSpline<2>>(s, false, kTHB); }
void lshape_adaptive_hb(benchmark::State& s) { l_shape_loop<HSpline>(s, kHB); }
void lshape_adaptive_thb(benchmark::State& s) { l_shape_loop<HSpline>(s, kTHB); }
void lshape_adaptive_lr(benchmark::State& s) { l_shape_loop<LRSpline<2>>(s, kTHB); }

}  // namespace

BENCHMARK(diagonal_hb)->Unit(benchmark::kMillisecond);
BENCHMARK(diagonal_thb)->Unit(benchmark::kMillisecond);
BENCHMARK(diagonal_lr)->Unit(benchmark::kMillisecond);
BENCHMARK(corner_hb)->Unit(benchmark::kMillisecond);
BENCHMARK(corner_thb)->Unit(benchmark::kMillisecond);
BENCHMARK(corner_lr)->Unit(benchmark::kMillisecond);
BENCHMARK(lshape_adaptive_hb)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(lshape_adaptive_thb)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(lshape_adaptive_lr)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_MAIN();
