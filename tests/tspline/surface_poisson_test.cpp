// The Laplace-Beltrami problem -div_S grad_S u + u = f - div_S g on curved T-mesh surfaces with star points (the
// closed cube of eight valence-3 star points, a curved valence-5 fan with T-junctions): with f = u and g the
// ambient gradient of a smooth u, u itself is the solution on whatever surface the patches describe, so the
// errors are the space's approximation: ambient linear functions exactly (the isoparametric space holds them),
// a smooth one at the optimal rates.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "star_mesh_tsm.hpp"
#include "t_mesh_poisson_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/surface_poisson.hpp"
#include "trivar/io/tsm_format.hpp"

namespace trivar {
namespace {

struct AmbientSolution {
  std::function<double(const double*)> u;
  std::function<void(const double*, double*)> grad;
};

ErrorNorms surface_solution_errors(const TMeshSurfaceSpace& space, const AmbientSolution& sol) {
  SurfacePoissonProblem pb;
  pb.reaction = 1;
  pb.source = sol.u;
  pb.flux_source = sol.grad;
  auto solver = make_solver("cholmod");
  const SurfacePoissonResult r = solve_surface_poisson(space, pb, *solver);
  return surface_error_norms(space, r.coefs, [&](const double* x, double* v, double* g) {
    v[0] = sol.u(x);
    sol.grad(x, g);
  });
}

const AmbientSolution surface_linear{[](const double* x) { return 0.4 - 0.8 * x[0] + 0.3 * x[1] + 1.2 * x[2]; },
                                     [](const double*, double* g) {
                                       g[0] = -0.8;
                                       g[1] = 0.3;
                                       g[2] = 1.2;
                                     }};
const AmbientSolution surface_smooth{[](const double* x) { return std::sin(1.3 * x[0]) * std::cos(0.9 * x[1]) + x[2] * x[2]; },
                                     [](const double* x, double* g) {
                                       g[0] = 1.3 * std::cos(1.3 * x[0]) * std::cos(0.9 * x[1]);
                                       g[1] = -0.9 * std::sin(1.3 * x[0]) * std::sin(0.9 * x[1]);
                                       g[2] = 2 * x[2];
                                     }};

TMeshSurface closed_cube() {
  return TMeshSurface(io::parse_tsm(test::tsm_text(test::cube_mesh(3)), "cube.tsm").mesh, 1);
}

TEST(SurfacePoisson, LinearFunctionsAreExactOnTheClosedCube) {
  const TMeshSurface s = closed_cube();
  TMeshSpaceReport rep;
  const TMeshSurfaceSpace space = t_mesh_surface_space(s, 2, &rep);
  EXPECT_EQ(rep.faces, 54);
  EXPECT_EQ(rep.corner_patches, 24);
  EXPECT_TRUE(space.space.boundary.empty());
  // Bicubic patches refined 2 x 2 (5 x 5 control points each): 9 inside each face, 3 inside each edge, one per
  // vertex (the star points' three corners joined); F = 54, E = 108, V = 56 (V - E + F = 2, a sphere).
  EXPECT_EQ(space.space.num_basis, 9 * 54 + 3 * 108 + 56);
  const ErrorNorms e = surface_solution_errors(space, surface_linear);
  EXPECT_LT(e.l2, 1e-11);
  EXPECT_LT(e.h1, 1e-10);
  // Without a reaction term a closed surface is refused.
  auto solver = make_solver("cholmod");
  EXPECT_THROW(solve_surface_poisson(space, SurfacePoissonProblem{}, *solver), Error);
}

// Fusion's box with one strip at 1.02, loaded after two global non-uniform Catmull-Clark steps: the space is
// built on the refined faces (one bicubic patch per face, the 24 at star points corner patches; V - E + F = 2
// with F = 864, E = 1728, V = 866), and reproduces the ambient linear functions.
TEST(SurfacePoisson, LinearFunctionsAreExactOnTheSteppedFusionBox) {
  const TMeshSurface s(io::read_tsm(std::string(TRIVAR_TEST_DATA) + "/tsm/fusion/a3_box3_inconsistent_knot3_readback.tsm").mesh, 1);
  ASSERT_EQ(s.global_steps(), 2);
  TMeshSpaceReport rep;
  const TMeshSurfaceSpace space = t_mesh_surface_space(s, 1, &rep);
  EXPECT_EQ(rep.faces, 864);
  EXPECT_EQ(rep.corner_patches, 24);
  EXPECT_EQ(space.space.num_basis, 4 * 864 + 2 * 1728 + 866);
  const ErrorNorms e = surface_solution_errors(space, surface_linear);
  EXPECT_LT(e.l2, 1e-10);
  EXPECT_LT(e.h1, 1e-9);
  std::printf("Fusion's 1.02 box after two global steps: %d functions, linear solution L2 %.1e, H1 %.1e\n",
              space.space.num_basis, e.l2, e.h1);
}

TEST(SurfacePoisson, SmoothSolutionConvergesAtTheOptimalRate) {
  const TMeshSurface cube = closed_cube();
  std::vector<double> l2, h1;
  for (int n : {2, 4, 8}) {
    const TMeshSurfaceSpace space = t_mesh_surface_space(cube, n);
    const ErrorNorms e = surface_solution_errors(space, surface_smooth);
    l2.push_back(e.l2);
    h1.push_back(e.h1);
    std::printf("closed cube surface, %d x %d elements per face: %d functions, L2 %.3e, H1 %.3e\n", n, n,
                space.space.num_basis, e.l2, e.h1);
  }
  for (std::size_t i = 1; i < l2.size(); ++i) {
    const double rl2 = std::log2(l2[i - 1] / l2[i]), rh1 = std::log2(h1[i - 1] / h1[i]);
    std::printf("closed cube surface: rates L2 %.2f, H1 %.2f\n", rl2, rh1);
    if (i + 1 == l2.size()) {
      EXPECT_GT(rl2, 3.6);
      EXPECT_GT(rh1, 2.7);
    }
  }
}

// An open curved surface with a valence-5 star point and T-junctions: the space holds the ambient linear
// functions (coefficients: their values at the control points, identified consistently across the cut sides),
// and -lap_S u = 1 with u = 0 on the boundary solves.
TEST(SurfacePoisson, CurvedFanWithTJunctionsLoadsAndSolves) {
  const TMeshSurface s = test::planar_t_mesh(test::tsm_text(test::fan_mesh_with_t_junctions(
      5, 8, 6, 2, 5, [](double x, double y) { return 0.05 * x * x - 0.03 * x * y + 0.2 * std::sin(0.4 * y); })));
  TMeshSpaceReport rep;
  const TMeshSurfaceSpace space = t_mesh_surface_space(s, 1, &rep);
  EXPECT_EQ(rep.faces, 5 * 64 + 3);
  EXPECT_GT(rep.patches, rep.faces);
  EXPECT_FALSE(space.space.boundary.empty());
  // The linear function's coefficients (its values at the control points) reproduce it on every patch.
  Eigen::VectorXd c = Eigen::VectorXd::Zero(space.space.num_basis);
  for (int p = 0; p < space.space.num_patches(); ++p)
    for (int i = 0; i < space.surfaces[static_cast<std::size_t>(p)].num_coefs(); ++i) {
      double X[3];
      space.surfaces[static_cast<std::size_t>(p)].control_point(i, X);
      c[space.space.global[static_cast<std::size_t>(p)][static_cast<std::size_t>(i)]] = surface_linear.u(X);
    }
  const ErrorNorms e = surface_error_norms(space, c, [](const double* x, double* v, double* g) {
    v[0] = surface_linear.u(x);
    surface_linear.grad(x, g);
  });
  EXPECT_LT(e.l2, 1e-11);
  EXPECT_LT(e.h1, 1e-10);
  SurfacePoissonProblem pb;
  pb.source = [](const double*) { return 1.0; };
  auto solver = make_solver("cholmod");
  const SurfacePoissonResult r = solve_surface_poisson(space, pb, *solver);
  EXPECT_GT(r.coefs.maxCoeff(), 0);
  EXPECT_GT(r.area, 5 * 64 * 0.5);  // the fan's plane area is 5 * 64 sin(72 deg); the surface is larger
  std::printf("curved valence-5 fan with T-junctions: %d patches, %d unknowns, area %.4f, max u %.4f\n", rep.patches,
              r.dofs, r.area, r.coefs.maxCoeff());
}

}  // namespace
}  // namespace trivar
