// HB, THB and LR B-splines on the same marked elements (the comparison of seed 000 section 4.2 and seed 004):
// the identity map on [0, 1]^2 as a bicubic spline with 8 x 8 elements, four levels of refinement of the
// elements whose open interior meets the diagonal (0,0)-(1,1), or the open corner square (0, 1/8)^2; and the
// adaptive L-shape loop (biquadratic, 16 steps, Dorfler 0.3). In 3D the identity map on [0, 1]^3 as a tricubic
// spline with 4^3 elements, three levels at the space diagonal or the corner cube (0, 1/4)^3. The timed part is the refinement (selection
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

// Per dimension: levels of marked refinement, elements per direction, the corner square's side.
template <int D>
struct Setup;
template <>
struct Setup<2> {
  static constexpr int levels = 4, elements = 8;
  static constexpr double corner = 0.125;
};
template <>
struct Setup<3> {
  static constexpr int levels = 3, elements = 4;
  static constexpr double corner = 0.25;
};

// The identity map on [0, 1]^D, degree p, n elements per direction (coefficients at the Greville points).
template <int D>
TensorSpline<D> unit_box(int p, int n) {
  std::array<KnotVector, D> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(p, n);
  const auto g = kv[0].greville();
  const int m = static_cast<int>(g.size());
  std::vector<double> c;
  int total = 1;
  for (int k = 0; k < D; ++k) total *= m;
  for (int i = 0; i < total; ++i)
    for (int k = 0, r = i; k < D; ++k, r /= m) c.push_back(g[static_cast<std::size_t>(r % m)]);
  return TensorSpline<D>(kv, D, false, c);
}

template <int D>
bool marked(const Box<D>& b, bool diagonal) {
  Param<D> zero{}, one, corner;
  one.fill(1.0);
  corner.fill(Setup<D>::corner);
  if (diagonal) return segment_meets_open<D>(zero, one, b);
  return box_meets_open<D>(Box<D>{zero, corner}, b);
}

template <int D>
void refine(LRSpline<D>& lr, bool diagonal) {
  std::vector<int> ids;
  for (int e = 0; e < lr.num_elements(); ++e)
    if (marked<D>(lr.element(e), diagonal)) ids.push_back(e);
  refine_elements(lr, std::span<const int>(ids), RefineOptions{});
}

template <int D>
void refine(HierarchicalSpline<D>& h, bool diagonal) {
  std::vector<int> ids;
  for (int e = 0; e < h.space().num_elements(); ++e)
    if (marked<D>(h.space().element_box(e), diagonal)) ids.push_back(e);
  h.refine_elements(ids);
}

// Stiffness non-zeros and mass condition number of a space.
template <int D>
void matrix_counters(benchmark::State& state, const RefinedSpace<D>& s) {
  auto system = [&](bool mass) {
    return assemble_refined_system<D>(
               s, 1, 1,
               [mass](const RefinedPoint<D>& p, const std::vector<double>& grad, double dV, Eigen::MatrixXd& K,
                      Eigen::VectorXd&) {
                 const Eigen::Index m = static_cast<Eigen::Index>(p.R.size());
                 if (mass) {
                   const Eigen::Map<const Eigen::VectorXd> R(p.R.data(), m);
                   K.noalias() += dV * R * R.transpose();
                 } else {
                   const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, D, Eigen::RowMajor>> G(grad.data(), m, D);
                   K.noalias() += dV * G * G.transpose();
                 }
               },
               [](const RefinedElement<D>&, Eigen::VectorXd&) {})
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

template <int D, class Kind>
void marked_refinement(benchmark::State& state, bool diagonal, HierarchicalBasis basis) {
  const TensorSpline<D> start = unit_box<D>(3, Setup<D>::elements);
  auto make = [&] {
    if constexpr (std::is_same_v<Kind, LRSpline<D>>) return LRSpline<D>(start);
    else return HierarchicalSpline<D>(start, basis);
  };
  for (auto _ : state) {
    Kind g = make();
    for (int l = 0; l < Setup<D>::levels; ++l) refine<D>(g, diagonal);
    benchmark::DoNotOptimize(&g);
  }
  Kind g = make();
  for (int l = 0; l < Setup<D>::levels; ++l) refine<D>(g, diagonal);
  matrix_counters<D>(state, refined_space(g, 1));
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
  matrix_counters<2>(state, refined_space(g, 1));
  state.counters["h1_error"] = rows.back().h1;
}

using HSpline = HierarchicalSpline<2>;
constexpr auto kHB = HierarchicalBasis::hb;
constexpr auto kTHB = HierarchicalBasis::thb;
void diagonal_hb(benchmark::State& s) { marked_refinement<2, HSpline>(s, true, kHB); }
void diagonal_thb(benchmark::State& s) { marked_refinement<2, HSpline>(s, true, kTHB); }
void diagonal_lr(benchmark::State& s) { marked_refinement<2, LRSpline<2>>(s, true, kTHB); }
void corner_hb(benchmark::State& s) { marked_refinement<2, HSpline>(s, false, kHB); }
void corner_thb(benchmark::State& s) { marked_refinement<2, HSpline>(s, false, kTHB); }
void corner_lr(benchmark::State& s) { marked_refinement<2, LRSpline<2>>(s, false, kTHB); }
using HVolume = HierarchicalSpline<3>;
void diagonal_3d_hb(benchmark::State& s) { marked_refinement<3, HVolume>(s, true, kHB); }
void diagonal_3d_thb(benchmark::State& s) { marked_refinement<3, HVolume>(s, true, kTHB); }
void diagonal_3d_lr(benchmark::State& s) { marked_refinement<3, LRSpline<3>>(s, true, kTHB); }
void corner_3d_hb(benchmark::State& s) { marked_refinement<3, HVolume>(s, false, kHB); }
void corner_3d_thb(benchmark::State& s) { marked_refinement<3, HVolume>(s, false, kTHB); }
void corner_3d_lr(benchmark::State& s) { marked_refinement<3, LRSpline<3>>(s, false, kTHB); }
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
BENCHMARK(diagonal_3d_hb)->Unit(benchmark::kMillisecond);
BENCHMARK(diagonal_3d_thb)->Unit(benchmark::kMillisecond);
BENCHMARK(diagonal_3d_lr)->Unit(benchmark::kMillisecond);
BENCHMARK(corner_3d_hb)->Unit(benchmark::kMillisecond);
BENCHMARK(corner_3d_thb)->Unit(benchmark::kMillisecond);
BENCHMARK(corner_3d_lr)->Unit(benchmark::kMillisecond);
BENCHMARK(lshape_adaptive_hb)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(lshape_adaptive_thb)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(lshape_adaptive_lr)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_MAIN();
