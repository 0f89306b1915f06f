// Poisson on planar T-meshes with both star points and T-junctions: the face patches cut until their sides
// conform (conforming_split: a T-junction's corner inside a neighbour's side, cascading along the extension),
// linear solutions reproduced exactly, and a manufactured solution converging at the optimal rates.
#include <gtest/gtest.h>

#include <cstdio>

#include "face_continuity.hpp"
#include "star_mesh_tsm.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/conforming_split.hpp"
#include "t_mesh_poisson_support.hpp"

namespace trivar {
namespace {

// The bicubic Bezier patch of the identity map on a box.
TensorSpline<2> identity_patch(const Box<2>& b) {
  std::array<KnotVector, 2> k;
  std::vector<double> c;
  for (int d = 0; d < 2; ++d)
    k[static_cast<std::size_t>(d)] = KnotVector(3, {b.lo[d], b.lo[d], b.lo[d], b.lo[d], b.hi[d], b.hi[d], b.hi[d], b.hi[d]});
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) c.insert(c.end(), {b.lo[0] + b.extent(0) * i / 3, b.lo[1] + b.extent(1) * j / 3});
  return TensorSpline<2>(k, 2, false, std::move(c));
}

// Two small patches on a long one, the long one on another long one: the T-junction at (1, 1) cuts the first
// long patch at x = 1, whose new corner (1, 0) cuts the second.
TEST(ConformingSplit, CutsCascadeAlongTheExtension) {
  std::vector<TensorSpline<2>> p;
  for (const Box<2>& b : {Box<2>{{0, 0}, {2, 1}}, Box<2>{{0, 1}, {1, 2}}, Box<2>{{1, 1}, {2, 2}}, Box<2>{{0, -1}, {2, 0}}})
    p.push_back(identity_patch(b));
  const ConformingPatches r = conforming_split(p, 1e-12);
  ASSERT_EQ(r.patches.size(), 6u);
  std::vector<int> per_owner(4, 0);
  for (std::size_t i = 0; i < r.patches.size(); ++i) {
    ++per_owner[static_cast<std::size_t>(r.owner[i])];
    // Still the identity: exact cuts.
    const Box<2> d = r.patches[i].domain();
    for (double a : {0.0, 0.3, 1.0}) {
      double x[2];
      const Param<2> u{d.lo[0] + a * d.extent(0), d.lo[1] + (1 - a) * d.extent(1)};
      r.patches[i].eval(u, x);
      EXPECT_NEAR(x[0], u[0], 1e-15);
      EXPECT_NEAR(x[1], u[1], 1e-15);
    }
    EXPECT_DOUBLE_EQ(r.patches[i].domain().extent(0), 1.0);
  }
  EXPECT_EQ(per_owner, (std::vector<int>{2, 1, 1, 2}));
  // A patch that is not one Bezier element is refused.
  const TensorSpline<2> a = identity_patch({{0, 0}, {1, 1}});
  std::vector<double> c(a.coefs().begin(), a.coefs().end());
  c.insert(c.end(), a.coefs().begin(), a.coefs().begin() + 8);  // one more column of control points
  const KnotVector two(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1});
  EXPECT_THROW(conforming_split({TensorSpline<2>({two, a.knots(1)}, 2, false, c)}, 1e-12), Error);
}

// The planar fan of 8 x 8 faces per sector with T-junctions in sector 0, row 6 (faces 2..4 split at 6.5).
TMeshSurface planar_t_fan(int valence) {
  return test::planar_t_mesh(
      test::tsm_text(test::fan_mesh_with_t_junctions(valence, 8, 6, 2, 5, [](double, double) { return 0.0; })));
}

TEST(TJunctionPoisson, TheMeshLoadsAndLinearSolutionsAreExact) {
  for (int valence : {3, 5}) {
    const TMeshSurface s = planar_t_fan(valence);
    EXPECT_EQ(s.count(FaceMethod::star), valence);
    const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
    EXPECT_LT(c.gap, 1e-12);
    EXPECT_LT(c.normal_angle, 1e-10);
    TMeshSpaceReport r;
    const MultipatchSpace<2> space = t_mesh_space(s, 1, &r);
    EXPECT_EQ(r.faces, valence * 64 + 3);  // three faces split in two
    EXPECT_GT(r.patches, r.faces);         // cut along the T-junctions' extensions
    const ErrorNorms e = test::linear_solution_errors(space);
    EXPECT_LT(e.h1, 1e-10) << valence;
    EXPECT_LT(e.l2, 1e-10) << valence;
    std::printf("valence-%d fan with T-junctions: %d faces, %d patches after the cuts, %d functions; linear solution: "
                "L2 %.1e, H1 %.1e\n", valence, r.faces, r.patches, space.num_basis, e.l2, e.h1);
  }
}

// The manufactured solution of t_mesh_poisson_test: L2 rate 4 and H1 rate 3 expected.
TEST(TJunctionPoisson, ManufacturedSolutionConvergesAtTheOptimalRate) {
  for (int valence : {3, 5}) {
    const TMeshSurface s = planar_t_fan(valence);
    std::vector<double> l2, h1;
    for (int n : {2, 4, 8}) {
      const MultipatchSpace<2> space = t_mesh_space(s, n);
      const ErrorNorms e = test::manufactured_errors(space);
      l2.push_back(e.l2);
      h1.push_back(e.h1);
      std::printf("valence %d with T-junctions, %d x %d elements per patch: %d dofs, L2 %.3e, H1 %.3e\n", valence, n, n,
                  space.num_basis, e.l2, e.h1);
    }
    const double rl2 = std::log2(l2[1] / l2[2]), rh1 = std::log2(h1[1] / h1[2]);
    std::printf("valence %d with T-junctions: rates L2 %.2f, H1 %.2f (from 4 x 4 to 8 x 8)\n", valence, rl2, rh1);
    EXPECT_GT(rl2, 3.55) << valence;
    EXPECT_GT(rh1, 2.6) << valence;
  }
}

}  // namespace
}  // namespace trivar
