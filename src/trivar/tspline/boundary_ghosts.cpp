#include "trivar/tspline/boundary_ghosts.hpp"

#include <array>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/tspline/homogeneous_point.hpp"

namespace trivar {

namespace {

HomogeneousPoint combine(const HomogeneousPoint& a, double sa, const HomogeneousPoint& b, double sb, const HomogeneousPoint& c, double sc) {
  HomogeneousPoint r{};
  for (std::size_t i = 0; i < 4; ++i) r[i] = sa * a[i] + sb * b[i] + sc * c[i];
  return r;
}

}  // namespace

GhostedMesh ghost_boundary(const TMesh& m, std::span<const int> stars, int reach) {
  GhostedMesh g{m, std::vector<int>(m.vertices.size(), -1)};
  TMesh& x = g.mesh;
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const int nl = static_cast<int>(m.links.size());
  const auto target = [&](int l) { return l < 0 || L(l).next < 0 || L(l).next >= nl ? -1 : L(L(l).next).vertex; };
  const auto is_face = [&](int f) { return f >= 0 && f < static_cast<int>(m.faces.size()) && m.live_face(f); };
  const auto opp_face = [&](int l) { return L(l).opp >= 0 && L(l).opp < nl && is_face(L(L(l).opp).face); };
  // Links leaving each vertex.
  std::vector<std::vector<int>> leaving(m.vertices.size());
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l)
    if (L(l).vertex >= 0) leaving[static_cast<std::size_t>(L(l).vertex)].push_back(l);
  const auto point = [&](int v) -> const RationalPoint& {
    const int p = m.vertices[static_cast<std::size_t>(v)].primary;
    require(p >= 0, [&] { return "T-mesh: boundary vertex " + std::to_string(v) + " near a boundary star point has no control point"; });
    return m.points[static_cast<std::size_t>(p)];
  };
  // Q0: the single end-condition block point (the vertex itself without a block at a star point).
  const auto block = [&](int v, bool star) -> HomogeneousPoint {
    const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(v)];
    if (mv.block.empty() && star) return homogeneous(point(v));
    require(mv.block.size() == 1 && mv.block[0] >= 0, [&] {
      return "T-mesh: boundary vertex " + std::to_string(v) + " near a boundary star point has " + std::to_string(mv.block.size()) +
             " end-condition block points; the ghost layer needs one";
    });
    return homogeneous(m.points[static_cast<std::size_t>(mv.block[0])]);
  };
  const auto add_point = [&](const HomogeneousPoint& h, int v) {
    require(h[3] > 0, [&] { return "T-mesh: the ghost layer at boundary vertex " + std::to_string(v) + " has weight " + std::to_string(h[3]) + " (weights vary too much near a boundary star point)"; });
    x.points.push_back(rational(h));
    return static_cast<int>(x.points.size()) - 1;
  };
  // A straight boundary vertex: two faces with corners there, one interior edge; its inner end, else -1.
  const auto inner_of_straight = [&](int v) {
    if (v < 0) return -1;
    int faces = 0, inner = -1, interior = 0;
    for (int l : leaving[static_cast<std::size_t>(v)]) {
      if (!is_face(L(l).face)) continue;
      ++faces;
      if (L(l).flag != 0) return -1;
      if (opp_face(l)) {
        ++interior;
        inner = target(l);
      }
    }
    return faces == 2 && interior == 1 ? inner : -1;
  };
  const auto new_link = [&](int vertex, int face, int edge) {
    TMeshLink k;
    k.vertex = vertex;
    k.face = face;
    k.edge = edge;
    x.links.push_back(k);
    return static_cast<int>(x.links.size()) - 1;
  };
  const auto new_edge = [&](double interval) {
    x.intervals.push_back(interval);
    return static_cast<int>(x.intervals.size()) - 1;
  };
  const auto outside = [&](int opp, int vertex) {  // a boundary link of the extended mesh
    const int o = new_link(vertex, -1, x.links[static_cast<std::size_t>(opp)].edge);
    x.links[static_cast<std::size_t>(o)].opp = opp;
    x.links[static_cast<std::size_t>(opp)].opp = o;
  };
  std::vector<int>& ghost = g.ghost;
  std::vector<char> is_star(m.vertices.size(), 0), in_layer(static_cast<std::size_t>(nl), 0);
  for (int v : stars) is_star[static_cast<std::size_t>(v)] = 1;
  // Each star point's chain of boundary links: up to `reach` on either side, between straight vertices. The
  // layer is their union: the ghost rows of a straight vertex do not depend on the star point that asks for them,
  // so layers that overlap (star points close along the boundary, or both ends of a slit) are one layer.
  for (int v : stars) {
    std::vector<int> out;
    for (int l : leaving[static_cast<std::size_t>(v)])
      if (!is_face(L(l).face)) out.push_back(l);
    require(out.size() == 1, [&] {
      return "T-mesh: boundary star point " + std::to_string(v) + " lies on " + std::to_string(out.size()) + " boundary arcs; it is evaluated on one";
    });
    int ahead = 0, behind = 0;
    for (int l = out[0], i = 0; i < reach && l >= 0 && l < nl; ++i, l = L(l).next) {
      const int b = target(l);
      if (b == v || inner_of_straight(b) < 0) break;
      in_layer[static_cast<std::size_t>(l)] = 1;
      ++ahead;
    }
    for (int l = L(out[0]).prev, i = 0; i < reach && l >= 0 && l < nl; ++i, l = L(l).prev) {
      const int a = L(l).vertex;
      if (a == v || inner_of_straight(a) < 0) break;
      in_layer[static_cast<std::size_t>(l)] = 1;
      ++behind;
    }
    require(ahead > 0 && behind > 0, [&] {
      return "T-mesh: boundary star point " + std::to_string(v) + " has a corner or a T-junction next to it on the boundary";
    });
  }
  // Ghost points: P-1 per vertex of the layer, and its point replaced by P0.
  for (int o = 0; o < nl; ++o) {
    if (!in_layer[static_cast<std::size_t>(o)]) continue;
    for (int u : {L(o).vertex, target(o)}) {
      if (ghost[static_cast<std::size_t>(u)] >= 0) continue;
      const bool star = is_star[static_cast<std::size_t>(u)] != 0;
      HomogeneousPoint q2{};
      if (star) {
        int n = 0;
        for (int l : leaving[static_cast<std::size_t>(u)])
          if (is_face(L(l).face) && opp_face(l) && target(l) >= 0) {
            const HomogeneousPoint h = homogeneous(point(target(l)));
            for (std::size_t c = 0; c < 4; ++c) q2[c] += h[c];
            ++n;
          }
        require(n > 0, [&] { return "T-mesh: boundary star point " + std::to_string(u) + " has no interior edge"; });
        for (double& c : q2) c /= n;
      } else {
        q2 = homogeneous(point(inner_of_straight(u)));
      }
      const HomogeneousPoint q0 = block(u, star), q1 = homogeneous(point(u));
      TMeshVertex& mv = x.vertices[static_cast<std::size_t>(u)];
      mv.primary = add_point(combine(q1, 1.5, q2, -0.5, q0, 0), u);
      mv.block.clear();
      mv.block_dims = {};
      TMeshVertex gv;
      gv.primary = add_point(combine(q0, 6, q1, -6, q2, 1), u);
      x.vertices.push_back(gv);
      ghost[static_cast<std::size_t>(u)] = static_cast<int>(x.vertices.size()) - 1;
    }
  }
  // The layer's runs of consecutive boundary links (a whole boundary loop when it closes).
  std::vector<char> placed(static_cast<std::size_t>(nl), 0);
  for (int o = 0; o < nl; ++o) {
    if (!in_layer[static_cast<std::size_t>(o)] || placed[static_cast<std::size_t>(o)]) continue;
    int first = o;
    for (int l = L(o).prev; l >= 0 && l < nl && in_layer[static_cast<std::size_t>(l)] && l != o; l = L(l).prev) first = l;
    std::vector<int> chain;
    for (int l = first; l >= 0 && l < nl && in_layer[static_cast<std::size_t>(l)] && !placed[static_cast<std::size_t>(l)]; l = L(l).next) {
      placed[static_cast<std::size_t>(l)] = 1;
      chain.push_back(l);
    }
    const bool closed = chain.size() > 2 && L(chain.back()).next == chain.front();
    // Ghost faces (a, b, G(b), G(a)) on the outside of each boundary link a -> b of the chain; the link a -> b
    // takes the place of the boundary link as the opposite of the inner face's b -> a.
    int first_side = -1;  // the first face's link G(a) -> a
    int last_side = -1;   // the previous face's link b -> G(b): the opposite of this face's G(a) -> a
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const int c = chain[i], a = L(c).vertex, b = target(c), inner = L(c).opp;
      require(inner >= 0 && inner < nl && L(c).edge >= 0 && L(c).edge < static_cast<int>(m.intervals.size()),
              [&] { return "T-mesh: boundary link " + std::to_string(c) + " has no opposite link or edge"; });
      const int f = static_cast<int>(x.faces.size());
      const int ga = ghost[static_cast<std::size_t>(a)], gb = ghost[static_cast<std::size_t>(b)];
      const double d = m.intervals[static_cast<std::size_t>(L(c).edge)];
      const bool last = i + 1 == chain.size();
      const int l0 = new_link(a, f, L(c).edge);
      const int l1 = new_link(b, f, closed && last ? x.links[static_cast<std::size_t>(first_side)].edge : new_edge(d));
      const int l2 = new_link(gb, f, new_edge(d));
      const int l3 = new_link(ga, f, i == 0 ? new_edge(d) : x.links[static_cast<std::size_t>(last_side)].edge);
      const std::array<int, 4> loop{l0, l1, l2, l3};
      for (std::size_t k = 0; k < 4; ++k) {
        x.links[static_cast<std::size_t>(loop[k])].next = loop[(k + 1) % 4];
        x.links[static_cast<std::size_t>(loop[k])].prev = loop[(k + 3) % 4];
      }
      x.links[static_cast<std::size_t>(l0)].opp = inner;
      x.links[static_cast<std::size_t>(inner)].opp = l0;
      if (i == 0) {
        first_side = l3;
        if (!closed) outside(l3, a);
      } else {
        x.links[static_cast<std::size_t>(l3)].opp = last_side;
        x.links[static_cast<std::size_t>(last_side)].opp = l3;
      }
      outside(l2, ga);
      if (last && closed) {
        x.links[static_cast<std::size_t>(l1)].opp = first_side;
        x.links[static_cast<std::size_t>(first_side)].opp = l1;
      } else if (last) {
        outside(l1, gb);
      }
      last_side = l1;
      x.faces.push_back({l0, l1, l2, l3});
    }
  }
  return g;
}

}  // namespace trivar
