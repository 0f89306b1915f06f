#include "trivar/iga/refined_modes.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "iga/iga_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"

// Eigenmodes on locally refined spaces: on an unrefined LR or THB space the tensor solver's eigenvalues (the
// same space, another assembly); on refined spaces the Rayleigh-Ritz bounds: a space containing another has
// eigenvalues between the exact ones and the smaller space's.

using namespace trivar;

namespace {

std::vector<Face> all_sides(int dim) {
  std::vector<Face> f;
  for (int k = 0; k < dim; ++k) f.push_back({k, 0}), f.push_back({k, 1});
  return f;
}

}  // namespace

TEST(RefinedModes, UnrefinedSpacesGiveTheTensorEigenvalues) {
  const TensorSpline<2> square = iga_test::distorted_box<2>(2, 4, false, 7);
  const ModesResult tensor = laplace_modes<2>(TensorSpace<2>{square}, all_sides(2), 5);
  const LRSpline<2> lr(square);
  const HierarchicalSpline<2> thb(square, HierarchicalBasis::thb);
  for (const RefinedSpace<2>& space : {refined_space(lr), refined_space(thb)}) {
    const ModesResult r = laplace_modes(space, all_sides(2), 5);
    EXPECT_EQ(r.dofs, tensor.dofs);
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(r.values[i], tensor.values[i], 1e-10 * tensor.values[i]) << i;
  }
  ElasticityProblem<2> pb;
  pb.material = {1000.0, 0.3, 2.0};
  pb.displacement = {{{Face{0, 0, 0}}, {}, nullptr}};
  const ModesResult elastic = elastic_modes(single_patch_space(TensorSpace<2>{square}), pb, 4);
  const ModesResult refined = elastic_modes(refined_space(lr), pb, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(refined.values[i], elastic.values[i], 1e-10 * elastic.values[i]) << i;
}

TEST(RefinedModes, LocalRefinementLowersTheEigenvaluesTowardsTheExactOnes) {
  // Unit square, u = 0 on the boundary: lambda = pi^2 (i^2 + j^2). The refined LR and THB spaces contain the
  // coarse tensor space, so each eigenvalue lies between the exact one and the coarse one.
  const TensorSpline<2> square = box_geometry<2>({0, 0}, {1, 1}, 2, 4);
  const ModesResult coarse = laplace_modes<2>(TensorSpace<2>{square}, all_sides(2), 4);
  const std::vector<double> exact = unit_box_laplace_eigenvalues(2, 4);
  LRSpline<2> lr(square);
  iga_test::refine_corner(lr, 0.5);
  iga_test::refine_corner(lr, 0.25);
  ASSERT_TRUE(iga_test::has_t_junction(lr));
  HierarchicalSpline<2> thb(square, HierarchicalBasis::thb);
  std::vector<int> corner;
  for (int e = 0; e < thb.space().num_elements(); ++e)
    if (thb.space().element_box(e).hi[0] <= 0.5 && thb.space().element_box(e).hi[1] <= 0.5) corner.push_back(e);
  thb.refine_elements(corner);
  for (const RefinedSpace<2>& space : {refined_space(lr), refined_space(thb)}) {
    const ModesResult r = laplace_modes(space, all_sides(2), 4);
    EXPECT_GT(r.dofs, coarse.dofs);
    for (int i = 0; i < 4; ++i) {
      EXPECT_GT(r.values[i], exact[static_cast<std::size_t>(i)]) << i;
      EXPECT_LT(r.values[i], coarse.values[i] - 1e-9 * coarse.values[i]) << i;
    }
  }
}

TEST(RefinedModes, ElasticModesOfAFreeBodyStartWithItsRigidMotions) {
  // No supports: three rigid-body motions in 2-D (omega^2 ~ 0), then the elastic modes.
  LRSpline<2> lr(box_geometry<2>({0, 0}, {2, 1}, 2, 4));
  iga_test::refine_corner(lr, 0.5);
  ElasticityProblem<2> pb;
  pb.material = {1000.0, 0.3, 1.0};
  const ModesResult r = elastic_modes(refined_space(lr), pb, 4);
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(r.values[i]), 1e-8 * r.values[3]) << i;
  EXPECT_GT(r.values[3], 1.0);
}

TEST(RefinedModes, RejectsAnInvalidMaterialAndTooManyModes) {
  const LRSpline<2> lr(box_geometry<2>({0, 0}, {1, 1}, 1, 2));
  ElasticityProblem<2> pb;
  pb.material = {-1.0, 0.3, 1.0};
  EXPECT_THROW(elastic_modes(refined_space(lr), pb, 2), Error);
  EXPECT_THROW(laplace_modes(refined_space(lr), all_sides(2), 5), Error);
}
