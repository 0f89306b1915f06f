#include "trivar/model/glue.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "trivar/model/block.hpp"
#include "trivar/model/revolve.hpp"
#include "trivar/model/vmodel.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/reparametrization.hpp"
#include "trivar/spline/split.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;

namespace {

VModel blocks_2x2x2() {
  VModel m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) m.add_cell(VCell(test::block_at(i, j, k)));
  m.glue();
  return m;
}

int count_valence(const VTopology& t, int valence) {
  int n = 0;
  for (int c = 0; c < static_cast<int>(t.curves.size()); ++c)
    n += static_cast<int>(t.cells_around_curve(c).size()) == valence ? 1 : 0;
  return n;
}

}  // namespace

// 2 x 2 x 2 unit cubes filling [0, 2]^3. The vertices form the 3 x 3 x 3 lattice: 27 V-points (1 centre in 8
// cells, 6 face centres in 4, 12 edge midpoints in 2, 8 corners in 1: 1*8 + 6*4 + 12*2 + 8*1 = 64 = 8 cells x 8
// corners). Edges along x: 3 x 3 lattice lines of 2 segments = 18, times 3 directions = 54 V-curves: 6 on the
// three centre lines (valence 4), 24 on the middle lines of the outer faces (valence 2), 24 on the outer edges
// of the cube (valence 1); 6*4 + 24*2 + 24*1 = 96 = 8 cells x 12 edges. Faces: per direction 3 lattice planes of
// 2 x 2 squares = 12, times 3 = 36 V-surfaces, of which the 3 middle planes give 12 shared and the 6 outer
// planes 24 boundary faces (2*12 + 24 = 48 = 8 cells x 6 faces). Euler: 27 - 54 + 36 - 8 = 1 (a ball), and on
// the boundary 26 - 48 + 24 = 2 (a sphere).
TEST(Glue, TwoByTwoByTwoBlocksHaveTheLatticeCounts) {
  const VModel m = blocks_2x2x2();
  const VTopology& t = m.topology();
  EXPECT_EQ(m.num_cells(), 8);
  EXPECT_EQ(t.points.size(), 27u);
  EXPECT_EQ(t.curves.size(), 54u);
  EXPECT_EQ(t.surfaces.size(), 36u);
  EXPECT_EQ(t.num_shared_surfaces(), 12);
  EXPECT_EQ(t.num_boundary_surfaces(), 24);
  EXPECT_EQ(count_valence(t, 4), 6);
  EXPECT_EQ(count_valence(t, 2), 24);
  EXPECT_EQ(count_valence(t, 1), 24);
  EXPECT_TRUE(t.non_conforming.empty());
  int corners_in[9] = {};
  for (const auto& p : t.points) ++corners_in[p.corners.size()];
  EXPECT_EQ(corners_in[8], 1);
  EXPECT_EQ(corners_in[4], 6);
  EXPECT_EQ(corners_in[2], 12);
  EXPECT_EQ(corners_in[1], 8);
  // Each V-curve has its two end points; each V-point's curves: 6 at the centre, 5 at face centres, 4 at edge
  // midpoints, 3 at the corners.
  for (const auto& p : t.points) {
    const std::size_t expected = p.corners.size() == 8 ? 6 : p.corners.size() == 4 ? 5 : p.corners.size() == 2 ? 4 : 3;
    EXPECT_EQ(p.curves.size(), expected);
  }
  // A shared curve on the centre line lies on 4 V-surfaces, an outer edge on 2.
  for (int c = 0; c < 54; ++c) {
    const std::size_t valence = t.cells_around_curve(c).size();
    EXPECT_EQ(t.curves[c].surfaces.size(), valence == 4 ? 4u : valence == 2 ? 3u : 2u);
  }
}

TEST(Glue, TwoByTwoByTwoRelationsAndNeighbours) {
  const VModel m = blocks_2x2x2();
  // Cell index i + 2 j + 4 k.
  EXPECT_EQ(m.relation(0, 1), CellRelation::face);
  EXPECT_EQ(m.relation(0, 3), CellRelation::curve);
  EXPECT_EQ(m.relation(0, 7), CellRelation::point);
  EXPECT_EQ(m.relation(5, 6), CellRelation::curve);
  EXPECT_EQ(m.neighbours(0), (std::vector<int>{1, 2, 4}));
  EXPECT_EQ(m.neighbours(0, CellRelation::curve), (std::vector<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(m.neighbours(0, CellRelation::point), (std::vector<int>{1, 2, 3, 4, 5, 6, 7}));
  // The z-edge through the centre of the model, from (1,1,0) to (1,1,1), is an edge of cells 0, 1, 2, 3.
  const int curve = m.topology().cell_edges[0][edge_through(2, 0b011)];
  EXPECT_EQ(m.cells_around_curve(curve), (std::vector<int>{0, 1, 2, 3}));
}

TEST(Glue, LShapeCounts) {
  // Three unit cubes at (0,0), (1,0), (0,1): per layer 8 lattice points (3 + 3 + 2), 5 x-edges and 5 y-edges;
  // 8 vertical edges. 16 points, 28 curves, 2 shared + 14 boundary faces; Euler 16 - 28 + 16 - 3 = 1.
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  m.add_cell(VCell(test::block_at(1, 0, 0)));
  m.add_cell(VCell(test::block_at(0, 1, 0)));
  const VTopology& t = m.glue();
  EXPECT_EQ(t.points.size(), 16u);
  EXPECT_EQ(t.curves.size(), 28u);
  EXPECT_EQ(t.num_shared_surfaces(), 2);
  EXPECT_EQ(t.num_boundary_surfaces(), 14);
  EXPECT_EQ(m.relation(1, 2), CellRelation::curve);  // the re-entrant vertical edge at (1, 1)
  // The re-entrant edge has valence 3.
  const int reentrant = t.cell_edges[0][edge_through(2, 0b011)];
  EXPECT_EQ(m.cells_around_curve(reentrant), (std::vector<int>{0, 1, 2}));
}

TEST(Glue, DetectsTheOrientationOfReparametrisedNeighbours) {
  // Cell 1 on [1, 2] x [0, 1]^2 with u reversed and v, w swapped: B(u, v, w) = (2 - u, w, v). Its face u1 lies
  // on x = 1 with (s', t') = (v, w) at the point (1, t', s'); cell 0's face u1 has (s, t) at (1, s, t), so
  // s' = t, t' = s: swap, no flips. Reversing B's v as well gives (1, t', 1 - s'): s' = 1 - t, a flip of s'.
  const TensorSpline<3> b = swap_directions(reverse(test::block_at(1, 0, 0), 0), 1, 2);
  for (int variant = 0; variant < 2; ++variant) {
    VModel m;
    m.add_cell(VCell(test::block_at(0, 0, 0, {1, 1, 1}, {2, 1, 3}, {2, 3, 1})));
    m.add_cell(VCell(variant ? reverse(b, 1) : b));
    const VTopology& t = m.glue();
    const HalfVSurface& h = t.halves[6 * 0 + 1];
    ASSERT_EQ(h.twin, 6 * 1 + 1);
    const FaceOrientation expected{true, variant == 1, false};
    EXPECT_EQ(h.to_twin, expected);
    EXPECT_EQ(t.halves[h.twin].to_twin, expected.inverse());
    // Different degrees and knots: geometrically coincident, reported as non-conforming.
    ASSERT_EQ(t.non_conforming.size(), 1u);
    EXPECT_EQ(t.non_conforming[0].reason, NonConformingFace::Reason::control_nets_differ);
    EXPECT_EQ(t.num_shared_surfaces(), 1);
    EXPECT_EQ(t.points.size(), 12u);
    EXPECT_EQ(t.curves.size(), 20u);
    // Independent check of the orientation: the two faces agree at mapped parameters.
    const auto fa = boundary_faces(m.cell(0).geometry())[1];
    const auto fb = boundary_faces(m.cell(1).geometry())[1];
    for (double s : {0.0, 0.3, 1.0})
      for (double tt : {0.0, 0.6, 1.0}) {
        const Param<2> st = h.to_twin.map({s, tt});
        double pa[3], pb[3];
        fa.eval({s, tt}, pa);
        fb.eval(st, pb);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(pa[k], pb[k], 1e-14);
      }
  }
}

TEST(Glue, ConformingNeighboursWithRotatedParametrisationAreNotReported) {
  const TensorSpline<3> b = reverse(swap_directions(test::block_at(0, 0, 1), 0, 1), 2);  // shares z = 1 via its w1 face
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  m.add_cell(VCell(b));
  const VTopology& t = m.glue();
  EXPECT_EQ(t.num_shared_surfaces(), 1);
  EXPECT_TRUE(t.non_conforming.empty());
  EXPECT_EQ(t.halves[5].twin, 6 + 5);
  EXPECT_EQ(t.halves[5].to_twin, (FaceOrientation{true, false, false}));
}

TEST(Glue, DifferentKnotsOnTheSharedFaceAreReportedNotThrown) {
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  m.add_cell(VCell(test::block_at(1, 0, 0, {1, 1, 1}, {1, 1, 1}, {1, 2, 3})));
  const VTopology& t = m.glue();
  ASSERT_EQ(t.non_conforming.size(), 1u);
  const auto& nf = t.non_conforming[0];
  EXPECT_EQ(nf.reason, NonConformingFace::Reason::control_nets_differ);
  EXPECT_EQ(nf.cell_a, 0);
  EXPECT_EQ(nf.face_a, 1);
  EXPECT_EQ(nf.cell_b, 1);
  EXPECT_EQ(nf.face_b, 0);
  EXPECT_FALSE(t.surfaces[t.halves[1].surface].conforming);
  EXPECT_EQ(nf.describe(), "cell 0 face 1 and cell 1 face 0: coincident, control nets differ");
}

TEST(Glue, PartialOverlapIsReportedAndLeftOnTheBoundary) {
  // A T-junction: cell 1 covers only y in [0, 0.5] of cell 0's face x = 1.
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  m.add_cell(VCell(test::block_at(1, 0, 0, {1, 0.5, 1})));
  const VTopology& t = m.glue();
  EXPECT_EQ(t.num_shared_surfaces(), 0);
  ASSERT_EQ(t.non_conforming.size(), 1u);
  EXPECT_EQ(t.non_conforming[0].reason, NonConformingFace::Reason::partial_overlap);
  EXPECT_EQ(t.non_conforming[0].face_a, 1);
  EXPECT_EQ(t.non_conforming[0].face_b, 0);
  // Touching along an edge only (cells at a right angle) is not an overlap.
  VModel diagonal;
  diagonal.add_cell(VCell(test::block_at(0, 0, 0)));
  diagonal.add_cell(VCell(test::block_at(1, 1, 0)));
  EXPECT_TRUE(diagonal.glue().non_conforming.empty());
  EXPECT_EQ(diagonal.relation(0, 1), CellRelation::curve);
}

TEST(Glue, RingOfFourRevolvedCells) {
  // Annulus r in [1, 2], z in [0, 1], revolved a full turn and cut at w = 1/4, 1/2, 3/4: four quarter cells.
  // Points: 4 per cut plane x 4 planes = 16; curves: 4 per cut plane (16) + 4 arcs per cell (16) = 32; faces:
  // 4 shared cut faces + 4 x 4 boundary faces. Euler 16 - 32 + 20 - 4 = 0 (a solid torus).
  const auto full = revolve<3>(make_rectangle_profile({0, 1}, {1, 2}), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                               2 * std::numbers::pi);
  auto [a, rest] = split_at(full, 2, 0.25);
  auto [b, rest2] = split_at(rest, 2, 0.5);
  auto [c, d] = split_at(rest2, 2, 0.75);
  VModel m;
  for (const auto* s : {&a, &b, &c, &d}) m.add_cell(VCell(*s));
  const VTopology& t = m.glue();
  EXPECT_EQ(t.points.size(), 16u);
  EXPECT_EQ(t.curves.size(), 32u);
  EXPECT_EQ(t.num_shared_surfaces(), 4);
  EXPECT_EQ(t.num_boundary_surfaces(), 16);
  EXPECT_TRUE(t.non_conforming.empty());
  EXPECT_EQ(m.neighbours(0), (std::vector<int>{1, 3}));
  EXPECT_EQ(m.relation(0, 2), CellRelation::none);

  // The uncut cell is glued to itself across its seam: 4 points, 4 profile edges + 4 closed arcs, 1 shared
  // (seam) + 4 boundary faces; Euler 4 - 8 + 5 - 1 = 0.
  VModel one;
  one.add_cell(VCell(full));
  const VTopology& u = one.glue();
  EXPECT_EQ(u.points.size(), 4u);
  EXPECT_EQ(u.curves.size(), 8u);
  EXPECT_EQ(u.num_shared_surfaces(), 1);
  EXPECT_EQ(u.num_boundary_surfaces(), 4);
  EXPECT_EQ(u.halves[4].twin, 5);
  EXPECT_TRUE(one.neighbours(0).empty());
}

TEST(Glue, ClosedEdgesRunningOppositeWays) {
  // Two full-turn annuli stacked in z, the upper one turning the other way: they share the two circles at z = 1,
  // which start and end at one V-point each. Every point of one circle lies on the other, so only the order of
  // the samples can tell that the upper cell runs along them backwards.
  const auto lower = revolve<3>(make_rectangle_profile({0, 1}, {1, 2}), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                                2 * std::numbers::pi);
  const auto upper = reverse(revolve<3>(make_rectangle_profile({1, 2}, {1, 2}), Eigen::Vector3d::Zero(),
                                        Eigen::Vector3d::UnitZ(), 2 * std::numbers::pi),
                             2);
  VModel m;
  m.add_cell(VCell(lower));
  m.add_cell(VCell(upper));
  const VTopology& t = m.glue();
  int shared_circles = 0;
  for (int i = 0; i < static_cast<int>(t.curves.size()); ++i) {
    if (t.cells_around_curve(i).size() < 2 || t.curves[i].points[0] != t.curves[i].points[1]) continue;
    ++shared_circles;
    for (const CellEdgeRef& e : t.curves[i].cell_edges) EXPECT_EQ(e.reversed, e.cell == 1) << "cell " << e.cell << " edge " << e.edge;
  }
  EXPECT_EQ(shared_circles, 2);
}

TEST(Glue, RejectsBadOptions) {
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  EXPECT_THROW(m.glue({.samples = 1}), Error);
  EXPECT_THROW(m.glue({.relative_tolerance = 0}), Error);
  VModel fresh;
  fresh.add_cell(VCell(test::block_at(0, 0, 0)));
  EXPECT_THROW(fresh.topology(), Error);
  // A cell needs a trivariate in 3-space.
  const auto planar = transform(make_block<3>({1, 1, 1}, {1, 1, 1}, {1, 1, 1}), Eigen::MatrixXd::Identity(2, 3),
                                Eigen::VectorXd::Zero(2));
  EXPECT_THROW(VCell{planar}, Error);
}

namespace {

std::string glue_error(VModel m, const GlueOptions& o = {}) {
  try {
    m.glue(o);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

// A tolerance near the model's size would merge every corner of a cell and leave no boundary.
TEST(Glue, TolerancesNearTheModelSizeAreRejected) {
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0, {3, 4, 12})));  // diagonal 13
  EXPECT_EQ(glue_error(m, {.relative_tolerance = 1e308}),
            "glue: relative tolerance 1e+308 is larger than 0.001 of the model's size (bounding-box diagonal 13)");
  EXPECT_EQ(glue_error(m, {.absolute_tolerance = 0.014}),
            "glue: absolute tolerance 0.014 is larger than 0.001 of the model's size (bounding-box diagonal 13)");
  EXPECT_EQ(glue_error(m, {.absolute_tolerance = 0.013}), "no error");
}

// Two copies of one cell glue face to face into a model without boundary; a third copy of a shared face makes
// an interior face. Neither is a solid: both are errors naming the cells.
TEST(Glue, DuplicatedCellsAreRejected) {
  VModel twice;
  twice.add_cell(VCell(test::block_at(0, 0, 0)));
  twice.add_cell(VCell(test::block_at(0, 0, 0)));
  EXPECT_EQ(glue_error(twice), "glue: cells 0 and 1 coincide (every face of one is glued to the other)");
  VModel three;
  three.add_cell(VCell(test::block_at(0, 0, 0)));
  three.add_cell(VCell(test::block_at(1, 0, 0)));
  three.add_cell(VCell(test::block_at(1, 0, 0)));
  // Face 1 (u = 1) of cell 0 pairs with face 0 of cell 1; face 0 of cell 2 is the third face there.
  EXPECT_EQ(glue_error(three),
            "glue: face 0 of cell 2 coincides with the face shared by cells 0 and 1: a face of more than two cells");
}

TEST(Glue, CollapsedCellsAreRejected) {
  VModel m;
  m.add_cell(VCell(test::block_at(0, 0, 0)));
  const Eigen::Matrix3d flatten = Eigen::Vector3d(1, 1, 0).asDiagonal();  // zero thickness in z
  m.add_cell(VCell(transform(make_block<3>({1, 1, 1}, {1, 1, 1}, {1, 1, 1}), flatten, Eigen::Vector3d(1, 0, 0))));
  EXPECT_EQ(glue_error(m), "glue: cell 1 is collapsed: volume 0 is no more than the tolerance 2.449489742783178e-07 "
                           "times its extent 1 x 1");
  // A thin but solid cell (a thousandth of the model) is a cell.
  VModel thin;
  thin.add_cell(VCell(test::block_at(0, 0, 0)));
  thin.add_cell(VCell(test::block_at(1, 0, 0, {1, 1, 1e-3})));
  EXPECT_EQ(glue_error(thin), "no error");
}
