#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"
#include "trivar/iga_petsc/petsc_session.hpp"

// A failure met by one rank only (its own elements, its own file) must reach every rank as the same error, or
// the ranks that did not fail wait forever in the next collective call. Under ctest these run on two ranks; a
// hang would show as the test timing out.

using namespace trivar;

namespace {

int last_rank() { return rank_partition().parts - 1; }

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(PetscRankFailure, EveryRankThrowsTheFailingRanksMessage) {
  const int rank = rank_partition().part;
  const std::string got = message_of([&] {
    on_every_rank([&] { require(rank != last_rank(), "input: bad record on the last rank"); });
  });
  EXPECT_EQ(got, "input: bad record on the last rank");
  // The ranks are still in step: a collective call after the failure completes with every rank's value.
  EXPECT_EQ(max_over_ranks(rank), last_rank());
}

TEST(PetscRankFailure, TheLowestFailingRankSpeaksAndResultsPassThrough) {
  const int rank = rank_partition().part;
  EXPECT_EQ(message_of([&] { on_every_rank([&] { throw Error("rank " + std::to_string(rank) + " failed"); }); }),
            "rank 0 failed");
  EXPECT_EQ(on_every_rank([&] { return 2 * rank; }), 2 * rank);
}

TEST(PetscRankFailure, AnInvalidMaterialInOneRanksSlabFailsEveryRank) {
  // Elasticity on the unit cube whose top element layer (the last rank's slab) has a negative Young's modulus:
  // only that rank meets it while assembling.
  const PoissonBenchmark<3> b = sine_box<3>(2, 4);
  const MultipatchSpace<3> space = single_patch_space(b.space);
  ElasticityProblem<3> pb;
  pb.material = {1000.0, 0.3, 1.0};
  pb.material_at = [good = pb.material](int, const double* x) {
    ElasticMaterial m = good;
    if (x[2] > 0.75) m.youngs_modulus = -1.0;
    return m;
  };
  pb.displacement.push_back({space.boundary, {}, nullptr});
  pb.body_force = [](const double*, double* f) { f[0] = f[1] = 0, f[2] = -1; };
  PetscSolverOptions o;
  o.preconditioner = "jacobi";
  const std::string got = message_of([&] { petsc_solve_elasticity(space, pb, o); });
  EXPECT_NE(got.find("elasticity: invalid material on patch 0"), std::string::npos) << got;
  EXPECT_EQ(max_over_ranks(1.0), 1.0);
}
