// Poisson on planar T-meshes with star points through the C0 multipatch space of their face patches: linear
// solutions reproduced exactly (the identification of side functions, also at the star point, is right), and
// a manufactured solution converging at the optimal rates of bicubic elements.
#include <gtest/gtest.h>

#include <cstdio>

#include "star_mesh_tsm.hpp"
#include "trivar/core/error.hpp"
#include "t_mesh_poisson_support.hpp"

namespace trivar {
namespace {

// The planar fan of 8 x 8 faces per sector.
TMeshSurface planar_fan(int valence) {
  return test::planar_t_mesh(test::tsm_text(test::fan_mesh(valence, 8, [](double, double) { return 0.0; })));
}

TEST(TMeshPoisson, LinearSolutionsAreExact) {
  for (int valence : {3, 5}) {
    const TMeshSurface s = planar_fan(valence);
    TMeshSpaceReport r;
    const MultipatchSpace<2> space = t_mesh_space(s, 1, &r);
    EXPECT_EQ(r.faces, valence * 64);
    EXPECT_EQ(r.patches, valence * 64);
    EXPECT_EQ(r.corner_patches, valence);
    // The fan's outer boundary: 8 faces per sector side, 2 sides per sector.
    EXPECT_EQ(space.boundary.size(), static_cast<std::size_t>(valence * 16));
    // Bicubic patches of one element share their corners and side points: V + 2 E + 4 F functions, with
    // F = 64 N faces, V = 72 N + 1 vertices and E = V + F - 1 edges (Euler, a disk).
    EXPECT_EQ(space.num_basis, 600 * valence + 1);
    const ErrorNorms e = test::linear_solution_errors(space);
    EXPECT_LT(e.h1, 1e-10) << valence;
    EXPECT_LT(e.l2, 1e-10) << valence;
  }
}

// u = sin(0.4 x) cos(0.3 y) + 0.05 x y on the fans (radius 8) under uniform refinement of every face: L2 rate
// p + 1 = 4 and H1 rate p = 3 with p = 3, the corner patches at the star point included (measured from 4 x 4 to
// 8 x 8 elements per face: 3.80 / 2.90 at valence 3, 3.94 / 2.96 at valence 5).
TEST(TMeshPoisson, ManufacturedSolutionConvergesAtTheOptimalRate) {
  for (int valence : {3, 5}) {
    const TMeshSurface s = planar_fan(valence);
    std::vector<double> l2, h1;
    for (int n : {1, 2, 4, 8}) {
      const MultipatchSpace<2> space = t_mesh_space(s, n);
      const ErrorNorms e = test::manufactured_errors(space);
      l2.push_back(e.l2);
      h1.push_back(e.h1);
      std::printf("valence %d, %d x %d elements per face: %d dofs, L2 %.3e, H1 %.3e\n", valence, n, n, space.num_basis,
                  e.l2, e.h1);
    }
    for (std::size_t i = 1; i < l2.size(); ++i) {
      const double rl2 = std::log2(l2[i - 1] / l2[i]), rh1 = std::log2(h1[i - 1] / h1[i]);
      std::printf("valence %d: rates L2 %.2f, H1 %.2f\n", valence, rl2, rh1);
      if (i + 1 == l2.size()) {  // the first halvings are pre-asymptotic (2.5 / 2.1, then 3.7 / 2.7 at valence 5)
        EXPECT_GT(rl2, 3.55) << valence;
        EXPECT_GT(rh1, 2.6) << valence;
      }
    }
  }
}

TEST(TMeshPoisson, CurvedOrBadInputIsRefused) {
  const io::TsmModel cube = io::parse_tsm(test::tsm_text(test::cube_mesh(3)), "cube.tsm");
  const TMeshSurface s(cube.mesh, 1);
  try {
    t_mesh_space(s, 1);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("planar"), std::string::npos) << e.what();
  }
  EXPECT_THROW(t_mesh_space(planar_fan(3), 0), Error);
}

}  // namespace
}  // namespace trivar
