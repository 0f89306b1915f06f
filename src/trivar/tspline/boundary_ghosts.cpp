#include "trivar/tspline/boundary_ghosts.hpp"

#include <array>
#include <deque>
#include <string>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

using Homogeneous = std::array<double, 4>;  // (w x, w y, w z, w)

Homogeneous homogeneous(const RationalPoint& p) { return {p.w * p.xyz[0], p.w * p.xyz[1], p.w * p.xyz[2], p.w}; }

Homogeneous combine(const Homogeneous& a, double sa, const Homogeneous& b, double sb, const Homogeneous& c, double sc) {
  Homogeneous r{};
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
  const auto block = [&](int v, bool star) -> Homogeneous {
    const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(v)];
    if (mv.block.empty() && star) return homogeneous(point(v));
    require(mv.block.size() == 1 && mv.block[0] >= 0, [&] {
      return "T-mesh: boundary vertex " + std::to_string(v) + " near a boundary star point has " + std::to_string(mv.block.size()) +
             " end-condition block points; the ghost layer needs one";
    });
    return homogeneous(m.points[static_cast<std::size_t>(mv.block[0])]);
  };
  const auto add_point = [&](const Homogeneous& h, int v) {
    require(h[3] > 0, [&] { return "T-mesh: the ghost layer at boundary vertex " + std::to_string(v) + " has weight " + std::to_string(h[3]) + " (weights vary too much near a boundary star point)"; });
    x.points.push_back({{h[0] / h[3], h[1] / h[3], h[2] / h[3]}, h[3]});
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
  for (int v : stars) {
    std::vector<int> out;
    for (int l : leaving[static_cast<std::size_t>(v)])
      if (!is_face(L(l).face)) out.push_back(l);
    require(out.size() == 1, [&] {
      return "T-mesh: boundary star point " + std::to_string(v) + " lies on " + std::to_string(out.size()) + " boundary arcs; it is evaluated on one";
    });
    // The chain of boundary links through v: up to `reach` on either side, between straight vertices.
    std::deque<int> chain;
    for (int l = out[0], i = 0; i < reach && l >= 0 && l < nl; ++i, l = L(l).next) {
      const int b = target(l);
      if (b == v || inner_of_straight(b) < 0) break;
      chain.push_back(l);
    }
    const std::size_t ahead = chain.size();
    for (int l = L(out[0]).prev, i = 0; i < reach && l >= 0 && l < nl; ++i, l = L(l).prev) {
      const int a = L(l).vertex;
      if (a == v || inner_of_straight(a) < 0) break;
      chain.push_front(l);
    }
    require(ahead > 0 && chain.size() > ahead, [&] {
      return "T-mesh: boundary star point " + std::to_string(v) + " has a corner or a T-junction next to it on the boundary";
    });
    // Ghost points: P-1 per vertex of the chain, and its point replaced by P0.
    std::vector<int> verts;
    for (int l : chain) verts.push_back(L(l).vertex);
    verts.push_back(target(chain.back()));
    for (int u : verts) {
      require(ghost[static_cast<std::size_t>(u)] < 0, [&] {
        return "T-mesh: boundary vertex " + std::to_string(u) + " lies within " + std::to_string(reach) +
               " edges of two boundary star points; the ghost layers around them overlap";
      });
      const bool star = u == v;
      Homogeneous q2{};
      if (star) {
        int n = 0;
        for (int l : leaving[static_cast<std::size_t>(v)])
          if (is_face(L(l).face) && opp_face(l) && target(l) >= 0) {
            const Homogeneous h = homogeneous(point(target(l)));
            for (std::size_t c = 0; c < 4; ++c) q2[c] += h[c];
            ++n;
          }
        require(n > 0, [&] { return "T-mesh: boundary star point " + std::to_string(v) + " has no interior edge"; });
        for (double& c : q2) c /= n;
      } else {
        q2 = homogeneous(point(inner_of_straight(u)));
      }
      const Homogeneous q0 = block(u, star), q1 = homogeneous(point(u));
      TMeshVertex& mv = x.vertices[static_cast<std::size_t>(u)];
      mv.primary = add_point(combine(q1, 1.5, q2, -0.5, q0, 0), u);
      mv.block.clear();
      mv.block_dims = {};
      TMeshVertex gv;
      gv.primary = add_point(combine(q0, 6, q1, -6, q2, 1), u);
      x.vertices.push_back(gv);
      ghost[static_cast<std::size_t>(u)] = static_cast<int>(x.vertices.size()) - 1;
    }
    // Ghost faces (a, b, G(b), G(a)) on the outside of each boundary link a -> b of the chain; the link a -> b takes
    // the place of the boundary link as the opposite of the inner face's b -> a.
    int last_side = -1;  // the previous face's link b -> G(b): the opposite of this face's G(a) -> a
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const int o = chain[i], a = L(o).vertex, b = target(o), inner = L(o).opp;
      require(inner >= 0 && inner < nl && L(o).edge >= 0 && L(o).edge < static_cast<int>(m.intervals.size()),
              [&] { return "T-mesh: boundary link " + std::to_string(o) + " has no opposite link or edge"; });
      const int f = static_cast<int>(x.faces.size());
      const int ga = ghost[static_cast<std::size_t>(a)], gb = ghost[static_cast<std::size_t>(b)];
      const double d = m.intervals[static_cast<std::size_t>(L(o).edge)];
      const int l0 = new_link(a, f, L(o).edge);
      const int l1 = new_link(b, f, new_edge(d));
      const int l2 = new_link(gb, f, new_edge(d));
      const int l3 = new_link(ga, f, i == 0 ? new_edge(d) : x.links[static_cast<std::size_t>(last_side)].edge);
      const std::array<int, 4> loop{l0, l1, l2, l3};
      for (std::size_t k = 0; k < 4; ++k) {
        x.links[static_cast<std::size_t>(loop[k])].next = loop[(k + 1) % 4];
        x.links[static_cast<std::size_t>(loop[k])].prev = loop[(k + 3) % 4];
      }
      x.links[static_cast<std::size_t>(l0)].opp = inner;
      x.links[static_cast<std::size_t>(inner)].opp = l0;
      if (i == 0)
        outside(l3, a);
      else {
        x.links[static_cast<std::size_t>(l3)].opp = last_side;
        x.links[static_cast<std::size_t>(last_side)].opp = l3;
      }
      outside(l2, ga);
      if (i + 1 == chain.size()) outside(l1, gb);
      last_side = l1;
      x.faces.push_back({l0, l1, l2, l3});
    }
  }
  return g;
}

}  // namespace trivar
