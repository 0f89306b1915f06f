#include <gtest/gtest.h>

#include <cmath>

#include "iga/iga_test_support.hpp"
#include "trivar/iga/adaptive_loop.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/refined_elasticity.hpp"
#include "trivar/iga/refined_modes.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"
#include "trivar/hier/hierarchical_spline.hpp"
#include "trivar/lr/lr_spline.hpp"

// Locally refined (LR) spaces on the ranks against the serial solve (CHOLMOD): the same errors to 1e-10.

using namespace trivar;

namespace {

PetscSolverOptions tight_options(const std::string& pc) {
  PetscSolverOptions o;
  o.preconditioner = pc;
  o.tolerance = 1e-13;
  return o;
}

}  // namespace

TEST(PetscRefined, PoissonOnALocallyRefinedSineCubeMatchesTheSerialSolve) {
  // T-junctions inside the cube: elements of one rank and the other share functions of every size.
  const PoissonBenchmark<3> b = sine_box<3>(2, 4);
  LRSpline<3> lr(b.space.geometry);
  iga_test::refine_corner(lr, 0.5);
  iga_test::refine_corner(lr, 0.25);
  ASSERT_TRUE(iga_test::has_t_junction(lr));
  const RefinedSpace<3> space = refined_space(lr);
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_poisson(space, b.problem, *serial);
  const ErrorNorms es = error_norms(space, s.coefs, 1, b.exact);
  for (const char* pc : {"gamg", "bjacobi"}) {
    SCOPED_TRACE(pc);
    const SolveResult d = petsc_solve_poisson(space, b.problem, tight_options(pc));
    EXPECT_EQ(d.dofs, s.dofs);
    const ErrorNorms ed = petsc_error_norms(space, d.coefs, 1, b.exact);
    EXPECT_LE(std::abs(ed.l2 - es.l2), 1e-10 * es.l2);
    EXPECT_LE(std::abs(ed.h1 - es.h1), 1e-10 * es.h1);
  }
}

TEST(PetscRefined, ElasticityOnALocallyRefinedBeamMatchesTheSerialSolve) {
  // A 2 x 1 beam clamped at x = 0 under gravity and a shear traction at x = 2 (element side loads of each
  // rank's elements): the same displacements as the serial solve.
  LRSpline<2> lr(box_geometry<2>({0, 0}, {2, 1}, 2, 4));
  iga_test::refine_corner(lr, 0.5);
  const RefinedSpace<2> space = refined_space(lr);
  ElasticityProblem<2> pb;
  pb.material = {1000.0, 0.3, 1.0};
  pb.body_force = [](const double*, double* f) { f[0] = 0, f[1] = -1; };
  pb.displacement = {{{Face{0, 0, 0}}, {}, nullptr}};
  pb.traction_faces = {Face{0, 1, 0}};
  pb.traction = [](const double* x, const double*, double* t) { t[0] = 0, t[1] = -x[1]; };
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_elasticity(space, pb, *serial);
  const SolveResult d = petsc_solve_elasticity(space, pb, tight_options("gamg"));
  EXPECT_EQ(d.dofs, s.dofs);
  EXPECT_LE((d.coefs - s.coefs).norm(), 1e-10 * s.coefs.norm());
}

// The adaptive loop with the distributed solve in each step: the same meshes (dofs, elements) and errors as the
// serial loop on every step, on LR and THB spaces (every rank runs the estimate and the refinement).
template <class Geometry>
void expect_same_adaptive_loop(const PoissonBenchmark<2>& b, Geometry serial_geometry) {
  Geometry distributed_geometry = serial_geometry;
  AdaptiveOptions o;
  o.steps = 3;
  o.beta = 0.3;
  const auto serial = adaptive_poisson<2>(serial_geometry, b.problem, b.exact, o);
  const auto distributed = adaptive_poisson<2>(
      distributed_geometry, b.problem, b.exact, o, {}, nullptr, 1,
      [](const RefinedSpace<2>& s, const PoissonProblem<2>& p) { return petsc_solve_poisson(s, p, tight_options("mumps")); });
  ASSERT_EQ(distributed.size(), serial.size());
  for (std::size_t i = 0; i < serial.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(distributed[i].dofs, serial[i].dofs);
    EXPECT_EQ(distributed[i].elements, serial[i].elements);
    EXPECT_LE(std::abs(distributed[i].l2 - serial[i].l2), 1e-10 * serial[i].l2);
    EXPECT_LE(std::abs(distributed[i].h1 - serial[i].h1), 1e-10 * serial[i].h1);
    EXPECT_LE(std::abs(distributed[i].estimate - serial[i].estimate), 1e-10 * serial[i].estimate);
  }
  EXPECT_GT(serial.back().elements, serial.front().elements);
}

TEST(PetscRefined, AdaptiveLoopOnTheLShapeMatchesTheSerialLoop) {
  const PoissonBenchmark<2> b = l_shape(2, 4);
  expect_same_adaptive_loop(b, LRSpline<2>(b.space.geometry));
  expect_same_adaptive_loop(b, HierarchicalSpline<2>(b.space.geometry, HierarchicalBasis::thb));
}

// Eigenmodes on locally refined spaces (T-junctions, so ranks share functions of several sizes): the serial
// eigenvalues to 1e-10, Laplace on an LR cube and free vibration on a THB plate clamped on one side.
TEST(PetscRefined, ModesOnLocallyRefinedSpacesMatchTheSerialEigenvalues) {
  LRSpline<3> cube(box_geometry<3>({0, 0, 0}, {1, 1, 1}, 2, 4));
  iga_test::refine_corner(cube, 0.5);
  iga_test::refine_corner(cube, 0.25);
  ASSERT_TRUE(iga_test::has_t_junction(cube));
  const RefinedSpace<3> lr = refined_space(cube);
  std::vector<Face> sides;
  for (int k = 0; k < 3; ++k) sides.push_back({k, 0}), sides.push_back({k, 1});
  const ModesResult s = laplace_modes(lr, sides, 4);
  const ModesResult d = petsc_laplace_modes(lr, sides, 4, tight_options("mumps"));
  EXPECT_EQ(d.dofs, s.dofs);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(d.values[i], s.values[i], 1e-10 * s.values[i]) << i;

  HierarchicalSpline<2> plate(box_geometry<2>({0, 0}, {2, 1}, 2, 4), HierarchicalBasis::thb);
  std::vector<int> corner;
  for (int e = 0; e < plate.space().num_elements(); ++e)
    if (plate.space().element_box(e).hi[0] <= 1.0) corner.push_back(e);
  plate.refine_elements(corner);
  const RefinedSpace<2> thb = refined_space(plate);
  ElasticityProblem<2> pb;
  pb.material = {1000.0, 0.3, 2.0};
  pb.displacement = {{{Face{0, 0, 0}}, {}, nullptr}};
  const ModesResult es = elastic_modes(thb, pb, 4);
  for (const char* pc : {"mumps", "gamg"}) {
    SCOPED_TRACE(pc);
    const ModesResult ed = petsc_elastic_modes(thb, pb, 4, tight_options(pc));
    EXPECT_EQ(ed.dofs, es.dofs);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(ed.values[i], es.values[i], 1e-10 * es.values[i]) << i;
  }
}
