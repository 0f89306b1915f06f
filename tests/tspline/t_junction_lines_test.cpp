// T-junctions near star points completed into knot lines (tspline/t_junction_lines): knot insertion along the rows
// the lines cross leaves the T-spline unchanged wherever it is one (against the same cage without the T-junctions,
// evaluated by its own charts), and Fusion 360's box with a split face near its star points loads as a closed
// surface, tangent-plane continuous, evaluated on the file's faces.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "chart_comparison.hpp"
#include "face_continuity.hpp"
#include "fusion_cages.hpp"
#include "star_mesh_tsm.hpp"
#include "triangulation_loops.hpp"
#include "tsm_error.hpp"
#include "support/temp_dir.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_junction_lines.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

io::TsmModel read_fusion_file(const std::string& name) { return io::read_tsm(std::string(TRIVAR_TEST_DATA) + "/tsm/fusion/" + name); }

TMesh mesh_of(const test::QuadMesh& q, const std::string& name) { return io::parse_tsm(test::tsm_text(q), name).mesh; }

// The corners of each face as a sorted key (faces of two meshes that share their vertex ids).
std::map<std::array<int, 4>, int> faces_by_corners(const TMeshSurface& s) {
  std::map<std::array<int, 4>, int> out;
  const TMesh& m = s.source_mesh();
  for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
    std::array<int, 4> c{};
    int i = 0;
    for (int l : m.faces[static_cast<std::size_t>(f)])
      if (m.links[static_cast<std::size_t>(l)].flag == 0) c[static_cast<std::size_t>(i++)] = m.links[static_cast<std::size_t>(l)].vertex;
    std::sort(c.begin(), c.end());
    out[c] = f;
  }
  return out;
}

// The exact faces of `plain` (away from star points) that `lines` has too, by their corners, and that `keep`
// takes (their corners, the plain face's centre point): the largest differences of the values and of the
// derivatives (relative) at 20 points each, how many faces, and how many of them have a corner in `moved`.
struct Agreement {
  int compared = 0, touched = 0;
  double values = 0, derivatives = 0;
};
template <class Keep>
Agreement agreement(const TMeshSurface& plain, const TMeshSurface& lines, const std::vector<char>& moved, const Keep& keep) {
  const auto plain_faces = faces_by_corners(plain);
  Agreement r;
  for (const auto& [corners, f] : faces_by_corners(lines)) {
    const auto it = plain_faces.find(corners);
    if (it == plain_faces.end() || plain.method(it->second) != FaceMethod::exact) continue;
    double centre[9];
    plain.eval(it->second, 0.5, 0.5, centre);
    if (!keep(corners, centre)) continue;
    r.touched += std::any_of(corners.begin(), corners.end(), [&](int c) { return static_cast<std::size_t>(c) < moved.size() && moved[static_cast<std::size_t>(c)]; });
    for (double u : {0.0, 0.21, 0.5, 0.83, 1.0})
      for (double v : {0.0, 0.37, 0.5, 1.0}) {
        double a[9], b[9];
        plain.eval(it->second, u, v, a);
        lines.eval_source(f, u, v, b);
        for (int k = 0; k < 3; ++k) r.values = std::max(r.values, std::abs(a[k] - b[k]));
        for (int k = 3; k < 9; ++k) r.derivatives = std::max(r.derivatives, std::abs(a[k] - b[k]) / (1 + std::abs(a[k])));
      }
    ++r.compared;
  }
  return r;
}

// More than `compared` exact faces compared, more than `touched` of them with a moved corner, and the surface there
// unchanged to rounding.
void expect_unchanged(const Agreement& g, int compared, int touched) {
  EXPECT_GT(g.compared, compared);
  EXPECT_GT(g.touched, touched);
  EXPECT_LT(g.values, 1e-13);
  EXPECT_LT(g.derivatives, 1e-12);
}

// Tangent-plane continuous across every edge and closed: the continuity measured.
test::Continuity expect_closed_g1(const TMeshSurface& s) {
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-9);
  EXPECT_EQ(test::closed_euler_characteristic(tessellate(s, 0.05)), 2);
  return c;
}

// Bent so that no coordinate is linear in the knots.
void bend(std::vector<std::array<double, 3>>& points) {
  for (auto& p : points) {
    const auto [x, y, z] = p;
    p = {x + 0.05 * std::sin(2 * y + z), y + 0.04 * std::cos(3 * x - z), z + 0.06 * std::sin(x * y + 1)};
  }
}

// Per vertex of the cage (`before`: its points), whether the completed mesh `done` moved its point.
std::vector<char> moved_points(const TMesh& done, const std::vector<std::array<double, 3>>& before) {
  std::vector<char> moved(before.size(), 0);
  for (std::size_t v = 0; v < before.size(); ++v) {
    const auto& p = done.points[static_cast<std::size_t>(done.vertices[v].primary)].xyz;
    moved[v] = std::hypot(p[0] - before[v][0], p[1] - before[v][1], p[2] - before[v][2]) > 1e-9;
  }
  return moved;
}

// The largest difference of values and derivatives of two surfaces on the first `faces` faces as given (at 9 points
// each).
double largest_difference(const TMeshSurface& a, const TMeshSurface& b, int faces) {
  double worst = 0;
  for (int f = 0; f < faces; ++f)
    for (double u : {0.0, 0.3, 1.0})
      for (double v : {0.0, 0.6, 1.0}) {
        double x[9], y[9];
        a.eval_source(f, u, v, x);
        b.eval_source(f, u, v, y);
        for (int k = 0; k < 9; ++k) worst = std::max(worst, std::abs(x[k] - y[k]));
      }
  return worst;
}

// Every end-condition block point moved off its vertex, as Rhino's grip maps place them (by vertex id and entry,
// so that two cages sharing vertex ids get the same blocks).
void move_blocks_off(TMesh& m) {
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    for (std::size_t k = 0; k < m.vertices[v].block.size(); ++k) {
      const double a = static_cast<double>(v), b = static_cast<double>(k);
      auto& x = m.points[static_cast<std::size_t>(m.vertices[v].block[k])].xyz;
      x = {x[0] + 0.05 * std::sin(3 * a + b), x[1] + 0.04 * std::cos(2 * a - b), x[2] + 0.06 * std::sin(a + 2 * b)};
    }
}

// A box of 11 x 11 faces per side, bent so that no coordinate is linear in the knots, and the same box with top face
// (4, 1) split 2 x 2 (its five new points off the surface, anywhere): T-junctions on the faces (3, 1), (5, 1),
// (4, 0) and (4, 2), the first within 3 face rings of the star point at the box's corner. Far from the split face
// the second cage's T-spline is the first's (the same points and knot vectors), so after its lines are completed
// (round the box at x = -1 + 9/11 and at y = -1 + 3/11, crossing rows of the other sides) the faces whose
// neighbourhood holds no star point must still be the first cage's surface: the rows' knot insertion is exact.
// With `strip` != 1 the edges along x between grid lines 3 and 4 (a strip of faces round the box) have that knot
// interval, which the insertion at x = 4.5 takes in its weights.
// With `rational`, weights 0.6 to 1.4 on the points (the same on both cages' common vertices). With `open` the box
// has no bottom: the lines run down the sides to its rim, a Bezier boundary whose rows the insertion ends in their
// end-condition nodes (on the vertices: tsm_text's grip map, or without `grip` none, as Fusion writes
// MULTIPLE_KNOTS, placed by bezier_equivalent; with `off` moved off the vertices, whose row along the rim, the
// boundary curve's control points, takes the insertion too).
void expect_insertion_exact(double strip, bool rational, bool open = false, bool grip = true, bool off = false) {
  test::QuadMesh box = test::box_mesh({11, 11, 11}, open);
  const std::vector<std::array<double, 3>> unbent = box.points;
  const auto grid_x = [&](int v) { return std::lround((unbent[static_cast<std::size_t>(v)][0] + 1) * 5.5); };
  for (const auto& q : box.quads)
    for (int k = 0; k < 4; ++k) {
      const int a = q[static_cast<std::size_t>(k)], b = q[static_cast<std::size_t>((k + 1) % 4)];
      if (std::min(grid_x(a), grid_x(b)) == 3 && std::max(grid_x(a), grid_x(b)) == 4) box.intervals[{a, b}] = strip;
    }
  bend(box.points);
  // The top side (z = 1): face (i, j) has corners (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1) in the grid.
  const test::QuadMesh split = test::split_face(box, test::top_face(unbent, box, 11, 4, 1), {0.02, -0.03, 0.01, 0.04, 0.07});
  const auto weighted = [&](TMesh m) {
    for (std::size_t v = 0; rational && v < m.vertices.size(); ++v) {
      const double w = 1 + 0.4 * std::sin(1.7 * static_cast<double>(v));
      m.points[static_cast<std::size_t>(m.vertices[v].primary)].w = w;
      for (int g : m.vertices[v].block) m.points[static_cast<std::size_t>(g)].w = w;
    }
    for (TMeshVertex& x : m.vertices)
      if (!grip) x.block.clear(), x.block_dims = {};
    if (off) move_blocks_off(m);
    return m;
  };
  const TMeshSurface plain(weighted(mesh_of(box, "box.tsm")), 1);
  const TMesh t_mesh = weighted(mesh_of(split, "split.tsm"));
  if (!open) {  // 4 sides x 12 edges, 4 on the box's edges shared
    EXPECT_EQ(std::count(t_mesh.intervals.begin(), t_mesh.intervals.end(), strip), strip == 1.0 ? static_cast<long>(t_mesh.intervals.size()) - 12 : 44);
  }
  const TMeshSurface lines(t_mesh, 1);
  ASSERT_NE(lines.completed_lines(), nullptr);
  // One line per direction, each closing on the opposite T-junction; open, each T-junction's line to the rim.
  EXPECT_EQ(lines.completed_lines()->lines, open ? 4 : 2);
  // The four boundary edges the lines end on carry their edge condition (tsm_text's on every boundary edge) on both
  // pieces.
  EXPECT_EQ(lines.mesh().conditions.size(), t_mesh.conditions.size() + (open ? 4 : 0));
  EXPECT_EQ(lines.global_steps(), 0);
  // Points the insertion moved.
  const std::vector<char> moved = moved_points(lines.mesh(), box.points);
  // Faces of the top side near the split face have other blending functions in the split cage: only the faces
  // below z = 1/2, which the lines cross on the sides and the bottom.
  const Agreement g = agreement(plain, lines, moved, [](const auto&, const double* centre) { return centre[2] <= 0.5; });
  // Faces with a corner the insertion moved: the comparison is not trivial there.
  expect_unchanged(g, 60, 10);
  std::printf("box 11 x 11 (strip %g%s%s%s) with a split face near a star point: %d lines, %d vertices inserted; %d exact faces of the cage "
              "without T-junctions (%d with moved corners): values %.1e, derivatives %.1e\n", strip, rational ? ", rational" : "",
              open ? (grip ? ", open" : ", open, no grip map") : "", off ? ", blocks off the vertices" : "", lines.completed_lines()->lines,
              lines.completed_lines()->vertices, g.compared, g.touched, g.values, g.derivatives);
}

TEST(TJunctionLines, KnotInsertionAlongTheRowsLeavesTheTSplineUnchanged) {
  expect_insertion_exact(1.0, false);
  expect_insertion_exact(1.7, false);
  expect_insertion_exact(1.7, true);
  expect_insertion_exact(1.7, true, true);
  expect_insertion_exact(1.7, false, true, false);
  expect_insertion_exact(1.7, true, true, true, true);
}

// A box of 11 x 11 x 3 faces as a subdivision-crease mesh (Fusion's SUBD_CREASES): open at the bottom, or closed
// with its bottom rim a sharp crease (`crease`). Face (2, 0) of the side y = -1, next to the rim and two face
// rings from the star point at the box's top corner, is split 2 x 2: one line runs round the box half a face above
// the rim, crossing every row up the sides next to its end at the rim, the other over the top and down the far side
// to the rim (closed: on across the crease and the bottom to the split face's midpoint on the rim, a T-junction of
// the bottom face). Each row up the sides ends in the natural end of the crease boundary (zero second derivative
// across it): Boehm's rule on its clamped form (crease_ends) keeps the rim's vertex and must leave the surface
// unchanged. The crease's two sides keep one set of vertices: the tessellation is closed.
// The reference is the cage without the split, which has the same crease boundary, on the faces of the far half
// (y > 0) that it evaluates exactly (away from the star points).
void expect_natural_end_insertion_exact(bool rational, bool crease) {
  test::QuadMesh box = test::box_mesh({11, 11, 3}, !crease);
  std::vector<std::array<double, 3>> unbent = box.points;
  // Whether vertex v lies on grid line g of axis k.
  const auto on = [&](int v, int k, int g) { return std::abs((unbent[static_cast<std::size_t>(v)][static_cast<std::size_t>(k)] + 1) * 5.5 - g) < 1e-9; };
  std::size_t side_face = box.quads.size();
  for (std::size_t f = 0; f < box.quads.size(); ++f) {
    const auto& q = box.quads[f];
    if (std::all_of(q.begin(), q.end(), [&](int v) { return on(v, 1, 0) && (on(v, 2, 0) || on(v, 2, 1)) && (on(v, 0, 2) || on(v, 0, 3)); }))
      side_face = f;
  }
  ASSERT_LT(side_face, box.quads.size());
  unbent = test::split_face(box, side_face, {0, 0, 0, 0, 0}).points;  // the split's new vertices too
  bend(box.points);
  const test::QuadMesh split = test::split_face(box, side_face, {0.02, -0.03, 0.01, 0.04, 0.07});
  const auto creased = [&](TMesh m) {
    m.end_conditions = EndConditions::subd_creases;
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      m.vertices[v].block.clear();
      m.vertices[v].block_dims = {};
      if (rational) m.points[static_cast<std::size_t>(m.vertices[v].primary)].w = 1 + 0.4 * std::sin(1.7 * static_cast<double>(v));
    }
    // The rim: the edges of the bottom (z = -1) on a side plane.
    for (const TMeshLink& k : m.links) {
      const int a = k.vertex, b = m.links[static_cast<std::size_t>(k.opp)].vertex;
      if (!crease || a < 0 || a > b || !on(a, 2, 0) || !on(b, 2, 0)) continue;
      for (int axis = 0; axis < 2; ++axis)
        for (int g : {0, 11})
          if (on(a, axis, g) && on(b, axis, g)) m.crease_edges.push_back(k.edge);
    }
    return m;
  };
  const TMeshSurface plain(creased(mesh_of(box, "box.tsm")), 1);
  const TMesh t_mesh = creased(mesh_of(split, "split.tsm"));
  if (crease) {
    EXPECT_EQ(t_mesh.crease_edges.size(), 45u);
  }
  const TMeshSurface lines(t_mesh, 1);
  ASSERT_NE(lines.completed_lines(), nullptr);
  EXPECT_EQ(lines.completed_lines()->lines, 2);
  // Points the insertion moved (in the Bezier end-condition form of both cages: at the rim Q1, which the rows'
  // second points shape).
  const TMesh &done = lines.mesh(), &before = plain.mesh();
  std::vector<char> moved(box.points.size(), 0);
  int rim_moved = 0;
  for (std::size_t v = 0; v < box.points.size(); ++v) {
    const auto& p = done.points[static_cast<std::size_t>(done.vertices[v].primary)].xyz;
    const auto& q = before.points[static_cast<std::size_t>(before.vertices[v].primary)].xyz;
    moved[v] = std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) > 1e-9;
    rim_moved += moved[v] && on(static_cast<int>(v), 2, 0);
  }
  const Agreement g = agreement(plain, lines, moved, [](const auto&, const double* centre) { return centre[1] >= 0; });
  expect_unchanged(g, 20, 10);
  // Every face, also those near the star points and the crease (Catmull-Clark, local subdivision): one tangent
  // plane across every edge off the crease, and closed across it.
  const test::Continuity cont = test::continuity(lines.mesh(), [&](int f, double u, double v, double* o) { lines.eval(f, u, v, o); });
  EXPECT_LT(cont.gap, 1e-12);
  EXPECT_LT(cont.normal_angle, 1e-9);
  if (crease) {
    EXPECT_EQ(test::closed_euler_characteristic(tessellate(lines, 0.05)), 2);
  }
  std::printf("box 11 x 11 x 3 (%s%s) with a split face next to its subdivision crease: %d lines, %d vertices inserted (Q1 moved at %d rim vertices); "
              "%d exact faces of the cage without T-junctions (%d with moved corners): values %.1e, derivatives %.1e; across %d edges gap %.1e, "
              "normals %.1e\n", crease ? "rim creased" : "open", rational ? ", rational" : "", lines.completed_lines()->lines,
              lines.completed_lines()->vertices, rim_moved, g.compared, g.touched, g.values, g.derivatives, cont.edges, cont.gap, cont.normal_angle);
}

TEST(TJunctionLines, NaturalEndInsertionAtASubdivisionCreaseLeavesTheSurfaceUnchanged) {
  expect_natural_end_insertion_exact(false, false);
  expect_natural_end_insertion_exact(true, false);
  expect_natural_end_insertion_exact(false, true);
  expect_natural_end_insertion_exact(true, true);
}

// A box of n x n x n faces as a subdivision-crease mesh whose top rim is a sharp crease (turning at the four top
// corners, which are star points of three faces), its top centre face split 2 x 2, as a Fusion user would crease and
// split a box. The lines cross the rim into the walls: rows along the crease go round its corners as the crease
// curve does, and each row on the top ends in the crease's natural end. The rim is the cubic B-spline of its points,
// which the split does not touch: the crease curve of both sides (evaluated by local subdivision of the completed
// mesh, unequal intervals along the crease) must be that of the box without the split, which keeps its equal
// intervals. Every other edge is smooth, and the tessellation is closed.
void expect_creased_rim_unchanged(int n) {
  const test::QuadMesh box = test::box_mesh({n, n, n});
  const std::size_t centre = test::top_face(box.points, box, n, n / 2, n / 2);
  const std::vector<std::array<double, 3>> unbent = test::split_face(box, centre, {0, 0, 0, 0, 0}).points;
  const auto rim = [&](int v) {
    const auto& p = unbent[static_cast<std::size_t>(v)];
    return std::abs(p[2] - 1) < 1e-9 && (std::abs(std::abs(p[0]) - 1) < 1e-9 || std::abs(std::abs(p[1]) - 1) < 1e-9);
  };
  const auto creased = [&](TMesh m) {
    m.end_conditions = EndConditions::subd_creases;
    for (const TMeshLink& k : m.links) {
      const int a = k.vertex, b = m.links[static_cast<std::size_t>(k.opp)].vertex;
      if (a < 0 || a > b || !rim(a) || !rim(b)) continue;
      const auto &pa = unbent[static_cast<std::size_t>(a)], &pb = unbent[static_cast<std::size_t>(b)];
      for (int axis = 0; axis < 2; ++axis)
        if (std::abs(pa[axis] - pb[axis]) < 1e-9 && std::abs(std::abs(pa[axis]) - 1) < 1e-9) m.crease_edges.push_back(k.edge);
    }
    return m;
  };
  const TMeshSurface plain(creased(mesh_of(box, "box.tsm")), 1);
  const TMeshSurface lines(creased(mesh_of(test::split_face(box, centre, {0.02, -0.03, 0.01, 0.04, 0.07}), "split.tsm")), 1);
  ASSERT_NE(lines.completed_lines(), nullptr);
  EXPECT_EQ(lines.completed_lines()->lines, 2);
  // The rim side of every face on it, in both cages, at the same fractions from the same corner.
  const auto rim_points = [&](const TMeshSurface& s, int f) {
    const TMesh& m = s.source_mesh();
    std::vector<int> c;
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    const std::size_t start = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), m.first_corner(f)) - loop.begin());
    for (std::size_t i = 0; i < loop.size(); ++i)
      if (const TMeshLink& l = m.links[static_cast<std::size_t>(loop[(start + i) % loop.size()])]; l.flag == 0) c.push_back(l.vertex);
    std::vector<std::array<double, 3>> out;
    for (int k = 0; k < 4; ++k) {
      const int a = c[static_cast<std::size_t>(k)], b = c[static_cast<std::size_t>((k + 1) % 4)];
      if (!rim(a) || !rim(b)) continue;
      for (double t : {0.0, 0.13, 0.5, 0.71, 1.0}) {
        const int lo = std::min(a, b);  // from the smaller vertex id: the same points whatever the face's orientation
        const double r = lo == a ? t : 1 - t;
        const std::array<double, 2> uv = k == 0 ? std::array<double, 2>{r, 0} : k == 1 ? std::array<double, 2>{1, r}
                                        : k == 2 ? std::array<double, 2>{1 - r, 1} : std::array<double, 2>{0, 1 - r};
        double x[9];
        s.eval_source(f, uv[0], uv[1], x);
        out.push_back({x[0], x[1], x[2]});
      }
    }
    return out;
  };
  const auto plain_faces = faces_by_corners(plain);
  int sides = 0;
  double worst = 0;
  for (const auto& [corners, f] : faces_by_corners(lines)) {
    const auto it = plain_faces.find(corners);
    if (it == plain_faces.end()) continue;  // a piece of the split face, off the rim
    const auto a = rim_points(plain, it->second), b = rim_points(lines, f);
    ASSERT_EQ(a.size(), b.size());
    sides += static_cast<int>(a.size()) / 5;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::hypot(a[i][0] - b[i][0], a[i][1] - b[i][1], a[i][2] - b[i][2]));
  }
  EXPECT_EQ(sides, 8 * n);  // 4 n rim edges, each a side of a top face and of a wall face
  EXPECT_LT(worst, 1e-12);
  const test::Continuity cont = expect_closed_g1(lines);
  std::printf("box %d x %d x %d with a creased top rim and a split top face: %d lines, %d vertices inserted; the rim on %d face sides against "
              "the box without the split: %.1e; across %d edges gap %.1e, normals %.1e; closed\n", n, n, n, lines.completed_lines()->lines,
              lines.completed_lines()->vertices, sides, worst, cont.edges, cont.gap, cont.normal_angle);
}

TEST(TJunctionLines, LinesCrossASharpCreaseAndGoRoundItsCorners) {
  expect_creased_rim_unchanged(3);
  expect_creased_rim_unchanged(5);
}

// A line that reaches a Bezier boundary next to a convex corner: the row along the boundary ends at the corner, in
// the corner's end-condition node across it, and the row of block points outside it (the boundary curve's control
// points) in the corner's diagonal node. A fan of 5 sectors of 6 x 6 faces with face (5, 1) of sector 0 split 2 x 2:
// the T-junction above it runs its line up to the boundary, whose last edge ends at the sector's corner (6, 6). The
// check needs no star point rule (and Catmull-Clark would not take a Bezier boundary this close): on a chart of
// sector 0 (its faces off the star point) the T-spline of the completed mesh must equal that of the fan without
// the split on the row of faces (2..5, 5), whose blending functions lie in the chart and do not reach the split;
// with the end-condition nodes on their vertices and off them (Rhino's grip maps).
void expect_line_to_a_corner_exact(bool off) {
  const int n = 6;
  const auto height = [](double x, double y) { return 0.3 * std::sin(x + 0.7 * y) + 0.05 * x * y; };
  const test::QuadMesh fan = test::fan_mesh(5, n, height);
  const auto quad = [&](int i, int j) { return static_cast<int>(j * n + i); };  // of sector 0
  TMesh plain = mesh_of(fan, "fan.tsm"), given = mesh_of(test::split_face(fan, static_cast<std::size_t>(quad(5, 1)), {0.02, -0.03, 0.01, 0.04, 0.07}), "split.tsm");
  if (off) {
    move_blocks_off(plain);
    move_blocks_off(given);
  }
  const std::optional<CompletedLines> done = complete_t_junction_lines(given, 5);
  ASSERT_TRUE(done.has_value());
  // Sector 0's faces off the star point (their vertices in the sector, the split's too); in the completed mesh the
  // pieces of those faces.
  const auto vertex = [&](int i, int j) {
    const double c = std::cos(2 * std::numbers::pi / 5), sn = std::sin(2 * std::numbers::pi / 5);
    for (std::size_t v = 0; v < fan.points.size(); ++v)
      if (std::hypot(fan.points[v][0] - (i + j * c), fan.points[v][1] - j * sn) < 1e-9) return static_cast<int>(v);
    return -1;
  };
  std::vector<char> in_sector(given.vertices.size(), 1);
  in_sector[static_cast<std::size_t>(vertex(0, 0))] = 0;
  for (std::size_t v = 0; v < fan.points.size(); ++v) {
    const double angle = std::atan2(fan.points[v][1], fan.points[v][0]);
    if (angle < -1e-9 || angle > 2 * std::numbers::pi / 5 + 1e-9) in_sector[v] = 0;
  }
  const auto region = [&](const TMesh& m) {
    std::vector<int> out;
    for (int f = 0; f < static_cast<int>(m.faces.size()); ++f)
      if (std::all_of(m.faces[static_cast<std::size_t>(f)].begin(), m.faces[static_cast<std::size_t>(f)].end(),
                      [&](int l) { return in_sector[static_cast<std::size_t>(m.links[static_cast<std::size_t>(l)].vertex)] != 0; }))
        out.push_back(f);
    return out;
  };
  const std::vector<int> sector = region(plain), split_sector = region(given);
  std::vector<int> pieces;
  for (int f = 0; f < static_cast<int>(done->pieces.size()); ++f)
    if (std::find(split_sector.begin(), split_sector.end(), done->pieces[static_cast<std::size_t>(f)].source) != split_sector.end()) pieces.push_back(f);
  // Seeds: the face (1, 3), which the lines do not split, in each mesh (the same layout in both charts).
  const auto face_at = [&](const TMesh& m, int i, int j) {
    const std::array<int, 4> want{vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)};
    for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
      int hits = 0;
      for (int l : m.faces[static_cast<std::size_t>(f)]) hits += std::count(want.begin(), want.end(), m.links[static_cast<std::size_t>(l)].vertex) > 0;
      if (hits == 4 && m.faces[static_cast<std::size_t>(f)].size() == 4) return f;
    }
    return -1;
  };
  const TChart before = t_spline_chart(plain, sector, face_at(plain, 1, 3), true),
               after = t_spline_chart(done->mesh, pieces, face_at(done->mesh, 1, 3), true);
  const TSplineSurface a(before.spline), b(after.spline);
  const auto st = [&](const TChart& c, int i, int j) {
    const TVertex& x = c.spline.image.vertices[static_cast<std::size_t>(c.vertex[static_cast<std::size_t>(vertex(i, j))])];
    return std::array<double, 2>{x.s, x.t};
  };
  const auto lo = st(before, 2, 5), hi = st(before, 6, 6);
  ASSERT_EQ(lo, st(after, 2, 5));
  ASSERT_EQ(hi, st(after, 6, 6));
  double worst = 0;
  for (int y = 0; y <= 10; ++y)
    for (int x = 0; x <= 40; ++x) {
      const Param<2> u{lo[0] + (hi[0] - lo[0]) * x / 40, lo[1] + (hi[1] - lo[1]) * y / 10};
      double pa[3], pb[3];
      a.eval(u, pa);
      b.eval(u, pb);
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(pa[k] - pb[k]));
    }
  EXPECT_LT(worst, 1e-13);
  std::printf("fan with a line to a convex corner (end-condition nodes %s): %d lines, %d vertices inserted; the completed T-spline "
              "against the fan without the split on a chart of sector 0, 451 points of its faces (2..5, 5): %.1e\n",
              off ? "off the vertices" : "on the vertices", done->lines, done->vertices, worst);
}

TEST(TJunctionLines, ALineToAConvexCornerOfABezierBoundaryIsKnotInsertion) {
  expect_line_to_a_corner_exact(false);
  expect_line_to_a_corner_exact(true);
}

// The agreement of `plain` and `lines` (agreement) on the faces of the fan whose corners lie more than 4 knot
// intervals from the split face's centre (the faces near it have other blending functions), and that it holds: more
// than 10 faces, to rounding.
Agreement expect_unchanged_away_from(const TMeshSurface& plain, const TMeshSurface& lines, const test::QuadMesh& fan, std::array<double, 2> centre) {
  const Agreement g = agreement(plain, lines, {}, [&](const std::array<int, 4>& corners, const double*) {
    return std::all_of(corners.begin(), corners.end(), [&](int v) {
      return std::hypot(fan.points[static_cast<std::size_t>(v)][0] - centre[0], fan.points[static_cast<std::size_t>(v)][1] - centre[1]) > 4;
    });
  });
  EXPECT_GT(g.compared, 10);
  EXPECT_LT(g.values, 1e-12);
  EXPECT_LT(g.derivatives, 1e-12);
  return g;
}

// Fusion's open forms: a star point on a subdivision-crease boundary (K = 4 faces) or a concave corner of it (K = 3),
// the irregular vertices whose faces local subdivision takes, with sectors of 7 x 7 faces and face (i, i) of the
// first sector split 2 x 2. Rows along the boundary go through the vertex as the crease curve does; rows from inside
// end in the crease's natural end there, as at every other vertex of the crease. Against the cage without the split
// on its exact faces (away from the vertex), and one tangent plane across every edge of the completed mesh.
void expect_lines_near_an_irregular_crease_vertex(int sectors, int i) {
  const int n = 7;
  const auto height = [](double x, double y) { return 0.3 * std::sin(x + 0.7 * y) + 0.05 * x * y; };
  const test::QuadMesh fan = test::half_fan_mesh(sectors, n, height);
  const auto subd = [](TMesh m) {
    m.end_conditions = EndConditions::subd_creases;
    for (TMeshVertex& v : m.vertices) v.block.clear(), v.block_dims = {};
    return m;
  };
  const TMeshSurface plain(subd(mesh_of(fan, "fan.tsm")), 1);
  const test::QuadMesh split = test::split_face(fan, static_cast<std::size_t>(i * n + i), {0.02, -0.03, 0.01, 0.04, 0.07});
  const TMeshSurface lines(subd(mesh_of(split, "split.tsm")), 1);
  ASSERT_NE(lines.completed_lines(), nullptr);
  const double c = std::cos(std::numbers::pi / sectors), sn = std::sin(std::numbers::pi / sectors);
  const Agreement g = expect_unchanged_away_from(plain, lines, fan, {(i + 0.5) * (1 + c), (i + 0.5) * sn});
  const test::Continuity cont = test::continuity(lines.mesh(), [&](int f, double u, double v, double* o) { lines.eval(f, u, v, o); });
  EXPECT_LT(cont.gap, 1e-12);
  EXPECT_LT(cont.normal_angle, 1e-8);
  std::printf("half fan of %d sectors (%s on the crease boundary), face (%d, %d) split: %d lines, %d vertices inserted; %d exact faces against "
              "the cage without the split: values %.1e, derivatives %.1e; across %d edges gap %.1e, normals %.1e\n", sectors,
              sectors == 3 ? "a concave corner" : "a star point", i, i, lines.completed_lines()->lines, lines.completed_lines()->vertices, g.compared,
              g.values, g.derivatives, cont.edges, cont.gap, cont.normal_angle);
}

TEST(TJunctionLines, NearAStarPointOrConcaveCornerOfASubdivisionCrease) {
  for (int sectors : {3, 4})
    for (int i : {1, 2}) expect_lines_near_an_irregular_crease_vertex(sectors, i);
}

// A subdivision-crease grid of 15 x 15 faces with a cone point (a creased vertex inside, on no crease), a dart (a
// crease from the boundary along the middle row ending inside) or a sharp edge between two darts (its two sides
// between the same two vertices) at its centre, and 49 of its faces, most next to that vertex, split 2 x 2 in turn
// (T-junctions on its four sides; on the crease the halves of a split crease edge stay creased). Rows through the
// cone point or a dart (its fan closed across the slit) pass them as rows pass a star point, and local subdivision
// takes the faces round them. Every placement must load, the completed surface continuous with one tangent plane across every edge but the crease's (the sides of the cut),
// and the exact faces 4 faces from the split face unchanged against the grid without the split.
TMesh with_creases(TMesh m, const std::vector<std::array<int, 2>>& crease, int cone) {
  m.end_conditions = EndConditions::subd_creases;
  for (TMeshVertex& v : m.vertices) v.block.clear(), v.block_dims = {};
  const auto edge = [&](int a, int b) {
    for (const TMeshLink& l : m.links)
      if (l.vertex == a && l.opp >= 0 && m.links[static_cast<std::size_t>(l.opp)].vertex == b) return l.edge;
    return -1;
  };
  for (const auto& [a, b] : crease) {
    if (const int e = edge(a, b); e >= 0) {
      m.crease_edges.push_back(e);
      continue;
    }
    for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v)  // the edge's midpoint, a T-junction on it
      if (edge(a, v) >= 0 && edge(v, b) >= 0) m.crease_edges.insert(m.crease_edges.end(), {edge(a, v), edge(v, b)});
  }
  if (cone >= 0) m.crease_vertices.push_back(cone);
  return m;
}

TEST(TJunctionLines, RowsThroughConePointsAndDarts) {
  const int n = 15, c = n / 2;
  const auto vertex = [&](int i, int j) { return j * (n + 1) + i; };
  test::QuadMesh grid = test::grid_cage(n, n);
  for (const int kind : {0, 1, 2}) {  // a cone point, a dart ending a crease from the boundary, a sharp edge between two darts
    const bool dart = kind > 0;
    std::vector<std::array<int, 2>> crease;
    for (int i = kind == 1 ? 0 : c; dart && i <= c; ++i) crease.push_back({vertex(i, c), vertex(i + 1, c)});
    const int cone = dart ? -1 : vertex(c, c);
    const TMeshSurface plain(with_creases(mesh_of(grid, "grid.tsm"), crease, cone), 1);
    int loaded = 0, placed = 0, compared = 0;
    double gap = 0, normals = 0, values = 0, derivatives = 0;
    for (const int i : {2, 4, 5, 6, 7, 8, 10})
      for (const int j : {2, 4, 5, 6, 7, 8, 10}) {
      const int f = j * n + i;
      ++placed;
      const test::QuadMesh split = test::split_face(grid, static_cast<std::size_t>(f), {0.02, -0.03, 0.01, 0.04, 0.07});
      try {
        const TMeshSurface lines(with_creases(mesh_of(split, "split.tsm"), crease, cone), 1);
        ++loaded;
        const test::Continuity cont = test::continuity(lines.mesh(), [&](int g, double u, double v, double* o) { lines.eval(g, u, v, o); });
        gap = std::max(gap, cont.gap);
        normals = std::max(normals, cont.normal_angle);
        const double x = f % n + 0.5, y = 1.3 * (f / n + 0.5);
        const Agreement g = agreement(plain, lines, {}, [&](const std::array<int, 4>& corners, const double*) {
          return std::all_of(corners.begin(), corners.end(), [&](int v) {
            return std::hypot(grid.points[static_cast<std::size_t>(v)][0] - x, grid.points[static_cast<std::size_t>(v)][1] - y) > 4;
          });
        });
        compared += g.compared;
        values = std::max(values, g.values);
        derivatives = std::max(derivatives, g.derivatives);
      } catch (const Error& e) {
        ADD_FAILURE() << "kind " << kind << ", face " << f << " split: " << e.what();
      }
      }
    std::printf("15 x 15 grid with a %s, %d faces split: %d load; gap %.1e, normals %.1e across every edge; %d exact faces "
                "against the grid without the split: values %.1e, derivatives %.1e\n",
                kind == 0 ? "cone point" : kind == 1 ? "dart" : "sharp edge between two darts", placed, loaded, gap, normals, compared,
                values, derivatives);
    EXPECT_EQ(loaded, placed);
    EXPECT_LT(gap, 1e-12);
    EXPECT_LT(normals, 1e-8);
    EXPECT_GT(compared, 1000);
    EXPECT_LT(values, 1e-13);
    EXPECT_LT(derivatives, 1e-12);
  }
}

// A subdivision-crease grid of 9 x 9 faces (its boundary a crease, its corners interpolated) with a face next to a
// corner split 2 x 2: the corner face gets a T-junction, and the natural end at a corner takes its four points, so its
// line is completed first (refused before). All eight such placements load, tangent-plane continuous, with the exact
// faces 4 faces from the split face unchanged against the grid without the split and one boundary loop.
TEST(TJunctionLines, ASplitFaceNextToACornerOfACreaseBoundary) {
  const int n = 9;
  const test::QuadMesh grid = test::grid_cage(n, n);
  const TMeshSurface plain(with_creases(mesh_of(grid, "grid.tsm"), {}, -1), 1);
  int loaded = 0, compared = 0;
  double gap = 0, normals = 0, values = 0;
  for (const auto& [i, j] : std::vector<std::array<int, 2>>{{1, 0}, {0, 1}, {7, 0}, {8, 1}, {0, 7}, {1, 8}, {8, 7}, {7, 8}}) {
    const test::QuadMesh split = test::split_face(grid, static_cast<std::size_t>(j * n + i), {0.02, -0.03, 0.01, 0.04, 0.07});
    const TMeshSurface lines(with_creases(mesh_of(split, "split.tsm"), {}, -1), 1);
    ASSERT_NE(lines.completed_lines(), nullptr);
    ++loaded;
    const test::Continuity cont = test::continuity(lines.mesh(), [&](int g, double u, double v, double* o) { lines.eval(g, u, v, o); });
    gap = std::max(gap, cont.gap);
    normals = std::max(normals, cont.normal_angle);
    const Agreement g = agreement(plain, lines, {}, [&](const std::array<int, 4>& corners, const double*) {
      return std::all_of(corners.begin(), corners.end(), [&](int v) {
        return std::hypot(grid.points[static_cast<std::size_t>(v)][0] - (i + 0.5), grid.points[static_cast<std::size_t>(v)][1] - 1.3 * (j + 0.5)) > 4;
      });
    });
    compared += g.compared;
    values = std::max({values, g.values, g.derivatives});
    EXPECT_EQ(test::boundary_loops(tessellate(lines, 0.05)), 1);
  }
  std::printf("9 x 9 subdivision-crease grid, a face next to a corner split: %d / 8 load; gap %.1e, normals %.1e across every "
              "edge; %d exact faces against the grid without the split %.1e\n", loaded, gap, normals, compared, values);
  EXPECT_LT(gap, 1e-12);
  EXPECT_LT(normals, 1e-9);
  EXPECT_GT(compared, 100);
  EXPECT_LT(values, 1e-12);
}

// The command line on a Fusion file of the grid with a dart and a split face next to it: read back as written (the
// crease list), the line counted, the completed faces evaluated as the library does.
TEST(TJunctionLines, ADartAndASplitFaceFromTheCommandLine) {
  const test::TempDir dir;
  const int n = 15, c = n / 2;
  const auto vertex = [&](int i, int j) { return j * (n + 1) + i; };
  std::vector<std::array<int, 2>> crease;
  for (int i = 0; i <= c; ++i) crease.push_back({vertex(i, c), vertex(i + 1, c)});
  const TMesh m = with_creases(mesh_of(test::split_face(test::grid_cage(n, n), static_cast<std::size_t>(c * n + c + 1),
                                                        {0.02, -0.03, 0.01, 0.04, 0.07}), "split.tsm"), crease, -1);
  io::TsmReport fusion;
  fusion.end_conditions = "SUBD_CREASES";
  const std::string path = dir.file("dart.tsm");
  io::write_tsm(path, m, fusion);
  const std::string info = test::run_cli(dir, "info " + path);
  EXPECT_NE(info.find("1 dart"), std::string::npos) << info;
  EXPECT_NE(info.find("near star points or irregular crease vertices completed first"), std::string::npos) << info;
  const TMeshSurface s(io::read_tsm(path).mesh, 1);
  ASSERT_NE(s.completed_lines(), nullptr);
  const std::array<double, 3> printed = test::cli_face_point(dir, path, c * n + c, 0.3, 0.6);
  double o[9];
  s.eval_source(c * n + c, 0.3, 0.6, o);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(printed[k], o[k], 1e-9);
}

// A subdivision-crease box of 4 x 4 faces per side with, on its top side one diagonal step from a corner's star
// point, a cone point or a sharp edge between two darts, or one of the box's edges creased from star point to star
// point (each a dart of three faces), and each of the top side's 16 faces split 2 x 2 in turn: the lines cross rows
// through the darts, the cone point and the star points; the star points with unequal intervals whose three rings
// reach a side of the crease take local subdivision. Every placement loads (before: 5, 1 and 0 of 16), closed and
// tangent-plane continuous across every edge but the crease's.
TEST(TJunctionLines, CreasesNextToTheStarPointsOfABox) {
  const int n = 4;
  int loaded = 0;
  double gap = 0, normals = 0;
  for (int kind = 0; kind < 3; ++kind)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        test::QuadMesh box = test::box_mesh({n, n, n});
        std::vector<std::array<double, 3>> unbent = box.points;
        const auto at = [&](double x, double y) {
          for (std::size_t v = 0; v < unbent.size(); ++v)
            if (std::hypot(unbent[v][0] - x, unbent[v][1] - y, unbent[v][2] - 1) < 1e-12) return static_cast<int>(v);
          return -1;
        };
        test::split_top_face(box, unbent, n, i, j, 0);
        bend(box.points);
        const int a = at(-0.5, -0.5), b = at(0, -0.5);
        std::vector<std::array<int, 2>> crease;
        if (kind == 1) crease.push_back({a, b});
        for (int k = 0; kind == 2 && k < n; ++k) crease.push_back({at(-1 + 0.5 * k, -1), at(-0.5 + 0.5 * k, -1)});
        try {
          const TMeshSurface s(with_creases(mesh_of(box, "box.tsm"), crease, kind == 0 ? a : -1), 1);
          const test::Continuity cont = expect_closed_g1(s);
          gap = std::max(gap, cont.gap);
          normals = std::max(normals, cont.normal_angle);
          ++loaded;
        } catch (const Error& e) {
          ADD_FAILURE() << "kind " << kind << ", top face (" << i << ", " << j << ") split: " << e.what();
        }
      }
  std::printf("box of 4 faces per side with a cone point or a sharp edge between two darts next to a star point, or a creased "
              "edge of the box, each top face split: %d / 48 load, gap %.1e, normals %.1e across every edge\n", loaded, gap, normals);
  EXPECT_EQ(loaded, 48);
}

// Fusion's box of 3 x 3 faces per side with the top side's centre face split 2 x 2 (T-junctions on the four faces
// round it, each next to two corner faces of star points) and a strip of interval 2 at x < -10/3: the two lines
// complete round the box, then two global non-uniform Catmull-Clark steps part the star points. The surface is
// closed, one tangent plane across every edge; on the file's faces the 61 vertices are the corners (the four
// T-junctions of two faces, on the side of the third), a T-junction's point on its T-face's side is the corner of
// the faces it is a corner of, and the derivatives are those of the file's (u, v) (central differences).
TEST(TJunctionLines, FusionBoxWithASplitFaceNearItsStarPoints) {
  const io::TsmModel file = read_fusion_file("a3_box3_tjunc_ring2_readback.tsm");
  const TMesh& given = file.mesh;
  const TMeshSurface s(given, 1);
  ASSERT_NE(s.completed_lines(), nullptr);
  EXPECT_EQ(s.completed_lines()->lines, 2);
  EXPECT_EQ(s.source_mesh().faces.size(), given.faces.size());
  const int nf = static_cast<int>(given.faces.size());
  const TSplineTriangulation t = tessellate(s, 0.05);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  const test::Continuity cont = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_LT(cont.gap, 1e-12);
  EXPECT_LT(cont.normal_angle, 1e-9);
  // Corners of the faces as given.
  std::vector<std::array<double, 3>> points;
  std::vector<int> faces_at;
  std::map<int, std::array<double, 3>> vertex_point;
  double same_vertex = 0;
  for (int f = 0; f < nf; ++f) {
    const auto& loop = given.faces[static_cast<std::size_t>(f)];
    const std::size_t start = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), given.first_corner(f)) - loop.begin());
    // Walk the loop from the first corner: per link its (u, v) on the face from the side lengths.
    std::array<double, 4> side_len{};
    int k = -1;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const TMeshLink& link = given.links[static_cast<std::size_t>(loop[(start + i) % loop.size()])];
      if (link.flag == 0) ++k;
      side_len[static_cast<std::size_t>(k)] += given.intervals[static_cast<std::size_t>(link.edge)];
    }
    k = -1;
    double along = 0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const TMeshLink& link = given.links[static_cast<std::size_t>(loop[(start + i) % loop.size()])];
      if (link.flag == 0) ++k, along = 0;
      const double r = along / side_len[static_cast<std::size_t>(k)];
      const std::array<double, 2> uv = k == 0 ? std::array<double, 2>{r, 0} : k == 1 ? std::array<double, 2>{1, r}
                                      : k == 2 ? std::array<double, 2>{1 - r, 1} : std::array<double, 2>{0, 1 - r};
      along += given.intervals[static_cast<std::size_t>(link.edge)];
      double x[9];
      s.eval_source(f, uv[0], uv[1], x);
      const std::array<double, 3> p{x[0], x[1], x[2]};
      if (const auto it = vertex_point.find(link.vertex); it != vertex_point.end())
        same_vertex = std::max(same_vertex, std::hypot(p[0] - it->second[0], p[1] - it->second[1], p[2] - it->second[2]));
      else
        vertex_point[link.vertex] = p;
      if (link.flag != 0) continue;  // a T-junction on this face's side: not a corner
      std::size_t i2 = 0;
      while (i2 < points.size() && std::hypot(points[i2][0] - p[0], points[i2][1] - p[1], points[i2][2] - p[2]) > 1e-11) ++i2;
      if (i2 == points.size()) points.push_back(p), faces_at.push_back(0);
      ++faces_at[i2];
    }
  }
  EXPECT_EQ(points.size(), 61u);
  EXPECT_EQ(std::count(faces_at.begin(), faces_at.end(), 3), 8);  // star points
  EXPECT_EQ(std::count(faces_at.begin(), faces_at.end(), 2), 4);  // T-junctions
  EXPECT_LT(same_vertex, 1e-12);  // a T-junction on its T-face's side is its point as the corner of the others
  std::vector<int> all(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) all[static_cast<std::size_t>(f)] = f;
  const double fd = test::finite_difference_error([&](int f, double u, double v, double* o) { s.eval_source(f, u, v, o); }, all,
                                                  {{0.3, 0.7}, {0.61, 0.2}, {0.74, 0.55}});
  EXPECT_LT(fd, 1e-5);
  std::printf("Fusion box with a split face near its star points: %d lines (%d vertices inserted), %d global steps, %d faces; "
              "watertight; across %d edges gap %.1e, normals %.1e; corners %zu, T-junction points %.1e; finite differences %.1e\n",
              s.completed_lines()->lines, s.completed_lines()->vertices, s.global_steps(), s.num_faces(), cont.edges, cont.gap,
              cont.normal_angle, points.size(), same_vertex, fd);
}

// The command line on that file: info says what was done (also in --json), eval takes a face as given (a T-face
// that a line splits), and the OBJ tessellation is closed.
TEST(TJunctionLines, CommandLine) {
  const std::string file = std::string(TRIVAR_TEST_DATA) + "/tsm/fusion/a3_box3_tjunc_ring2_readback.tsm";
  const test::TempDir dir;
  const std::string info = test::run_cli(dir, "info " + file);
  EXPECT_NE(info.find("2 T-junction lines near star points completed first (21 vertices inserted"), std::string::npos) << info;
  EXPECT_NE(info.find("the 57 faces as given are 80 faces"), std::string::npos) << info;
  EXPECT_NE(test::run_cli(dir, "info " + file + " --json").find("\"t_junction_lines\": 2"), std::string::npos);
  const TMeshSurface s(read_fusion_file("a3_box3_tjunc_ring2_readback.tsm").mesh, 1);
  const int t_face = 10;  // the face named in the refusal before: a T-face next to the split face
  ASSERT_GT(s.source_mesh().faces[t_face].size(), 4u);
  double x[9];
  s.eval_source(t_face, 0.8, 0.3, x);
  const std::array<double, 3> cli = test::cli_face_point(dir, file, t_face, 0.8, 0.3);
  EXPECT_LT(std::hypot(cli[0] - x[0], cli[1] - x[1], cli[2] - x[2]), 1e-14 * std::hypot(x[0], x[1], x[2]));
  test::run_cli(dir, "convert " + file + " " + dir.file("box.obj") + " --tolerance 0.05");
  EXPECT_EQ(test::closed_euler_characteristic(test::obj_triangles(dir.file("box.obj"))), 2);
}

// A closed mesh has no boundary for its end conditions to shape: the same box read as SUBD_CREASES (Fusion's
// subdivision-crease setting) completes the same lines and evaluates the same surface.
TEST(TJunctionLines, ClosedSubdivisionCreaseMesh) {
  const TMesh given = read_fusion_file("a3_box3_tjunc_ring2_readback.tsm").mesh;
  TMesh creased = given;
  creased.end_conditions = EndConditions::subd_creases;
  const TMeshSurface a(given, 1), b(creased, 1);
  ASSERT_NE(b.completed_lines(), nullptr);
  EXPECT_EQ(b.completed_lines()->lines, 2);
  EXPECT_EQ(largest_difference(a, b, static_cast<int>(given.faces.size())), 0.0);
}

// A deleted face slot (an `f` record without a link, as Rhino's exports keep them after edits) is no face: Fusion's
// box with the split face and a deleted slot after its faces completes the same lines and gives the same surface,
// and the deleted face is refused by name.
TEST(TJunctionLines, DeletedFaceSlotsAreNoFaces) {
  std::ifstream in(std::string(TRIVAR_TEST_DATA) + "/tsm/fusion/a3_box3_tjunc_ring2_readback.tsm");
  std::stringstream text;
  text << in.rdbuf();
  std::string with_slot = text.str();
  const std::size_t last_face = with_slot.rfind("\nf ");
  ASSERT_NE(last_face, std::string::npos);
  with_slot.insert(with_slot.find('\n', last_face + 1) + 1, "f\n");
  const TMesh given = io::parse_tsm(text.str(), "box.tsm").mesh, slotted = io::parse_tsm(with_slot, "slotted.tsm").mesh;
  ASSERT_EQ(slotted.faces.size(), given.faces.size() + 1);
  ASSERT_TRUE(slotted.faces.back().empty());
  const TMeshSurface a(given, 1), b(slotted, 1);
  ASSERT_NE(b.completed_lines(), nullptr);
  EXPECT_EQ(b.completed_lines()->lines, 2);
  EXPECT_EQ(b.num_faces(), a.num_faces());
  EXPECT_EQ(largest_difference(a, b, static_cast<int>(given.faces.size())), 0.0);
  double x[9];
  try {
    b.eval_source(static_cast<int>(given.faces.size()), 0.5, 0.5, x);
    ADD_FAILURE() << "a deleted face evaluated";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "T-mesh: face 57 is deleted");
  }
}

// A line half a face from a star point crosses the star point's spoke, and no row goes straight on past a star point
// (its node there is the backward spokes' weighted as the subdivision rules weight their intervals). The box of
// 11 x 11 faces per side, bent, with top face (5, 0) split 2 x 2: one line runs round the box half a face from its
// front edges and crosses four box edges next to a corner. Away from the star points the rows' insertion is still
// the T-spline's: the exact faces below z = 1/2 of the cage without the split agree to rounding. Next to them the
// surface is trivar's rule: tangent-plane continuous, closed, and on the faces at the star points within 5 % of a
// face's width of the cage without the split (the star points' limit points move most: taking the star point itself
// or the spoke reflected through it as the node beyond moves them 1.8 and 2.9 times as far).
TEST(TJunctionLines, ALineNextToAStarPointCrossesItsSpoke) {
  test::QuadMesh box = test::box_mesh({11, 11, 11});
  const std::vector<std::array<double, 3>> unbent = box.points;
  bend(box.points);
  const TMeshSurface plain(mesh_of(box, "box.tsm"), 1);
  const TMeshSurface lines(mesh_of(test::split_face(box, test::top_face(unbent, box, 11, 5, 0), {0, 0, 0, 0, 0}), "split.tsm"), 1);
  ASSERT_NE(lines.completed_lines(), nullptr);
  EXPECT_EQ(lines.completed_lines()->lines, 2);
  const std::vector<char> moved = moved_points(lines.mesh(), box.points);
  std::vector<char> corner(box.points.size(), 0);
  for (std::size_t v = 0; v < box.points.size(); ++v)
    corner[v] = std::all_of(unbent[v].begin(), unbent[v].end(), [](double x) { return std::abs(x) == 1; });
  const Agreement g = agreement(plain, lines, moved, [](const auto&, const double* centre) { return centre[2] <= 0.5; });
  expect_unchanged(g, 80, 30);
  // The faces at the star points the line passes against the cage without the split.
  const auto plain_faces = faces_by_corners(plain);
  double near_star = 0;
  int star_faces = 0;
  for (const auto& [corners, f] : faces_by_corners(lines)) {
    const auto it = plain_faces.find(corners);
    if (it == plain_faces.end() || std::none_of(corners.begin(), corners.end(), [&](int c) { return static_cast<std::size_t>(c) < corner.size() && corner[static_cast<std::size_t>(c)]; }))
      continue;
    ++star_faces;
    for (double u : {0.0, 0.25, 0.5, 0.75, 1.0})
      for (double v : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        double a[9], b[9];
        plain.eval(it->second, u, v, a);
        lines.eval_source(f, u, v, b);
        near_star = std::max(near_star, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
      }
  }
  EXPECT_EQ(star_faces, 24);
  EXPECT_GT(near_star, 1e-4);  // no T-spline there: the rule's surface, not the cage's
  EXPECT_LT(near_star, 0.05 * 2 / 11);
  const test::Continuity cont = expect_closed_g1(lines);
  // The cube of 3 x 3 faces per side with its corner face split: both lines cross a spoke of the corner's star point.
  const test::QuadMesh cube = test::box_mesh({3, 3, 3});
  const TMeshSurface corner_split(mesh_of(test::split_face(cube, test::top_face(cube.points, cube, 3, 0, 0), {0, 0, 0, 0, 0.1}), "corner.tsm"), 1);
  ASSERT_NE(corner_split.completed_lines(), nullptr);
  const test::Continuity cc = expect_closed_g1(corner_split);
  std::printf("box 11 x 11 with a split face whose line passes next to four star points: %d exact faces of the cage without the split "
              "(%d with moved corners) %.1e / %.1e; the %d faces at those star points within %.1e of it (face width %.2f); across %d "
              "edges gap %.1e, normals %.1e; the cube of 3 x 3 with its corner face split: %d lines, gap %.1e, normals %.1e\n",
              g.compared, g.touched, g.values, g.derivatives, star_faces, near_star, 2.0 / 11, cont.edges, cont.gap, cont.normal_angle,
              corner_split.completed_lines()->lines, cc.gap, cc.normal_angle);
}

// Splits that nest: the box of 11 x 11 faces per side, bent, with top face (2, 1) split 2 x 2, then the quarter of it
// at (4, 2) of the halved grid, then the quarter of that at (8, 4). A line of the innermost T-junctions crosses a row
// that ends at the stem of another T-junction (its line would continue the row), so that line is completed first
// and the first goes on from where it stopped (refused before). Away from the star points the T-spline is still the
// cage's: the exact faces below z = 1/2 of the cage without the splits agree to rounding; tangent-plane continuous
// across every edge, closed.
TEST(TJunctionLines, NestedSplitsCompleteTheLinesOfStemsFirst) {
  test::QuadMesh box = test::box_mesh({11, 11, 11});
  std::vector<std::array<double, 3>> unbent = box.points;
  bend(box.points);
  test::QuadMesh nested = box;
  test::split_top_face(nested, unbent, 11, 2, 1, 0);
  test::split_top_face(nested, unbent, 11, 4, 2, 1);
  test::split_top_face(nested, unbent, 11, 8, 4, 2);
  const TMeshSurface plain(mesh_of(box, "box.tsm"), 1), lines(mesh_of(nested, "nested.tsm"), 1);
  ASSERT_NE(lines.completed_lines(), nullptr);
  EXPECT_EQ(lines.completed_lines()->lines, 6);
  const std::vector<char> moved = moved_points(lines.mesh(), box.points);
  const Agreement g = agreement(plain, lines, moved, [](const auto&, const double* centre) { return centre[2] <= 0.5; });
  expect_unchanged(g, 80, 10);
  const test::Continuity cont = expect_closed_g1(lines);
  std::printf("box 11 x 11 with three nested splits near a star point: %d lines (%d vertices inserted); %d exact faces of the cage "
              "without them (%d with moved corners) %.1e / %.1e; across %d edges gap %.1e, normals %.1e\n",
              lines.completed_lines()->lines, lines.completed_lines()->vertices, g.compared, g.touched, g.values, g.derivatives, cont.edges,
              cont.gap, cont.normal_angle);
}

// A box of n x n faces per side, bent, with top face (i, j) split 6 or 7 rings from the star points' faces: its
// T-junctions need no lines (they lie beyond the Catmull-Clark faces' reach), but the faces 4 rings out, within two
// rings of them, are no Catmull-Clark faces either: they are the T-spline of a chart without star points that holds
// their knot vectors, grown from them over the mesh (refused before, when only charts of whole rings round them were
// tried, or large charts that a knot line far away crosses). Against the T-spline of the box's top side alone, or
// with `front` of its top and front sides (their own chart), on every face whose three rings it holds: `compared`
// faces, `four_rings_out` of them 4 rings from the star points' faces; tangent-plane continuous, closed.
void expect_faces_near_a_star_point_and_a_t_junction(int n, int i, int j, bool front, int compared, int four_rings_out) {
  test::QuadMesh box = test::box_mesh({n, n, n});
  std::vector<std::array<double, 3>> unbent = box.points;
  bend(box.points);
  test::split_top_face(box, unbent, n, i, j, 0);
  const TMesh mesh = mesh_of(box, "split.tsm");
  const TMeshSurface s(mesh, 1);
  EXPECT_EQ(s.completed_lines(), nullptr);
  std::vector<int> in_chart;
  std::vector<char> taken(mesh.faces.size(), 0);
  std::vector<int> ring(mesh.faces.size(), -1);  // top faces: face rings from the corner faces of the top side
  for (int f = 0; f < s.num_faces(); ++f) {
    std::array<double, 3> c{};
    for (int v : s.corners(f))
      for (std::size_t k = 0; k < 3; ++k) c[k] += unbent[static_cast<std::size_t>(v)][k] / 4;
    const bool top = std::abs(c[2] - 1) < 1e-12;
    if (!top && !(front && std::abs(c[1] + 1) < 1e-12)) continue;
    in_chart.push_back(f);
    taken[static_cast<std::size_t>(f)] = 1;
    if (top) {
      const auto edge = [&](double x) { return static_cast<int>(std::floor(std::min(x + 1, 1 - x) * n / 2)); };
      ring[static_cast<std::size_t>(f)] = std::max(edge(c[0]), edge(c[1]));
    }
  }
  const TChart chart = t_spline_chart(mesh, in_chart, in_chart.front(), false);
  const TSplineSurface side(chart.spline, 1);
  double worst = 0;
  int faces = 0, four = 0;
  for (int f : in_chart) {
    const std::vector<int> hood = test::face_rings(mesh, f, 3);
    if (!std::all_of(hood.begin(), hood.end(), [&](int g) { return taken[static_cast<std::size_t>(g)] != 0; })) continue;
    ++faces;
    four += ring[static_cast<std::size_t>(f)] == 4;
    const auto corners = s.corners(f);
    const auto st = [&](int v) {
      const TVertex& x = chart.spline.image.vertices[static_cast<std::size_t>(chart.vertex[static_cast<std::size_t>(v)])];
      return std::array<double, 2>{x.s, x.t};
    };
    const auto p0 = st(corners[0]), p1 = st(corners[1]), p3 = st(corners[3]);
    for (double u : {0.0, 0.3, 1.0})
      for (double v : {0.0, 0.6, 1.0}) {
        double a[9], b[9];
        s.eval(f, u, v, a);
        side.eval_first_derivatives(Param<2>{p0[0] + u * (p1[0] - p0[0]) + v * (p3[0] - p0[0]), p0[1] + u * (p1[1] - p0[1]) + v * (p3[1] - p0[1])}, b);
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(a[k] - b[k]));
      }
  }
  EXPECT_EQ(faces, compared);
  EXPECT_EQ(four, four_rings_out);
  EXPECT_LT(worst, 1e-13);
  const test::Continuity cont = expect_closed_g1(s);
  std::printf("box %d x %d with top face (%d, %d) split: %d faces, %d exact in charts; against the T-spline of the top side%s on %d faces "
              "(%d of them 4 rings from the star points' faces): %.1e; across %d edges gap %.1e, normals %.1e\n",
              n, n, i, j, s.num_faces(), s.count(FaceMethod::exact), front ? " and the front side" : "", faces, four, worst, cont.edges,
              cont.gap, cont.normal_angle);
}

TEST(TJunctionLines, FacesNearAStarPointAndATJunctionSixRingsOut) {
  expect_faces_near_a_star_point_and_a_t_junction(13, 6, 6, false, 52, 12);
  expect_faces_near_a_star_point_and_a_t_junction(15, 7, 0, true, 219, 18);
}

// A star point on a Bezier boundary (a half fan of K = 4 and 5 sectors of 7 x 7 faces) with a face split 2 x 2: a
// row crossed by a line that runs through the star point, or ends there, goes on along the ghost spoke of its
// ghost layer (the fan closed as the ghost layer closes it, the node beyond from nurcc_across_weights as at an
// interior star point); a line that ends on the boundary next to it (face (1, 1) of sector 0) inserts into the
// boundary row through it, whose block row takes the star point's block node and past it the virtual node shifted
// by the same offset. Against the cage without the split on its exact faces 4 knot intervals and more from the
// split face's centre, G1 across every edge of the completed mesh, one boundary loop.
TEST(TJunctionLines, RowsThroughAStarPointOfABezierBoundary) {
  const int n = 7;
  const auto height = [](double x, double y) { return 0.3 * std::sin(x + 0.7 * y) + 0.05 * x * y; };
  for (const auto& [sectors, sector, i, j] : {std::array<int, 4>{4, 0, 3, 0}, {4, 0, 1, 1}, {4, 1, 1, 1}, {5, 1, 1, 2}}) {
    const test::QuadMesh fan = test::half_fan_mesh(sectors, n, height);
    const TMeshSurface plain(mesh_of(fan, "fan.tsm"), 1);
    const test::QuadMesh split = test::split_face(fan, static_cast<std::size_t>((sector * n + j) * n + i), {0.02, -0.03, 0.01, 0.04, 0.07});
    const TMeshSurface lines(mesh_of(split, "split.tsm"), 1);
    ASSERT_NE(lines.completed_lines(), nullptr);
    EXPECT_EQ(lines.boundary_star_faces(), sectors);
    // The split face's centre: sector k spans the spokes at angles pi k / K and pi (k + 1) / K.
    const double a0 = std::numbers::pi * sector / sectors, a1 = std::numbers::pi * (sector + 1) / sectors;
    const Agreement g = expect_unchanged_away_from(
        plain, lines, fan, {(i + 0.5) * std::cos(a0) + (j + 0.5) * std::cos(a1), (i + 0.5) * std::sin(a0) + (j + 0.5) * std::sin(a1)});
    const test::Continuity cont = test::continuity(lines.mesh(), [&](int f, double u, double v, double* o) { lines.eval(f, u, v, o); });
    EXPECT_LT(cont.gap, 1e-12);
    EXPECT_LT(cont.normal_angle, 1e-9);
    EXPECT_EQ(test::boundary_loops(tessellate(lines, 0.05)), 1);
    std::printf("half fan of %d sectors (a star point on a Bezier boundary), sector %d face (%d, %d) split: %d lines, %d vertices inserted; %d "
                "exact faces against the cage without the split: values %.1e, derivatives %.1e; across %d edges gap %.1e, normals %.1e\n",
                sectors, sector, i, j, lines.completed_lines()->lines, lines.completed_lines()->vertices, g.compared, g.values, g.derivatives,
                cont.edges, cont.gap, cont.normal_angle);
  }
}
// A grip map that gives the rim vertices where a line ends no end-condition nodes (the others keep theirs): the
// insertion along the rim has no row of block points there, and the mesh is refused in one line naming the
// T-junction and the vertex.
TEST(TJunctionLines, AMissingEndConditionNodeIsRefused) {
  const test::QuadMesh box = test::box_mesh({11, 11, 11}, true);
  TMesh m = mesh_of(test::split_face(box, test::top_face(box.points, box, 11, 4, 1), {0.02, -0.03, 0.01, 0.04, 0.07}), "split.tsm");
  for (std::size_t v = 0; v < box.points.size(); ++v)  // the rim round the foot of the line at x = -1 + 9 / 11
    if (box.points[v][2] < -1 + 1e-9 && std::abs(box.points[v][0] + 1 - 9.0 / 11) < 0.3) {
      m.vertices[v].block.clear();
      m.vertices[v].block_dims = {};
    }
  test::expect_surface_refusal(m, "has no end-condition node for a row it crosses");
}

// Open boxes of 2 to 6 faces per side (Bezier rim within reach of the star points: its ghost layer) with a top face
// split: the lines cut the side walls down to the rim, whose ghost layer then has unequal intervals along it and
// the interval into the mesh across it; faces whose points read the layer with another interval take its knots.
// One surface, G1 across every edge, one boundary loop.
TEST(TJunctionLines, SmallOpenBoxesWithASplitTopFace) {
  for (const auto& [n, i, j] : {std::array<int, 3>{2, 0, 0}, {4, 0, 0}, {4, 1, 0}, {6, 2, 1}}) {
    test::QuadMesh box = test::box_mesh({n, n, n}, true);
    const auto unbent = box.points;
    bend(box.points);
    const TMeshSurface s(mesh_of(test::split_face(box, test::top_face(unbent, box, n, i, j), {0, 0, 0, 0, 0}), "split.tsm"), 1);
    ASSERT_NE(s.completed_lines(), nullptr);
    EXPECT_EQ(s.completed_lines()->lines, 4);
    const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
    EXPECT_LT(c.gap, 1e-12) << n;
    EXPECT_LT(c.normal_angle, 1e-9) << n;
    EXPECT_EQ(test::boundary_loops(tessellate(s, 0.05)), 1) << n;
    std::printf("open box of %d faces, top face (%d, %d) split: %d faces, %d by local subdivision; %d edges: gap %.1e, normals %.1e\n", n, i, j,
                s.num_faces(), s.count(FaceMethod::crease), c.edges, c.gap, c.normal_angle);
  }
}

}  // namespace
}  // namespace trivar
