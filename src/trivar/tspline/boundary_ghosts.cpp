#include "trivar/tspline/boundary_ghosts.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <initializer_list>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/tspline/homogeneous_point.hpp"

namespace trivar {

// The blossom of the clamped cubic's first piece [0, d1] with one argument 0 is the quadratic
// c(x, y) = A + B (x + y) + C x y fixed by Q0 = c(0, 0), Q1 = c(0, d1), Q2 = c(d1, d1 + d2); the ghost row is
// P-1 = c(-2 g, -g) and the boundary row P0 = c(-g, d1).
GhostRows clamped_end_rows(const HomogeneousPoint& q0, const HomogeneousPoint& q1, const HomogeneousPoint& q2, double d1, double d2, double g) {
  GhostRows r{};
  for (std::size_t i = 0; i < 4; ++i) {
    const double a = q0[i], b = (q1[i] - q0[i]) / d1, c = (q2[i] - a - b * (2 * d1 + d2)) / (d1 * (d1 + d2));
    r.ghost[i] = a - 3 * g * b + 2 * g * g * c;
    r.point[i] = a + (d1 - g) * b - g * d1 * c;
  }
  return r;
}

namespace {

// The knot intervals across the boundary at a vertex: from it to the next row inside (d1) and on to the one after
// (d2).
struct Spacing {
  double d1 = 1, d2 = 1;
};

GhostRows rows(const HomogeneousPoint& q0, const HomogeneousPoint& q1, const HomogeneousPoint& q2, Spacing s, double g) {
  return clamped_end_rows(q0, q1, q2, s.d1, s.d2, g);
}

}  // namespace

GhostedMesh ghost_boundary(const TMesh& m, std::span<const int> stars, int reach) {
  const std::size_t nv = m.vertices.size();
  GhostedMesh g{m, std::vector<int>(nv, -1)};
  TMesh& x = g.mesh;
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const int nl = static_cast<int>(m.links.size());
  const auto target = [&](int l) { return l < 0 || L(l).next < 0 || L(l).next >= nl ? -1 : L(L(l).next).vertex; };
  const auto is_face = [&](int f) { return f >= 0 && f < static_cast<int>(m.faces.size()) && m.live_face(f); };
  const auto opp_face = [&](int l) { return L(l).opp >= 0 && L(l).opp < nl && is_face(L(L(l).opp).face); };
  // Links leaving each vertex.
  std::vector<std::vector<int>> leaving(nv);
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l)
    if (L(l).vertex >= 0) leaving[static_cast<std::size_t>(L(l).vertex)].push_back(l);
  // is_star: the star points on the boundary (the others only place the layer).
  std::vector<char> is_star(nv, 0), in_layer(static_cast<std::size_t>(nl), 0);
  std::vector<int> boundary_stars;
  for (int v : stars)
    if (std::any_of(leaving[static_cast<std::size_t>(v)].begin(), leaving[static_cast<std::size_t>(v)].end(), [&](int l) { return !is_face(L(l).face); })) {
      is_star[static_cast<std::size_t>(v)] = 1;
      boundary_stars.push_back(v);
    }
  const auto point = [&](int v) -> HomogeneousPoint {
    const int p = m.vertices[static_cast<std::size_t>(v)].primary;
    require(p >= 0, [&] { return "T-mesh: boundary vertex " + std::to_string(v) + " near a boundary star point has no control point"; });
    return homogeneous(m.points[static_cast<std::size_t>(p)]);
  };
  // Q0: the single end-condition block point (the vertex itself without a block at a star point).
  const auto block = [&](int v) -> HomogeneousPoint {
    const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(v)];
    if (mv.block.empty() && is_star[static_cast<std::size_t>(v)]) return point(v);
    require(mv.block.size() == 1 && mv.block[0] >= 0, [&] {
      return "T-mesh: boundary vertex " + std::to_string(v) + " near a boundary star point has " + std::to_string(mv.block.size()) +
             " end-condition block points; the ghost layer needs one";
    });
    return homogeneous(m.points[static_cast<std::size_t>(mv.block[0])]);
  };
  // The block point of corner v at the offset `dirs` (directions of its frame, one step each).
  const auto corner_block = [&](int v, std::initializer_list<int> dirs) -> HomogeneousPoint {
    static constexpr std::array<std::array<int, 2>, 4> step{{{0, 1}, {-1, 0}, {0, -1}, {1, 0}}};  // N, W, S, E
    std::array<int, 2> want{};
    for (int d : dirs)
      for (std::size_t c = 0; c < 2; ++c) want[c] += step[static_cast<std::size_t>(d)][c];
    const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(v)];
    std::size_t gi = 0;
    if (mv.block.size() == 3)
      for (std::size_t k = 0; k < 4; ++k)
        for (int i = 1; i <= mv.block_dims[k]; ++i)
          for (int j = 0; j <= mv.block_dims[(k + 1) % 4] && gi < mv.block.size(); ++j, ++gi) {
            const std::array<int, 2> at{i * step[k][0] + j * step[(k + 1) % 4][0], i * step[k][1] + j * step[(k + 1) % 4][1]};
            if (at == want && mv.block[gi] >= 0) return homogeneous(m.points[static_cast<std::size_t>(mv.block[gi])]);
          }
    throw Error("T-mesh: corner vertex " + std::to_string(v) + " near a boundary star point has no end-condition block of three points (one across "
                "each side and the diagonal one); the ghost layer needs them");
  };
  // A straight boundary vertex: two faces with corners there, one interior edge; the link along it, else -1.
  const auto inner_of_straight = [&](int v) {
    if (v < 0) return -1;
    int faces = 0, inner = -1, interior = 0;
    for (int l : leaving[static_cast<std::size_t>(v)]) {
      if (!is_face(L(l).face)) continue;
      ++faces;
      if (L(l).flag != 0) return -1;
      if (opp_face(l)) {
        ++interior;
        inner = l;
      }
    }
    return faces == 2 && interior == 1 ? inner : -1;
  };
  const auto interval = [&](int l) { return m.intervals[static_cast<std::size_t>(L(l).edge)]; };
  // The intervals along link l and the next link straight on (its own where the line does not go on straight: a
  // vertex there other than of four faces is a star point or a T-junction, whose faces the ghost layer does not
  // make exact).
  const auto spacing_along = [&](int l) {
    const int n = straight_link(m, l);
    return Spacing{interval(l), n >= 0 ? interval(n) : interval(l)};
  };
  // A boundary star point's interior edges (its spokes into the mesh).
  const auto spokes_of = [&](int v) {
    std::vector<int> out;
    for (int l : leaving[static_cast<std::size_t>(v)])
      if (is_face(L(l).face) && opp_face(l) && target(l) >= 0) out.push_back(l);
    require(!out.empty(), [&] { return "T-mesh: boundary star point " + std::to_string(v) + " has no interior edge"; });
    return out;
  };
  // A corner: one face there, a quadrilateral without T-junctions; its link leaving the corner, else -1.
  const auto corner_link = [&](int v) {
    int lf = -1, faces = 0;
    for (int l : leaving[static_cast<std::size_t>(v)])
      if (is_face(L(l).face)) {
        ++faces;
        lf = l;
      }
    if (faces != 1) return -1;
    const auto& loop = m.faces[static_cast<std::size_t>(L(lf).face)];
    const bool quad = loop.size() == 4 && std::all_of(loop.begin(), loop.end(), [&](int l) { return L(l).flag == 0; });
    return quad && L(L(lf).prev).opp >= 0 ? lf : -1;
  };
  // The layer runs through straight vertices and through corners whose two sides are longer than one edge (their
  // neighbours straight, or a star point: the 1-D rule needs the next vertex inside on each side).
  const auto continues = [&](int v) {
    if (inner_of_straight(v) >= 0) return true;
    const int lf = corner_link(v);
    if (lf < 0) return false;
    for (int n : {target(lf), L(L(lf).prev).vertex})
      if (!is_star[static_cast<std::size_t>(n)] && inner_of_straight(n) < 0) return false;
    return true;
  };
  // Steps across faces from the nearest star point (on a grid: the larger of the two index distances).
  std::vector<int> steps(nv, INT_MAX);
  {
    std::vector<std::vector<int>> faces_at(nv);
    for (int f = 0; f < static_cast<int>(m.faces.size()); ++f)
      if (is_face(f))
        for (int l : m.faces[static_cast<std::size_t>(f)]) faces_at[static_cast<std::size_t>(L(l).vertex)].push_back(f);
    std::vector<int> front(stars.begin(), stars.end());
    for (int v : stars) steps[static_cast<std::size_t>(v)] = 0;
    for (int r = 1; r <= reach && !front.empty(); ++r) {
      std::vector<int> next;
      for (int v : front)
        for (int f : faces_at[static_cast<std::size_t>(v)])
          for (int l : m.faces[static_cast<std::size_t>(f)]) {
            const int w = L(l).vertex;
            if (steps[static_cast<std::size_t>(w)] > r) {
              steps[static_cast<std::size_t>(w)] = r;
              next.push_back(w);
            }
          }
      front = std::move(next);
    }
  }
  const auto new_link = [&](int vertex, int face, int edge) {
    TMeshLink k;
    k.vertex = vertex;
    k.face = face;
    k.edge = edge;
    x.links.push_back(k);
    return static_cast<int>(x.links.size()) - 1;
  };
  const auto new_edge = [&](double d) {
    x.intervals.push_back(d);
    return static_cast<int>(x.intervals.size()) - 1;
  };
  const auto outside = [&](int opp, int vertex) {  // a boundary link of the extended mesh
    const int o = new_link(vertex, -1, x.links[static_cast<std::size_t>(opp)].edge);
    x.links[static_cast<std::size_t>(o)].opp = opp;
    x.links[static_cast<std::size_t>(opp)].opp = o;
  };
  const auto add_face = [&](const std::array<int, 4>& loop) {
    for (std::size_t k = 0; k < 4; ++k) {
      x.links[static_cast<std::size_t>(loop[k])].next = loop[(k + 1) % 4];
      x.links[static_cast<std::size_t>(loop[k])].prev = loop[(k + 3) % 4];
    }
    x.faces.push_back({loop.begin(), loop.end()});
  };
  const auto link_pair = [&](int a, int b) {
    x.links[static_cast<std::size_t>(a)].opp = b;
    x.links[static_cast<std::size_t>(b)].opp = a;
  };
  // The layer: the boundary links between vertices within `reach` steps that it runs through (or boundary star
  // points). The ghost rows of a vertex do not depend on the star point that asks for them, so layers that overlap
  // (star points close along the boundary, or both ends of a slit) are one layer.
  const auto in_reach = [&](int u) {
    return u >= 0 && steps[static_cast<std::size_t>(u)] <= reach && (is_star[static_cast<std::size_t>(u)] || continues(u));
  };
  for (int l = 0; l < nl; ++l)
    if (L(l).vertex >= 0 && !is_face(L(l).face) && L(l).next >= 0 && L(l).next < nl) in_layer[static_cast<std::size_t>(l)] = in_reach(L(l).vertex) && in_reach(target(l));
  // A run of the layer that no boundary star point needs (placed by star points inside the mesh) is dropped where a
  // vertex has no end-condition node to build it from (no grip map, a hole's rim): the faces near it stay as
  // without the layer. At a boundary star point such a vertex is an error below.
  const auto has_nodes = [&](int u) {
    const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(u)];
    const auto valid = [&](int b) { return b >= 0; };
    if (is_star[static_cast<std::size_t>(u)] || mv.primary < 0) return is_star[static_cast<std::size_t>(u)] && mv.primary >= 0;
    const int lf = corner_link(u);
    if (lf < 0) return mv.block.size() == 1 && valid(mv.block[0]);
    return mv.block.size() == 3 && std::all_of(mv.block.begin(), mv.block.end(), valid) && L(lf).frame >= 0 && L(L(L(lf).prev).opp).frame >= 0;
  };
  // The layer's runs of consecutive boundary links (a whole boundary loop when it closes).
  const auto layer_runs = [&] {
    std::vector<std::vector<int>> runs;
    std::vector<char> seen(static_cast<std::size_t>(nl), 0);
    for (int o = 0; o < nl; ++o) {
      if (!in_layer[static_cast<std::size_t>(o)] || seen[static_cast<std::size_t>(o)]) continue;
      int first = o;
      for (int l = L(o).prev; l >= 0 && l < nl && in_layer[static_cast<std::size_t>(l)] && l != o; l = L(l).prev) first = l;
      std::vector<int> run;
      for (int l = first; l >= 0 && l < nl && in_layer[static_cast<std::size_t>(l)] && !seen[static_cast<std::size_t>(l)]; l = L(l).next) {
        seen[static_cast<std::size_t>(l)] = 1;
        run.push_back(l);
      }
      runs.push_back(std::move(run));
    }
    return runs;
  };
  for (const std::vector<int>& run : layer_runs()) {
    bool star = false, nodes = true;
    for (int l : run)
      for (int u : {L(l).vertex, target(l)}) {
        star = star || is_star[static_cast<std::size_t>(u)];
        nodes = nodes && has_nodes(u);
      }
    if (!star && !nodes)
      for (int l : run) in_layer[static_cast<std::size_t>(l)] = 0;
  }
  for (int v : boundary_stars) {
    std::vector<int> out;
    for (int l : leaving[static_cast<std::size_t>(v)])
      if (!is_face(L(l).face)) out.push_back(l);
    require(out.size() == 1, [&] {
      return "T-mesh: boundary star point " + std::to_string(v) + " lies on " + std::to_string(out.size()) + " boundary arcs; it is evaluated on one";
    });
    const int behind = L(out[0]).prev;
    const auto star_pair = [&](int l) { return is_star[static_cast<std::size_t>(L(l).vertex)] && is_star[static_cast<std::size_t>(target(l))]; };
    require(in_layer[static_cast<std::size_t>(out[0])] && !star_pair(out[0]) && behind >= 0 && behind < nl &&
                in_layer[static_cast<std::size_t>(behind)] && !star_pair(behind),
            [&] {
              return "T-mesh: boundary star point " + std::to_string(v) +
                     " has a T-junction, a corner with a side of one edge or another star point next to it on the boundary";
            });
  }
  // Ghost points. A straight vertex or a star point: P-1 and its point replaced by P0. A corner: the tensor
  // product of the rule across its two sides (the T-spline there is the product of two clamped ends), on the 3 x 3
  // rows (block, vertex, inside) of each side: its point P(0, 0), a ghost across each side and a diagonal one.
  std::vector<std::array<int, 2>> corner_ghost(nv, {-1, -1});  // a corner's ghosts across its arriving link, diagonal
  // The ghost interval: the interval into the mesh that most vertices of the layer have (straight vertices: their
  // interior edge's; boundary star points: the mean of their interior edges'), so that faces whose intervals are
  // all equal keep the uniform rules through the layer; every interval where they are all equal.
  std::vector<double> into;
  for (int l = 0; l < nl; ++l)
    if (in_layer[static_cast<std::size_t>(l)]) {
      const int u = L(l).vertex;
      if (is_star[static_cast<std::size_t>(u)]) {
        const std::vector<int> spokes = spokes_of(u);
        double mean = 0;
        for (int k : spokes) mean += interval(k) / static_cast<double>(spokes.size());
        into.push_back(mean);
      } else if (const int k = inner_of_straight(u); k >= 0) {
        into.push_back(interval(k));
      }
    }
  std::sort(into.begin(), into.end());
  double gap = into.empty() ? 1 : into.front();
  for (std::size_t i = 0, best = 0; i < into.size();) {
    std::size_t j = i;
    while (j < into.size() && into[j] - into[i] <= 1e-12 * into[i]) ++j;
    if (j - i > best) {
      best = j - i;
      gap = into[i];
    }
    i = j;
  }
  g.interval = gap;
  const auto vertex_rows = [&](int u) {  // a straight vertex or a star point: the mean of its spokes inside
    HomogeneousPoint q2{};
    Spacing sp{0, 0};
    const std::vector<int> inner = is_star[static_cast<std::size_t>(u)] ? spokes_of(u) : std::vector<int>{inner_of_straight(u)};
    const double share = 1.0 / static_cast<double>(inner.size());
    for (int l : inner) {
      const HomogeneousPoint h = point(target(l));
      for (std::size_t c = 0; c < 4; ++c) q2[c] += share * h[c];
      const Spacing a = spacing_along(l);
      sp.d1 += share * a.d1;
      sp.d2 += share * a.d2;
    }
    return rows(block(u), point(u), q2, sp, gap);
  };
  const auto add_point = [&](const HomogeneousPoint& h, int v) {
    require(h[3] > 0, [&] { return "T-mesh: the ghost layer at boundary vertex " + std::to_string(v) + " has weight " + std::to_string(h[3]) + " (weights vary too much near a boundary star point)"; });
    x.points.push_back(rational(h));
    return static_cast<int>(x.points.size()) - 1;
  };
  const auto new_ghost = [&](const HomogeneousPoint& h, int v) {
    TMeshVertex gv;
    gv.primary = add_point(h, v);
    x.vertices.push_back(gv);
    return static_cast<int>(x.vertices.size()) - 1;
  };
  for (int o = 0; o < nl; ++o) {
    if (!in_layer[static_cast<std::size_t>(o)]) continue;
    for (int u : {L(o).vertex, target(o)}) {
      if (g.ghost[static_cast<std::size_t>(u)] >= 0) continue;
      const int lf = is_star[static_cast<std::size_t>(u)] ? -1 : corner_link(u);
      HomogeneousPoint p{}, leaving_ghost{};
      if (lf < 0) {
        const GhostRows r = vertex_rows(u);
        p = r.point;
        leaving_ghost = r.ghost;
      } else {
        // Side a runs along lf (to na), side b along the boundary link leaving u (to nb); the rule runs across the
        // first side on the three lines parallel to it (across the second side), then across the second side. The
        // first side is a's unless only nb is a star point, whose rows (from the mean of its interior edges) then
        // enter as they are.
        const int ob = L(L(lf).prev).opp, na = target(lf), nb = L(L(lf).prev).vertex;
        require(L(lf).frame >= 0 && L(ob).frame >= 0, [&] {
          return "T-mesh: corner vertex " + std::to_string(u) + " near a boundary star point has no frame for its end-condition block";
        });
        const int out_a = (L(ob).frame + 2) % 4, out_b = (L(lf).frame + 2) % 4;  // outwards across sides a and b
        const HomogeneousPoint qa = corner_block(u, {out_a}), qb = corner_block(u, {out_b}), qd = corner_block(u, {out_a, out_b});
        const bool b_first = is_star[static_cast<std::size_t>(nb)] && !is_star[static_cast<std::size_t>(na)];
        const int first = b_first ? nb : na, second = b_first ? na : nb;
        // The intervals along side a from u (lf's, then the boundary's next) and along side b (ob's, then the next).
        const Spacing sa{interval(lf), interval(L(L(ob).prev).prev)}, sb{interval(ob), interval(L(ob).next)};
        const Spacing towards_second = b_first ? sa : sb, towards_first = b_first ? sb : sa;
        const GhostRows r0 = rows(qd, b_first ? qa : qb, block(second), towards_second, gap);
        const GhostRows r1 = rows(b_first ? qb : qa, point(u), point(second), towards_second, gap);
        const GhostRows r2 = vertex_rows(first);
        // The corner's point and its ghost across the second side; its ghost across the first side and the diagonal one.
        const GhostRows on_line = rows(r0.point, r1.point, r2.point, towards_first, gap);
        const GhostRows beyond = rows(r0.ghost, r1.ghost, r2.ghost, towards_first, gap);
        p = on_line.point;
        const HomogeneousPoint& arriving_ghost = b_first ? on_line.ghost : beyond.point;
        leaving_ghost = b_first ? beyond.point : on_line.ghost;
        corner_ghost[static_cast<std::size_t>(u)] = {new_ghost(arriving_ghost, u), new_ghost(beyond.ghost, u)};
      }
      TMeshVertex& mv = x.vertices[static_cast<std::size_t>(u)];
      mv.primary = add_point(p, u);
      mv.block.clear();
      mv.block_dims = {};
      g.ghost[static_cast<std::size_t>(u)] = new_ghost(leaving_ghost, u);
    }
  }
  // The face (c, G_b(c), D(c), G_a(c)) at corner c between the ghost faces of its arriving link (whose side
  // c -> G_a(c) is `arriving_side`) and its leaving link; returns its side c -> G_b(c). Its sides are across the
  // boundary: the ghost interval.
  const auto corner_face = [&](int c, int arriving_side) {
    const int f = static_cast<int>(x.faces.size());
    const auto [ga, gd] = corner_ghost[static_cast<std::size_t>(c)];
    const int gb = g.ghost[static_cast<std::size_t>(c)];
    const int k0 = new_link(c, f, new_edge(gap));
    const int k1 = new_link(gb, f, new_edge(gap));
    const int k2 = new_link(gd, f, new_edge(gap));
    const int k3 = new_link(ga, f, x.links[static_cast<std::size_t>(arriving_side)].edge);
    add_face({k0, k1, k2, k3});
    link_pair(k3, arriving_side);
    outside(k1, gd);
    outside(k2, ga);
    return k0;
  };
  // Each run of the layer, a whole boundary loop started after a vertex that is not a corner.
  for (std::vector<int> chain : layer_runs()) {
    const bool closed = chain.size() > 2 && L(chain.back()).next == chain.front();
    const auto not_corner = [&](int l) { return corner_ghost[static_cast<std::size_t>(L(l).vertex)][0] < 0; };
    if (closed) std::rotate(chain.begin(), std::find_if(chain.begin(), chain.end(), not_corner), chain.end());
    // Ghost faces (a, b, G(b), G(a)) on the outside of each boundary link a -> b of the chain; the link a -> b
    // takes the place of the boundary link as the opposite of the inner face's b -> a.
    int first_side = -1;  // the first face's link G(a) -> a
    int last_side = -1;   // the previous face's link b -> G(b) (or the corner face's c -> G_b(c)): the opposite of this face's G(a) -> a
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const int c = chain[i], a = L(c).vertex, b = target(c), inner = L(c).opp;
      require(inner >= 0 && inner < nl && L(c).edge >= 0 && L(c).edge < static_cast<int>(m.intervals.size()),
              [&] { return "T-mesh: boundary link " + std::to_string(c) + " has no opposite link or edge"; });
      const double d = m.intervals[static_cast<std::size_t>(L(c).edge)];
      if (i > 0 && corner_ghost[static_cast<std::size_t>(a)][0] >= 0)
        last_side = corner_face(a, last_side);
      const int f = static_cast<int>(x.faces.size());
      const int ga = g.ghost[static_cast<std::size_t>(a)];
      const int arriving_ghost = corner_ghost[static_cast<std::size_t>(b)][0];  // b a corner
      const int gb = arriving_ghost >= 0 ? arriving_ghost : g.ghost[static_cast<std::size_t>(b)];
      const bool last = i + 1 == chain.size();
      const int l0 = new_link(a, f, L(c).edge);
      const int l1 = new_link(b, f, closed && last ? x.links[static_cast<std::size_t>(first_side)].edge : new_edge(gap));
      const int l2 = new_link(gb, f, new_edge(d));
      const int l3 = new_link(ga, f, i == 0 ? new_edge(gap) : x.links[static_cast<std::size_t>(last_side)].edge);
      add_face({l0, l1, l2, l3});
      link_pair(l0, inner);
      x.links[static_cast<std::size_t>(c)].vertex = -1;  // the boundary link it replaces: a deleted slot
      x.links[static_cast<std::size_t>(c)].opp = -1;
      if (i == 0) {
        first_side = l3;
        if (!closed) outside(l3, a);
      } else {
        link_pair(l3, last_side);
      }
      outside(l2, ga);
      if (last && closed)
        link_pair(l1, first_side);
      else if (last)
        outside(l1, gb);
      last_side = l1;
    }
  }
  return g;
}

}  // namespace trivar
