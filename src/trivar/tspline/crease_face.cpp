#include "trivar/tspline/crease_face.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>
#include <string>

#include <Eigen/Eigenvalues>

#include "trivar/core/error.hpp"
#include "trivar/tspline/catmull_clark_patch.hpp"

namespace trivar {

namespace {

using NetPoint = std::array<double, 4>;

void add_scaled(NetPoint& a, const NetPoint& b, double s) {
  for (std::size_t i = 0; i < 4; ++i) a[i] += s * b[i];
}

// The quads at each vertex: (quad, corner).
using NetIncidence = std::vector<std::vector<std::array<int, 2>>>;

NetIncidence net_incidence(const CreaseNet& n) {
  NetIncidence inc(n.points.size());
  for (int q = 0; q < static_cast<int>(n.quads.size()); ++q)
    for (int k = 0; k < 4; ++k) inc[static_cast<std::size_t>(n.quads[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)])].push_back({q, k});
  return inc;
}

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

// The two neighbours of a crease vertex along its crease edges.
std::array<int, 2> crease_neighbours(const CreaseNet& n, const NetIncidence& inc, int v) {
  std::vector<int> nb;
  for (const auto& [q, k] : inc[static_cast<std::size_t>(v)]) {
    const auto& a = n.quads[static_cast<std::size_t>(q)];
    const auto& s = n.sharp[static_cast<std::size_t>(q)];
    if (s[static_cast<std::size_t>(k)]) nb.push_back(a[static_cast<std::size_t>((k + 1) % 4)]);
    if (s[static_cast<std::size_t>((k + 3) % 4)]) nb.push_back(a[static_cast<std::size_t>((k + 3) % 4)]);
  }
  std::sort(nb.begin(), nb.end());
  nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
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

// At a vertex, from the eigenstructure of its one ring's subdivision matrix (limit_frame).
struct LimitFrame {
  std::optional<NetPoint> point;                 // a dart's limit position
  std::optional<std::array<NetPoint, 2>> plane;  // tangent vectors
};
LimitFrame limit_frame(const CreaseNet& n, const NetIncidence& inc, int v);

// The limit position of vertex v (its limit mask; a dart's from its eigenvector, limit_frame).
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
    case VertexRule::dart: return *limit_frame(n, inc, v).point;
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

// The 4 x 4 points of quads[0] when its corners are regular (eval_uniform_bicubic's layout), homogeneous: the
// quads round it unfolded onto the grid from their shared sides, the points missing beyond a crease boundary the
// natural ghosts 2 P0 - P1 (first across one direction, then the other: the tensor product at a corner).
std::array<NetPoint, 16> net_grid(const CreaseNet& n, const NetIncidence& inc) {
  std::vector<std::array<int, 2>> at(n.points.size(), {INT_MIN, 0});
  std::vector<char> done(n.quads.size(), 0);
  static constexpr std::array<std::array<int, 2>, 4> unit{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  for (int k = 0; k < 4; ++k) at[static_cast<std::size_t>(n.quads[0][static_cast<std::size_t>(k)])] = unit[static_cast<std::size_t>(k)];
  std::vector<int> todo{0};
  done[0] = 1;
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

// The limit tangent plane at vertex v from the eigenstructure of its one ring's subdivision matrix S (the ring
// maps to itself: v, then round its faces in order each face's next vertex and diagonal vertex, and for a boundary
// vertex the last face's previous vertex): the left eigenvectors of the two largest eigenvalues below 1 give
// tangent vectors l . P (homogeneous). Empty when the plane is not so defined: complex eigenvalues, or the second
// eigenvalue repeated apart from the first (a crease vertex of one face, whose cross direction shares its
// eigenvalue 1/4 with the crease curve's curvature; of four faces, 0.61 then 1/2 twice), or a corner inside the
// mesh (a cone point). A dart's ring closes over its slit (the slit's two sides one edge, whose edge point is the
// midpoint); its limit position is l . P with l the left eigenvector of eigenvalue 1 (summing to 1): the
// midpoint rule on the slit moves it off the smooth mask's.
LimitFrame limit_frame(const CreaseNet& n, const NetIncidence& inc, int v) {
  const auto& around = inc[static_cast<std::size_t>(v)];
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
  const Eigen::EigenSolver<Eigen::MatrixXd> es(S.transpose());
  std::vector<Eigen::Index> order(static_cast<std::size_t>(sz));
  for (Eigen::Index i = 0; i < sz; ++i) order[static_cast<std::size_t>(i)] = i;
  const auto lambda = [&](Eigen::Index i) { return es.eigenvalues()(i); };
  const Eigen::MatrixXcd vectors = es.eigenvectors();  // computed on the call: kept for the columns below
  const auto apply = [&](Eigen::Index col, double scale) {
    NetPoint x{};
    for (Eigen::Index i = 0; i < sz; ++i)
      add_scaled(x, n.points[static_cast<std::size_t>(ring[static_cast<std::size_t>(i)])], scale * vectors(i, col).real());
    return x;
  };
  LimitFrame out;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return std::abs(lambda(a) - 1.0) < std::abs(lambda(b) - 1.0) || (std::abs(lambda(a) - 1.0) == std::abs(lambda(b) - 1.0) && a < b);
  });
  if (rule == VertexRule::dart) out.point = apply(order[0], 1 / vectors.col(order[0]).real().sum());
  for (Eigen::Index i = 0; i < sz; ++i)
    if (std::abs(lambda(i).imag()) > 1e-12) return out;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return lambda(a).real() > lambda(b).real(); });
  const double l1 = lambda(order[1]).real(), l2 = lambda(order[2]).real(), l3 = sz > 3 ? lambda(order[3]).real() : 0;
  if (std::abs(lambda(order[0]).real() - 1) > 1e-12 || l1 >= 1 - 1e-12 || (std::abs(l2 - l3) < 1e-9 && std::abs(l1 - l2) > 1e-9))
    return out;
  out.plane = {apply(order[1], 1), apply(order[2], 1)};
  return out;
}

constexpr int crease_cached_levels = 12;
constexpr int crease_max_levels = 40;

}  // namespace

CreaseNet refine(const CreaseNet& n, int child) {
  const NetIncidence inc = net_incidence(n);
  const std::size_t nq = n.quads.size();
  std::vector<char> first(nq, 0);
  first[0] = 1;
  first = net_ring(n, inc, first);
  CreaseNet x;
  std::vector<int> vertex_point(n.points.size(), -1), face_pt(nq, -1);
  // At the smaller end: (other end, point); a crease side's other end as -1 - end when it runs from the larger end
  // (a slit between two darts has both its sides between the same two vertices).
  std::vector<std::vector<std::array<int, 2>>> edge_point(n.points.size());
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
    } else if (rule == VertexRule::crease) {
      add_scaled(r, p, 0.75);
      for (int w : crease_neighbours(n, inc, v)) add_scaled(r, n.points[static_cast<std::size_t>(w)], 0.125);
    } else {
      // Smooth, or a dart: the smooth rule over its fan from one side of the slit to the other, each quad's side
      // leaving v counting its edge once (the slit's two sides, one edge, carry equal points at every level).
      const auto& around = inc[static_cast<std::size_t>(v)];
      const double k = static_cast<double>(around.size());
      int open = 0;
      for (const auto& [q, c] : around) open += net_across(n, inc, q, c) < 0;
      require(open == (rule == VertexRule::dart ? 1 : 0), [&] {
        return "crease net: " + std::string(rule == VertexRule::dart ? "dart " : "smooth vertex ") + std::to_string(v) + " has " +
               std::to_string(open) + " open sides in its ring of faces, not " + (rule == VertexRule::dart ? "1" : "0");
      });
      add_scaled(r, p, (k - 2) / k);
      for (const auto& [q, c] : around) {
        add_scaled(r, n.points[static_cast<std::size_t>(n.quads[static_cast<std::size_t>(q)][static_cast<std::size_t>((c + 1) % 4)])], 1 / (k * k));
        add_scaled(r, net_face_point(n, q), 1 / (k * k));
      }
    }
    return id = new_point(r, rule);
  };
  const auto face = [&](int q) {
    int& id = face_pt[static_cast<std::size_t>(q)];
    return id >= 0 ? id : id = new_point(net_face_point(n, q), VertexRule::smooth);
  };
  const auto edge = [&](int q, int k) {
    const auto& a = n.quads[static_cast<std::size_t>(q)];
    const int from = a[static_cast<std::size_t>(k)], to = a[static_cast<std::size_t>((k + 1) % 4)];
    auto& list = edge_point[static_cast<std::size_t>(std::min(from, to))];
    const int key = n.sharp[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)] && from > to ? -1 - from : std::max(from, to);
    for (const auto& [o, id] : list)
      if (o == key) return id;
    NetPoint r{};
    add_scaled(r, n.points[static_cast<std::size_t>(from)], 0.5);
    add_scaled(r, n.points[static_cast<std::size_t>(to)], 0.5);
    VertexRule rule = VertexRule::crease;
    if (!n.sharp[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)]) {
      const int o = net_across(n, inc, q, k);
      require(o >= 0, [&] { return "crease net: edge " + std::to_string(from) + "-" + std::to_string(to) + " has one face and is no crease"; });
      for (std::size_t c = 0; c < 4; ++c) r[c] = 0.5 * r[c] + 0.25 * (net_face_point(n, q)[c] + net_face_point(n, o)[c]);
      rule = VertexRule::smooth;
    }
    const int id = new_point(r, rule);
    list.push_back({key, id});
    return id;
  };
  // The children of the first ring (their points need only the net's two rings); quads[0]'s at `child` first.
  std::vector<int> order;
  for (int q = 0; q < static_cast<int>(nq); ++q)
    if (first[static_cast<std::size_t>(q)]) order.push_back(q);
  for (int q : order) {
    std::array<int, 4> children{0, 1, 2, 3};
    if (q == 0) std::swap(children[0], children[static_cast<std::size_t>(child)]);  // quads[0]'s child `child` first
    for (int c : children) {
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
    }
  }
  // Keep the new quads[0]'s two rings.
  const NetIncidence xinc = net_incidence(x);
  std::vector<char> keep(x.quads.size(), 0);
  keep[0] = 1;
  keep = net_ring(x, xinc, net_ring(x, xinc, keep));
  CreaseNet y;
  std::vector<int> id(x.points.size(), -1);
  for (std::size_t q = 0; q < x.quads.size(); ++q) {
    if (!keep[q]) continue;
    std::array<int, 4> quad{};
    for (std::size_t k = 0; k < 4; ++k) {
      int& i = id[static_cast<std::size_t>(x.quads[q][k])];
      if (i < 0) {
        i = static_cast<int>(y.points.size());
        y.points.push_back(x.points[static_cast<std::size_t>(x.quads[q][k])]);
        y.rules.push_back(x.rules[static_cast<std::size_t>(x.quads[q][k])]);
      }
      quad[k] = i;
    }
    y.quads.push_back(quad);
    y.sharp.push_back(x.sharp[q]);
  }
  return y;
}

namespace {

// The quarter of [0, 1]^2 that holds (u, v), and (u, v) in it.
int quarter_of(double& u, double& v) {
  const int q = v >= 0.5 ? (u >= 0.5 ? 2 : 3) : (u >= 0.5 ? 1 : 0);
  u = 2 * u - (u >= 0.5 ? 1 : 0);
  v = 2 * v - (v >= 0.5 ? 1 : 0);
  return q;
}

}  // namespace

CreaseFace::CreaseFace(CreaseNet net) : net_(std::move(net)) {
  for (const NetPoint& p : net_.points) rational_ = rational_ || p[3] != 1.0;
  const NetIncidence inc = net_incidence(net_);
  bool all_regular = true;
  for (int c = 0; c < 4; ++c) all_regular = all_regular && regular_vertex(net_, inc, net_.quads[0][static_cast<std::size_t>(c)]);
  if (all_regular) {
    grid_ = net_grid(net_, inc);
    return;
  }
  // Sub-faces are regular but at the face's irregular corners (edge and face points are regular vertices): the
  // quarters at regular corners, and along the chain of sub-faces at each irregular corner the three others of
  // every level.
  for (int c = 0; c < 4; ++c) {
    const auto sub = [](const CreaseNet& n, int k) {
      const CreaseNet r = refine(n, k);
      return net_grid(r, net_incidence(r));
    };
    if (regular_vertex(net_, inc, net_.quads[0][static_cast<std::size_t>(c)])) {
      quarters_[static_cast<std::size_t>(c)] = sub(net_, c);
      continue;
    }
    auto& chain = chains_[static_cast<std::size_t>(c)];
    auto& side = sides_[static_cast<std::size_t>(c)];
    for (int l = 1; l <= crease_cached_levels; ++l) {
      chain.push_back(refine(l == 1 ? net_ : chain.back(), c));
      side.emplace_back();
      for (int k = 0; k < 4; ++k)
        if (k != c) side.back()[static_cast<std::size_t>(k)] = sub(chain.back(), k);
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
    const NetPoint p = net_limit_point(net_, inc, vc);
    const LimitFrame frame = limit_frame(net_, inc, vc);
    std::copy(p.begin(), p.end(), out.begin());
    const auto& plane = frame.plane;
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
  for (std::size_t l = 0; l < chain.size(); ++l) {
    const int k = quarter_of(u, v);
    scale *= 2;
    if (k != c) {
      eval_net_bicubic(sides_[static_cast<std::size_t>(c)][l][static_cast<std::size_t>(k)], u, v, scale, out);
      return;
    }
  }
  // Beyond the cached levels (within 2^-crease_cached_levels of the corner): refine on.
  CreaseNet net = chain.back();
  for (;;) {
    const int k = quarter_of(u, v);
    scale *= 2;
    net = refine(net, k);
    if (k != c) {
      eval_net_bicubic(net_grid(net, net_incidence(net)), u, v, scale, out);
      return;
    }
  }
}

}  // namespace trivar
