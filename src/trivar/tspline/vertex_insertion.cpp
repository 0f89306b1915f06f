#include "trivar/tspline/vertex_insertion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/tspline/local_knots.hpp"

namespace trivar {

namespace {

// The varying axis of a segment (0: along s) and its range there.
int along(const KnotSegment& g) { return g.from[0] == g.to[0] ? 1 : 0; }

bool on_segment(const KnotSegment& g, double s, double t, int axis) {
  if (along(g) != axis) return false;
  const double p[2] = {s, t};
  const double lo = std::min(g.from[axis], g.to[axis]), hi = std::max(g.from[axis], g.to[axis]);
  return g.from[1 - axis] == p[1 - axis] && lo <= p[axis] && p[axis] <= hi;
}

// Along axis k from (s, t) in direction sign: the nearest crossing with a segment perpendicular to k (the next
// knot line), or NaN when there is none.
double next_line(const std::vector<KnotSegment>& grid, double s, double t, int k, int sign) {
  const double p[2] = {s, t};
  double best = std::numeric_limits<double>::quiet_NaN();
  for (const KnotSegment& g : grid) {
    if (along(g) == k) continue;  // perpendicular to k: constant in k
    const double c = g.from[k];
    const double lo = std::min(g.from[1 - k], g.to[1 - k]), hi = std::max(g.from[1 - k], g.to[1 - k]);
    if (p[1 - k] < lo || p[1 - k] > hi || (c - p[k]) * sign <= 0) continue;
    if (std::isnan(best) || std::abs(c - p[k]) < std::abs(best - p[k])) best = c;
  }
  return best;
}

}  // namespace

const char* joint_name(Joint j) {
  switch (j) {
    case Joint::single: return "single vertex";
    case Joint::t: return "T-joint";
    case Joint::i: return "I-joint";
    case Joint::l: return "L-joint";
  }
  return "?";
}

Joint insert_vertex(std::vector<KnotSegment>& grid, const VertexInsertion& v) {
  const auto where = [&] { return "vertex insertion at (" + std::to_string(v.s) + ", " + std::to_string(v.t) + "): "; };
  int n = 0;
  for (bool a : v.arms) n += a;
  const bool opposite = n == 2 && v.arms[0] == v.arms[2];
  const Joint joint = n == 0 ? Joint::single : n == 1 ? Joint::t : n == 2 && opposite ? Joint::i : Joint::l;
  require(n <= 2, [&] { return where() + std::to_string(n) + " arms (a joint has at most two new edges)"; });
  for (const KnotSegment& g : grid)
    for (const auto& e : {g.from, g.to})
      require(e[0] != v.s || e[1] != v.t, [&] { return where() + "already a vertex"; });
  // The existing edge the vertex lies on, per axis.
  std::array<int, 2> on{-1, -1};
  for (std::size_t i = 0; i < grid.size(); ++i)
    for (int k = 0; k < 2; ++k)
      if (on_segment(grid[i], v.s, v.t, k)) on[static_cast<std::size_t>(k)] = static_cast<int>(i);
  require(on[0] < 0 || on[1] < 0, [&] { return where() + "already a vertex (a crossing of knot lines)"; });
  if (joint == Joint::single || joint == Joint::t)
    require(on[0] >= 0 || on[1] >= 0, [&] { return where() + "a " + joint_name(joint) + " must lie on an existing edge"; });
  if (joint == Joint::l) require(on[0] >= 0 || on[1] >= 0, [&] {
    return where() + "an L-joint inside a face leaves an L-shaped face (T-images hold rectangular faces)";
  });
  // Split the edge the vertex lies on, so the vertex exists also without arms.
  for (int k = 0; k < 2; ++k)
    if (on[static_cast<std::size_t>(k)] >= 0) {
      KnotSegment& g = grid[static_cast<std::size_t>(on[static_cast<std::size_t>(k)])];
      KnotSegment rest = g;
      const std::array<double, 2> p{v.s, v.t};
      (g.from[k] < g.to[k] ? g.to : g.from) = p;
      (rest.from[k] < rest.to[k] ? rest.from : rest.to) = p;
      grid.push_back(rest);
    }
  for (int d = 0; d < 4; ++d) {
    if (!v.arms[static_cast<std::size_t>(d)]) continue;
    const int k = tdir_axis(d), sign = tdir_sign(d);
    require(on[static_cast<std::size_t>(k)] < 0, [&] {
      return where() + "the " + kTDirNames[static_cast<std::size_t>(d)] + " arm runs along an existing edge";
    });
    const double end = next_line(grid, v.s, v.t, k, sign);
    require(!std::isnan(end), [&] {
      return where() + "the " + kTDirNames[static_cast<std::size_t>(d)] + " arm meets no knot line";
    });
    KnotSegment arm{{v.s, v.t}, {v.s, v.t}};
    arm.to[static_cast<std::size_t>(k)] = end;
    grid.push_back(arm);
  }
  return joint;
}

std::vector<MeshRectangle<2>> lr_refinement(const TSpline& refined, const VertexInsertion& v) {
  int vertex = -1;
  for (int i = 0; i < static_cast<int>(refined.image.vertices.size()); ++i)
    if (refined.image.vertices[static_cast<std::size_t>(i)].s == v.s && refined.image.vertices[static_cast<std::size_t>(i)].t == v.t) vertex = i;
  require(vertex >= 0, "LR refinement of a vertex insertion: (" + std::to_string(v.s) + ", " + std::to_string(v.t) +
                           ") is not a vertex of the refined T-mesh");
  const auto knots = local_knot_vectors(refined);
  Box<2> support = Box<2>::empty();
  for (std::size_t n = 0; n < refined.connect.nodes.size(); ++n) {
    const TNode& x = refined.connect.nodes[n];
    if (x.kind != TAnchorKind::vertex || x.anchor != vertex) continue;
    for (int k = 0; k < 2; ++k)
      for (double u : {knots[n][static_cast<std::size_t>(k)].front(), knots[n][static_cast<std::size_t>(k)].back()}) {
        double p[2] = {v.s, v.t};
        p[k] = u;
        support.extend(p);
      }
  }
  // The direction of refinement: the axis whose knot the vertex adds. A vertical arm or a vertex on a
  // horizontal edge (no vertical link) adds the knot s = v.s; a horizontal arm or a vertex on a vertical edge
  // adds t = v.t.
  const TVertex& x = refined.image.vertices[static_cast<std::size_t>(vertex)];
  const bool vertical = x.links[0] >= 0 || x.links[2] >= 0, horizontal = x.links[1] >= 0 || x.links[3] >= 0;
  const bool arm_v = v.arms[0] || v.arms[2], arm_h = v.arms[1] || v.arms[3];
  std::vector<MeshRectangle<2>> out;
  if (arm_v || (!arm_h && !vertical))
    out.push_back(MeshRectangle<2>::make(0, v.s, {v.s, support.lo[1]}, {v.s, support.hi[1]}));
  if (arm_h || (!arm_v && !horizontal))
    out.push_back(MeshRectangle<2>::make(1, v.t, {support.lo[0], v.t}, {support.hi[0], v.t}));
  return out;
}

}  // namespace trivar
