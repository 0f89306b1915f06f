#include "trivar/tspline/crease_face.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>
#include <span>
#include <string>

#include <Eigen/Eigenvalues>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/tspline/catmull_clark_patch.hpp"
#include "trivar/tspline/non_uniform_catmull_clark.hpp"

namespace trivar {

namespace {

using NetPoint = std::array<double, 4>;

void add_scaled(NetPoint& a, const NetPoint& b, double s) {
  for (std::size_t i = 0; i < 4; ++i) a[i] += s * b[i];
}

// The quads at each vertex: (quad, corner) in the order of the quads. One array for all vertices: the nets are
// rebuilt at every level, and a vector per vertex made allocation most of their cost.
class NetIncidence {
public:
  explicit NetIncidence(const CreaseNet& n) : start_(n.points.size() + 1, 0), at_(4 * n.quads.size()) {
    for (const auto& a : n.quads)
      for (int v : a) ++start_[static_cast<std::size_t>(v) + 1];
    for (std::size_t v = 1; v < start_.size(); ++v) start_[v] += start_[v - 1];
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int q = 0; q < static_cast<int>(n.quads.size()); ++q)
      for (int k = 0; k < 4; ++k) at_[static_cast<std::size_t>(fill[static_cast<std::size_t>(n.quads[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)])]++)] = {q, k};
  }
  std::span<const std::array<int, 2>> operator[](std::size_t v) const {
    return {at_.data() + start_[v], at_.data() + start_[v + 1]};
  }

private:
  std::vector<int> start_;  // vertex v's quads: at_[start_[v] .. start_[v + 1])
  std::vector<std::array<int, 2>> at_;
};

NetIncidence net_incidence(const CreaseNet& n) { return NetIncidence(n); }

// The quads sharing a vertex with `from` (and those).
std::vector<char> net_ring(const CreaseNet& n, const NetIncidence& inc, const std::vector<char>& from) {
  std::vector<char> out = from;
  for (std::size_t q = 0; q < n.quads.size(); ++q)
    if (from[q])
      for (int v : n.quads[q])
        for (const auto& [r, k] : inc[static_cast<std::size_t>(v)]) out[static_cast<std::size_t>(r)] = 1;
  return out;
}

// The quad across side k of quad q (the one holding the side the other way), -1: none in the net or a crease side
// (the two sides of a slit ending at two darts join the same two vertices).
int net_across(const CreaseNet& n, const NetIncidence& inc, int q, int k) {
  if (n.sharp[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)]) return -1;
  const auto& a = n.quads[static_cast<std::size_t>(q)];
  const int from = a[static_cast<std::size_t>(k)], to = a[static_cast<std::size_t>((k + 1) % 4)];
  for (const auto& [r, i] : inc[static_cast<std::size_t>(to)])
    if (n.quads[static_cast<std::size_t>(r)][static_cast<std::size_t>((i + 1) % 4)] == from) return r;
  return -1;
}

// The neighbours of a crease vertex along its crease edges in the net.
std::vector<int> crease_edges(const CreaseNet& n, const NetIncidence& inc, int v) {
  std::vector<int> nb;
  for (const auto& [q, k] : inc[static_cast<std::size_t>(v)]) {
    const auto& a = n.quads[static_cast<std::size_t>(q)];
    const auto& s = n.sharp[static_cast<std::size_t>(q)];
    if (s[static_cast<std::size_t>(k)]) nb.push_back(a[static_cast<std::size_t>((k + 1) % 4)]);
    if (s[static_cast<std::size_t>((k + 3) % 4)]) nb.push_back(a[static_cast<std::size_t>((k + 3) % 4)]);
  }
  std::sort(nb.begin(), nb.end());
  nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  return nb;
}

// The two neighbours of a crease vertex along its crease edges.
std::array<int, 2> crease_neighbours(const CreaseNet& n, const NetIncidence& inc, int v) {
  const std::vector<int> nb = crease_edges(n, inc, v);
  require(nb.size() == 2, [&] { return "crease net: crease vertex " + std::to_string(v) + " has " + std::to_string(nb.size()) + " crease edges, not 2"; });
  return {nb[0], nb[1]};
}

NetPoint net_face_point(const CreaseNet& n, int q) {
  NetPoint f{};
  for (int v : n.quads[static_cast<std::size_t>(q)]) add_scaled(f, n.points[static_cast<std::size_t>(v)], 0.25);
  return f;
}

bool regular_vertex(const CreaseNet& n, const NetIncidence& inc, int v) {
  const std::size_t faces = inc[static_cast<std::size_t>(v)].size();
  switch (n.rules[static_cast<std::size_t>(v)]) {
    case VertexRule::smooth: return faces == 4;
    case VertexRule::crease: return faces == 2;
    case VertexRule::corner: return faces == 1;
    case VertexRule::dart: return false;
  }
  return false;
}

// Unequal knot intervals (NURCC, non_uniform_catmull_clark): the weights of the rules from the intervals of the
// net's sides. Every interval beyond an edge's end is read along its line (line_beyond); where the line ends at
// a crease boundary (an edge across it at its crease vertex, any edge at a corner) the natural end takes the
// edge's own interval, which makes the rules there midpoint knot insertion of the clamped natural-end cubic of
// crease_ends. The same holds at irregular crease vertices and corners (whatever their number of faces): an
// interior edge ends there, and the crease curve continues along its two crease edges.
double side_interval(const CreaseNet& n, int q, int k) {
  return n.intervals.empty() ? 1.0 : n.intervals[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)];
}

bool equal_intervals(const CreaseNet& n) {
  if (n.intervals.empty()) return true;
  const double d0 = n.intervals[0][0];
  for (const auto& q : n.intervals)
    for (double d : q)
      if (std::abs(d - d0) > 1e-12 * d0) return false;
  return true;
}

// The knot interval of edge v-w.
double edge_interval(const CreaseNet& n, const NetIncidence& inc, int v, int w) {
  for (const auto& [q, c] : inc[static_cast<std::size_t>(v)]) {
    const auto& a = n.quads[static_cast<std::size_t>(q)];
    if (a[static_cast<std::size_t>((c + 1) % 4)] == w) return side_interval(n, q, c);
    if (a[static_cast<std::size_t>((c + 3) % 4)] == w) return side_interval(n, q, (c + 3) % 4);
  }
  throw Error("crease net: no edge " + std::to_string(v) + "-" + std::to_string(w));
}

// The quads round vertex v counter-clockwise (quad, corner of v), each the next across the side arriving at v:
// face k lies between spoke k (its side leaving v) and spoke k + 1. Empty when the ring is open in the net.
std::vector<std::array<int, 2>> closed_fan(const CreaseNet& n, const NetIncidence& inc, int v) {
  const auto around = inc[static_cast<std::size_t>(v)];
  std::vector<std::array<int, 2>> fan{around[0]};
  for (;;) {
    const auto [q, c] = fan.back();
    const int r = net_across(n, inc, q, (c + 3) % 4);
    if (r < 0 || fan.size() > around.size()) return {};
    if (r == fan[0][0]) return fan;
    int k = 0;
    while (n.quads[static_cast<std::size_t>(r)][static_cast<std::size_t>(k)] != v) ++k;
    fan.push_back({r, k});
  }
}

// A dart's quads counter-clockwise from the side of its slit whose side leaving v is open to the quad whose side
// arriving at v is the slit's other side: the closed fan of the mesh before it was cut, face k between spoke k and
// spoke k + 1, the slit spoke 0 (and again, from its other side, spoke N). Empty when the ring is not such a fan.
std::vector<std::array<int, 2>> dart_fan(const CreaseNet& n, const NetIncidence& inc, int v) {
  const auto around = inc[static_cast<std::size_t>(v)];
  std::vector<std::array<int, 2>> fan;
  for (const auto& [q, c] : around)
    if (net_across(n, inc, q, c) < 0) fan.push_back({q, c});
  if (fan.size() != 1) return {};
  for (;;) {
    const auto [q, c] = fan.back();
    const int r = net_across(n, inc, q, (c + 3) % 4);
    if (r < 0) return fan.size() == around.size() ? fan : std::vector<std::array<int, 2>>{};
    if (fan.size() >= around.size()) return {};
    int k = 0;
    while (n.quads[static_cast<std::size_t>(r)][static_cast<std::size_t>(k)] != v) ++k;
    fan.push_back({r, k});
  }
}

// The fan of a smooth vertex (closed_fan) or a dart (dart_fan), over which NURCC's smooth rule runs.
std::vector<std::array<int, 2>> smooth_fan(const CreaseNet& n, const NetIncidence& inc, int v) {
  return n.rules[static_cast<std::size_t>(v)] == VertexRule::dart ? dart_fan(n, inc, v) : closed_fan(n, inc, v);
}

// The knot intervals beyond each vertex v on the lines through it, per neighbour w: on the line from w through v,
// the opposite edge of four faces, the other crease edge along a crease, at a star point NURCC's interval across
// (nurcc_across of its spokes). None where the line ends (the natural end) or leaves the net (points the
// evaluation never reads). Built once per net: the rules read them many times.
using NetLines = std::vector<std::vector<std::pair<int, double>>>;

// At four spokes the interval across is the opposite spoke's (nurcc_across weighs it alone, by 1): read directly,
// as the nets' vertices are mostly such.
double spoke_across(std::span<const double> spokes, int k) {
  return spokes.size() == 4 ? spokes[static_cast<std::size_t>((k + 2) % 4)] : nurcc_across(spokes, k);
}

// The lines through vertex v (net_lines' entry).
std::vector<std::pair<int, double>> vertex_lines(const CreaseNet& n, const NetIncidence& inc, int v) {
  std::vector<std::pair<int, double>> at;
  if (inc[static_cast<std::size_t>(v)].empty()) return at;
  if (n.rules[static_cast<std::size_t>(v)] == VertexRule::crease) {
    const std::vector<int> nb = crease_edges(n, inc, v);
    if (nb.size() == 2) at = {{nb[0], edge_interval(n, inc, v, nb[1])}, {nb[1], edge_interval(n, inc, v, nb[0])}};
  } else if (n.rules[static_cast<std::size_t>(v)] == VertexRule::smooth || n.rules[static_cast<std::size_t>(v)] == VertexRule::dart) {
    const auto fan = smooth_fan(n, inc, v);
    std::vector<double> spokes;
    for (const auto& [q, c] : fan) spokes.push_back(side_interval(n, q, c));
    for (std::size_t k = 0; k < fan.size(); ++k)
      at.emplace_back(n.quads[static_cast<std::size_t>(fan[k][0])][static_cast<std::size_t>((fan[k][1] + 1) % 4)], spoke_across(spokes, static_cast<int>(k)));
    // A dart's slit seen from its other side is spoke 0 again.
    if (n.rules[static_cast<std::size_t>(v)] == VertexRule::dart && !fan.empty())
      at.emplace_back(n.quads[static_cast<std::size_t>(fan.back()[0])][static_cast<std::size_t>((fan.back()[1] + 3) % 4)], spoke_across(spokes, 0));
  }
  return at;
}

NetLines net_lines(const CreaseNet& n, const NetIncidence& inc) {
  NetLines lines(n.points.size());
  for (int v = 0; v < static_cast<int>(n.points.size()); ++v) lines[static_cast<std::size_t>(v)] = vertex_lines(n, inc, v);
  return lines;
}

std::optional<double> beyond_in(const std::vector<std::pair<int, double>>& at, int from) {
  for (const auto& [w, d] : at)
    if (w == from) return d;
  return std::nullopt;
}

std::optional<double> line_beyond(const NetLines& lines, int from, int v) { return beyond_in(lines[static_cast<std::size_t>(v)], from); }

// The edge curve point of edge from-to of interval d.
NetPoint curve_point(const CreaseNet& n, const NetLines& lines, int from, int to, double d) {
  const auto w = nurcc_curve_weights(line_beyond(lines, to, from).value_or(d), d, line_beyond(lines, from, to).value_or(d));
  NetPoint r{};
  add_scaled(r, n.points[static_cast<std::size_t>(from)], w[0]);
  add_scaled(r, n.points[static_cast<std::size_t>(to)], w[1]);
  return r;
}

// The face point: the tensor product of the curve rules of its two directions, each with the means of its two
// rows' intervals beyond (equal on a grid; they differ only next to a star point, as in NonUniformStar).
NetPoint nurcc_face_point(const CreaseNet& n, const NetLines& lines, int q) {
  const auto& a = n.quads[static_cast<std::size_t>(q)];
  const auto P = [&](int k) { return a[static_cast<std::size_t>(k)]; };
  // Rows s0 -> e0 and s1 -> e1 of intervals d0, d1.
  const auto weights = [&](int s0, int e0, double d0, int s1, int e1, double d1) {
    const double before = 0.5 * (line_beyond(lines, e0, s0).value_or(d0) + line_beyond(lines, e1, s1).value_or(d1));
    const double after = 0.5 * (line_beyond(lines, s0, e0).value_or(d0) + line_beyond(lines, s1, e1).value_or(d1));
    return nurcc_curve_weights(before, 0.5 * (d0 + d1), after);
  };
  const auto wu = weights(P(0), P(1), side_interval(n, q, 0), P(3), P(2), side_interval(n, q, 2));
  const auto wv = weights(P(0), P(3), side_interval(n, q, 3), P(1), P(2), side_interval(n, q, 1));
  NetPoint f{};
  add_scaled(f, n.points[static_cast<std::size_t>(P(0))], wu[0] * wv[0]);
  add_scaled(f, n.points[static_cast<std::size_t>(P(1))], wu[1] * wv[0]);
  add_scaled(f, n.points[static_cast<std::size_t>(P(2))], wu[1] * wv[1]);
  add_scaled(f, n.points[static_cast<std::size_t>(P(3))], wu[0] * wv[1]);
  return f;
}

// The vertices of the 4 x 4 grid round quads[centre] (eval_uniform_bicubic's layout, -1 where missing beyond a
// crease boundary): the quads round it unfolded onto the grid from their shared sides.
std::array<int, 16> net_slots(const CreaseNet& n, const NetIncidence& inc, int centre = 0) {
  std::vector<std::array<int, 2>> at(n.points.size(), {INT_MIN, 0});
  std::vector<char> done(n.quads.size(), 0);
  static constexpr std::array<std::array<int, 2>, 4> unit{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  for (int k = 0; k < 4; ++k) at[static_cast<std::size_t>(n.quads[static_cast<std::size_t>(centre)][static_cast<std::size_t>(k)])] = unit[static_cast<std::size_t>(k)];
  std::vector<int> todo{centre};
  done[static_cast<std::size_t>(centre)] = 1;
  std::array<int, 16> slot;
  slot.fill(-1);
  while (!todo.empty()) {
    const int q = todo.back();
    todo.pop_back();
    const auto& a = n.quads[static_cast<std::size_t>(q)];
    for (int v : a) {
      const auto [x, y] = at[static_cast<std::size_t>(v)];
      if (x >= -1 && x <= 2 && y >= -1 && y <= 2) slot[static_cast<std::size_t>((x + 1) + 4 * (y + 1))] = v;
    }
    for (int k = 0; k < 4; ++k) {
      const int r = net_across(n, inc, q, k);
      if (r < 0 || done[static_cast<std::size_t>(r)]) continue;
      const int from = a[static_cast<std::size_t>(k)], to = a[static_cast<std::size_t>((k + 1) % 4)];
      const auto pf = at[static_cast<std::size_t>(from)], pt = at[static_cast<std::size_t>(to)];
      // r holds the side to -> from; its next corners lie one step to the left of that direction.
      const std::array<int, 2> d{pf[0] - pt[0], pf[1] - pt[1]}, left{-d[1], d[0]};
      const auto& b = n.quads[static_cast<std::size_t>(r)];
      int i = 0;
      while (b[static_cast<std::size_t>(i)] != to) ++i;
      const std::array<int, 2> p2{pf[0] + left[0], pf[1] + left[1]}, p3{pt[0] + left[0], pt[1] + left[1]};
      // Only the quads of the 3 x 3 block round the face.
      if (std::min({p2[0], p3[0], pf[0], pt[0]}) < -1 || std::max({p2[0], p3[0], pf[0], pt[0]}) > 2 ||
          std::min({p2[1], p3[1], pf[1], pt[1]}) < -1 || std::max({p2[1], p3[1], pf[1], pt[1]}) > 2)
        continue;
      at[static_cast<std::size_t>(b[static_cast<std::size_t>((i + 2) % 4)])] = p2;
      at[static_cast<std::size_t>(b[static_cast<std::size_t>((i + 3) % 4)])] = p3;
      done[static_cast<std::size_t>(r)] = 1;
      todo.push_back(r);
    }
  }
  return slot;
}

// The 4 x 4 points of quads[centre] when its corners are regular and the intervals equal, homogeneous: the
// points missing beyond a crease boundary the natural ghosts 2 P0 - P1 (first across one direction, then the
// other: the tensor product at a corner).
std::array<NetPoint, 16> net_grid(const CreaseNet& n, const NetIncidence& inc, int centre = 0) {
  const std::array<int, 16> slot = net_slots(n, inc, centre);
  std::array<NetPoint, 16> g{};
  std::array<bool, 16> have{};
  for (std::size_t s = 0; s < 16; ++s)
    if (slot[s] >= 0) {
      g[s] = n.points[static_cast<std::size_t>(slot[s])];
      have[s] = true;
    }
  const auto idx = [](int x, int y) { return static_cast<std::size_t>((x + 1) + 4 * (y + 1)); };
  for (int pass = 0; pass < 2; ++pass)
    for (int y = -1; y <= 2; ++y)
      for (int x = -1; x <= 2; ++x) {
        const std::size_t s = pass == 0 ? idx(x, y) : idx(y, x);
        if (have[s] || (x != -1 && x != 2)) continue;
        const int x0 = x == -1 ? 0 : 1, x1 = x == -1 ? 1 : 0;
        const std::size_t a = pass == 0 ? idx(x0, y) : idx(y, x0), b = pass == 0 ? idx(x1, y) : idx(y, x1);
        if (!have[a] || !have[b]) continue;
        for (std::size_t c = 0; c < 4; ++c) g[s][c] = 2 * g[a][c] - g[b][c];
        have[s] = true;
      }
  require(std::all_of(have.begin(), have.end(), [](bool h) { return h; }), [] { return std::string("crease net: the points round a regular sub-face are not a 4 x 4 grid"); });
  return g;
}

void eval_net_bicubic(const std::array<NetPoint, 16>& g, double u, double v, double scale, double* out) {
  std::array<std::array<double, 3>, 16> x{}, w{};
  for (std::size_t s = 0; s < 16; ++s) {
    x[s] = {g[s][0], g[s][1], g[s][2]};
    w[s] = {g[s][3], 0, 0};
  }
  double a[9], b[9];
  eval_uniform_bicubic(x, u, v, a);
  eval_uniform_bicubic(w, u, v, b);
  for (int k = 0; k < 3; ++k) {
    const double f = k == 0 ? 1 : scale;
    for (int c = 0; c < 3; ++c) out[4 * k + c] = f * a[3 * k + c];
    out[4 * k + 3] = f * b[3 * k];
  }
}

// Unequal intervals: quads[0] as a B-spline cell when the 16 vertices of its grid are regular (then the rules
// that make its sub-faces never reach an irregular vertex: they are knot insertion of this cell), else none. Its
// knots are the intervals of the grid's lines and those beyond its ends; where a line ends at a crease boundary
// (a grid point missing beyond it, or the line ending at its last point) the cell is the clamped natural end of
// crease_ends: the end point P0, then Q1 = a P0 + b P1 (natural_end_weights), repeated knots at the boundary.
std::optional<CreaseFace::Cell> net_cell(const CreaseNet& n, const NetIncidence& inc) {
  const std::array<int, 16> slot = net_slots(n, inc);
  for (int s : slot)
    if (s >= 0 && !regular_vertex(n, inc, s)) return std::nullopt;
  // The lines through the grid's ends alone are read.
  const auto beyond = [&](int from, int v) { return beyond_in(vertex_lines(n, inc, v), from); };
  CreaseFace::Cell cell{};
  std::array<bool, 16> have{};
  for (std::size_t s = 0; s < 16; ++s)
    if (slot[s] >= 0) {
      cell.points[s] = n.points[static_cast<std::size_t>(slot[s])];
      have[s] = true;
    }
  // Direction d: i along it, j across (grid positions -1..2).
  for (int d = 0; d < 2; ++d) {
    const auto idx = [d](int i, int j) { return static_cast<std::size_t>(d == 0 ? (i + 1) + 4 * (j + 1) : (j + 1) + 4 * (i + 1)); };
    const auto at = [&](int i) { return slot[idx(i, 0)]; };
    const bool low_missing = at(-1) < 0, high_missing = at(2) < 0;
    std::array<double, 5> h{};  // intervals -2..2 round the cell [0, 1]
    h[2] = edge_interval(n, inc, at(0), at(1));
    bool low_ends = false, high_ends = false;
    if (!low_missing) {
      h[1] = edge_interval(n, inc, at(-1), at(0));
      const auto b = beyond(at(0), at(-1));
      low_ends = !b;
      h[0] = b.value_or(0);
    }
    if (!high_missing) {
      h[3] = edge_interval(n, inc, at(1), at(2));
      const auto b = beyond(at(1), at(2));
      high_ends = !b;
      h[4] = b.value_or(0);
    }
    const auto mix = [](const NetPoint& a, const NetPoint& b, std::array<double, 2> w) {
      NetPoint r{};
      add_scaled(r, a, w[0]);
      add_scaled(r, b, w[1]);
      return r;
    };
    for (int j = -1; j <= 2; ++j) {
      if (!have[idx(0, j)]) continue;  // a row beyond a boundary across: made by the other direction
      std::array<NetPoint, 4> p{}, q{};
      for (int i = 0; i < 4; ++i) p[static_cast<std::size_t>(i)] = q[static_cast<std::size_t>(i)] = cell.points[idx(i - 1, j)];
      if (low_missing) {
        q[0] = p[1];
        q[1] = mix(p[1], p[2], natural_end_weights(h[2], high_missing ? h[2] : h[3]));
      } else if (low_ends) {
        q[0] = mix(p[0], p[1], natural_end_weights(h[1], h[2]));
      }
      if (high_missing) {
        q[3] = p[2];
        q[2] = mix(p[2], p[1], natural_end_weights(h[2], low_missing ? h[2] : h[1]));
      } else if (high_ends) {
        q[3] = mix(p[3], p[2], natural_end_weights(h[3], h[2]));
      }
      for (int i = 0; i < 4; ++i) {
        cell.points[idx(i - 1, j)] = q[static_cast<std::size_t>(i)];
        have[idx(i - 1, j)] = true;
      }
    }
    if (low_missing) h[0] = h[1] = 0;
    if (high_missing) h[3] = h[4] = 0;
    auto& t = cell.knots[static_cast<std::size_t>(d)];
    t[2] = 0;
    t[3] = 1;
    t[4] = 1 + h[3] / h[2];
    t[5] = t[4] + h[4] / h[2];
    t[1] = -h[1] / h[2];
    t[0] = t[1] - h[0] / h[2];
  }
  require(std::all_of(have.begin(), have.end(), [](bool h) { return h; }), [] { return std::string("crease net: the points round a regular sub-face are not a 4 x 4 grid"); });
  return cell;
}

}  // namespace

void eval_cell(const CreaseFace::Cell& c, double u, double v, double scale, double* out) {
  double bu[8], bv[8];
  basis_derivatives(c.knots[0].data(), 3, 2, u, 1, bu);
  basis_derivatives(c.knots[1].data(), 3, 2, v, 1, bv);
  std::fill(out, out + 12, 0.0);
  for (std::size_t t = 0; t < 4; ++t)
    for (std::size_t s = 0; s < 4; ++s) {
      const NetPoint& p = c.points[s + 4 * t];
      const double w0 = bu[s] * bv[t], w1 = bu[4 + s] * bv[t] * scale, w2 = bu[s] * bv[4 + t] * scale;
      for (std::size_t i = 0; i < 4; ++i) {
        out[i] += w0 * p[i];
        out[4 + i] += w1 * p[i];
        out[8 + i] += w2 * p[i];
      }
    }
}

namespace {

// The one ring of vertex v, which its subdivision maps to itself: v, then round its faces in order each face's
// next vertex and diagonal vertex, and for a boundary vertex the last face's previous vertex (empty when open in
// the net).
std::vector<int> one_ring(const CreaseNet& n, const NetIncidence& inc, int v) {
  const auto around = inc[static_cast<std::size_t>(v)];
  const VertexRule rule = n.rules[static_cast<std::size_t>(v)];
  // The faces in order (each next across the side arriving at v), from the one after a crease side if any.
  int q = around[0][0], c = around[0][1];
  bool on_crease = false;
  for (const auto& [r, k] : around)
    if (n.sharp[static_cast<std::size_t>(r)][static_cast<std::size_t>(k)]) q = r, c = k, on_crease = true;
  if (rule == VertexRule::corner && !on_crease) return {};
  const bool closed = rule == VertexRule::smooth || rule == VertexRule::dart;
  std::vector<int> ring{v};
  const std::size_t k = around.size();
  for (std::size_t j = 0; j < k; ++j) {
    const auto& a = n.quads[static_cast<std::size_t>(q)];
    ring.push_back(a[static_cast<std::size_t>((c + 1) % 4)]);
    ring.push_back(a[static_cast<std::size_t>((c + 2) % 4)]);
    if (j + 1 == k) {
      if (!closed) ring.push_back(a[static_cast<std::size_t>((c + 3) % 4)]);
      break;
    }
    const int r = net_across(n, inc, q, (c + 3) % 4);
    if (r < 0) return {};
    c = 0;
    while (n.quads[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] != v) ++c;
    q = r;
  }
  return ring;
}

// The limit at a vertex.
struct CornerLimit {
  NetPoint point;
  std::optional<std::array<NetPoint, 2>> plane;  // tangent vectors
};

// The limit at a vertex from the eigenstructure of its one ring's subdivision matrix S (one solve for both): the
// position l . P with l the left eigenvector of eigenvalue 1 (the rows of S sum to 1), scaled to sum 1; the left
// eigenvectors of the two largest eigenvalues below 1 give tangent vectors l . P (homogeneous). No plane when it is
// not so defined: complex eigenvalues, or the second eigenvalue repeated apart from the first (a crease vertex of
// one face, whose cross direction shares its eigenvalue 1/4 with the crease curve's curvature; of four faces, 0.61
// then 1/2 twice).
CornerLimit eigen_limit(const Eigen::MatrixXd& S, const CreaseNet& n, const std::vector<int>& ring) {
  const auto sz = S.rows();
  const Eigen::EigenSolver<Eigen::MatrixXd> es(S.transpose());
  const auto lambda = [&](Eigen::Index i) { return es.eigenvalues()(i); };
  const Eigen::MatrixXcd vectors = es.eigenvectors();  // computed on the call: kept for the columns below
  const auto apply = [&](Eigen::Index col, double scale) {
    NetPoint x{};
    for (Eigen::Index i = 0; i < sz; ++i)
      add_scaled(x, n.points[static_cast<std::size_t>(ring[static_cast<std::size_t>(i)])], scale * vectors(i, col).real());
    return x;
  };
  Eigen::Index one = 0;
  for (Eigen::Index i = 1; i < sz; ++i)
    if (std::abs(lambda(i) - 1.0) < std::abs(lambda(one) - 1.0)) one = i;
  CornerLimit out{apply(one, 1 / vectors.col(one).real().sum()), std::nullopt};
  for (Eigen::Index i = 0; i < sz; ++i)
    if (std::abs(lambda(i).imag()) > 1e-12) return out;
  std::vector<Eigen::Index> order(static_cast<std::size_t>(sz));
  for (Eigen::Index i = 0; i < sz; ++i) order[static_cast<std::size_t>(i)] = i;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return lambda(a).real() > lambda(b).real(); });
  const double l1 = lambda(order[1]).real(), l2 = lambda(order[2]).real(), l3 = sz > 3 ? lambda(order[3]).real() : 0;
  if (std::abs(lambda(order[0]).real() - 1) > 1e-12 || l1 >= 1 - 1e-12 || (std::abs(l2 - l3) < 1e-9 && std::abs(l1 - l2) > 1e-9))
    return out;
  out.plane = {apply(order[1], 1), apply(order[2], 1)};
  return out;
}

// The subdivision matrix of vertex v's one ring (one_ring, not empty) under the rules with equal intervals. A
// dart's ring closes over its slit: the slit's two sides are one edge, whose edge point is the midpoint.
Eigen::MatrixXd uniform_ring_matrix(const CreaseNet& n, const NetIncidence& inc, int v, const std::vector<int>& ring) {
  const VertexRule rule = n.rules[static_cast<std::size_t>(v)];
  const bool closed = rule == VertexRule::smooth || rule == VertexRule::dart;  // a dart's ring closes over its slit
  const std::size_t k = inc[static_cast<std::size_t>(v)].size();
  const auto sz = static_cast<Eigen::Index>(ring.size());
  const auto e = [&](std::size_t j) { return static_cast<Eigen::Index>(1 + 2 * (j % k)); };  // edge neighbour j
  const auto d = [&](std::size_t j) { return static_cast<Eigen::Index>(2 + 2 * j); };       // diagonal j
  const Eigen::Index last = closed ? -1 : sz - 1;                                              // boundary: e_k
  const auto edge = [&](std::size_t j) { return j == k && last >= 0 ? last : e(j); };  // e_k: e_0 round a smooth vertex
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(sz, sz);
  const auto face = [&](Eigen::Index row, std::size_t j, double w) {  // w times the face point of face j
    for (Eigen::Index x : {Eigen::Index{0}, e(j), d(j), edge(j + 1)}) S(row, x) += w / 4;
  };
  const double kd = static_cast<double>(k);
  if (rule == VertexRule::corner) {
    S(0, 0) = 1;
  } else if (rule == VertexRule::crease) {
    S(0, 0) = 0.75;
    S(0, e(0)) += 0.125;
    S(0, last) += 0.125;
  } else {
    S(0, 0) = (kd - 2) / kd;
    for (std::size_t j = 0; j < k; ++j) {
      S(0, e(j)) += 1 / (kd * kd);
      face(0, j, 1 / (kd * kd));
    }
  }
  for (std::size_t j = 0; j <= k; ++j) {
    if (j == k && closed) break;
    const Eigen::Index row = edge(j);
    if (rule != VertexRule::smooth && (j == 0 || j == k)) {  // along the crease (a dart's slit): the midpoint
      S(row, 0) += 0.5;
      S(row, row) += 0.5;
      continue;
    }
    S(row, 0) += 0.25;
    S(row, row) += 0.25;
    face(row, (j + k - 1) % k, 0.25);
    face(row, j % k, 0.25);
  }
  for (std::size_t j = 0; j < k; ++j) face(d(j), j, 1);
  return S;
}

// The limit position of vertex v by its limit mask (not a dart's: uniform_limit).
NetPoint net_limit_point(const CreaseNet& n, const NetIncidence& inc, int v) {
  const NetPoint& p = n.points[static_cast<std::size_t>(v)];
  NetPoint r{};
  switch (n.rules[static_cast<std::size_t>(v)]) {
    case VertexRule::corner: return p;
    case VertexRule::crease: {
      const auto nb = crease_neighbours(n, inc, v);
      add_scaled(r, p, 4.0 / 6);
      for (int w : nb) add_scaled(r, n.points[static_cast<std::size_t>(w)], 1.0 / 6);
      return r;
    }
    case VertexRule::dart:  // never asked: uniform_limit takes its eigenvector
    case VertexRule::smooth: {
      const double k = static_cast<double>(inc[static_cast<std::size_t>(v)].size());
      add_scaled(r, p, k / (k + 5));
      for (const auto& [q, c] : inc[static_cast<std::size_t>(v)]) {
        const auto& a = n.quads[static_cast<std::size_t>(q)];
        add_scaled(r, n.points[static_cast<std::size_t>(a[static_cast<std::size_t>((c + 1) % 4)])], 4 / (k * (k + 5)));
        add_scaled(r, n.points[static_cast<std::size_t>(a[static_cast<std::size_t>((c + 2) % 4)])], 1 / (k * (k + 5)));
      }
      return r;
    }
  }
  return r;
}


// The limit at vertex v with equal intervals: the position by its limit mask, a dart's from its one ring's
// eigenvector (the slit's midpoint rule moves it off the smooth mask); the tangent plane from the eigenstructure
// (none at a cone point: a corner inside the mesh, whose ring is empty).
CornerLimit uniform_limit(const CreaseNet& n, const NetIncidence& inc, int v) {
  const std::vector<int> ring = one_ring(n, inc, v);
  const bool dart = n.rules[static_cast<std::size_t>(v)] == VertexRule::dart;
  if (ring.empty()) {
    require(!dart, [&] { return "crease net: the one ring of dart " + std::to_string(v) + " is open"; });
    return {net_limit_point(n, inc, v), std::nullopt};
  }
  const CornerLimit frame = eigen_limit(uniform_ring_matrix(n, inc, v, ring), n, ring);
  return {dart ? frame.point : net_limit_point(n, inc, v), frame.plane};
}

constexpr int crease_cached_levels = 12;
constexpr int crease_max_levels = 40;

// One subdivision step of the net's first ring: the children of the quads sharing a vertex with quads[0] (their
// points need only the net's two rings), quads[0]'s four first (its child k is quad k), then four per quad of the
// ring in the net's order. The four sub-faces of quads[0] share it (kept_net; net_grid centred on one).
CreaseNet subdivide(const CreaseNet& n) {
  const NetIncidence inc = net_incidence(n);
  const std::size_t nq = n.quads.size();
  std::vector<char> first(nq, 0);
  first[0] = 1;
  first = net_ring(n, inc, first);
  const bool uniform = equal_intervals(n);
  const NetLines lines = uniform ? NetLines{} : net_lines(n, inc);
  CreaseNet x;
  std::vector<int> vertex_point(n.points.size(), -1), face_pt(nq, -1);
  // Per edge at its smaller end a list (edge_head, then edge_next) of (other end, point); a crease side's other
  // end as -1 - end when it runs from the larger end (a slit between two darts has both its sides between the same
  // two vertices).
  std::vector<int> edge_head(n.points.size(), -1);
  struct EdgePoint {
    int key, id, next;
  };
  std::vector<EdgePoint> edge_point;
  edge_point.reserve(4 * nq);
  // At most 9 new points per quad of the first ring (fewer: they share them).
  const auto ring_quads = static_cast<std::size_t>(std::count(first.begin(), first.end(), 1));
  x.points.reserve(9 * ring_quads);
  x.rules.reserve(9 * ring_quads);
  x.quads.reserve(4 * ring_quads);
  x.sharp.reserve(4 * ring_quads);
  if (!n.intervals.empty()) x.intervals.reserve(4 * ring_quads);
  // Equal intervals: the quads' centroids (their face points), each summed once; the vertex and edge rules read
  // them again.
  std::vector<NetPoint> centroid(uniform ? nq : 0);
  std::vector<char> summed(uniform ? nq : 0, 0);
  const auto centre = [&](int q) -> const NetPoint& {
    if (!summed[static_cast<std::size_t>(q)]) {
      centroid[static_cast<std::size_t>(q)] = net_face_point(n, q);
      summed[static_cast<std::size_t>(q)] = 1;
    }
    return centroid[static_cast<std::size_t>(q)];
  };
  const auto new_point = [&](const NetPoint& p, VertexRule r) {
    x.points.push_back(p);
    x.rules.push_back(r);
    return static_cast<int>(x.points.size()) - 1;
  };
  const auto vertex = [&](int v) {
    int& id = vertex_point[static_cast<std::size_t>(v)];
    if (id >= 0) return id;
    const NetPoint& p = n.points[static_cast<std::size_t>(v)];
    const VertexRule rule = n.rules[static_cast<std::size_t>(v)];
    NetPoint r{};
    if (rule == VertexRule::corner) {
      r = p;
    } else if (rule == VertexRule::crease && uniform) {
      add_scaled(r, p, 0.75);
      for (int w : crease_neighbours(n, inc, v)) add_scaled(r, n.points[static_cast<std::size_t>(w)], 0.125);
    } else if (rule == VertexRule::crease) {
      // The crease curve's vertex rule with its edge curve points.
      const auto nb = crease_neighbours(n, inc, v);
      const double a = edge_interval(n, inc, v, nb[0]), b = edge_interval(n, inc, v, nb[1]);
      const auto w = nurcc_curve_vertex_weights(a, b);
      add_scaled(r, curve_point(n, lines, v, nb[0], a), w[0]);
      add_scaled(r, curve_point(n, lines, v, nb[1], b), w[1]);
      add_scaled(r, p, w[2]);
    } else {
      // Smooth, or a dart: the smooth rule over its fan from one side of the slit to the other, each quad's side
      // leaving v counting its edge once (the slit's two sides, one edge, carry equal points at every level).
      const auto around = inc[static_cast<std::size_t>(v)];
      const double k = static_cast<double>(around.size());
      int open = 0;
      for (const auto& [q, c] : around) open += net_across(n, inc, q, c) < 0;
      require(open == (rule == VertexRule::dart ? 1 : 0), [&] {
        return "crease net: " + std::string(rule == VertexRule::dart ? "dart " : "smooth vertex ") + std::to_string(v) + " has " +
               std::to_string(open) + " open sides in its ring of faces, not " + (rule == VertexRule::dart ? "1" : "0");
      });
      if (uniform) {
        add_scaled(r, p, (k - 2) / k);
        for (const auto& [q, c] : around) {
          add_scaled(r, n.points[static_cast<std::size_t>(n.quads[static_cast<std::size_t>(q)][static_cast<std::size_t>((c + 1) % 4)])], 1 / (k * k));
          add_scaled(r, centre(q), 1 / (k * k));
        }
      } else {
        // NURCC's vertex rule over its spokes in order (the tensor product rule at a vertex of four faces), a dart's
        // from one side of its slit to the other.
        const auto fan = smooth_fan(n, inc, v);
        require(fan.size() == around.size(), [&] { return "crease net: vertex " + std::to_string(v) + " has no fan of faces round it"; });
        std::vector<double> spokes;
        for (const auto& [q, c] : fan) spokes.push_back(side_interval(n, q, c));
        const VertexWeights vw = nurcc_vertex_weights(spokes);
        for (std::size_t j = 0; j < fan.size(); ++j) {
          const auto [q, c] = fan[j];
          add_scaled(r, nurcc_face_point(n, lines, q), vw.faces[j]);
          add_scaled(r, curve_point(n, lines, v, n.quads[static_cast<std::size_t>(q)][static_cast<std::size_t>((c + 1) % 4)], spokes[j]), vw.curves[j]);
        }
        add_scaled(r, p, vw.self);
      }
    }
    return id = new_point(r, rule);
  };
  const auto face = [&](int q) {
    int& id = face_pt[static_cast<std::size_t>(q)];
    return id >= 0 ? id : id = new_point(uniform ? centre(q) : nurcc_face_point(n, lines, q), VertexRule::smooth);
  };
  const auto edge = [&](int q, int k) {
    const auto& a = n.quads[static_cast<std::size_t>(q)];
    const int from = a[static_cast<std::size_t>(k)], to = a[static_cast<std::size_t>((k + 1) % 4)];
    int& head = edge_head[static_cast<std::size_t>(std::min(from, to))];
    const int key = n.sharp[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)] && from > to ? -1 - from : std::max(from, to);
    for (int e = head; e >= 0; e = edge_point[static_cast<std::size_t>(e)].next)
      if (edge_point[static_cast<std::size_t>(e)].key == key) return edge_point[static_cast<std::size_t>(e)].id;
    NetPoint r{};
    const double d = side_interval(n, q, k);
    if (uniform) {
      add_scaled(r, n.points[static_cast<std::size_t>(from)], 0.5);
      add_scaled(r, n.points[static_cast<std::size_t>(to)], 0.5);
    } else {
      r = curve_point(n, lines, from, to, d);
    }
    VertexRule rule = VertexRule::crease;
    if (!n.sharp[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)]) {
      const int o = net_across(n, inc, q, k);
      require(o >= 0, [&] { return "crease net: edge " + std::to_string(from) + "-" + std::to_string(to) + " has one face and is no crease"; });
      if (uniform) {
        const NetPoint &fq = centre(q), &fo = centre(o);
        for (std::size_t c = 0; c < 4; ++c) r[c] = 0.5 * r[c] + 0.25 * (fq[c] + fo[c]);
      } else {
        // (e_o F_q + e_q F_o) / (2 (e_q + e_o)) + M / 2, e the faces' intervals across the edge.
        int j = 0;
        while (n.quads[static_cast<std::size_t>(o)][static_cast<std::size_t>(j)] != to) ++j;
        const double eq = side_interval(n, q, (k + 1) % 4), eo = side_interval(n, o, (j + 1) % 4);
        const NetPoint fq = x.points[static_cast<std::size_t>(face(q))], fo = x.points[static_cast<std::size_t>(face(o))];
        for (std::size_t c = 0; c < 4; ++c) r[c] = 0.5 * r[c] + (eo * fq[c] + eq * fo[c]) / (2 * (eq + eo));
      }
      rule = VertexRule::smooth;
    }
    const int id = new_point(r, rule);
    edge_point.push_back({key, id, head});
    head = static_cast<int>(edge_point.size()) - 1;
    return id;
  };
  for (int q = 0; q < static_cast<int>(nq); ++q) {
    if (!first[static_cast<std::size_t>(q)]) continue;
    for (int c = 0; c < 4; ++c) {
      const auto& a = n.quads[static_cast<std::size_t>(q)];
      const auto& s = n.sharp[static_cast<std::size_t>(q)];
      const int V = vertex(a[static_cast<std::size_t>(c)]), F = face(q);
      const int E = edge(q, c), P = edge(q, (c + 3) % 4);
      // Child c keeps the parent's orientation: its corner 0 is the one with the smallest (u, v) in the parent.
      std::array<int, 4> quad{};
      std::array<bool, 4> sh{};
      const bool sc = s[static_cast<std::size_t>(c)], sp = s[static_cast<std::size_t>((c + 3) % 4)];
      switch (c) {
        case 0: quad = {V, E, F, P}; sh = {sc, false, false, sp}; break;
        case 1: quad = {P, V, E, F}; sh = {sp, sc, false, false}; break;
        case 2: quad = {F, P, V, E}; sh = {false, sp, sc, false}; break;
        default: quad = {E, F, P, V}; sh = {false, false, sp, sc}; break;
      }
      x.quads.push_back(quad);
      x.sharp.push_back(sh);
      if (!n.intervals.empty()) {
        // The child's sides lie along the parent's sides at its corner c (halved: only ratios enter).
        const auto& d = n.intervals[static_cast<std::size_t>(q)];
        const double du = d[c < 2 ? 0 : 2], dv = d[c == 1 || c == 2 ? 1 : 3];
        x.intervals.push_back({du, dv, du, dv});
      }
    }
  }
  return x;
}

// The net kept round child `child` of the parent's quads[0] in its subdivision x: its two rings, renumbered, with
// that child as quads[0] and the others in the order of a subdivision made for that child alone (quads[0]'s
// children with `child` swapped to the front, then the ring's), so that the rules sum in the same order whether
// the four sub-faces share x or not.
CreaseNet kept_net(const CreaseNet& x, const NetIncidence& xinc, int child) {
  std::vector<char> keep(x.quads.size(), 0);
  keep[static_cast<std::size_t>(child)] = 1;
  keep = net_ring(x, xinc, net_ring(x, xinc, keep));
  // quads[0]'s children with `child` swapped to the front, then the rest.
  std::array<std::size_t, 4> head{0, 1, 2, 3};
  std::swap(head[0], head[static_cast<std::size_t>(child)]);
  CreaseNet y;
  y.points.reserve(x.points.size());
  y.rules.reserve(x.points.size());
  y.quads.reserve(x.quads.size());
  y.sharp.reserve(x.quads.size());
  if (!x.intervals.empty()) y.intervals.reserve(x.quads.size());
  std::vector<int> id(x.points.size(), -1);
  for (std::size_t i = 0; i < x.quads.size(); ++i) {
    const std::size_t q = i < 4 ? head[i] : i;
    if (!keep[q]) continue;
    std::array<int, 4> quad{};
    for (std::size_t k = 0; k < 4; ++k) {
      int& p = id[static_cast<std::size_t>(x.quads[q][k])];
      if (p < 0) {
        p = static_cast<int>(y.points.size());
        y.points.push_back(x.points[static_cast<std::size_t>(x.quads[q][k])]);
        y.rules.push_back(x.rules[static_cast<std::size_t>(x.quads[q][k])]);
      }
      quad[k] = p;
    }
    y.quads.push_back(quad);
    y.sharp.push_back(x.sharp[q]);
    if (!x.intervals.empty()) y.intervals.push_back(x.intervals[q]);
  }
  return y;
}

}  // namespace

CreaseNet refine(const CreaseNet& n, int child) {
  const CreaseNet x = subdivide(n);
  return kept_net(x, net_incidence(x), child);
}

namespace {

// The quarter of [0, 1]^2 that holds (u, v), and (u, v) in it.
int quarter_of(double& u, double& v) {
  const int q = v >= 0.5 ? (u >= 0.5 ? 2 : 3) : (u >= 0.5 ? 1 : 0);
  u = 2 * u - (u >= 0.5 ? 1 : 0);
  v = 2 * v - (v >= 0.5 ? 1 : 0);
  return q;
}

// Unequal intervals: the limit point and tangent plane at the irregular corner c of quads[0] from the eigenvectors
// of its one ring's subdivision matrix, read off refine itself (the rules are linear in the points: S's column j
// is the refined ring of the ring's point j alone). From level 3 on the intervals the rules read round the vertex
// are its spokes' first intervals (halved alike), so the map is the same at every level (stationary).
CornerLimit ring_limit(const CreaseNet& net, int c) {
  CreaseNet a = net;
  for (int l = 0; l < 3; ++l) a = refine(a, c);
  const int v = a.quads[0][static_cast<std::size_t>(c)];
  const std::vector<int> ring = one_ring(a, net_incidence(a), v);
  // A cone point (a corner inside the mesh): interpolated, no tangent plane.
  if (ring.empty() && a.rules[static_cast<std::size_t>(v)] == VertexRule::corner) return {a.points[static_cast<std::size_t>(v)], std::nullopt};
  require(!ring.empty(), "crease net: the one ring of an irregular vertex is open");
  const auto m = static_cast<Eigen::Index>(ring.size());
  // A dart's ring closes over its slit: the slit's other side (the last quad's side arriving at the dart), a vertex
  // of its own in the net, carries the point of its first side (ring[1]) at every level.
  int twin = -1;
  if (a.rules[static_cast<std::size_t>(v)] == VertexRule::dart) {
    const auto fan = dart_fan(a, net_incidence(a), v);
    require(!fan.empty(), "crease net: the fan of a dart is open elsewhere than at its slit");
    twin = a.quads[static_cast<std::size_t>(fan.back()[0])][static_cast<std::size_t>((fan.back()[1] + 3) % 4)];
  }
  Eigen::MatrixXd S(m, m);
  std::vector<int> next;
  for (Eigen::Index j0 = 0; j0 < m; j0 += 4) {
    CreaseNet unit = a;
    for (NetPoint& p : unit.points) p = {};
    for (Eigen::Index t = 0; t < 4 && j0 + t < m; ++t) unit.points[static_cast<std::size_t>(ring[static_cast<std::size_t>(j0 + t)])][static_cast<std::size_t>(t)] = 1;
    if (twin >= 0) unit.points[static_cast<std::size_t>(twin)] = unit.points[static_cast<std::size_t>(ring[1])];
    const CreaseNet b = refine(unit, c);
    if (next.empty()) next = one_ring(b, net_incidence(b), b.quads[0][static_cast<std::size_t>(c)]);
    require(static_cast<Eigen::Index>(next.size()) == m, "crease net: the one ring of an irregular vertex changes under subdivision");
    for (Eigen::Index i = 0; i < m; ++i)
      for (Eigen::Index t = 0; t < 4 && j0 + t < m; ++t) S(i, j0 + t) = b.points[static_cast<std::size_t>(next[static_cast<std::size_t>(i)])][static_cast<std::size_t>(t)];
  }
  return eigen_limit(S, a, ring);
}

}  // namespace

int CreaseFace::build_node(const CreaseNet& net, int level) {
  const int id = static_cast<int>(tree_.size());
  tree_.emplace_back();
  if (auto cell = net_cell(net, net_incidence(net))) {
    tree_[static_cast<std::size_t>(id)].cell = std::move(cell);
  } else if (level == crease_cached_levels) {
    tree_[static_cast<std::size_t>(id)].net = net;
  } else {
    const CreaseNet x = subdivide(net);
    const NetIncidence xinc = net_incidence(x);
    for (int k = 0; k < 4; ++k) {
      const int child = build_node(kept_net(x, xinc, k), level + 1);
      tree_[static_cast<std::size_t>(id)].children[static_cast<std::size_t>(k)] = child;
    }
  }
  return id;
}

CreaseFace::CreaseFace(CreaseNet net) : net_(std::move(net)) {
  for (const NetPoint& p : net_.points) rational_ = rational_ || p[3] != 1.0;
  const NetIncidence inc = net_incidence(net_);
  const bool uniform = equal_intervals(net_);
  bool all_regular = true;
  for (int c = 0; c < 4; ++c) {
    irregular_[static_cast<std::size_t>(c)] = !regular_vertex(net_, inc, net_.quads[0][static_cast<std::size_t>(c)]);
    all_regular = all_regular && !irregular_[static_cast<std::size_t>(c)];
  }
  if (uniform && all_regular) {
    grid_ = net_grid(net_, inc);
    return;
  }
  // Unequal intervals: sub-faces down to those whose 4 x 4 points are regular vertices (B-spline cells; the faces
  // next to an irregular vertex are not, as next to NonUniformStar's star point), also away from the corners.
  if (!uniform) build_node(net_, 0);
  // Sub-faces are regular but at the face's irregular corners (edge and face points are regular vertices): the
  // quarters at regular corners, and along the chain of sub-faces at each irregular corner the three others of
  // every level. One subdivision of a net gives all four sub-faces of its quads[0]: the next net of the chain
  // and the three others.
  const CreaseNet x0 = uniform ? subdivide(net_) : CreaseNet{};
  const NetIncidence inc0 = net_incidence(x0);
  for (int c = 0; c < 4 && uniform; ++c) {
    if (!irregular(c)) {
      quarters_[static_cast<std::size_t>(c)] = net_grid(x0, inc0, c);
      continue;
    }
    auto& chain = chains_[static_cast<std::size_t>(c)];
    auto& side = sides_[static_cast<std::size_t>(c)];
    chain.push_back(kept_net(x0, inc0, c));
    for (int l = 1; l <= crease_cached_levels; ++l) {
      const CreaseNet x = subdivide(chain.back());
      const NetIncidence xinc = net_incidence(x);
      side.emplace_back();
      for (int k = 0; k < 4; ++k)
        if (k != c) side.back()[static_cast<std::size_t>(k)] = net_grid(x, xinc, k);
      chain.push_back(kept_net(x, xinc, c));
    }
  }
  // At an irregular corner: its limit position, and the derivatives 2^-30 into the face along its diagonal (the
  // face's directions there) moved into the limit tangent plane where the eigenstructure defines it.
  static constexpr std::array<std::array<double, 2>, 4> corner_uv{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  const double d = std::ldexp(1.0, -30);
  for (int c = 0; c < 4; ++c) {
    if (!irregular(c)) continue;
    const auto& cu = corner_uv[static_cast<std::size_t>(c)];
    auto& out = corner_values_[static_cast<std::size_t>(c)];
    eval_off_corners(cu[0] == 0 ? d : 1 - d, cu[1] == 0 ? d : 1 - d, out.data());
    const int vc = net_.quads[0][static_cast<std::size_t>(c)];
    // Named members, not a structured binding: clang 14 does not capture bindings in the lambda below.
    const CornerLimit limit = uniform ? uniform_limit(net_, inc, vc) : ring_limit(net_, c);
    const NetPoint& p = limit.point;
    const auto& plane = limit.plane;
    std::copy(p.begin(), p.end(), out.begin());
    if (!plane) continue;
    // Cartesian: the tangents (t - x t_w) / w and the face's derivatives (X' - x W') / W; each derivative loses
    // its component along the plane's normal (X' moves by W times the Cartesian change).
    const double w = p[3];
    const auto cartesian = [&](const double* h) {
      return Eigen::Vector3d((h[0] - p[0] / w * h[3]) / w, (h[1] - p[1] / w * h[3]) / w, (h[2] - p[2] / w * h[3]) / w);
    };
    const Eigen::Vector3d normal = cartesian((*plane)[0].data()).cross(cartesian((*plane)[1].data())).normalized();
    for (int k = 1; k <= 2; ++k) {
      const Eigen::Vector3d off = normal * normal.dot(cartesian(out.data() + 4 * k));
      for (int i = 0; i < 3; ++i) out[static_cast<std::size_t>(4 * k + i)] -= w * off(i);
    }
  }
}

void CreaseFace::for_each_cell(int corner_level, const std::function<void(const Cell&, const std::array<double, 2>&, double)>& f) const {
  // The squares' corners stay exact in doubles down to 2^-61 (t_mesh_patches takes up to 60 levels of a quarter).
  require(corner_level >= 1 && corner_level <= 61, "crease face: corner squares of 2^-1 .. 2^-61 of the face only");
  static constexpr std::array<std::array<double, 2>, 4> corner_uv{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  // Dyadic squares: the comparisons are exact.
  const auto in_corner = [&](const std::array<double, 2>& lo, double side, int level) {
    if (level < corner_level) return false;
    for (int c = 0; c < 4; ++c) {
      const auto& cu = corner_uv[static_cast<std::size_t>(c)];
      if (irregular(c) && (cu[0] == 0 ? lo[0] == 0 : lo[0] + side == 1) && (cu[1] == 0 ? lo[1] == 0 : lo[1] + side == 1)) return true;
    }
    return false;
  };
  const auto child_lo = [](const std::array<double, 2>& lo, double side, int k) {
    return std::array<double, 2>{lo[0] + (k == 1 || k == 2 ? side / 2 : 0), lo[1] + (k >= 2 ? side / 2 : 0)};
  };
  // Past the cached levels the kept nets are refined on; every sub-face away from the corner squares is a cell
  // within a level (its 4 x 4 points then miss the irregular corner).
  const std::function<void(const CreaseNet&, const std::array<double, 2>&, double, int)> net_cells =
      [&](const CreaseNet& net, const std::array<double, 2>& lo, double side, int level) {
        if (in_corner(lo, side, level)) return;
        if (const auto cell = net_cell(net, net_incidence(net))) return f(*cell, lo, side);
        const CreaseNet x = subdivide(net);
        const NetIncidence xinc = net_incidence(x);
        for (int k = 0; k < 4; ++k) net_cells(kept_net(x, xinc, k), child_lo(lo, side, k), side / 2, level + 1);
      };
  const std::function<void(int, const std::array<double, 2>&, double, int)> node_cells =
      [&](int id, const std::array<double, 2>& lo, double side, int level) {
        const Node& node = tree_[static_cast<std::size_t>(id)];
        if (in_corner(lo, side, level)) return;
        if (node.cell) return f(*node.cell, lo, side);
        if (node.net) return net_cells(*node.net, lo, side, level);
        for (int k = 0; k < 4; ++k) node_cells(node.children[static_cast<std::size_t>(k)], child_lo(lo, side, k), side / 2, level + 1);
      };
  if (has_cells()) node_cells(0, {0, 0}, 1, 0);
}

void CreaseFace::eval(double u, double v, double* out) const {
  // Irregular corners stay irregular at every level (edge and face points are regular), so only points at (or
  // within 2^-crease_max_levels of) the face's own irregular corners never reach a regular sub-face.
  static constexpr std::array<std::array<double, 2>, 4> corner_uv{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  const double snap = std::ldexp(1.0, -crease_max_levels);
  for (int c = 0; c < 4; ++c) {
    const auto& cu = corner_uv[static_cast<std::size_t>(c)];
    if (std::abs(u - cu[0]) > snap || std::abs(v - cu[1]) > snap || !irregular(c)) continue;
    std::copy_n(corner_values_[static_cast<std::size_t>(c)].begin(), 12, out);
    return;
  }
  eval_off_corners(u, v, out);
}

void CreaseFace::eval_off_corners(double u, double v, double* out) const {
  if (!tree_.empty()) {
    double scale = 1;
    for (const Node* node = &tree_[0];;) {
      if (node->cell) {
        eval_cell(*node->cell, u, v, scale, out);
        return;
      }
      if (node->net) {
        // Beyond the cached levels (within 2^-crease_cached_levels of an irregular corner): refine on.
        CreaseNet net = *node->net;
        for (;;) {
          const int k = quarter_of(u, v);
          scale *= 2;
          net = refine(net, k);
          if (const auto cell = net_cell(net, net_incidence(net))) {
            eval_cell(*cell, u, v, scale, out);
            return;
          }
        }
      }
      const int k = quarter_of(u, v);
      scale *= 2;
      node = &tree_[static_cast<std::size_t>(node->children[static_cast<std::size_t>(k)])];
    }
  }
  if (grid_) {
    eval_net_bicubic(*grid_, u, v, 1, out);
    return;
  }
  const int c = quarter_of(u, v);
  double scale = 2;
  const auto& chain = chains_[static_cast<std::size_t>(c)];
  if (chain.empty()) {
    eval_net_bicubic(quarters_[static_cast<std::size_t>(c)], u, v, scale, out);
    return;
  }
  // Down the cached chain towards the irregular corner c: chain[l] is the sub-face of level l + 1.
  const auto& side = sides_[static_cast<std::size_t>(c)];
  for (std::size_t l = 0; l < side.size(); ++l) {
    const int k = quarter_of(u, v);
    scale *= 2;
    if (k != c) {
      eval_net_bicubic(side[l][static_cast<std::size_t>(k)], u, v, scale, out);
      return;
    }
  }
  // Beyond the cached levels (within 2^-(crease_cached_levels + 1) of the corner): subdivide on from the last net
  // of the chain, the sub-face at c that the last cached level's (u, v) lies in.
  CreaseNet net = chain.back();
  for (;;) {
    const int k = quarter_of(u, v);
    scale *= 2;
    const CreaseNet x = subdivide(net);
    const NetIncidence xinc = net_incidence(x);
    if (k != c) {
      eval_net_bicubic(net_grid(x, xinc, k), u, v, scale, out);
      return;
    }
    net = kept_net(x, xinc, k);
  }
}

}  // namespace trivar
