// Multi-block LR models with a T-joint: three planar blocks, a long one below two short ones (one of them
// parametrised rotated by 180 degrees). Checks that the interfaces are found, that only the first row of the long
// block is split (at the T-joint, multiplicity p), that identified functions are equal on both sides of every
// interface (evaluated through each block's own elements), that one function is shared by the three blocks at
// the T-joint, and that a Poisson problem whose solution is a quadratic polynomial (in the space, since the
// blocks are affine) is solved exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/fit/multiblock_space.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/refined_assembly.hpp"
#include "trivar/iga/refined_elasticity.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/spline/knot_insertion.hpp"

namespace trivar {
namespace {

constexpr int kBlockDegree = 2;

double greville(const std::vector<double>& t, int i, int degree) {
  double s = 0;
  for (int k = 1; k <= degree; ++k) s += t[static_cast<std::size_t>(i + k)];
  return s / degree;
}

// The affine map (u, v) -> origin + u * eu + v * ev as a tensor spline of the given degree on the knots
// (Greville points reproduce linear maps exactly).
TensorSpline<2> affine_tensor(const std::vector<double>& u, const std::vector<double>& v, std::array<double, 2> origin,
                              std::array<double, 2> eu, std::array<double, 2> ev, int degree = kBlockDegree) {
  const KnotVector ku(degree, u), kv(degree, v);
  std::vector<double> pts;
  for (int j = 0; j < kv.size(); ++j)
    for (int i = 0; i < ku.size(); ++i) {
      const double a = greville(u, i, degree), b = greville(v, j, degree);
      pts.push_back(origin[0] + a * eu[0] + b * ev[0]);
      pts.push_back(origin[1] + a * eu[1] + b * ev[1]);
    }
  return TensorSpline<2>::from_cartesian({ku, kv}, 2, pts);
}

LRSpline<2> affine_block(const std::vector<double>& u, const std::vector<double>& v, std::array<double, 2> origin,
                         std::array<double, 2> eu, std::array<double, 2> ev, int degree = kBlockDegree) {
  return LRSpline<2>(affine_tensor(u, v, origin, eu, ev, degree));
}

// Long block [0, 2] x [0, 1]; above it [0, 1] x [1, 2] and [1, 2] x [1, 2], the latter rotated by 180 degrees.
// The T-joint is the point (1, 1): u = 0.5 of the long block's top, not one of its knots.
std::vector<TensorSpline<2>> t_joint_tensors() {
  return {affine_tensor({0, 0, 0, 0.3, 0.7, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1}, {0, 0}, {2, 0}, {0, 1}),
          affine_tensor({0, 0, 0, 0.25, 0.5, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1}, {0, 1}, {1, 0}, {0, 1}),
          affine_tensor({0, 0, 0, 0.4, 1, 1, 1}, {0, 0, 0, 0.6, 1, 1, 1}, {2, 2}, {-1, 0}, {0, -1})};
}

std::vector<LRSpline<2>> t_joint_blocks() {
  std::vector<LRSpline<2>> out;
  for (const auto& t : t_joint_tensors()) out.emplace_back(t);
  return out;
}

// The values of the functions of block b's elements at parameter u of that block, by global id.
std::map<int, double> values_at(const MultiblockSpace<2>& m, int b, const Param<2>& u) {
  std::map<int, double> out;
  for (std::size_t e = 0; e < m.space.elements.size(); ++e) {
    const RefinedElement<2>& el = m.space.elements[e];
    if (m.element_block[e] != b) continue;
    if (u[0] < el.box.lo[0] || u[0] > el.box.hi[0] || u[1] < el.box.lo[1] || u[1] > el.box.hi[1]) continue;
    RefinedPoint<2> pt;
    refined_point(m.space, el, u, pt);
    for (std::size_t l = 0; l < el.ids.size(); ++l)
      if (std::abs(pt.R[l]) > 1e-14) out[el.ids[l]] = pt.R[l];
    break;
  }
  return out;
}

TEST(MultiblockSpace, TJointInterfacesAreConforming) {
  const std::vector<LRSpline<2>> in = t_joint_blocks();
  const MultiblockSpace<2> m = multiblock_space(in);
  ASSERT_EQ(m.interfaces.size(), 3u);

  // Only B-splines of the first rows along interfaces changed: the long block's top row (three of them split at
  // the T-joint, u = 0.5, and more by the neighbours' knot lines); nothing further inside.
  for (int b = 0; b < 3; ++b) {
    const LRSpline<2>& s = m.blocks[static_cast<std::size_t>(b)];
    std::map<std::array<std::vector<double>, 2>, std::vector<double>> after;
    for (const auto& f : s.basis_functions()) after[f.knots] = f.coef;
    int changed = 0, at_joint = 0;
    for (const auto& f : in[static_cast<std::size_t>(b)].basis_functions()) {
      const auto it = after.find(f.knots);
      if (it != after.end() && it->second == f.coef) continue;
      ++changed;
      bool first_row = false;
      for (int sd = 0; sd < 4; ++sd) {
        const double end = DomainSide{sd / 2, sd % 2}.value(s);
        first_row = first_row || std::count(f.knots[static_cast<std::size_t>(sd / 2)].begin(), f.knots[static_cast<std::size_t>(sd / 2)].end(), end) == kBlockDegree + 1;
      }
      EXPECT_TRUE(first_row) << "block " << b;
      if (b == 0) {
        EXPECT_EQ(f.knots[1].back(), 1.0);
        at_joint += f.knots[0].front() < 0.5 && f.knots[0].back() > 0.5;
      }
    }
    if (b == 0) {
      EXPECT_EQ(at_joint, 3);  // the transition B-splines: top row, support across u = 0.5
    }
    EXPECT_LE(changed, 6);
  }
  int knot_at_joint = 0;
  for (int id : side_row(m.blocks[0], {1, 1}, 0)) {
    const auto& t = m.blocks[0].basis_function(id).knots[0];
    knot_at_joint = std::max(knot_at_joint, static_cast<int>(std::count(t.begin(), t.end(), 0.5)));
  }
  EXPECT_EQ(knot_at_joint, kBlockDegree);

  // Identified functions are equal on both sides of every interface.
  for (const BlockInterface<2>& f : m.interfaces)
    for (int k = 1; k < 40; ++k) {
      const int a0 = 1 - f.side[0].dir, a1 = f.along[a0];
      Param<2> u0 = f.lo[0], u1 = f.lo[1];
      u0[a0] = f.lo[0][a0] + (f.hi[0][a0] - f.lo[0][a0]) * k / 40.0;
      u1[a1] = f.lo[1][a1] + (f.hi[1][a1] - f.lo[1][a1]) * k / 40.0;
      const auto a = values_at(m, f.block[0], u0), c = values_at(m, f.block[1], u1);
      ASSERT_EQ(a.size(), c.size()) << k;
      for (const auto& [id, value] : a) {
        ASSERT_TRUE(c.count(id)) << id;
        EXPECT_NEAR(value, c.at(id), 1e-13);
      }
    }
  // The T-joint: exactly one function belongs to all three blocks, and it is 1 at (1, 1).
  std::map<int, std::set<int>> owners;
  for (int b = 0; b < 3; ++b)
    for (int g : m.global[static_cast<std::size_t>(b)]) owners[g].insert(b);
  int shared = -1, count = 0;
  for (const auto& [g, bs] : owners)
    if (bs.size() == 3) shared = g, ++count;
  ASSERT_EQ(count, 1);
  EXPECT_NEAR(values_at(m, 0, {0.5, 1.0}).at(shared), 1.0, 1e-14);
  EXPECT_NEAR(m.space.control[2 * static_cast<std::size_t>(shared)], 1.0, 1e-14);
  EXPECT_NEAR(m.space.control[2 * static_cast<std::size_t>(shared) + 1], 1.0, 1e-14);
}

// u = x^2 - x y + 2 y^2 + x: -laplace u = -6. Dirichlet values from the L2 projection of u (exact, as u lies in
// the space), the interior from the Galerkin system; both must be u to rounding.
TEST(MultiblockSpace, PoissonReproducesAQuadraticOnATJointModel) {
  const MultiblockSpace<2> m = multiblock_space(t_joint_blocks());
  const auto exact = [](const std::array<double, 2>& x) { return x[0] * x[0] - x[0] * x[1] + 2 * x[1] * x[1] + x[0]; };
  auto mass = assemble_refined_system<2>(
      m.space, 1, 1,
      [&](const RefinedPoint<2>& pt, const std::vector<double>&, double dV, Eigen::MatrixXd& K, Eigen::VectorXd& b) {
        const auto n = static_cast<Eigen::Index>(pt.R.size());
        for (Eigen::Index i = 0; i < n; ++i) {
          b[i] += dV * exact(pt.x) * pt.R[static_cast<std::size_t>(i)];
          for (Eigen::Index j = 0; j < n; ++j) K(i, j) += dV * pt.R[static_cast<std::size_t>(i)] * pt.R[static_cast<std::size_t>(j)];
        }
      },
      [](const RefinedElement<2>&, Eigen::VectorXd&) {});
  const Eigen::VectorXd projected = Eigen::MatrixXd(mass.A).ldlt().solve(mass.b);
  auto poisson = assemble_refined_system<2>(
      m.space, 1, 1,
      [&](const RefinedPoint<2>& pt, const std::vector<double>& grad, double dV, Eigen::MatrixXd& K, Eigen::VectorXd& b) {
        const auto n = static_cast<Eigen::Index>(pt.R.size());
        for (Eigen::Index i = 0; i < n; ++i) {
          b[i] += dV * -6.0 * pt.R[static_cast<std::size_t>(i)];
          for (Eigen::Index j = 0; j < n; ++j)
            K(i, j) += dV * (grad[static_cast<std::size_t>(2 * i)] * grad[static_cast<std::size_t>(2 * j)] +
                             grad[static_cast<std::size_t>(2 * i + 1)] * grad[static_cast<std::size_t>(2 * j + 1)]);
        }
      },
      [](const RefinedElement<2>&, Eigen::VectorXd&) {});
  const int N = m.space.num_basis;
  std::vector<char> fixed(static_cast<std::size_t>(N), 0);
  for (int i : m.boundary) fixed[static_cast<std::size_t>(i)] = 1;
  std::vector<int> free;
  for (int i = 0; i < N; ++i)
    if (!fixed[static_cast<std::size_t>(i)]) free.push_back(i);
  ASSERT_GT(free.size(), 10u);
  const Eigen::MatrixXd K(poisson.A);
  Eigen::MatrixXd Kff(free.size(), free.size());
  Eigen::VectorXd rhs(free.size());
  for (std::size_t a = 0; a < free.size(); ++a) {
    rhs[static_cast<Eigen::Index>(a)] = poisson.b[free[a]];
    for (int j : m.boundary) rhs[static_cast<Eigen::Index>(a)] -= K(free[a], j) * projected[j];
    for (std::size_t c = 0; c < free.size(); ++c) Kff(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(c)) = K(free[a], free[c]);
  }
  const Eigen::VectorXd x = Kff.ldlt().solve(rhs);
  Eigen::VectorXd solution = projected;
  for (std::size_t a = 0; a < free.size(); ++a) solution[free[a]] = x[static_cast<Eigen::Index>(a)];
  // Pointwise on every element, through the solution coefficients.
  double worst = 0, worst_projection = 0;
  for (const RefinedElement<2>& el : m.space.elements) {
    RefinedPoint<2> pt;
    for (double a : {0.1, 0.5, 0.9})
      for (double b : {0.2, 0.7}) {
        refined_point(m.space, el, {el.box.lo[0] + a * (el.box.hi[0] - el.box.lo[0]), el.box.lo[1] + b * (el.box.hi[1] - el.box.lo[1])}, pt);
        double uh = 0, up = 0;
        for (std::size_t l = 0; l < el.ids.size(); ++l) {
          uh += solution[el.ids[l]] * pt.R[l];
          up += projected[el.ids[l]] * pt.R[l];
        }
        worst = std::max(worst, std::abs(uh - exact(pt.x)));
        worst_projection = std::max(worst_projection, std::abs(up - exact(pt.x)));
      }
  }
  EXPECT_LT(worst_projection, 1e-11);
  EXPECT_LT(worst, 1e-10);
}

// u = sin(pi x / 2) sin(pi y / 2) e^(x / 4), the manufactured solution of the convergence tests: its value,
// -lap u, and value with gradient.
double sine_hill(const double* x) {
  const double pi = std::acos(-1.0);
  return std::sin(pi * x[0] / 2) * std::sin(pi * x[1] / 2) * std::exp(x[0] / 4);
}

double sine_hill_source(const double* x) {
  const double pi = std::acos(-1.0);
  const double s = std::sin(pi * x[0] / 2), c = std::cos(pi * x[0] / 2), t = std::sin(pi * x[1] / 2), e = std::exp(x[0] / 4);
  return -((-pi * pi / 4 * s + pi / 4 * c + s / 16) * t * e - pi * pi / 4 * s * t * e);
}

void sine_hill_exact(const double* x, double* value, double* grad) {
  const double pi = std::acos(-1.0);
  value[0] = sine_hill(x);
  const double s = std::sin(pi * x[0] / 2), c = std::cos(pi * x[0] / 2), t = std::sin(pi * x[1] / 2),
               d = std::cos(pi * x[1] / 2), e = std::exp(x[0] / 4);
  grad[0] = (pi / 2 * c + s / 4) * t * e;
  grad[1] = pi / 2 * s * d * e;
}

// Successive errors under halving fall at the optimal rates: p + 1 in L2, p in H1.
void expect_optimal_rates(const std::vector<double>& l2, const std::vector<double>& h1) {
  for (std::size_t i = 1; i < l2.size(); ++i) {
    EXPECT_NEAR(std::log2(l2[i - 1] / l2[i]), kBlockDegree + 1, 0.3) << l2[i - 1] << " " << l2[i];
    EXPECT_NEAR(std::log2(h1[i - 1] / h1[i]), kBlockDegree, 0.3) << h1[i - 1] << " " << h1[i];
  }
}

// The same T-joint model with knot lines across whole blocks is a tensor multipatch space: iga's multipatch
// Poisson solver (assembler, Dirichlet projection, CHOLMOD) on it converges at the optimal rates p + 1 (L2) and p
// (H1) for u = sin(pi x / 2) sin(pi y / 2) e^(x / 4) under uniform refinement of the blocks.
TEST(MultiblockSpace, TensorMultipatchPoissonConvergesAtTheOptimalRate) {
  const auto u = sine_hill;
  PoissonProblem<2> problem;
  problem.source = sine_hill_source;
  const ExactSolution<2> exact = sine_hill_exact;
  std::vector<double> l2, h1;
  for (int n : {1, 2, 4}) {
    std::vector<LRSpline<2>> blocks;
    for (const auto& c : t_joint_tensors()) blocks.emplace_back(refine_uniform(c, Ints<2>{n, n}));
    const MultiblockSpace<2> m = multiblock_space(blocks, {0.0, true});
    const MultipatchSpace<2> space = tensor_multipatch(m);
    ASSERT_EQ(space.boundary.size(), 7u);  // the square's sides: three of the long block, two of each upper one
    problem.dirichlet = {DirichletCondition<2>{space.boundary, {}, [u](const double* x, double* v) { v[0] = u(x); }}};
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_poisson(space, problem, *solver, 1);
    const ErrorNorms e = error_norms(space, r.coefs, 1, exact, 1);
    l2.push_back(e.l2);
    h1.push_back(e.h1);
  }
  expect_optimal_rates(l2, h1);
  // The locally matched (LR) model cannot be a tensor multipatch space: its long block is locally refined.
  EXPECT_THROW(tensor_multipatch(multiblock_space(t_joint_blocks())), Error);
}

// Two blocks: [0, 2] x [0, 1] and [0, 1] x [1, 2] above its left half. The long block's top is partly an
// interface and partly boundary (the T-joint (1, 1) is the short block's corner).
std::vector<LRSpline<2>> two_block_t_joint(int n = 1) {
  return {LRSpline<2>(refine_uniform(affine_tensor({0, 0, 0, 0.3, 0.7, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1}, {0, 0}, {2, 0}, {0, 1}), Ints<2>{n, n})),
          LRSpline<2>(refine_uniform(affine_tensor({0, 0, 0, 0.6, 1, 1, 1}, {0, 0, 0, 0.4, 1, 1, 1}, {0, 1}, {1, 0}, {0, 1}), Ints<2>{n, n}))};
}

// The largest difference between a discrete field (coefs component-major) and `exact` at points spread over every
// element of a multi-block space.
double largest_pointwise_error(const MultiblockSpace<2>& m, const Eigen::VectorXd& coefs, int components,
                               const std::function<void(const double*, double*)>& exact) {
  double worst = 0;
  RefinedPoint<2> pt;
  std::vector<double> e(static_cast<std::size_t>(components));
  for (const RefinedElement<2>& el : m.space.elements)
    for (double a : {0.0, 0.3, 1.0})
      for (double b : {0.0, 0.6, 1.0}) {
        refined_point(m.space, el, {el.box.lo[0] + a * el.box.extent(0), el.box.lo[1] + b * el.box.extent(1)}, pt);
        exact(pt.x.data(), e.data());
        for (int c = 0; c < components; ++c) {
          double uh = 0;
          for (std::size_t l = 0; l < el.ids.size(); ++l) uh += coefs[c * m.space.num_basis + el.ids[l]] * pt.R[l];
          worst = std::max(worst, std::abs(uh - e[static_cast<std::size_t>(c)]));
        }
      }
  return worst;
}

// iga's Poisson solver on the multi-block space itself (Dirichlet faces Face{dir, side, block}, projected onto the
// functions of the boundary parts of the block sides): u = x^2 - x y + 2 y^2 + x lies in the space of affine
// blocks, so the solution is u to rounding, on two blocks (a side partly boundary) and on three.
TEST(MultiblockSpace, IgaPoissonReproducesAQuadraticOnTwoAndThreeBlockTJointModels) {
  const auto u = [](const double* x) { return x[0] * x[0] - x[0] * x[1] + 2 * x[1] * x[1] + x[0]; };
  for (const auto& blocks : {two_block_t_joint(), t_joint_blocks()}) {
    const MultiblockSpace<2> m = multiblock_space(blocks);
    const std::vector<Face> faces = boundary_faces(m);
    EXPECT_EQ(faces.size(), 7u);  // two blocks: 4 (one partly boundary) + 3; three: 3 + 2 + 2
    if (blocks.size() == 2) {
      ASSERT_EQ(m.partial_sides.size(), 1u);
      EXPECT_EQ(m.partial_sides[0].first, 0);
      // The long block's top: the elements left of the joint are on the interface, those right of it not.
      for (const RefinedElement<2>& el : m.space.elements)
        if (el.block == 0 && el.box.hi[1] == 1.0) {
          EXPECT_EQ(el.interface_sides == (1u << 3), el.box.hi[0] <= 0.5) << el.box.lo[0];
        }
    }
    PoissonProblem<2> problem;
    problem.source = [](const double*) { return -6.0; };
    problem.dirichlet = {DirichletCondition<2>{faces, {}, [&](const double* x, double* v) { v[0] = u(x); }}};
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_poisson(m.space, problem, *solver, 1);
    EXPECT_GT(r.dofs, 10);
    EXPECT_LT(largest_pointwise_error(m, r.coefs, 1, [&](const double* x, double* v) { v[0] = u(x); }), 1e-10) << blocks.size();
    const ErrorNorms e = error_norms(m.space, r.coefs, 1, [&](const double* x, double* v, double* g) {
      v[0] = u(x);
      g[0] = 2 * x[0] - x[1] + 1;
      g[1] = -x[0] + 4 * x[1];
    });
    EXPECT_LT(e.h1, 1e-9);
  }
}

// iga's elasticity solver on the multi-block space: a linear displacement (constant strain, no body force) held on
// the whole boundary is reproduced to rounding (the patch test across T-joints).
TEST(MultiblockSpace, IgaElasticityPassesThePatchTestAcrossTJoints) {
  const auto disp = [](const double* x, double* v) {
    v[0] = 0.01 * x[0] + 0.02 * x[1] + 0.03;
    v[1] = -0.005 * x[0] + 0.015 * x[1];
  };
  for (const auto& blocks : {two_block_t_joint(), t_joint_blocks()}) {
    const MultiblockSpace<2> m = multiblock_space(blocks);
    ElasticityProblem<2> problem;
    problem.material = {1000.0, 0.3, 1.0};
    problem.displacement = {DirichletCondition<2>{boundary_faces(m), {}, disp}};
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_elasticity(m.space, problem, *solver, 1);
    EXPECT_LT(largest_pointwise_error(m, r.coefs, 2, disp), 1e-10) << blocks.size();
  }
}

// A manufactured solution on LR blocks matched locally (knot lines over the first rows only), the upper blocks
// refined twice as finely as the lower one so every refinement keeps non-matching interfaces: iga's refined
// Poisson solver converges at the optimal rates p + 1 (L2) and p (H1).
TEST(MultiblockSpace, IgaPoissonOnLocallyMatchedBlocksConvergesAtTheOptimalRates) {
  const auto u = sine_hill;
  PoissonProblem<2> problem;
  problem.source = sine_hill_source;
  const ExactSolution<2> exact = sine_hill_exact;
  std::vector<double> l2, h1;
  for (int n : {1, 2, 4}) {
    const std::vector<TensorSpline<2>> coarse = t_joint_tensors();
    std::vector<LRSpline<2>> blocks;
    for (std::size_t b = 0; b < coarse.size(); ++b) {
      const int k = b == 0 ? n : 2 * n;
      blocks.emplace_back(refine_uniform(coarse[b], Ints<2>{k, k}));
    }
    const MultiblockSpace<2> m = multiblock_space(blocks);
    problem.dirichlet = {DirichletCondition<2>{boundary_faces(m), {}, [u](const double* x, double* v) { v[0] = u(x); }}};
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_poisson(m.space, problem, *solver, 1);
    const ErrorNorms e = error_norms(m.space, r.coefs, 1, exact, 1);
    l2.push_back(e.l2);
    h1.push_back(e.h1);
  }
  expect_optimal_rates(l2, h1);
}

TEST(MultiblockSpace, BadBlocksGiveOneLineErrors) {
  std::vector<LRSpline<2>> blocks = t_joint_blocks();
  // The upper right block bulges along its bottom: the sides meet at both ends but are different curves.
  {
    auto bent = blocks;
    std::vector<LRBSpline<2>> basis(bent[2].basis_functions().begin(), bent[2].basis_functions().end());
    for (auto& f : basis)
      if (f.knots[1][1] == 1.0 && f.coef[0] > 1.01 && f.coef[0] < 1.99) f.coef[1] -= 0.05;
    bent[2] = LRSpline<2>(bent[2].degrees(), 2, false, basis, bent[2].mesh());
    try {
      multiblock_space(bent);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("differ in between"), std::string::npos) << e.what();
    }
  }
  blocks[1] = affine_block({0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 0, 0, 1, 1, 1, 1}, {0, 1}, {1, 0}, {0, 1}, 3);
  try {
    multiblock_space(blocks);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("block 1 has degrees (3, 3)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace trivar
