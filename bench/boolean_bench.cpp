// Booleans of V-models with tens of cells (cad/boolean): a 4 x 4 x 2 lattice of 32 box cells minus a 7-cell
// ball, and the union of the lattice with the ball, attributes blended by formula; and a 7-cell ball minus a
// 5-cell cylinder (curved faces only); the lattice split by a tilted plane. Then the analysis of a result: the
// faces its 32 cells share (trimmed_interfaces) and the detrimmed space over all of them (trimmed_model_space).
#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include "trivar/cad/boolean.hpp"
#include "trivar/cad/split.hpp"
#include "trivar/iga/trimmed_model_space.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/primitives.hpp"
#include "trivar/spline/affine_transform.hpp"

using namespace trivar;

namespace {

VModel lattice(int nx, int ny, int nz) {
  VModel m;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        VCell c(make_box({Eigen::Vector3d::Ones(), Eigen::Vector3d(i, j, k)}).front());
        c.set_attribute("material", Attribute::constant({1, 0}));
        m.add_cell(std::move(c));
      }
  m.glue();
  return m;
}

VModel ball_model(double r, const Eigen::Vector3d& c) {
  VModel m;
  for (const SplineVolume& s : make_ball({r, c})) {
    VCell cell(s);
    cell.set_attribute("material", Attribute::constant({0, 1}));
    m.add_cell(std::move(cell));
  }
  m.glue();
  return m;
}

void BM_LatticeMinusBall(benchmark::State& state) {
  const VModel a = lattice(4, 4, 2), b = ball_model(1.3, {2, 2, 1});
  cad::BooleanReport rep;
  for (auto _ : state) benchmark::DoNotOptimize(cad::boolean(a, b, cad::BooleanOp::subtract, {}, &rep));
  state.counters["cells_in"] = a.num_cells() + b.num_cells();
  state.counters["cells_out"] = rep.cells;
}
BENCHMARK(BM_LatticeMinusBall)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_LatticeUnionBallBlended(benchmark::State& state) {
  const VModel a = lattice(4, 4, 2), b = ball_model(1.3, {2, 2, 1});
  cad::BooleanOptions o;
  o.default_rule = {cad::BlendRule::formula, "min(1, max(0, z - 1))"};
  cad::BooleanReport rep;
  for (auto _ : state) benchmark::DoNotOptimize(cad::boolean(a, b, cad::BooleanOp::unite, o, &rep));
  state.counters["cells_in"] = a.num_cells() + b.num_cells();
  state.counters["cells_out"] = rep.cells;
}
BENCHMARK(BM_LatticeUnionBallBlended)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_BallMinusCylinder(benchmark::State& state) {
  const VModel a = ball_model(1, Eigen::Vector3d::Zero());
  VModel b;
  for (const SplineVolume& s : make_cylinder({0.4, 3})) b.add_cell(VCell(transform(s, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -1.5))));
  b.glue();
  cad::BooleanReport rep;
  for (auto _ : state) benchmark::DoNotOptimize(cad::boolean(a, b, cad::BooleanOp::subtract, {}, &rep));
  state.counters["cells_in"] = a.num_cells() + b.num_cells();
  state.counters["cells_out"] = rep.cells;
}
BENCHMARK(BM_BallMinusCylinder)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_LatticeSplitByPlane(benchmark::State& state) {
  const VModel a = lattice(4, 4, 2);
  const cad::SplitPlane plane{{2, 2, 1}, {1, 0.5, 2}};
  cad::BooleanReport rep;
  for (auto _ : state) benchmark::DoNotOptimize(cad::split(a, plane, {}, &rep));
  state.counters["cells_in"] = a.num_cells();
  state.counters["cells_out"] = rep.cells;
}
BENCHMARK(BM_LatticeSplitByPlane)->Unit(benchmark::kMillisecond)->Iterations(3);

// The lattice minus the ball (32 trimmed cells), made once.
const VModel& lattice_minus_ball() {
  static const VModel m = cad::boolean(lattice(4, 4, 2), ball_model(1.3, {2, 2, 1}), cad::BooleanOp::subtract);
  return m;
}

void BM_TrimmedInterfacesOfLatticeMinusBall(benchmark::State& state) {
  const VModel& m = lattice_minus_ball();
  TrimmedInterfaces t;
  for (auto _ : state) benchmark::DoNotOptimize(t = trimmed_interfaces(m));
  state.counters["cells"] = m.num_cells();
  state.counters["shared_faces"] = t.shared;
  state.counters["boundary_faces"] = t.boundary;
}
BENCHMARK(BM_TrimmedInterfacesOfLatticeMinusBall)->Unit(benchmark::kMillisecond);

// Quadratics on n^3 elements over the 4 x 4 x 2 box, octree depth 2, one thread.
void BM_TrimmedModelSpaceOfLatticeMinusBall(benchmark::State& state) {
  const VModel& m = lattice_minus_ball();
  const int n = static_cast<int>(state.range(0));
  int cut = 0;
  for (auto _ : state) {
    const TrimmedModelSpace tm = trimmed_model_space(m, 2, n, 1);
    cut = tm.cut;
    benchmark::DoNotOptimize(tm.space.elements.data());
  }
  state.counters["elements"] = n * n * n;
  state.counters["cut"] = cut;
}
BENCHMARK(BM_TrimmedModelSpaceOfLatticeMinusBall)->Arg(8)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
