#include "trivar/tspline/averaging_face.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {
namespace {

using H = std::array<double, 4>;

// Levels kept in the tree; deeper ones (within 2^-kCachedLevels of an irregular corner) are refined at evaluation.
constexpr int kCachedLevels = 10;
// Within 2^-kCornerLevels of an irregular corner a point takes the corner's values, whose derivatives are those
// 2^-kDerivativeLevel from it.
constexpr int kCornerLevels = 50;
constexpr int kDerivativeLevel = 30;

// Per vertex of a net its number of faces and whether its fan is closed (a face on both sides of every edge at it),
// read from the sides' twins; the twins found by sorting the directed edges when the net does not carry them (the
// nets refine builds do).
struct NetTopology {
  std::vector<int> twin;
  std::vector<int> faces;
  std::vector<char> closed;
  explicit NetTopology(const QuadNet& net) : twin(net.twin), faces(net.points.size(), 0), closed(net.points.size(), 1) {
    if (twin.empty()) {
      twin.assign(4 * net.quads.size(), -1);
      std::vector<std::pair<std::uint64_t, int>> edges;
      edges.reserve(4 * net.quads.size());
      const auto key = [](int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); };
      for (std::size_t q = 0; q < net.quads.size(); ++q)
        for (std::size_t k = 0; k < 4; ++k) edges.push_back({key(net.quads[q][k], net.quads[q][(k + 1) % 4]), static_cast<int>(4 * q + k)});
      std::sort(edges.begin(), edges.end());
      for (std::size_t q = 0; q < net.quads.size(); ++q)
        for (std::size_t k = 0; k < 4; ++k) {
          const std::uint64_t back = key(net.quads[q][(k + 1) % 4], net.quads[q][k]);
          const auto it = std::lower_bound(edges.begin(), edges.end(), std::pair<std::uint64_t, int>{back, INT_MIN});
          if (it != edges.end() && it->first == back) twin[4 * q + k] = it->second;
        }
    }
    for (std::size_t q = 0; q < net.quads.size(); ++q)
      for (std::size_t k = 0; k < 4; ++k) {
        ++faces[static_cast<std::size_t>(net.quads[q][k])];
        if (twin[4 * q + k] < 0) closed[static_cast<std::size_t>(net.quads[q][k])] = closed[static_cast<std::size_t>(net.quads[q][(k + 1) % 4])] = 0;
      }
  }
};

// The (p + 1)^2 points of quad q when its block of 2 m + 1 faces per side is a grid whose inner vertices have four
// faces each, else none. The block is walked cell by cell from the face: a cell is a quad and the quad corner at
// the cell's corner 0.
std::optional<std::vector<H>> regular_grid(const QuadNet& net, const NetTopology& topo, int q0, int passes) {
  const int b = passes, cells = 2 * b + 1, side = cells + 1;
  std::vector<std::array<int, 2>> cell(static_cast<std::size_t>(cells * cells), {-1, 0});
  std::vector<int> grid(static_cast<std::size_t>(side * side), -1), place(net.points.size(), -1);
  static constexpr std::array<int, 4> dx{0, 1, 1, 0}, dy{0, 0, 1, 1}, nx{0, 1, 0, -1}, ny{-1, 0, 1, 0};
  std::vector<std::array<int, 2>> todo{{0, 0}};
  cell[static_cast<std::size_t>(b * cells + b)] = {q0, 0};
  for (std::size_t t = 0; t < todo.size(); ++t) {
    const auto [i, j] = todo[t];
    const auto [q, r] = cell[static_cast<std::size_t>((j + b) * cells + i + b)];
    std::array<int, 4> v{};
    for (int k = 0; k < 4; ++k) {
      v[static_cast<std::size_t>(k)] = net.quads[static_cast<std::size_t>(q)][static_cast<std::size_t>((r + k) % 4)];
      const int at = (j + b + dy[static_cast<std::size_t>(k)]) * side + i + b + dx[static_cast<std::size_t>(k)];
      int& g = grid[static_cast<std::size_t>(at)];
      int& p = place[static_cast<std::size_t>(v[static_cast<std::size_t>(k)])];
      if ((g >= 0 && g != v[static_cast<std::size_t>(k)]) || (p >= 0 && p != at)) return std::nullopt;
      g = v[static_cast<std::size_t>(k)];
      p = at;
    }
    for (int k = 0; k < 4; ++k) {
      const int ni = i + nx[static_cast<std::size_t>(k)], nj = j + ny[static_cast<std::size_t>(k)];
      if (std::abs(ni) > b || std::abs(nj) > b) continue;
      // Side k of the cell is side r + k of its quad; the cell across has the twin side as its side k + 2.
      const int twin = topo.twin[static_cast<std::size_t>(4 * q + (r + k) % 4)];
      if (twin < 0) return std::nullopt;
      const std::array<int, 2> next{twin / 4, (twin % 4 - k + 2 + 8) % 4};
      std::array<int, 2>& c = cell[static_cast<std::size_t>((nj + b) * cells + ni + b)];
      if (c[0] < 0) {
        c = next;
        todo.push_back({ni, nj});
      } else if (c != next) {
        return std::nullopt;
      }
    }
  }
  for (int j = 1; j < cells; ++j)
    for (int i = 1; i < cells; ++i)
      if (const int g = grid[static_cast<std::size_t>(j * side + i)]; g < 0 || topo.faces[static_cast<std::size_t>(g)] != 4 || !topo.closed[static_cast<std::size_t>(g)])
        return std::nullopt;
  if (std::find(grid.begin(), grid.end(), -1) != grid.end()) return std::nullopt;
  std::vector<H> out;
  out.reserve(grid.size());
  for (int g : grid) out.push_back(net.points[static_cast<std::size_t>(g)]);
  return out;
}

}  // namespace

QuadNet averaging_refine(const QuadNet& net, const std::vector<int>& sub_faces, int passes, int rings) {
  // Linear subdivision: the old vertices keep their ids, then edge midpoints and face centroids; the four sub-quads
  // of quad q are 4 q + k, k at corner k, oriented as q. A new vertex's fan: an old vertex's as before, an edge
  // point's closed with four faces when its edge has two, a face point's closed with four.
  const NetTopology topo(net);
  std::vector<H> pts = net.points;
  std::vector<int> faces = topo.faces;
  std::vector<char> closed = topo.closed;
  std::vector<int> side_point(4 * net.quads.size(), -1);
  std::vector<std::array<int, 4>> quads;
  quads.reserve(4 * net.quads.size());
  for (std::size_t q = 0; q < net.quads.size(); ++q) {
    const auto& quad = net.quads[q];
    std::array<int, 4> e{};
    for (std::size_t k = 0; k < 4; ++k) {
      const int t = topo.twin[4 * q + k];
      if (t >= 0 && side_point[static_cast<std::size_t>(t)] >= 0) {
        e[k] = side_point[static_cast<std::size_t>(t)];
      } else {
        e[k] = static_cast<int>(pts.size());
        H m;
        for (std::size_t i = 0; i < 4; ++i) m[i] = 0.5 * (net.points[static_cast<std::size_t>(quad[k])][i] + net.points[static_cast<std::size_t>(quad[(k + 1) % 4])][i]);
        pts.push_back(m);
        faces.push_back(t >= 0 ? 4 : 2);
        closed.push_back(t >= 0);
      }
      side_point[4 * q + k] = e[k];
    }
    H c{};
    for (int v : quad)
      for (std::size_t i = 0; i < 4; ++i) c[i] += 0.25 * net.points[static_cast<std::size_t>(v)][i];
    const int f = static_cast<int>(pts.size());
    pts.push_back(c);
    faces.push_back(4);
    closed.push_back(1);
    quads.push_back({quad[0], e[0], f, e[3]});
    quads.push_back({e[0], quad[1], e[1], f});
    quads.push_back({f, e[1], quad[2], e[2]});
    quads.push_back({e[3], f, e[2], quad[3]});
  }
  // The sub-quads' twins: inside a quad sub-quad k's sides k + 1 and k + 2 meet sub-quads k + 1 and k + 3; across
  // side k of q the first half (sub-quad k's side k) meets the second half of the twin side k' of q' (sub-quad
  // k' + 1's side k'), and the second half (sub-quad k + 1's side k) the first (sub-quad k''s side k').
  std::vector<int> twin(4 * quads.size(), -1);
  for (std::size_t q = 0; q < net.quads.size(); ++q)
    for (std::size_t k = 0; k < 4; ++k) {
      const std::size_t a = 4 * q + k, b = 4 * q + (k + 1) % 4, d = 4 * q + (k + 3) % 4;
      twin[4 * a + (k + 1) % 4] = static_cast<int>(4 * b + (k + 3) % 4);
      twin[4 * a + (k + 2) % 4] = static_cast<int>(4 * d + k);
      if (const int t = topo.twin[4 * q + k]; t >= 0) {
        const std::size_t q2 = static_cast<std::size_t>(t / 4), k2 = static_cast<std::size_t>(t % 4);
        twin[4 * a + k] = static_cast<int>(4 * (4 * q2 + (k2 + 1) % 4) + k2);
        twin[4 * b + k] = static_cast<int>(4 * (4 * q2 + k2) + k2);
      }
    }
  // Averaging passes. A point is right when its vertex's fan is closed and the points it averages were right.
  std::vector<char> right(pts.size(), 1);
  std::vector<H> sum(pts.size());
  std::vector<char> next(pts.size());
  for (int pass = 0; pass < passes; ++pass) {
    std::fill(sum.begin(), sum.end(), H{});
    for (std::size_t v = 0; v < pts.size(); ++v) next[v] = closed[v] && right[v];
    for (const auto& q : quads) {
      H c{};
      bool ok = true;
      for (int v : q) {
        ok = ok && right[static_cast<std::size_t>(v)];
        for (std::size_t i = 0; i < 4; ++i) c[i] += 0.25 * pts[static_cast<std::size_t>(v)][i];
      }
      for (int v : q) {
        for (std::size_t i = 0; i < 4; ++i) sum[static_cast<std::size_t>(v)][i] += c[i];
        if (!ok) next[static_cast<std::size_t>(v)] = 0;
      }
    }
    for (std::size_t v = 0; v < pts.size(); ++v)
      if (closed[v])
        for (std::size_t i = 0; i < 4; ++i) pts[v][i] = sum[v][i] / faces[v];
    right.swap(next);
  }
  // The sub-faces' face rings, in ring order from them (vertex -> quads in compressed rows).
  std::vector<int> start(pts.size() + 1, 0), at_vertex(4 * quads.size());
  for (const auto& q : quads)
    for (int v : q) ++start[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < pts.size(); ++v) start[v + 1] += start[v];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t q = 0; q < quads.size(); ++q)
      for (int v : quads[q]) at_vertex[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<int>(q);
  }
  std::vector<int> kept = sub_faces;
  std::vector<char> taken(quads.size(), 0), seen(pts.size(), 0);
  for (int q : kept) taken[static_cast<std::size_t>(q)] = 1;
  for (std::size_t begin = 0, ring = 0; ring < static_cast<std::size_t>(rings); ++ring) {
    const std::size_t end = kept.size();
    for (std::size_t i = begin; i < end; ++i)
      for (int v : quads[static_cast<std::size_t>(kept[i])]) {
        if (seen[static_cast<std::size_t>(v)]) continue;
        seen[static_cast<std::size_t>(v)] = 1;
        for (int j = start[static_cast<std::size_t>(v)]; j < start[static_cast<std::size_t>(v) + 1]; ++j)
          if (const int q = at_vertex[static_cast<std::size_t>(j)]; !taken[static_cast<std::size_t>(q)]) {
            taken[static_cast<std::size_t>(q)] = 1;
            kept.push_back(q);
          }
      }
    begin = end;
  }
  QuadNet out;
  out.quads.reserve(kept.size());
  std::vector<int> id(pts.size(), -1), new_quad(quads.size(), -1);
  for (std::size_t i = 0; i < kept.size(); ++i) new_quad[static_cast<std::size_t>(kept[i])] = static_cast<int>(i);
  out.twin.reserve(4 * kept.size());
  for (int q : kept)
    for (std::size_t k = 0; k < 4; ++k) {
      const int t = twin[4 * static_cast<std::size_t>(q) + k];
      const int to = t < 0 ? -1 : new_quad[static_cast<std::size_t>(t / 4)];
      out.twin.push_back(to < 0 ? -1 : 4 * to + t % 4);
    }
  for (int q : kept) {
    std::array<int, 4> quad{};
    for (std::size_t k = 0; k < 4; ++k) {
      const int v = quads[static_cast<std::size_t>(q)][k];
      if (id[static_cast<std::size_t>(v)] < 0) {
        require(right[static_cast<std::size_t>(v)], "averaging subdivision: the net is too small for the rules at a vertex it keeps");
        id[static_cast<std::size_t>(v)] = static_cast<int>(out.points.size());
        out.points.push_back(pts[static_cast<std::size_t>(v)]);
      }
      quad[k] = id[static_cast<std::size_t>(v)];
    }
    out.quads.push_back(quad);
  }
  return out;
}

AveragingFace::AveragingFace(QuadNet net, int degree) : degree_(degree), passes_((degree - 1) / 2), rings_((degree - 1) / 2 + 1) {
  require(degree >= 3 && degree <= 15 && degree % 2 == 1, [&] { return "averaging subdivision: degree " + std::to_string(degree) + ", not odd from 3 to 15"; });
  require(!net.quads.empty(), "averaging subdivision: an empty net");
  for (const H& p : net.points) rational_ = rational_ || p[3] != 1.0;
  // Level by level, one net round every sub-face not yet regular: (tree node, its quad in the net).
  tree_.emplace_back();
  std::vector<std::array<int, 2>> pending{{0, 0}};
  for (int level = 0; !pending.empty(); ++level) {
    std::vector<std::array<int, 2>> next;
    std::vector<int> sub_faces;
    const NetTopology topo(net);
    for (const auto [node, q] : pending) {
      if (auto g = regular_grid(net, topo, q, passes_)) {
        tree_[static_cast<std::size_t>(node)].grid = std::move(g);
      } else if (level == kCachedLevels) {
        tree_[static_cast<std::size_t>(node)].deep = q;
      } else {
        for (int c = 0; c < 4; ++c) {
          tree_[static_cast<std::size_t>(node)].children[static_cast<std::size_t>(c)] = static_cast<int>(tree_.size());
          next.push_back({static_cast<int>(tree_.size()), static_cast<int>(sub_faces.size())});
          tree_.emplace_back();
          sub_faces.push_back(4 * q + c);
        }
      }
    }
    if (level == kCachedLevels) {
      deep_ = std::move(net);
      break;
    }
    if (!next.empty()) net = averaging_refine(net, sub_faces, passes_, rings_);
    pending = std::move(next);
  }
  for (int c = 0; c < 4; ++c) {
    int node = 0;
    while (tree_[static_cast<std::size_t>(node)].children[0] >= 0) node = tree_[static_cast<std::size_t>(node)].children[static_cast<std::size_t>(c)];
    const int q = tree_[static_cast<std::size_t>(node)].deep;
    if (q < 0) continue;
    // Sub-face c's corner c is the face's corner c on every level: its point converges to the limit. The derivatives
    // are taken on level 30 at the sub-face's opposite corner, 2^-30 from the face's corner along the diagonal.
    double size = 0;  // of the coordinates, whose rounding the rules' sums repeat
    for (const H& p : deep_.points)
      for (double x : p) size = std::max(size, std::abs(x));
    std::array<double, 12> values{};
    H at = deep_.points[static_cast<std::size_t>(deep_.quads[static_cast<std::size_t>(q)][static_cast<std::size_t>(c)])];
    QuadNet z = averaging_refine(deep_, {4 * q + c}, passes_, rings_);
    for (int level = kCachedLevels + 1;; ++level) {
      if (level == kDerivativeLevel)
        descend(z, 0, level, c == 1 || c == 2 ? 0 : 1, c >= 2 ? 0 : 1, std::ldexp(1.0, kDerivativeLevel), values.data());
      const H next = z.points[static_cast<std::size_t>(z.quads[0][static_cast<std::size_t>(c)])];
      double change = 0;
      for (std::size_t i = 0; i < 4; ++i) change = std::max(change, std::abs(next[i] - at[i]));
      at = next;
      if (change <= 1e-15 * size && level >= kDerivativeLevel) break;
      require(level < 400, "averaging subdivision: the corner point does not converge");
      z = averaging_refine(z, {c}, passes_, rings_);
    }
    std::copy(at.begin(), at.end(), values.begin());
    corner_values_[static_cast<std::size_t>(c)] = values;
  }
}

// The uniform B-spline of degree p on the points: control point i has the knots i - p .. i + 1, the face [0, 1].
void AveragingFace::eval_grid(const Grid& g, double u, double v, double scale, double* out) const {
  const int p = degree_, n = p + 1;
  double knots[2 * kMaxDegree + 2];
  for (int j = 0; j < 2 * n; ++j) knots[j] = j - p;
  double bu[2 * (kMaxDegree + 1)], bv[2 * (kMaxDegree + 1)];
  basis_derivatives(knots, p, p, std::clamp(u, 0.0, 1.0), 1, bu);
  basis_derivatives(knots, p, p, std::clamp(v, 0.0, 1.0), 1, bv);
  std::fill(out, out + 12, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const H& x = g[static_cast<std::size_t>(j * n + i)];
      const double w0 = bu[i] * bv[j], wu = scale * bu[n + i] * bv[j], wv = scale * bu[i] * bv[n + j];
      for (std::size_t c = 0; c < 4; ++c) {
        out[c] += w0 * x[c];
        out[4 + c] += wu * x[c];
        out[8 + c] += wv * x[c];
      }
    }
}

void AveragingFace::descend(const QuadNet& start, int q, int level, double u, double v, double scale, double* out) const {
  QuadNet net;
  const QuadNet* at = &start;
  for (;; ++level) {
    if (auto g = regular_grid(*at, NetTopology(*at), q, passes_)) {
      eval_grid(*g, u, v, scale, out);
      return;
    }
    require(level <= kCornerLevels + 2, "averaging subdivision: no regular sub-face holds the point");
    const int cu = u >= 0.5, cv = v >= 0.5;
    net = averaging_refine(*at, {4 * q + (cv ? (cu ? 2 : 3) : (cu ? 1 : 0))}, passes_, rings_);
    at = &net;
    q = 0;
    u = 2 * u - cu;
    v = 2 * v - cv;
    scale *= 2;
  }
}

void AveragingFace::for_each_square(int corner_level, const std::function<void(const std::array<double, 2>&, double, int)>& f) const {
  using Lo = std::array<double, 2>;
  // The irregular corner the square has as its own corner (-1: none).
  const auto corner_of = [&](const Lo& lo, double side) {
    for (int c = 0; c < 4; ++c) {
      const double cu = c == 1 || c == 2 ? 1.0 : 0.0, cv = c >= 2 ? 1.0 : 0.0;
      if (irregular(c) && (lo[0] == cu || lo[0] + side == cu) && (lo[1] == cv || lo[1] + side == cv)) return c;
    }
    return -1;
  };
  const auto child_lo = [](const Lo& lo, double half, int k) {
    return Lo{lo[0] + (k == 1 || k == 2 ? half : 0), lo[1] + (k >= 2 ? half : 0)};
  };
  // Below the cached levels: the four sub-faces of quad q refined together.
  std::function<void(const QuadNet&, int, int, const Lo&, double)> below = [&](const QuadNet& net, int q, int level, const Lo& lo, double side) {
    if (regular_grid(net, NetTopology(net), q, passes_)) return f(lo, side, -1);
    if (const int c = corner_of(lo, side); c >= 0 && level >= corner_level) return f(lo, side, c);
    require(level < 64, "averaging subdivision: no regular sub-faces tile the face");
    const QuadNet fine = averaging_refine(net, {4 * q, 4 * q + 1, 4 * q + 2, 4 * q + 3}, passes_, rings_);
    for (int k = 0; k < 4; ++k) below(fine, k, level + 1, child_lo(lo, side / 2, k), side / 2);
  };
  std::function<void(int, int, const Lo&, double)> walk = [&](int node, int level, const Lo& lo, double side) {
    const Node& n = tree_[static_cast<std::size_t>(node)];
    if (n.grid) return f(lo, side, -1);
    if (n.deep >= 0) return below(deep_, n.deep, level, lo, side);
    if (const int c = corner_of(lo, side); c >= 0 && level >= corner_level) return f(lo, side, c);
    for (int k = 0; k < 4; ++k) walk(n.children[static_cast<std::size_t>(k)], level + 1, child_lo(lo, side / 2, k), side / 2);
  };
  walk(0, 0, {0, 0}, 1);
}

void AveragingFace::eval(double u, double v, double* out) const {
  u = std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0);
  const double near = std::ldexp(1.0, -kCornerLevels);
  for (int c = 0; c < 4; ++c) {
    const double cu = c == 1 || c == 2 ? 1.0 : 0.0, cv = c >= 2 ? 1.0 : 0.0;
    if (corner_values_[static_cast<std::size_t>(c)] && std::abs(u - cu) < near && std::abs(v - cv) < near) {
      std::copy(corner_values_[static_cast<std::size_t>(c)]->begin(), corner_values_[static_cast<std::size_t>(c)]->end(), out);
      return;
    }
  }
  int node = 0;
  double scale = 1;
  for (;;) {
    const Node& n = tree_[static_cast<std::size_t>(node)];
    if (n.grid) {
      eval_grid(*n.grid, u, v, scale, out);
      return;
    }
    if (n.deep >= 0) {
      descend(deep_, n.deep, kCachedLevels, u, v, scale, out);
      return;
    }
    const int cu = u >= 0.5, cv = v >= 0.5;
    node = n.children[static_cast<std::size_t>(cv ? (cu ? 2 : 3) : (cu ? 1 : 0))];
    u = 2 * u - cu;
    v = 2 * v - cv;
    scale *= 2;
  }
}

}  // namespace trivar
