// Multi-block volumes with non-matching faces and T-joints: a long triquadratic block [0, 2] x [0, 1] x [0, 1] with
// two blocks on its top face (the second turned by 180 degrees about z), and a block on one quarter of a square
// slab's top (its face's edges run inside the slab's face in both directions). Checks that the common parts are
// found, that identified functions agree on both sides of every interface, and that iga's solvers reproduce a
// quadratic Poisson solution and a linear displacement (the patch test) across the T-joints.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/fit/multiblock_space.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/refined_elasticity.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/lr/linear_independence.hpp"

namespace trivar {
namespace {

// The affine map u -> origin + sum_k u_k e_k as a triquadratic spline on the knots (Greville points reproduce it).
TensorSpline<3> affine_volume(const std::array<std::vector<double>, 3>& t, std::array<double, 3> origin,
                              const std::array<std::array<double, 3>, 3>& e) {
  std::array<KnotVector, 3> kv{KnotVector(2, t[0]), KnotVector(2, t[1]), KnotVector(2, t[2])};
  const std::array<std::vector<double>, 3> g{kv[0].greville(), kv[1].greville(), kv[2].greville()};
  std::vector<double> pts;
  for (double c : g[2])
    for (double b : g[1])
      for (double a : g[0])
        for (int k = 0; k < 3; ++k) pts.push_back(origin[static_cast<std::size_t>(k)] + a * e[0][static_cast<std::size_t>(k)] + b * e[1][static_cast<std::size_t>(k)] + c * e[2][static_cast<std::size_t>(k)]);
  return TensorSpline<3>::from_cartesian(kv, 3, pts);
}

std::vector<LRSpline<3>> three_volume_t_joint() {
  return {LRSpline<3>(affine_volume({{{0, 0, 0, 0.3, 0.7, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1}}}, {0, 0, 0},
                                    {{{2, 0, 0}, {0, 1, 0}, {0, 0, 1}}})),
          LRSpline<3>(affine_volume({{{0, 0, 0, 0.25, 0.5, 1, 1, 1}, {0, 0, 0, 0.4, 1, 1, 1}, {0, 0, 0, 1, 1, 1}}}, {0, 0, 1},
                                    {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}})),
          LRSpline<3>(affine_volume({{{0, 0, 0, 0.4, 1, 1, 1}, {0, 0, 0, 0.6, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1}}}, {2, 1, 1},
                                    {{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}}}))};
}

// A slab [0, 2] x [0, 2] x [0, 1] (spans x spans x 1) and a block [0, 1] x [0, 1] x [1, 2] on one quarter of its
// top, parametrised with its first two directions swapped.
std::vector<LRSpline<3>> quarter_on_slab(int spans = 10) {
  std::vector<double> tenths{0, 0, 0};
  for (int i = 1; i < spans; ++i) tenths.push_back(static_cast<double>(i) / spans);
  tenths.insert(tenths.end(), {1, 1, 1});
  return {LRSpline<3>(affine_volume({{tenths, tenths, {0, 0, 0, 1, 1, 1}}}, {0, 0, 0},
                                    {{{2, 0, 0}, {0, 2, 0}, {0, 0, 1}}})),
          LRSpline<3>(affine_volume({{{0, 0, 0, 0.5, 1, 1, 1}, {0, 0, 0, 0.35, 1, 1, 1}, {0, 0, 0, 1, 1, 1}}}, {0, 0, 1},
                                    {{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}}}))};
}

// The values of the functions of block b's element holding parameter u, by global id.
std::map<int, double> volume_function_values(const MultiblockSpace<3>& m, int b, const Param<3>& u) {
  std::map<int, double> out;
  for (std::size_t e = 0; e < m.space.elements.size(); ++e) {
    const RefinedElement<3>& el = m.space.elements[e];
    if (el.block != b || !el.box.contains(u)) continue;
    RefinedPoint<3> pt;
    refined_point(m.space, el, u, pt);
    for (std::size_t l = 0; l < el.ids.size(); ++l)
      if (std::abs(pt.R[l]) > 1e-14) out[el.ids[l]] = pt.R[l];
    break;
  }
  return out;
}

double volume_pointwise_error(const MultiblockSpace<3>& m, const Eigen::VectorXd& coefs, int components,
                              const std::function<void(const double*, double*)>& exact) {
  double worst = 0, e[3];
  RefinedPoint<3> pt;
  for (const RefinedElement<3>& el : m.space.elements)
    for (double a : {0.0, 0.7})
      for (double b : {0.2, 1.0})
        for (double c : {0.0, 0.5, 1.0}) {
          refined_point(m.space, el, {el.box.lo[0] + a * el.box.extent(0), el.box.lo[1] + b * el.box.extent(1), el.box.lo[2] + c * el.box.extent(2)}, pt);
          exact(pt.x.data(), e);
          for (int k = 0; k < components; ++k) {
            double uh = 0;
            for (std::size_t l = 0; l < el.ids.size(); ++l) uh += coefs[k * m.space.num_basis + el.ids[l]] * pt.R[l];
            worst = std::max(worst, std::abs(uh - e[k]));
          }
        }
  return worst;
}

// Matching matched blocks changes nothing (the common parts end on the knots the first matching inserted, even
// where the refined geometry puts the corners' projections a rounding error off them): the unit cube as a slab
// with two blocks on top, uniform knots of different spacings.
TEST(MultiblockVolumes, MatchingIsIdempotent) {
  const auto uniform_block = [](std::array<int, 3> n, std::array<double, 3> o, std::array<std::array<double, 3>, 3> e) {
    std::array<std::vector<double>, 3> t;
    for (std::size_t k = 0; k < 3; ++k) {
      t[k] = {0, 0, 0};
      for (int i = 1; i < n[k]; ++i) t[k].push_back(static_cast<double>(i) / n[k]);
      t[k].insert(t[k].end(), {1, 1, 1});
    }
    return LRSpline<3>(affine_volume(t, o, e));
  };
  const MultiblockSpace<3> m = multiblock_space(std::vector<LRSpline<3>>{
      uniform_block({6, 7, 4}, {0, 0, 0}, {{{1, 0, 0}, {0, 1, 0}, {0, 0, 0.5}}}),
      uniform_block({3, 5, 4}, {0, 0, 0.5}, {{{0.5, 0, 0}, {0, 1, 0}, {0, 0, 0.5}}}),
      uniform_block({4, 6, 3}, {1, 1, 0.5}, {{{-0.5, 0, 0}, {0, -1, 0}, {0, 0, 0.5}}})});
  const MultiblockSpace<3> again = multiblock_space(m.blocks);
  EXPECT_EQ(again.space.num_basis, m.space.num_basis);
  for (std::size_t b = 0; b < 3; ++b) {
    EXPECT_EQ(again.blocks[b].num_basis(), m.blocks[b].num_basis());
    EXPECT_EQ(again.blocks[b].num_elements(), m.blocks[b].num_elements());
  }
}

TEST(MultiblockVolumes, MatchedFacesAgreeAcrossTJoints) {
  for (const auto& blocks : {three_volume_t_joint(), quarter_on_slab()}) {
    const MultiblockSpace<3> m = multiblock_space(blocks);
    ASSERT_EQ(m.interfaces.size(), blocks.size() == 2 ? 1u : 3u);  // three blocks: the upper two also meet at x = 1
    EXPECT_EQ(m.partial_sides.size(), blocks.size() == 2 ? 1u : 0u);  // the slab's top is partly boundary
    for (const BlockInterface<3>& f : m.interfaces) {
      if (f.block[0] == 0) {
        EXPECT_EQ(f.side[0].dir, 2);  // the long block's / slab's top
        EXPECT_EQ(f.side[0].end, 1);
      }
      // Every identified function has the same value from both sides at points spread over the common part, and
      // the geometry agrees there.
      const int a = f.side[0].dir == 0 ? 1 : 0, b = 3 - f.side[0].dir - a;
      for (int i = 1; i < 9; ++i)
        for (int j = 1; j < 9; ++j) {
          Param<3> u0 = f.lo[0], u1 = f.lo[1];
          u0[a] += (f.hi[0][a] - f.lo[0][a]) * i / 9.0;
          u0[b] += (f.hi[0][b] - f.lo[0][b]) * j / 9.0;
          u1[f.along[a]] += (f.hi[1][f.along[a]] - f.lo[1][f.along[a]]) * i / 9.0;
          u1[f.along[b]] += (f.hi[1][f.along[b]] - f.lo[1][f.along[b]]) * j / 9.0;
          const auto v0 = volume_function_values(m, f.block[0], u0), v1 = volume_function_values(m, f.block[1], u1);
          ASSERT_EQ(v0.size(), v1.size()) << i << " " << j;
          for (const auto& [id, value] : v0) {
            ASSERT_TRUE(v1.count(id)) << id;
            EXPECT_NEAR(value, v1.at(id), 1e-12);
          }
          double x[3], y[3];
          m.blocks[static_cast<std::size_t>(f.block[0])].eval(u0, x);
          m.blocks[static_cast<std::size_t>(f.block[1])].eval(u1, y);
          for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], y[k], 1e-12);
        }
    }
  }
}

// The neighbour's knot planes and the edges of the common part (T-joint planes, multiplicity p) enter a face over
// the common part only (widened to the supports of the first-row B-splines meeting it): the slab's B-splines
// beyond the quarter block's reach keep their knots and coefficients (planes across the whole face would split
// those near the slab's left edge and across x = 1 too), every matched block passes the peeling test of linear
// independence, and the local planes need fewer coefficients than edge planes across the whole face.
TEST(MultiblockVolumes, FacesAreRefinedOnlyWhereTheNeighbourNeedsIt) {
  for (const auto& blocks : {three_volume_t_joint(), quarter_on_slab()}) {
    const MultiblockSpace<3> m = multiblock_space(blocks);
    for (const LRSpline<3>& b : m.blocks) EXPECT_EQ(peeling_test(b).status, Independence::independent);
  }
  const std::vector<LRSpline<3>> in = quarter_on_slab();
  const MultiblockSpace<3> m = multiblock_space(in);
  std::map<std::array<std::vector<double>, 3>, std::vector<double>> after;
  for (const auto& f : m.blocks[0].basis_functions()) after[f.knots] = f.coef;
  int far = 0;
  for (const auto& f : in[0].basis_functions())
    // v >= 0.8 (y >= 1.6, beyond the reach of the block on [0, 1]^2), across the plane u = 0.5 (x = 1) too.
    if (f.knots[1].front() >= 0.8 - 1e-12) {
      ++far;
      const auto it = after.find(f.knots);
      ASSERT_NE(it, after.end());
      EXPECT_EQ(it->second, f.coef);
    }
  EXPECT_EQ(far, 2 * 12 * 3);  // two rows of 12 x 3 B-splines in u and w
  EXPECT_GT(m.blocks[0].num_basis(), in[0].num_basis());

  // The same model with the T-joint planes across the whole face: conforming too, more coefficients.
  MultiblockOptions whole_face;
  whole_face.whole_face_edges = true;
  for (const auto& blocks : {three_volume_t_joint(), quarter_on_slab()}) {
    const MultiblockSpace<3> local = multiblock_space(blocks), wide = multiblock_space(blocks, whole_face);
    for (const LRSpline<3>& b : wide.blocks) EXPECT_EQ(peeling_test(b).status, Independence::independent);
    EXPECT_LE(local.space.num_basis, wide.space.num_basis);
    RecordProperty("coefficients_local_" + std::to_string(blocks.size()), local.space.num_basis);
    RecordProperty("coefficients_whole_face_" + std::to_string(blocks.size()), wide.space.num_basis);
  }
  EXPECT_LT(m.space.num_basis, multiblock_space(in, whole_face).space.num_basis);
}

// Two faces crossing like the bars of a plus sign (a slab long in x, a block long in y on it): no corner of either
// face lies on the other, so no common part can be bounded by corners; refused naming both blocks and faces.
TEST(MultiblockVolumes, PlusShapedOverlapIsRefusedNamingBothBlocks) {
  const std::array<std::vector<double>, 3> knots{{{0, 0, 0, 0.5, 1, 1, 1}, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1}}};
  const std::vector<LRSpline<3>> plus{LRSpline<3>(affine_volume(knots, {0, 1, 0}, {{{3, 0, 0}, {0, 1, 0}, {0, 0, 1}}})),
                                      LRSpline<3>(affine_volume(knots, {2, 0, 1}, {{{0, 3, 0}, {-1, 0, 0}, {0, 0, 1}}}))};
  try {
    multiblock_space(plus);
    FAIL() << "plus-shaped overlap accepted";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("block 0 side w = hi"), std::string::npos) << msg;
    EXPECT_NE(msg.find("block 1 side w = lo"), std::string::npos) << msg;
    EXPECT_NE(msg.find("plus-shaped"), std::string::npos) << msg;
  }
  // Blocks that merely touch along an edge or a corner pass.
  const std::vector<LRSpline<3>> apart{LRSpline<3>(affine_volume(knots, {0, 0, 0}, {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}})),
                                       LRSpline<3>(affine_volume(knots, {1, 1, 1}, {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}))};
  EXPECT_TRUE(multiblock_space(apart).interfaces.empty());
}

TEST(MultiblockVolumes, IgaSolversReproduceQuadraticAndLinearFields) {
  const auto u = [](const double* x) { return x[0] * x[0] - x[1] * x[2] + 2 * x[2] * x[2] + x[0] - 0.5 * x[1]; };
  const auto disp = [](const double* x, double* v) {
    v[0] = 0.01 * x[0] + 0.02 * x[1] - 0.01 * x[2] + 0.03;
    v[1] = -0.005 * x[0] + 0.015 * x[1];
    v[2] = 0.002 * x[0] - 0.01 * x[2] + 0.001;
  };
  for (const auto& blocks : {three_volume_t_joint(), quarter_on_slab(3)}) {
    const MultiblockSpace<3> m = multiblock_space(blocks);
    PoissonProblem<3> poisson;
    poisson.source = [](const double*) { return -6.0; };
    poisson.dirichlet = {DirichletCondition<3>{boundary_faces(m), {}, [&](const double* x, double* v) { v[0] = u(x); }}};
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_poisson(m.space, poisson, *solver, 1);
    EXPECT_GT(r.dofs, 0);
    EXPECT_LT(volume_pointwise_error(m, r.coefs, 1, [&](const double* x, double* v) { v[0] = u(x); }), 1e-10) << blocks.size();

    ElasticityProblem<3> elastic;
    elastic.material = {1000.0, 0.3, 1.0};
    elastic.displacement = {DirichletCondition<3>{boundary_faces(m), {}, disp}};
    const SolveResult e = solve_elasticity(m.space, elastic, *solver, 1);
    EXPECT_LT(volume_pointwise_error(m, e.coefs, 3, disp), 1e-10) << blocks.size();
  }
  // With knot planes across whole blocks the three-block model is iga's tensor multipatch space (no side partly
  // boundary), and its multipatch Poisson solver reproduces the quadratic too.
  const MultiblockSpace<3> whole = multiblock_space(three_volume_t_joint(), {0.0, true});
  const MultipatchSpace<3> patches = tensor_multipatch(whole);
  PoissonProblem<3> poisson;
  poisson.source = [](const double*) { return -6.0; };
  poisson.dirichlet = {DirichletCondition<3>{patches.boundary, {}, [&](const double* x, double* v) { v[0] = u(x); }}};
  auto solver = make_solver("cholmod");
  const SolveResult r = solve_poisson(patches, poisson, *solver, 1);
  const ErrorNorms e = error_norms(patches, r.coefs, 1, [&](const double* x, double* v, double* g) {
    v[0] = u(x);
    g[0] = 2 * x[0] + 1;
    g[1] = -x[2] - 0.5;
    g[2] = -x[1] + 4 * x[2];
  }, 1);
  EXPECT_LT(e.l2, 1e-10);
  EXPECT_LT(e.h1, 1e-9);
  EXPECT_THROW(tensor_multipatch(multiblock_space(quarter_on_slab(3), {0.0, true})), Error);
}

}  // namespace
}  // namespace trivar
