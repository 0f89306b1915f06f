// The complete V-topology of Booleans' results (seed 001: V-surfaces, V-curves, V-points, neighbours), against
// counts worked out by hand from the shapes of the cells, and the Euler characteristic of every cell's boundary
// and of the model's boundary (V - E + F, faces with holes counted as 2 - loops) against the boundary mesh's.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include "trivar/cad/boolean.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/primitives.hpp"
#include "trivar/model/trimmed_interfaces.hpp"
#include "trivar/model/trimmed_tessellation.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;
using cad::BooleanOp;

namespace {

VModel topo_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& size) { return test::glued(make_box({size, lo})); }

struct TopologyCounts {
  int shared, boundary, curves, points, boundary_euler;
};

// The counts, no defects, and what must hold whatever the counts: every cell edge on exactly one V-curve and
// every vertex on one V-point, the V-curves' ends among their V-points, the Euler characteristic of the model's
// boundary equal to the boundary mesh's.
TrimmedInterfaces expect_topology(const VModel& m, const TopologyCounts& want) {
  const TrimmedInterfaces t = trimmed_interfaces(m);
  EXPECT_EQ(t.shared, want.shared);
  EXPECT_EQ(t.boundary, want.boundary);
  EXPECT_EQ(static_cast<int>(t.curves.size()), want.curves);
  EXPECT_EQ(static_cast<int>(t.points.size()), want.points);
  EXPECT_EQ(t.boundary_euler, want.boundary_euler);
  EXPECT_TRUE(t.defects.empty()) << t.defects.front();
  EXPECT_TRUE(t.non_conforming.empty());
  const ModelTessellation mesh = trimmed_boundary_mesh(m);
  EXPECT_TRUE(is_watertight(mesh.mesh));
  EXPECT_EQ(euler_characteristic(mesh.mesh), t.boundary_euler);
  std::size_t uses = 0;
  for (std::size_t i = 0; i < t.curves.size(); ++i) {
    const VCurve& c = t.curves[i];
    uses += c.cell_edges.size();
    EXPECT_GE(c.surfaces.size(), 2u) << "V-curve " << i;  // an edge where faces meet
    for (const CellEdgeRef& e : c.cell_edges) EXPECT_EQ(t.edge_curve[static_cast<std::size_t>(e.cell)][static_cast<std::size_t>(e.edge)], static_cast<int>(i));
    for (int p : c.points) {
      const auto& pc = t.points[static_cast<std::size_t>(p)].curves;
      EXPECT_NE(std::find(pc.begin(), pc.end(), static_cast<int>(i)), pc.end());
    }
  }
  std::size_t edges = 0;
  for (const auto& cell : t.edge_curve) edges += static_cast<std::size_t>(std::count_if(cell.begin(), cell.end(), [](int c) { return c >= 0; }));
  EXPECT_EQ(uses, edges);
  return t;
}

// The V-curves with n cells around them.
int curves_with_valence(const TrimmedInterfaces& t, std::size_t n) {
  int k = 0;
  for (const VCurve& c : t.curves) {
    std::vector<int> cells;
    for (const CellEdgeRef& e : c.cell_edges) cells.push_back(e.cell);
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    k += cells.size() == n ? 1 : 0;
  }
  return k;
}

}  // namespace

// Two unit cubes sharing a face: 11 V-surfaces (the shared face and 10 boundary faces), 12 + 12 - 4 = 20
// V-curves (the four edges of the shared face are the two cells'), 8 + 8 - 4 = 12 V-points; each cube's boundary
// 8 - 12 + 6 = 2, the model's 12 - 20 + 10 = 2.
TEST(TrimmedTopology, CubesSharingAFace) {
  const VModel u = cad::boolean(topo_box({0, 0, 0}, {1, 1, 1}), topo_box({1, 0, 0}, {1, 1, 1}), BooleanOp::unite);
  const TrimmedInterfaces t = expect_topology(u, {1, 10, 20, 12, 2});
  EXPECT_EQ(t.cell_euler, (std::vector<int>{2, 2}));
  EXPECT_EQ(curves_with_valence(t, 2), 4);
  EXPECT_EQ(curves_with_valence(t, 1), 16);
  // The shared face's edges bound it and one boundary face of each cube; the others two boundary faces.
  for (const VCurve& c : t.curves) EXPECT_EQ(c.surfaces.size(), c.cell_edges.size() == 2 ? 3u : 2u);
  for (const VPoint& p : t.points) EXPECT_EQ(p.curves.size(), p.corners.size() == 2 ? 4u : 3u);
  // Read back from the file, the same topology.
  const VModel back = io::vmodel_from_json(io::to_json(u), "two cubes");
  expect_topology(back, {1, 10, 20, 12, 2});
}

// Three cells: A = [0, 1]^3 united with B = [0.6, 1.6] x [0, 1] x [0, 0.45]. A only is an L-prism along y (8
// faces, 18 edges, 12 vertices), A and B both and B only are boxes. Faces x = 0.6 and z = 0.45 (A only / both)
// and x = 1 (both / B only) are shared: 3 shared, 8 + 6 + 6 - 6 = 14 boundary faces. In each plane y = 0, 1
// lie 9 distinct vertices ((x, z): (0, 0), (0.6, 0), (1, 0), (1.6, 0), (0.6, 0.45), (1, 0.45), (1.6, 0.45),
// (1, 1), (0, 1)) and 11 distinct edges (6 of A only, 2 more of both, 3 more of B only), with one edge along y per
// vertex: 18 V-points, 22 + 9 = 31 V-curves. The edge along y at (0.6, 0.45) lies between shared faces only
// (inside the model), so the boundary has 18 - 30 + 14 = 2.
TEST(TrimmedTopology, ThreeCellUnion) {
  const VModel m = cad::boolean(topo_box({0, 0, 0}, {1, 1, 1}), topo_box({0.6, 0, 0}, {1, 1, 0.45}), BooleanOp::unite);
  ASSERT_EQ(m.num_cells(), 3);
  const TrimmedInterfaces t = expect_topology(m, {3, 14, 31, 18, 2});
  EXPECT_EQ(t.cell_euler, (std::vector<int>{2, 2, 2}));
  // In all three cells: the edge along y at (1, 0.45). In two: per plane y = 0, 1 the edges (0.6, 0)-(0.6, 0.45)
  // and (0.6, 0.45)-(1, 0.45) (A only, both) and (1, 0)-(1, 0.45) (both, B only); along y at (0.6, 0.45),
  // (0.6, 0) and (1, 0).
  EXPECT_EQ(curves_with_valence(t, 3), 1);
  EXPECT_EQ(curves_with_valence(t, 2), 6 + 3);
}

// A Boolean of a Boolean: the two cubes above minus the slot [0.5, 1.5] x [-1, 2] x [0.7, 2] across their top.
// Each cube becomes an L-prism along y (profile (0, 0), (1, 0), (1, 0.7), (0.5, 0.7), (0.5, 1), (0, 1) and its
// mirror), sharing x = 1 below z = 0.7: 8 + 8 - 1 = 15 V-surfaces (1 shared), per plane y = 0, 1 6 + 6 - 2 = 10
// vertices and 6 + 6 - 1 = 11 edges, plus 10 edges along y: 20 V-points, 32 V-curves, boundary 20 - 32 + 14 = 2.
TEST(TrimmedTopology, BooleanOfABoolean) {
  const VModel two = cad::boolean(topo_box({0, 0, 0}, {1, 1, 1}), topo_box({1, 0, 0}, {1, 1, 1}), BooleanOp::unite);
  const VModel slot = cad::boolean(two, topo_box({0.5, -1, 0.7}, {1, 3, 1.3}), BooleanOp::subtract);
  ASSERT_EQ(slot.num_cells(), 2);
  EXPECT_NEAR(slot.volume(), 2 - 0.3, 1e-12);
  const TrimmedInterfaces t = expect_topology(slot, {1, 14, 32, 20, 2});
  EXPECT_EQ(t.cell_euler, (std::vector<int>{2, 2}));
  EXPECT_EQ(t.neighbours[0], std::vector<int>{1});
}

// The unit ball (core cube of half-width 0.9 / sqrt(3) = 0.52) minus a cylinder of radius 0.4 along z: the hole
// goes through the core and the +z and -z cells only. Those three become torus-like cells (Euler
// characteristic 0): the core has its 6 faces (top and bottom with a hole: 2 loops) and 4 wall faces (the
// cylinder's four quarter patches), 12 + 8 arcs + 4 wall lines = 24 edges and 8 + 8 vertices; the +z and -z
// cells likewise. The four side cells are untouched (2). The model: 18 faces between cells as in the ball,
// 6 sphere patches + 3 x 4 wall faces on the boundary; V-points: 8 sphere corners + 8 core corners + 4 x 4 on
// the circles at z = +-0.917 (sphere) and z = +-0.52 (core); V-curves: 12 sphere patch edges + 8 radial edges +
// 12 core edges + 16 arcs + 12 wall lines = 60. Boundary: 24 - 40 + (4 + 12) = 0, a torus.
TEST(TrimmedTopology, BallMinusCylinder) {
  const VModel b = test::glued(make_ball({1, Eigen::Vector3d::Zero(), 0.9}));
  const VModel cyl = test::glued(make_cylinder({0.4, 3}), {0, 0, -1.5});
  const VModel ring = cad::boolean(b, cyl, BooleanOp::subtract);
  ASSERT_EQ(ring.num_cells(), 7);
  const TrimmedInterfaces t = expect_topology(ring, {18, 18, 60, 32, 0});
  std::vector<int> chi = t.cell_euler;
  std::sort(chi.begin(), chi.end());
  EXPECT_EQ(chi, (std::vector<int>{0, 0, 0, 2, 2, 2, 2}));
}
