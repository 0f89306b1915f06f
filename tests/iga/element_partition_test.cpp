#include <gtest/gtest.h>

#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/multipatch_assembly.hpp"

using namespace trivar;

namespace {

// The parts of a partition, each assembled alone, against the whole: the sums agree to rounding and each part's
// rows are exactly the functions supported on its layers.
void expect_parts_sum_to_whole(const std::function<SparseMatrix(const ElementPartition&)>& assemble, int parts) {
  const SparseMatrix whole = assemble({});
  SparseMatrix sum(whole.rows(), whole.cols());
  for (int p = 0; p < parts; ++p) {
    const SparseMatrix part = assemble({p, parts});
    ASSERT_EQ(part.rows(), whole.rows());
    // A non-empty row holds the whole row's pattern.
    for (Eigen::Index r = 0; r < part.outerSize(); ++r) {
      const auto n = part.outerIndexPtr()[r + 1] - part.outerIndexPtr()[r];
      if (n > 0) {
        EXPECT_EQ(n, whole.outerIndexPtr()[r + 1] - whole.outerIndexPtr()[r]) << "row " << r;
      }
    }
    sum += part;
  }
  EXPECT_LE((SparseMatrix(sum - whole)).coeffs().cwiseAbs().maxCoeff(), 1e-13 * whole.coeffs().cwiseAbs().maxCoeff());
}

}  // namespace

TEST(ElementPartition, SlabsCoverTheLayersOnce) {
  for (int layers : {1, 5, 7, 64})
    for (int parts : {1, 2, 3, 8}) {
      int next = 0;
      for (int p = 0; p < parts; ++p) {
        const auto [b, e] = ElementPartition{p, parts}.layers(layers);
        EXPECT_EQ(b, next);
        EXPECT_LE(e - b, layers / parts + 1);
        next = e;
      }
      EXPECT_EQ(next, layers);
    }
}

TEST(ElementPartition, PartsOfAPoissonMatrixSumToTheWhole) {
  const PoissonBenchmark<3> b = sine_box<3>(3, 7);
  const MultipatchSpace<3> space = single_patch_space(b.space);
  const BilinearForm<3> form = poisson_form(b.problem);
  for (int parts : {2, 3, 7})
    expect_parts_sum_to_whole(
        [&](const ElementPartition& p) { return assemble_matrix<3>(space, [&](int) { return form; }, 1, p); },
        parts);
}

TEST(ElementPartition, PartsOfARationalElasticityMatrixAndLoadSumToTheWhole) {
  const ElasticityBenchmark<2> b = plate_with_hole(2, 5);
  const MultipatchSpace<2> space = single_patch_space(b.space);
  expect_parts_sum_to_whole(
      [&](const ElementPartition& p) { return elastic_stiffness(space, b.problem, 1, p); }, 3);
  const auto f = [](const double* x, double* out) { out[0] = x[0] * x[1], out[1] = 1 + x[0]; };
  const Eigen::VectorXd whole = assemble_load<2>(space, 2, f, 1);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(whole.size());
  for (int p = 0; p < 3; ++p) sum += assemble_load<2>(space, 2, f, 1, {p, 3});
  EXPECT_LE((sum - whole).lpNorm<Eigen::Infinity>(), 1e-14 * whole.lpNorm<Eigen::Infinity>());
}

TEST(ElementPartition, ErrorSquaresOfThePartsSumToTheWhole) {
  const PoissonBenchmark<3> b = sine_box<3>(2, 5);
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(b.space.num_basis(), 0.0, 1.0);
  const ErrorNorms whole = error_norms(b.space, c, 1, b.exact, 1);
  double l2 = 0, h1 = 0;
  for (int p = 0; p < 2; ++p) {
    const ErrorNorms e = error_norms(b.space, c, 1, b.exact, 1, {p, 2});
    l2 += e.l2 * e.l2;
    h1 += e.h1 * e.h1;
  }
  EXPECT_NEAR(std::sqrt(l2), whole.l2, 1e-13 * whole.l2);
  EXPECT_NEAR(std::sqrt(h1), whole.h1, 1e-13 * whole.h1);
}
