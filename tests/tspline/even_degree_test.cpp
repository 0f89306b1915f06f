// Even and mixed degrees on drawn T-meshes: nodes on faces (even x even) and on the links along the even
// direction (odd x even), with the open-end layers of t_mesh_builder. A tensor mesh must give exactly the
// tensor B-splines (their knot windows, from spline/knot_vector); a T-junction mesh (the line s = 3 of a 6 x 6
// grid stopping at t = 3) must stay a partition of unity, reproduce linear functions with its Greville points
// (both hold for analysis-suitable T-splines of any degree, Li, Zheng, Sederberg, Hughes, Scott 2012) and be
// linearly independent.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "trivar/spline/knot_vector.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/local_knots.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

using Knots = std::array<std::vector<double>, 2>;

std::vector<KnotSegment> grid(const std::vector<double>& s, const std::vector<double>& t, double stop_at = -1) {
  std::vector<KnotSegment> g;
  for (double y : t) g.push_back({{s.front(), y}, {s.back(), y}});
  for (double x : s) g.push_back({{x, t.front()}, {x, x == 3.0 && stop_at > 0 ? stop_at : t.back()}});
  return g;
}

RationalPoint origin(double, double, int, int) { return {}; }

class EvenDegrees : public ::testing::TestWithParam<std::array<int, 2>> {};

TEST_P(EvenDegrees, TensorMeshGivesTheTensorBSplines) {
  const Ints<2> p{GetParam()[0], GetParam()[1]};
  const std::vector<double> bs{0.0, 0.5, 1.75, 2.0, 3.0, 4.5}, bt{-1.0, 0.0, 0.25, 2.0, 2.5};
  const TSpline ts = t_spline_from_segments(p, grid(bs, bt), origin);
  std::set<Knots> tensor;
  const KnotVector ks = KnotVector::from_breakpoints(p[0], bs), kt = KnotVector::from_breakpoints(p[1], bt);
  for (int b = 0; b < kt.size(); ++b)
    for (int a = 0; a < ks.size(); ++a) {
      Knots k;
      for (int i = 0; i < p[0] + 2; ++i) k[0].push_back(ks[a + i]);
      for (int i = 0; i < p[1] + 2; ++i) k[1].push_back(kt[b + i]);
      tensor.insert(k);
    }
  const auto knots = local_knot_vectors(ts);
  EXPECT_EQ(knots.size(), tensor.size());
  EXPECT_EQ(std::set<Knots>(knots.begin(), knots.end()), tensor);
  // Node kinds follow the parities: faces for even x even, links for mixed, vertices for odd x odd.
  const TAnchorKind interior = p[0] % 2 == 0 && p[1] % 2 == 0 ? TAnchorKind::face
                               : p[0] % 2 != p[1] % 2        ? TAnchorKind::link
                                                             : TAnchorKind::vertex;
  int on_interior_kind = 0;
  for (const TNode& n : ts.connect.nodes) on_interior_kind += n.kind == interior;
  EXPECT_GE(on_interior_kind, static_cast<int>((bs.size() - 1) * (bt.size() - 1)) / 2);
}

TEST_P(EvenDegrees, TJunctionMeshIsAPartitionOfUnityAndReproducesLinears) {
  const Ints<2> p{GetParam()[0], GetParam()[1]};
  const std::vector<double> b{0, 1, 2, 3, 4, 5, 6};
  TSpline ts = t_spline_from_segments(p, grid(b, b, 3.0), origin);
  place_at_greville_points(ts);
  const TSplineSurface surf(ts);
  // Hand counts: the tensor count less the anchors the missing half line merges (three faces or links above
  // t = 3, and the top boundary's anchors at s = 3 with their layers).
  const std::map<std::array<int, 2>, std::size_t> expected{{{2, 2}, 64 - 4}, {{3, 2}, 72 - 4}, {{2, 3}, 72 - 4},
                                                           {{4, 2}, 80 - 4}, {{4, 4}, 100 - 5}};
  EXPECT_EQ(ts.connect.nodes.size(), expected.at(GetParam()));
  EXPECT_LT(surf.partition_of_unity().max_defect, 1e-13);
  for (double s : {0.0, 0.4, 2.9, 3.0, 3.3, 4.7, 6.0})
    for (double t : {0.0, 1.2, 3.0, 3.5, 5.9, 6.0}) {
      double x[3];
      surf.eval({s, t}, x);
      EXPECT_NEAR(x[0], s, 1e-13) << s << " " << t;
      EXPECT_NEAR(x[1], t, 1e-13) << s << " " << t;
    }
  EXPECT_EQ(classify(ts, surf).independence, Independence::independent);
}

INSTANTIATE_TEST_SUITE_P(Degrees, EvenDegrees,
                         ::testing::Values(std::array<int, 2>{2, 2}, std::array<int, 2>{3, 2}, std::array<int, 2>{2, 3},
                                           std::array<int, 2>{4, 2}, std::array<int, 2>{4, 4}));

}  // namespace
}  // namespace trivar
