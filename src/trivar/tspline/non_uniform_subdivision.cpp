#include "trivar/tspline/non_uniform_subdivision.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/tspline/link_builder.hpp"
#include "trivar/tspline/non_uniform_catmull_clark.hpp"
#include "trivar/tspline/sharp_creases.hpp"

namespace trivar {

namespace {

using H = std::array<double, 4>;  // homogeneous (w x, w y, w z, w)

void add(H& a, const H& b, double s) {
  for (std::size_t c = 0; c < 4; ++c) a[c] += s * b[c];
}

// Why the mesh is not one nurcc_step takes; empty when it is.
std::string unsupported(const TMesh& m) {
  if (m.degree != 3) return "degree " + std::to_string(m.degree) + ", not 3";
  for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    if (loop.empty()) return "face " + std::to_string(f) + " is deleted (a hole)";
    if (loop.size() != 4) return "face " + std::to_string(f) + " is not a quadrilateral without T-junctions";
    for (std::size_t i = 0; i < 4; ++i) {
      const TMeshLink& k = m.links[static_cast<std::size_t>(loop[i])];
      const TMeshLink& o = m.links[static_cast<std::size_t>(k.opp)];
      if (o.face < 0) return "edge " + std::to_string(k.edge) + " is on the boundary (closed meshes only)";
      const double d = m.intervals[static_cast<std::size_t>(k.edge)];
      const double e = m.intervals[static_cast<std::size_t>(m.links[static_cast<std::size_t>(loop[(i + 2) % 4])].edge)];
      if (!(d > 0) || std::abs(d - e) > 1e-12 * d)
        return "face " + std::to_string(f) + " has knot intervals " + std::to_string(d) + " and " + std::to_string(e) +
               " on opposite sides (positive and equal needed)";
    }
  }
  if (has_creases(m) || !m.conditions.empty()) return "it has sharp creases";
  for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v) {
    const TMeshVertex& x = m.vertices[static_cast<std::size_t>(v)];
    if (x.live && (x.primary < 0 || !x.block.empty())) return "vertex " + std::to_string(v) + " has no control point or repeated-knot nodes";
  }
  return {};
}

// The links leaving each vertex counter-clockwise (face(spoke k) lies between spokes k and k + 1), and each link's
// position among its vertex's spokes.
struct Spokes {
  std::vector<std::vector<int>> of;
  std::vector<int> index;
};

Spokes spokes(const TMesh& m) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  Spokes s;
  s.of.resize(m.vertices.size());
  s.index.assign(m.links.size(), -1);
  for (int l0 = 0; l0 < static_cast<int>(m.links.size()); ++l0) {
    const int v = L(l0).vertex;
    if (v < 0 || L(l0).face < 0 || !s.of[static_cast<std::size_t>(v)].empty()) continue;
    auto& ring = s.of[static_cast<std::size_t>(v)];
    int l = l0;
    do {
      s.index[static_cast<std::size_t>(l)] = static_cast<int>(ring.size());
      ring.push_back(l);
      l = L(L(l).prev).opp;
    } while (l != l0 && ring.size() <= m.links.size());
  }
  return s;
}

// Whether the knot intervals of the links that `take` accepts are equal (to 1e-12 relative).
template <class Take>
bool equal_intervals(const TMesh& m, const Take& take) {
  double lo = INFINITY, hi = 0;
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l)
    if (take(l)) {
      const double d = m.intervals[static_cast<std::size_t>(m.links[static_cast<std::size_t>(l)].edge)];
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  return hi - lo <= 1e-12 * hi;
}

}  // namespace

TMesh nurcc_step(const TMesh& m) {
  const std::string why = unsupported(m);
  require(why.empty(), [&] { return "T-mesh: global non-uniform Catmull-Clark step: " + why; });
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const auto d = [&](int l) { return m.intervals[static_cast<std::size_t>(L(l).edge)]; };
  const Spokes sp = spokes(m);
  // across[l]: the interval beyond link l's vertex opposite l (nurcc_across of its vertex's spokes).
  std::vector<double> across(m.links.size(), 0);
  for (const auto& ring : sp.of) {
    std::vector<double> iv;
    for (int l : ring) iv.push_back(d(l));
    for (std::size_t k = 0; k < ring.size(); ++k) across[static_cast<std::size_t>(ring[k])] = nurcc_across(iv, static_cast<int>(k));
  }
  const auto beyond_end = [&](int l) { return across[static_cast<std::size_t>(L(l).opp)]; };  // past l's far end
  std::vector<H> p(m.vertices.size());
  for (std::size_t v = 0; v < p.size(); ++v)
    if (m.vertices[v].live) {
      const RationalPoint& x = m.points[static_cast<std::size_t>(m.vertices[v].primary)];
      p[v] = {x.w * x.xyz[0], x.w * x.xyz[1], x.w * x.xyz[2], x.w};
    }
  const auto P = [&](int l) -> const H& { return p[static_cast<std::size_t>(L(l).vertex)]; };
  // The edge curve point of link l (from its vertex to the next).
  const auto curve = [&](int l) {
    const auto w = nurcc_curve_weights(beyond_end(L(l).opp), d(l), beyond_end(l));
    H c{};
    add(c, P(l), w[0]);
    add(c, P(L(l).next), w[1]);
    return c;
  };
  const int nv = static_cast<int>(m.vertices.size()), ne = static_cast<int>(m.intervals.size()), nf = static_cast<int>(m.faces.size());
  std::vector<H> fp(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    // Corners P0..P3 from the first corner link l0 = P0 -> P1; u along l0, v along l3 reversed.
    const int l0 = m.first_corner(f), l1 = L(l0).next, l2 = L(l1).next, l3 = L(l2).next;
    const double bu = 0.5 * (beyond_end(L(l0).opp) + beyond_end(l2)), au = 0.5 * (beyond_end(l0) + beyond_end(L(l2).opp));
    const double bv = 0.5 * (beyond_end(l3) + beyond_end(L(l1).opp)), av = 0.5 * (beyond_end(L(l3).opp) + beyond_end(l1));
    const auto wu = nurcc_curve_weights(bu, d(l0), au), wv = nurcc_curve_weights(bv, d(l1), av);
    H& c = fp[static_cast<std::size_t>(f)];
    add(c, P(l0), wu[0] * wv[0]);
    add(c, P(l1), wu[1] * wv[0]);
    add(c, P(l2), wu[1] * wv[1]);
    add(c, P(l3), wu[0] * wv[1]);
  }
  const auto F = [&](int l) -> const H& { return fp[static_cast<std::size_t>(L(l).face)]; };
  std::vector<H> ep(static_cast<std::size_t>(ne));
  std::vector<char> done(static_cast<std::size_t>(ne), 0);
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
    if (L(l).vertex < 0 || done[static_cast<std::size_t>(L(l).edge)]) continue;
    done[static_cast<std::size_t>(L(l).edge)] = 1;
    // Each face weighted by the other's interval across the edge.
    const int o = L(l).opp;
    const double ea = d(L(l).next), eb = d(L(o).next);
    H& c = ep[static_cast<std::size_t>(L(l).edge)];
    add(c, F(l), eb / (2 * (ea + eb)));
    add(c, F(o), ea / (2 * (ea + eb)));
    add(c, curve(l), 0.5);
  }
  std::vector<H> vp(p.size());
  for (std::size_t v = 0; v < p.size(); ++v) {
    const auto& ring = sp.of[v];
    if (ring.empty()) continue;
    std::vector<double> iv;
    for (int l : ring) iv.push_back(d(l));
    const VertexWeights vw = nurcc_vertex_weights(iv);
    H& c = vp[v];
    add(c, p[v], vw.self);
    for (std::size_t k = 0; k < ring.size(); ++k) {
      add(c, F(ring[k]), vw.faces[k]);
      add(c, curve(ring[k]), vw.curves[k]);
    }
  }
  TMesh r;
  r.degree = m.degree;
  r.force_bezier = m.force_bezier;
  r.end_conditions = m.end_conditions;
  const auto point = [&](const H& h) {
    r.points.push_back({{h[0] / h[3], h[1] / h[3], h[2] / h[3]}, h[3]});
    r.vertices.push_back({});
    r.vertices.back().primary = static_cast<int>(r.points.size()) - 1;
  };
  for (std::size_t v = 0; v < p.size(); ++v) {
    point(sp.of[v].empty() ? p[v] : vp[v]);
    r.vertices.back().live = m.vertices[v].live && !sp.of[v].empty();
  }
  for (const H& h : ep) point(h.back() != 0 ? h : H{0, 0, 0, 1});  // deleted edges keep their slot
  for (const H& h : fp) point(h);
  for (int e = 0; e < ne; ++e) r.vertices[static_cast<std::size_t>(nv + e)].live = done[static_cast<std::size_t>(e)] != 0;
  // Links, edges and intervals.
  LinkBuilder links(r);
  const auto quad = [&](std::array<int, 4> v, std::array<double, 4> iv) { links.add_face(v, std::array<char, 4>{}, iv); };
  for (int f = 0; f < nf; ++f) {
    const int l0 = m.first_corner(f), l1 = L(l0).next, l2 = L(l1).next, l3 = L(l2).next;
    const int c0 = L(l0).vertex, c1 = L(l1).vertex, c2 = L(l2).vertex, c3 = L(l3).vertex;
    const int e0 = nv + L(l0).edge, e1 = nv + L(l1).edge, e2 = nv + L(l2).edge, e3 = nv + L(l3).edge, x = nv + ne + f;
    const double hu = d(l0) / 2, hv = d(l1) / 2;
    quad({c0, e0, x, e3}, {hu, hv, hu, hv});
    quad({e0, c1, e1, x}, {hu, hv, hu, hv});
    quad({x, e1, c2, e2}, {hu, hv, hu, hv});
    quad({e3, x, e2, c3}, {hu, hv, hu, hv});
  }
  return r;
}

int nurcc_steps_needed(const TMesh& m, int apart) {
  const auto live = [&](int l) { return m.links[static_cast<std::size_t>(l)].vertex >= 0; };
  if (equal_intervals(m, live)) return 0;  // uniform Catmull-Clark needs no steps
  const std::vector<int> stars = star_points(m);
  if (stars.size() < 2 || !unsupported(m).empty()) return 0;
  const Spokes sp = spokes(m);
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  // Edge distances from a vertex (breadth first over the edges).
  const auto distances = [&](int s) {
    std::vector<int> dist(m.vertices.size(), INT_MAX), front{s};
    dist[static_cast<std::size_t>(s)] = 0;
    for (std::size_t i = 0; i < front.size(); ++i)
      for (int l : sp.of[static_cast<std::size_t>(front[i])]) {
        const int t = L(L(l).next).vertex;
        if (dist[static_cast<std::size_t>(t)] == INT_MAX) {
          dist[static_cast<std::size_t>(t)] = dist[static_cast<std::size_t>(front[i])] + 1;
          front.push_back(t);
        }
      }
    return dist;
  };
  // A star point needs non-uniform Catmull-Clark when the edges of its three rings of faces (ends within 4 edges)
  // have unequal knot intervals.
  int closest = INT_MAX;
  for (int s : stars) {
    const std::vector<int> dist = distances(s);
    if (equal_intervals(m, [&](int l) {
          return L(l).vertex >= 0 && L(l).face >= 0 && dist[static_cast<std::size_t>(L(l).vertex)] <= 4 &&
                 dist[static_cast<std::size_t>(L(L(l).next).vertex)] <= 4;
        }))
      continue;
    for (int t : stars)
      if (t != s) closest = std::min(closest, dist[static_cast<std::size_t>(t)]);
  }
  int steps = 0;
  for (long long gap = closest; closest != INT_MAX && gap < apart; gap *= 2) ++steps;
  return steps;
}

}  // namespace trivar
