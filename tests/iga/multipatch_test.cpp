#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/primitives.hpp"
#include "trivar/model/torus.hpp"
#include "trivar/model/vmodel.hpp"

using namespace trivar;

namespace {

// The trilinear cell x = lo + (hi - lo) * t with t the parameters (u, v, w) permuted by `perm` (t_k =
// u_perm[k]) and reversed where flip[k]: every cell of a model can be oriented differently, as in real
// block-structured meshes.
TensorSpline<3> oriented_block(const Param<3>& lo, const Param<3>& hi, std::array<int, 3> perm,
                               std::array<bool, 3> flip) {
  std::array<KnotVector, 3> knots;
  for (auto& k : knots) k = KnotVector::open_uniform(1, 1);
  std::vector<double> pts;
  for (int c = 0; c < 8; ++c) {
    const double u[3] = {double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)};
    for (int k = 0; k < 3; ++k) {
      const double t = flip[k] ? 1 - u[perm[k]] : u[perm[k]];
      pts.push_back(lo[k] + (hi[k] - lo[k]) * t);
    }
  }
  return TensorSpline<3>::from_cartesian(knots, 3, pts);
}

// [0, 1]^3 as 2 x 2 x 2 cells, each with its own orientation.
VModel eight_cell_cube() {
  const std::array<std::array<int, 3>, 8> perms{{{0, 1, 2}, {1, 0, 2}, {2, 1, 0}, {0, 2, 1},
                                                 {1, 2, 0}, {2, 0, 1}, {0, 1, 2}, {1, 0, 2}}};
  VModel m;
  for (int c = 0; c < 8; ++c) {
    const Param<3> lo{0.5 * (c & 1), 0.5 * ((c >> 1) & 1), 0.5 * ((c >> 2) & 1)};
    const Param<3> hi{lo[0] + 0.5, lo[1] + 0.5, lo[2] + 0.5};
    const std::array<bool, 3> flip{(c % 3) == 0, (c % 2) == 1, c >= 5};
    m.add_cell(VCell(oriented_block(lo, hi, perms[static_cast<std::size_t>(c)], flip)));
  }
  m.glue();
  return m;
}

// The coordinate axis a planar axis-aligned boundary face is normal to, and its value there.
std::pair<int, double> face_plane(const MultipatchSpace<3>& s, const Face& f) {
  const TensorSpace<3>& patch = s.patches[static_cast<std::size_t>(f.patch)];
  const std::vector<int> ids = face_basis(patch, f);
  double first[3], x[3];
  patch.geometry.control_point(ids.front(), first);
  for (int axis = 0; axis < 3; ++axis) {
    bool constant = true;
    for (int id : ids) {
      patch.geometry.control_point(id, x);
      constant = constant && std::abs(x[axis] - first[axis]) < 1e-12;
    }
    if (constant) return {axis, first[axis]};
  }
  throw Error("face_plane: not an axis-aligned plane");
}

VModel model_of(const CellComplex& cells) {
  VModel m;
  for (const auto& c : cells) m.add_cell(VCell(c));
  m.glue();
  return m;
}

}  // namespace

TEST(Multipatch, CountsSharedFunctionsOnce) {
  // 2 cells of n elements per direction and degree p, C^0 across the interfaces: 2 (n + p) - 1 functions per
  // direction.
  const VModel m = eight_cell_cube();
  for (int p : {1, 2, 3}) {
    const MultipatchSpace<3> s = multipatch_space(m, p, 2);
    const int per_dir = 2 * (2 + p) - 1;
    EXPECT_EQ(s.num_basis, per_dir * per_dir * per_dir) << "p = " << p;
    EXPECT_EQ(s.boundary.size(), 24u);  // 8 cells x 3 outer faces
  }
}

TEST(Multipatch, ReproducesAQuadraticAcrossDifferentlyOrientedCells) {
  // u = x^2 + 2 y z - z + x y / 2: -lap u = -2. Quadratics lie in the space of every affine cell with p = 2,
  // so the discrete solution is exact, whatever the cells' orientations, iff the interfaces are numbered right.
  const VModel m = eight_cell_cube();
  const MultipatchSpace<3> s = multipatch_space(m, 2, 2);
  PoissonProblem<3> pb;
  pb.source = [](const double*) { return -2.0; };
  pb.dirichlet.push_back({s.boundary, {}, [](const double* x, double* u) {
                            u[0] = x[0] * x[0] + 2 * x[1] * x[2] - x[2] + 0.5 * x[0] * x[1];
                          }});
  auto solver = make_solver("cholmod");
  const SolveResult r = solve_poisson(s, pb, *solver);
  const ErrorNorms e = error_norms<3>(s, r.coefs, 1, [](const double* x, double* u, double* g) {
    u[0] = x[0] * x[0] + 2 * x[1] * x[2] - x[2] + 0.5 * x[0] * x[1];
    g[0] = 2 * x[0] + 0.5 * x[1];
    g[1] = 2 * x[2] + 0.5 * x[0];
    g[2] = 2 * x[1] - 1;
  });
  EXPECT_LT(e.l2, 1e-11);
  EXPECT_LT(e.h1, 1e-10);
}

TEST(Multipatch, SineCubeOnEightCellsConvergesAtOptimalRates) {
  const VModel m = eight_cell_cube();
  const PoissonBenchmark<3> b = sine_box<3>(2, 1);
  for (int p : {2, 3}) {
    double prev_l2 = 0, prev_h1 = 0;
    for (int n : {3, 6}) {
      const MultipatchSpace<3> s = multipatch_space(m, p, n);
      PoissonProblem<3> pb = b.problem;
      pb.dirichlet = {{s.boundary, {}, nullptr}};
      auto solver = make_solver("cholmod");
      const ErrorNorms e = error_norms<3>(s, solve_poisson(s, pb, *solver).coefs, 1, b.exact);
      if (n == 6) {
        EXPECT_NEAR(std::log2(prev_l2 / e.l2), p + 1, 0.3) << "p = " << p;
        EXPECT_NEAR(std::log2(prev_h1 / e.h1), p, 0.2) << "p = " << p;
      }
      prev_l2 = e.l2;
      prev_h1 = e.h1;
    }
  }
}

TEST(Multipatch, PoissonOnTheSevenCellBall) {
  // -lap u = 1 in the ball of radius R, u = 0 on the sphere: u = (R^2 - r^2) / 6. The sphere patches are exact
  // rational quartics, so the error is the discretisation error alone (the rational maps do not reproduce the
  // quadratic) and falls at nearly the optimal rate.
  BallSpec spec;
  spec.radius = 1.5;
  const VModel m = model_of(make_ball(spec));
  ASSERT_EQ(m.num_cells(), 7);
  const double R = spec.radius;
  auto exact = [R](const double* x, double* u, double* g) {
    u[0] = (R * R - x[0] * x[0] - x[1] * x[1] - x[2] * x[2]) / 6;
    for (int k = 0; k < 3; ++k) g[k] = -x[k] / 3;
  };
  std::vector<double> l2;
  for (int n : {2, 4}) {
    const MultipatchSpace<3> s = multipatch_space(m, 4, n);
    EXPECT_EQ(s.boundary.size(), 6u);
    PoissonProblem<3> pb;
    pb.source = [](const double*) { return 1.0; };
    pb.dirichlet = {{s.boundary, {}, nullptr}};
    auto solver = make_solver("cholmod");
    l2.push_back(error_norms<3>(s, solve_poisson(s, pb, *solver).coefs, 1, exact).l2);
  }
  // Measured: 9.5e-4 and 1.2e-4 (rate 3.0); at n = 8, 6.7e-6 (rate 4.2, approaching 5).
  EXPECT_LT(l2[1], 2e-4);
  EXPECT_GT(std::log2(l2[0] / l2[1]), 2.7);
}

TEST(Multipatch, PoissonOnTheTorusWhoseCellsCloseOnThemselves) {
  // Every cell of the torus runs once around the axis and meets itself. With rho the distance to the core
  // circle (rho^2 = (s - R)^2 + z^2, s = sqrt(x^2 + y^2)), u = a^2 - rho^2 vanishes on the surface and
  // -lap u = lap rho^2 = 6 - 2 R / s.
  TorusSpec spec;
  const VModel m = model_of(make_torus(spec));
  const double R = spec.major_radius, a = spec.minor_radius;
  auto exact = [R, a](const double* x, double* u, double* g) {
    const double s = std::hypot(x[0], x[1]);
    u[0] = a * a - (s - R) * (s - R) - x[2] * x[2];
    g[0] = -2 * (s - R) * x[0] / s;
    g[1] = -2 * (s - R) * x[1] / s;
    g[2] = -2 * x[2];
  };
  std::vector<double> l2, h1;
  for (int n : {2, 4}) {
    const MultipatchSpace<3> s = multipatch_space(m, 2, n);
    EXPECT_EQ(s.boundary.size(), 4u);
    PoissonProblem<3> pb;
    pb.source = [R](const double* x) { return 6 - 2 * R / std::hypot(x[0], x[1]); };
    pb.dirichlet = {{s.boundary, {}, nullptr}};
    auto solver = make_solver("cholmod");
    const ErrorNorms e = error_norms<3>(s, solve_poisson(s, pb, *solver).coefs, 1, exact);
    l2.push_back(e.l2);
    h1.push_back(e.h1);
  }
  // Measured (p = 2, n = 2, 4, 8, 16): L2 5.1e-4, 5.1e-5, 5.9e-6, 7.2e-7 (rates 3.3, 3.1, 3.0) and H1 rates
  // 2.3, 2.1, 2.0.
  EXPECT_NEAR(std::log2(l2[0] / l2[1]), 3.2, 0.4);
  EXPECT_NEAR(std::log2(h1[0] / h1[1]), 2.2, 0.3);
}

TEST(Multipatch, CompositeBarTakesEachCellsMaterial) {
  // Two cells in series along x under end traction T, lateral rollers: uniaxial strain, sigma_xx = T in both,
  // strain T / (lambda_i + 2 mu_i), so u_x is piecewise linear with a kink at the interface: exact in the space.
  VModel m;
  m.add_cell(VCell(oriented_block({0, 0, 0}, {1, 0.5, 0.5}, {0, 1, 2}, {false, false, false})));
  m.add_cell(VCell(oriented_block({1, 0, 0}, {2, 0.5, 0.5}, {2, 0, 1}, {true, false, true})));
  m.glue();
  const MultipatchSpace<3> s = multipatch_space(m, 1, 3);
  const std::array<ElasticMaterial, 2> mat{{{1000, 0.3, 1}, {250, 0.2, 1}}};
  const double T = 7;
  ElasticityProblem<3> pb;
  pb.material_at = [&](int patch, const double*) { return mat[static_cast<std::size_t>(patch)]; };
  for (const Face& f : s.boundary) {
    const auto [axis, value] = face_plane(s, f);
    if (axis == 0 && value > 1.5)
      pb.traction_faces.push_back(f);
    else
      pb.displacement.push_back({{f}, {axis}, nullptr});
  }
  pb.traction = [T](const double*, const double* n, double* t) {
    for (int k = 0; k < 3; ++k) t[k] = T * n[0] * (k == 0 ? 1 : 0);
  };
  auto solver = make_solver("cholmod");
  const SolveResult r = solve_elasticity(s, pb, *solver);
  const double e1 = T / (mat[0].lambda() + 2 * mat[0].mu()), e2 = T / (mat[1].lambda() + 2 * mat[1].mu());
  const ErrorNorms e = error_norms<3>(s, r.coefs, 3, [&](const double* x, double* u, double* g) {
    u[0] = x[0] <= 1 ? e1 * x[0] : e1 + e2 * (x[0] - 1);
    u[1] = u[2] = 0;
    for (int k = 0; k < 9; ++k) g[k] = 0;
    g[0] = x[0] <= 1 ? e1 : e2;
  });
  EXPECT_LT(e.l2, 1e-12 * (e1 + e2));
  EXPECT_LT(e.h1, 1e-10 * (e1 + e2));
  // An invalid material on the second cell is reported.
  pb.material_at = [&](int patch, const double*) { return patch == 0 ? mat[0] : ElasticMaterial{250, 0.5, 1}; };
  EXPECT_THROW(solve_elasticity(s, pb, *solver), Error);
}

namespace {

// Free vibration of the unit cube with rollers on every face (normal displacement zero, tangential traction
// zero): u = (A s_x c_y c_z, B c_x s_y c_z, C c_x c_y s_z) with s_k = sin(pi l_k x_k), c_k = cos(pi l_k x_k)
// solves Navier's equation; (A, B, C) parallel to l gives omega^2 = (lambda + 2 mu) pi^2 |l|^2 / rho
// (dilatational), perpendicular to l gives mu pi^2 |l|^2 / rho (shear). Non-trivial modes, lowest first:
// shear l = (1,1,0) x3, shear l = (1,1,1) x2, dilatational l = (1,0,0) x3, shear l = (2,1,0) x6.
std::vector<double> roller_cube_lowest(const ElasticMaterial& m) {
  const double pi2 = M_PI * M_PI, mu = m.mu(), pw = m.lambda() + 2 * m.mu();
  std::vector<double> v;
  for (int i = 0; i < 3; ++i) v.push_back(2 * pi2 * mu / m.density);
  for (int i = 0; i < 2; ++i) v.push_back(3 * pi2 * mu / m.density);
  for (int i = 0; i < 3; ++i) v.push_back(pi2 * pw / m.density);
  std::sort(v.begin(), v.end());
  return v;
}

ElasticityProblem<3> rollers(const MultipatchSpace<3>& s, const ElasticMaterial& m) {
  ElasticityProblem<3> pb;
  pb.material = m;
  for (const Face& f : s.boundary) pb.displacement.push_back({{f}, {face_plane(s, f).first}, nullptr});
  return pb;
}

}  // namespace

TEST(Multipatch, ElasticModesOfTheRollerCube) {
  const ElasticMaterial mat{200, 0.3, 7.8};
  const std::vector<double> exact = roller_cube_lowest(mat);
  const std::vector<double> listed = roller_cube_eigenvalues(mat, 8);
  for (int i = 0; i < 8; ++i)
    EXPECT_NEAR(listed[static_cast<std::size_t>(i)], exact[static_cast<std::size_t>(i)], 1e-12 * exact[7]);
  // One patch and eight differently oriented cells give the same spectrum.
  const Param<3> lo{0, 0, 0}, hi{1, 1, 1};
  const MultipatchSpace<3> one = single_patch_space(TensorSpace<3>{box_geometry<3>(lo, hi, 3, 4)});
  const MultipatchSpace<3> eight = multipatch_space(eight_cell_cube(), 3, 2);
  for (const MultipatchSpace<3>* s : {&one, &eight}) {
    const ModesResult r = elastic_modes(*s, rollers(*s, mat), 8);
    for (int i = 0; i < 8; ++i)
      EXPECT_NEAR(r.values[i], exact[static_cast<std::size_t>(i)], 2e-4 * exact[static_cast<std::size_t>(i)])
          << "mode " << i << ", " << s->num_patches() << " patches";
  }
}

TEST(Multipatch, FreeFreeBodyHasSixRigidModes) {
  // No conditions: three translations and three rotations with omega^2 = 0, then the first elastic mode.
  const MultipatchSpace<3> s = multipatch_space(eight_cell_cube(), 2, 2);
  ElasticityProblem<3> pb;
  pb.material = {100, 0.25, 1};
  const ModesResult r = elastic_modes(s, pb, 7);
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(r.values[i]), 1e-8 * r.values[6]) << i;
  EXPECT_GT(r.values[6], 1.0);
}

TEST(Multipatch, FreeBallVibratesAtLambsTorsionalFrequency) {
  // A free elastic sphere (Lamb 1882): six rigid-body modes, then the torsional modes of degree 2 (5-fold)
  // at omega a / c_s = xi, the first root of j_2(xi) = xi j_2'(xi), below the 5-fold spheroidal ones
  // (xi = 2.640 for nu = 1/4). With E = 1000, nu = 1/4, rho = 1 and a = 20, c_s = 20, so omega^2 = xi^2.
  auto j2 = [](double x) { return (3 / (x * x * x) - 1 / x) * std::sin(x) - 3 * std::cos(x) / (x * x); };
  auto torsional = [&](double x) { return j2(x) - x * (j2(x + 1e-6) - j2(x - 1e-6)) / 2e-6; };
  double lo = 2, hi = 3;
  for (int i = 0; i < 60; ++i) (torsional(lo) * torsional(0.5 * (lo + hi)) <= 0 ? hi : lo) = 0.5 * (lo + hi);
  const double exact = lo * lo;  // 6.2557
  BallSpec spec;
  spec.radius = 20;
  const MultipatchSpace<3> s = multipatch_space(model_of(make_ball(spec)), 3, 1);
  ElasticityProblem<3> pb;
  pb.material = {1000, 0.25, 1};
  const ModesResult r = elastic_modes(s, pb, 12);
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(r.values[i]), 1e-9 * exact) << i;
  for (int i = 6; i < 11; ++i) EXPECT_NEAR(r.values[i], exact, 5e-3 * exact) << i;  // measured 3e-3
  EXPECT_NEAR(r.values[11], 2.640 * 2.640, 1e-2 * 2.640 * 2.640);
}

TEST(Multipatch, LaplaceModesOnEightCells) {
  const MultipatchSpace<3> s = multipatch_space(eight_cell_cube(), 3, 3);
  const ModesResult r = laplace_modes(s, s.boundary, 4);
  const std::vector<double> exact = unit_box_laplace_eigenvalues(3, 4);
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(r.values[i], exact[static_cast<std::size_t>(i)], 1e-4 * exact[static_cast<std::size_t>(i)]);
}

TEST(Multipatch, RejectsModelsItCannotNumber) {
  VModel unglued;
  unglued.add_cell(VCell(oriented_block({0, 0, 0}, {1, 1, 1}, {0, 1, 2}, {false, false, false})));
  EXPECT_THROW(multipatch_space(unglued, 2, 2), Error);
  // A face split in two against a whole face (a T-junction) is not conforming.
  VModel t;
  t.add_cell(VCell(oriented_block({0, 0, 0}, {1, 1, 1}, {0, 1, 2}, {false, false, false})));
  t.add_cell(VCell(oriented_block({1, 0, 0}, {2, 0.5, 1}, {0, 1, 2}, {false, false, false})));
  t.add_cell(VCell(oriented_block({1, 0.5, 0}, {2, 1, 1}, {0, 1, 2}, {false, false, false})));
  t.glue();
  EXPECT_THROW(multipatch_space(t, 2, 2), Error);
}
