#include "trivar/tspline/local_knots.hpp"

#include <algorithm>
#include <map>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

// The T-image edges as knot lines: for each axis k, the edges perpendicular to it grouped by their coordinate
// along k, sorted, each line a list of closed intervals in the other parameter. A ray along k from x on the
// line y meets the nearest line beyond x holding an interval that contains y.
class KnotRays {
public:
  explicit KnotRays(const TImage& im) {
    std::array<std::map<double, std::vector<std::array<double, 2>>>, 2> by;
    for (int e = 0; e < static_cast<int>(im.edges.size()); ++e) {
      const Box<2> b = im.edge_box(e);
      const int k = b.lo[0] == b.hi[0] ? 0 : 1;  // a vertical edge is a knot line of s
      by[k][b.lo[k]].push_back({b.lo[1 - k], b.hi[1 - k]});
    }
    for (int k = 0; k < 2; ++k)
      for (auto& [c, spans] : by[k]) lines_[k].push_back({c, std::move(spans)});
  }

  // The next knot line along axis k in direction sign (+1, -1) strictly beyond x, on the line y; x itself when
  // there is none.
  double next(int k, int sign, double x, double y) const {
    const auto& L = lines_[k];
    auto it = std::upper_bound(L.begin(), L.end(), x, [](double v, const Line& l) { return v < l.c; });
    if (sign > 0) {
      for (; it != L.end(); ++it)
        if (it->covers(y)) return it->c;
    } else {
      auto r = std::make_reverse_iterator(it);
      for (; r != L.rend(); ++r)
        if (r->c < x && r->covers(y)) return r->c;
    }
    return x;
  }

private:
  struct Line {
    double c;
    std::vector<std::array<double, 2>> spans;
    bool covers(double y) const {
      return std::any_of(spans.begin(), spans.end(), [y](const auto& s) { return s[0] <= y && y <= s[1]; });
    }
  };
  std::array<std::vector<Line>, 2> lines_;
};

// The knots on one side of node n along axis k (direction d of the compass), nearest first.
void side_knots(const TSpline& ts, const KnotRays& rays, const std::vector<Box<2>>& anchors, int n, int d, int count,
                std::vector<double>& out) {
  const int k = tdir_axis(d), sign = tdir_sign(d);
  const Box<2>& a = anchors[static_cast<std::size_t>(n)];
  const double line = 0.5 * (a.lo[1 - k] + a.hi[1 - k]);
  double x = sign > 0 ? a.hi[k] : a.lo[k];
  int steps = count;
  if (ts.degrees[k] % 2 == 0) {  // the anchor's own side is the first knot
    out.push_back(x);
    --steps;
  }
  int node = n;  // the T-connect is followed while neighbours repeat the anchor interval
  for (int i = 0; i < steps; ++i) {
    if (node >= 0) {
      const int m = ts.connect.nodes[static_cast<std::size_t>(node)].neighbours[static_cast<std::size_t>(d)];
      if (m >= 0 && anchors[static_cast<std::size_t>(m)].lo[k] == a.lo[k] &&
          anchors[static_cast<std::size_t>(m)].hi[k] == a.hi[k]) {
        out.push_back(x);
        node = m;
        continue;
      }
      node = -1;
    }
    x = rays.next(k, sign, x, line);
    out.push_back(x);
  }
}

}  // namespace

std::vector<std::array<std::vector<double>, 2>> local_knot_vectors(const TSpline& ts) {
  validate(ts);
  const KnotRays rays(ts.image);
  const auto& nodes = ts.connect.nodes;
  std::vector<Box<2>> anchors(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) anchors[i] = anchor_box(ts, nodes[i]);
  std::vector<std::array<std::vector<double>, 2>> knots(nodes.size());
  std::vector<double> lower, upper;
  for (int n = 0; n < static_cast<int>(nodes.size()); ++n)
    for (int k = 0; k < 2; ++k) {
      const int p = ts.degrees[k];
      const int count = p % 2 == 1 ? (p + 1) / 2 : p / 2 + 1;
      lower.clear();
      upper.clear();
      side_knots(ts, rays, anchors, n, k == 0 ? 1 : 2, count, lower);  // west / south
      side_knots(ts, rays, anchors, n, k == 0 ? 3 : 0, count, upper);  // east / north
      auto& kv = knots[static_cast<std::size_t>(n)][static_cast<std::size_t>(k)];
      kv.assign(lower.rbegin(), lower.rend());
      if (p % 2 == 1) kv.push_back(anchors[static_cast<std::size_t>(n)].lo[k]);
      kv.insert(kv.end(), upper.begin(), upper.end());
      require(kv.back() > kv.front(), [&] {
        return "T-spline: node " + std::to_string(n) + " has an empty support in direction " + (k == 0 ? "s" : "t") +
               " (all its local knots equal " + std::to_string(kv.front()) + ")";
      });
    }
  return knots;
}

std::vector<LRBSpline<2>> blending_functions(const TSpline& ts) {
  auto knots = local_knot_vectors(ts);
  std::vector<LRBSpline<2>> basis(knots.size());
  for (std::size_t i = 0; i < knots.size(); ++i) {
    basis[i].knots = std::move(knots[i]);
    const RationalPoint& p = ts.pointset.points[static_cast<std::size_t>(ts.connect.nodes[i].point)];
    basis[i].coef = {p.w * p.xyz[0], p.w * p.xyz[1], p.w * p.xyz[2], p.w};
  }
  return basis;
}

}  // namespace trivar
