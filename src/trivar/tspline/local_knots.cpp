#include "trivar/tspline/local_knots.hpp"

#include <algorithm>
#include <map>

#include "trivar/core/error.hpp"
#include "trivar/tspline/knot_rays.hpp"

namespace trivar {

namespace {

// The T-connect facts the rays need: per node its anchor box; per vertex (odd degrees) how many repeated-knot
// layers its node block has along each axis, counted in the row of its first node.
struct ConnectView {
  std::vector<Box<2>> anchors;
  std::map<std::array<double, 2>, std::array<int, 2>> block_layers;  // vertex (s, t) -> layers along s, t
};

bool coincident(const ConnectView& cv, int a, int b, int k) {
  return cv.anchors[static_cast<std::size_t>(a)].lo[k] == cv.anchors[static_cast<std::size_t>(b)].lo[k] &&
         cv.anchors[static_cast<std::size_t>(a)].hi[k] == cv.anchors[static_cast<std::size_t>(b)].hi[k];
}

ConnectView connect_view(const TSpline& ts) {
  ConnectView cv;
  const auto& nodes = ts.connect.nodes;
  cv.anchors.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) cv.anchors[i] = anchor_box(ts, nodes[i]);
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
    const TNode& n = nodes[static_cast<std::size_t>(i)];
    if (n.kind != TAnchorKind::vertex) continue;
    const TVertex& v = ts.image.vertices[static_cast<std::size_t>(n.anchor)];
    auto [it, fresh] = cv.block_layers.try_emplace({v.s, v.t}, std::array<int, 2>{0, 0});
    if (!fresh) continue;  // the first node of the vertex defines its rows
    for (int k = 0; k < 2; ++k)
      for (int d : {k == 0 ? 1 : 0, k == 0 ? 3 : 2})  // both ways along axis k
        for (int m = i;;) {
          const int next = nodes[static_cast<std::size_t>(m)].neighbours[static_cast<std::size_t>(d)];
          if (next < 0 || !coincident(cv, next, m, k)) break;
          ++it->second[static_cast<std::size_t>(k)];
          m = next;
        }
  }
  return cv;
}

// The knots on one side of node n along axis k (direction d of the compass), nearest first. A ray that leaves
// the faces (the domain's boundary, also where the domain is not convex or has holes) stops: the knot repeats.
// A ray that meets a vertex whose node block repeats the knot (Bezier end conditions of a boundary, also an
// inner one) takes the knot as often as the block has nodes along the ray.
void side_knots(const TSpline& ts, const KnotRays& rays, const ConnectView& cv, int n, int d, int count,
                std::vector<double>& out) {
  const int k = tdir_axis(d), sign = tdir_sign(d);
  const Box<2>& a = cv.anchors[static_cast<std::size_t>(n)];
  const double line = 0.5 * (a.lo[1 - k] + a.hi[1 - k]);
  double x = sign > 0 ? a.hi[k] : a.lo[k];
  int steps = count;
  if (ts.degrees[k] % 2 == 0) {  // the anchor's own side is the first knot
    out.push_back(x);
    --steps;
  }
  int node = n;      // the T-connect is followed while neighbours repeat the anchor interval
  int pending = 0;   // repeats owed to a node block the ray met
  for (int i = 0; i < steps; ++i) {
    if (node >= 0) {
      const int m = ts.connect.nodes[static_cast<std::size_t>(node)].neighbours[static_cast<std::size_t>(d)];
      if (m >= 0 && coincident(cv, m, node, k)) {
        out.push_back(x);
        node = m;
        continue;
      }
      node = -1;
    }
    if (pending > 0) {
      out.push_back(x);
      --pending;
      continue;
    }
    const double next = rays.next(k, sign, x, line);
    std::array<double, 2> mid;
    mid[static_cast<std::size_t>(k)] = 0.5 * (x + next);
    mid[static_cast<std::size_t>(1 - k)] = line;
    if (next != x && rays.inside(mid[0], mid[1])) {
      x = next;
      std::array<double, 2> at;
      at[static_cast<std::size_t>(k)] = x;
      at[static_cast<std::size_t>(1 - k)] = line;
      if (auto it = cv.block_layers.find(at); it != cv.block_layers.end()) pending = it->second[static_cast<std::size_t>(k)];
    }
    out.push_back(x);
  }
}

}  // namespace

std::vector<std::array<std::vector<double>, 2>> local_knot_vectors(const TSpline& ts) {
  validate(ts);
  const KnotRays rays(ts.image);
  const auto& nodes = ts.connect.nodes;
  const ConnectView cv = connect_view(ts);
  std::vector<std::array<std::vector<double>, 2>> knots(nodes.size());
  std::vector<double> lower, upper;
  for (int n = 0; n < static_cast<int>(nodes.size()); ++n)
    for (int k = 0; k < 2; ++k) {
      const int p = ts.degrees[k];
      const int count = p % 2 == 1 ? (p + 1) / 2 : p / 2 + 1;
      lower.clear();
      upper.clear();
      side_knots(ts, rays, cv, n, k == 0 ? 1 : 2, count, lower);  // west / south
      side_knots(ts, rays, cv, n, k == 0 ? 3 : 0, count, upper);  // east / north
      auto& kv = knots[static_cast<std::size_t>(n)][static_cast<std::size_t>(k)];
      kv.assign(lower.rbegin(), lower.rend());
      if (p % 2 == 1) kv.push_back(cv.anchors[static_cast<std::size_t>(n)].lo[k]);
      kv.insert(kv.end(), upper.begin(), upper.end());
      require(kv.back() > kv.front(), [&] {
        return "T-spline: node " + std::to_string(n) + " has an empty support in direction " + (k == 0 ? "s" : "t") +
               " (all its local knots equal " + std::to_string(kv.front()) + ")";
      });
    }
  return knots;
}

std::vector<LRBSpline<2>> blending_functions(const TSpline& ts) {
  require(!ts.image.faces.empty(), "T-spline: no faces (a TSM model with star points has no global (s, t); it is evaluated face by face, TMeshSurface)");
  auto knots = local_knot_vectors(ts);
  std::vector<LRBSpline<2>> basis(knots.size());
  for (std::size_t i = 0; i < knots.size(); ++i) {
    basis[i].knots = std::move(knots[i]);
    const RationalPoint& p = ts.pointset.points[static_cast<std::size_t>(ts.connect.nodes[i].point)];
    basis[i].coef = {p.w * p.xyz[0], p.w * p.xyz[1], p.w * p.xyz[2], p.w};
  }
  return basis;
}

void place_at_greville_points(TSpline& ts) {
  const auto knots = local_knot_vectors(ts);
  for (std::size_t i = 0; i < knots.size(); ++i) {
    RationalPoint& point = ts.pointset.points[static_cast<std::size_t>(ts.connect.nodes[i].point)];
    for (std::size_t k = 0; k < 2; ++k) {
      const std::vector<double>& t = knots[i][k];
      double g = 0;
      for (std::size_t j = 1; j + 1 < t.size(); ++j) g += t[j];
      point.xyz[k] = g / static_cast<double>(t.size() - 2);
    }
  }
}

}  // namespace trivar
