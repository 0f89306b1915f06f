#include "trivar/tspline/crease_ends.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/tspline/homogeneous_point.hpp"
#include "trivar/tspline/non_uniform_catmull_clark.hpp"
#include "trivar/tspline/sharp_creases.hpp"

namespace trivar {

namespace {

HomogeneousPoint mix(const HomogeneousPoint& a, double sa, const HomogeneousPoint& b, double sb) {
  HomogeneousPoint r{};
  for (std::size_t i = 0; i < 4; ++i) r[i] = sa * a[i] + sb * b[i];
  return r;
}

// The natural end across the boundary along one inward line: Q1 = a P0 + b P1.
struct EndWeights {
  double a, b;
};
EndWeights end_weights(double d1, double d2) {
  const auto [a, b] = natural_end_weights(d1, d2);
  return {a, b};
}

}  // namespace

TMesh bezier_equivalent(const TMesh& given) {
  // Sharp creases inside the mesh: cut open, their sides crease boundaries like the outer one.
  return has_creases(given) ? bezier_equivalent_of_cut(split_creases(given)) : bezier_equivalent_of_cut(given);
}

TMesh bezier_equivalent_of_cut(const TMesh& m) {
  // Bezier end conditions: as they are, unless no vertex carries a block (a file without grip map), where the
  // repeated-knot nodes of every boundary vertex sit on the vertex itself.
  const bool crease = m.end_conditions == EndConditions::subd_creases;
  if (!crease && std::any_of(m.vertices.begin(), m.vertices.end(), [](const TMeshVertex& v) { return !v.block.empty(); })) return m;
  const std::size_t nv = m.vertices.size();
  const int nl = static_cast<int>(m.links.size());
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const auto fail = [&](int v, const std::string& what) {
    const int from = m.vertices[static_cast<std::size_t>(v)].split_from;
    throw Error("T-mesh: boundary vertex " + (from >= 0 ? std::to_string(from) + " (a side of its sharp crease)" : std::to_string(v)) + " " + what);
  };
  require(!crease || m.degree == 3, [&] { return "T-mesh: subdivision-crease boundaries are defined for degree 3, not " + std::to_string(m.degree); });
  const auto in_face = [&](int l) { return L(l).face >= 0 && m.live_face(L(l).face); };
  std::vector<std::vector<int>> leaving(nv);
  for (int l = 0; l < nl; ++l)
    if (L(l).vertex >= 0) leaving[static_cast<std::size_t>(L(l).vertex)].push_back(l);
  const std::vector<int> angle = vertex_angles(m).degrees;
  const auto boundary_links = [&](int v) {
    std::vector<int> out;
    for (int l : leaving[static_cast<std::size_t>(v)])
      if (!in_face(l)) out.push_back(l);
    return out;
  };
  const auto star = [&](int v) {
    const int a = angle[static_cast<std::size_t>(v)];
    return boundary_links(v).empty() ? a != 360 : a > 270;
  };
  const auto other_end = [&](int l) { return L(L(l).opp).vertex; };
  const auto point = [&](int v) {
    const int p = m.vertices[static_cast<std::size_t>(v)].primary;
    require(p >= 0, [&] { return "T-mesh: vertex " + std::to_string(v) + " at the crease boundary has no control point"; });
    return homogeneous(m.points[static_cast<std::size_t>(p)]);
  };
  const auto interval = [&](int l) { return m.intervals[static_cast<std::size_t>(L(l).edge)]; };
  // The second inward knot interval of a boundary node along link k (leaving the boundary vertex): the edge after
  // k's end u on the same line, else the depth of the face beyond u when k runs into a T-junction there, else
  // (u on the boundary across: a line of one interval) the interval of k itself. Near a star point the frames
  // do not say which link is straight on; Catmull-Clark there needs equal intervals.
  const auto second_interval = [&](int k) {
    const int u = other_end(k), back = L(k).opp;
    if (star(u) || L(back).frame < 0) return interval(k);
    for (int l : leaving[static_cast<std::size_t>(u)])
      if (L(l).frame == (L(back).frame + 2) % 4) return interval(l);
    for (int s : leaving[static_cast<std::size_t>(u)]) {
      if (!in_face(s) || L(s).flag != 1) continue;
      int c = L(s).next;
      for (int n = 0; n < nl && L(c).flag != 0; ++n) c = L(c).next;
      double depth = 0;
      for (int n = 0; n < nl; ++n, c = L(c).next) {
        depth += interval(c);
        if (L(L(c).next).flag == 0) break;
      }
      return depth;
    }
    return interval(k);
  };
  TMesh x = m;
  x.end_conditions = EndConditions::bezier;
  x.force_bezier = true;
  const auto add_point = [&](const HomogeneousPoint& h) {
    x.points.push_back(rational(h));
    return static_cast<int>(x.points.size()) - 1;
  };
  // Irregular crease-boundary vertices have no Bezier form: their faces are evaluated by local subdivision
  // (crease_face), the charts of the others keep away from them; their points stay as they are.
  std::vector<char> irregular(nv, 0);
  for (int v : irregular_crease_vertices(m)) irregular[static_cast<std::size_t>(v)] = 1;
  for (std::size_t vi = 0; vi < nv; ++vi) {
    const int v = static_cast<int>(vi);
    if (!m.vertices[vi].live || irregular[vi]) continue;
    const std::vector<int> out = boundary_links(v);
    if (out.empty()) continue;
    if (out.size() != 1) fail(v, "lies on " + std::to_string(out.size()) + " boundary arcs; a crease boundary is converted on one");
    const int o = out[0];
    if (L(o).frame < 0) fail(v, "has no frame direction on its outside link; the end-condition block needs one");
    std::vector<int> interior, faces;  // its links inside faces: into the interior, and all
    for (int l : leaving[vi])
      if (in_face(l)) {
        faces.push_back(l);
        if (in_face(L(l).opp)) interior.push_back(l);
      }
    const HomogeneousPoint p0 = point(v);
    TMeshVertex& xv = x.vertices[vi];
    const std::size_t primary = static_cast<std::size_t>(xv.primary);
    xv.block.clear();
    xv.block_dims = {};
    // Block positions in the vertex frame: outwards is counter-clockwise after the outside link.
    const int outward = (L(o).frame + 1) % 4;
    const int a = angle[vi];
    if (!crease) {
      // A boundary star point keeps no block (its ghost layer takes the vertex as Q0).
      if (a > 270) continue;
      if (a == 270) fail(v, "is a concave corner without end-condition block points; place them in the file's grip map");
      if (m.degree != 3) fail(v, "has no end-condition block points; without a grip map they are placed for degree 3, not " + std::to_string(m.degree));
      xv.block_dims[static_cast<std::size_t>(outward)] = 1;
      if (a == 90) xv.block_dims[static_cast<std::size_t>((outward + 1) % 4)] = 1;
      for (int k = 0; k < (a == 90 ? 3 : 1); ++k) xv.block.push_back(add_point(p0));
      continue;
    }
    if (a == 180) {
      if (interior.empty()) fail(v, "is a T-junction on the boundary (no interior edge); a crease boundary needs one at every boundary vertex");
      const EndWeights w = end_weights(interval(interior[0]), second_interval(interior[0]));
      x.points[primary] = rational(mix(p0, w.a, point(other_end(interior[0])), w.b));
      xv.block_dims[static_cast<std::size_t>(outward)] = 1;
      xv.block = {add_point(p0)};
    } else if (a == 90) {
      // The corner face's links: l along its first side from v, the outside link o along the other boundary
      // edge; the face's points P00 = v, P10, P11, P01 counter-clockwise.
      const int l = faces[0];
      const auto& loop = m.faces[static_cast<std::size_t>(L(l).face)];
      if (loop.size() != 4) fail(v, "is a corner of a face with T-junctions; the crease corner needs a quadrilateral");
      const HomogeneousPoint p10 = point(other_end(l)), p11 = point(L(L(L(l).next).next).vertex), p01 = point(other_end(o));
      const EndWeights s = end_weights(interval(l), second_interval(l)), t = end_weights(interval(o), second_interval(o));
      x.points[primary] = rational(mix(mix(p0, s.a * t.a, p10, s.b * t.a), 1, mix(p01, s.a * t.b, p11, s.b * t.b), 1));
      // Wedge `outward` (opposite l, beyond the edge of o) holds the node a P00 + b P01 of the rule along o and
      // the diagonal node P00; the wedge after it (opposite o) the node a P00 + b P10 of the rule along l.
      const int next = (outward + 1) % 4;
      xv.block_dims[static_cast<std::size_t>(outward)] = 1;
      xv.block_dims[static_cast<std::size_t>(next)] = 1;
      const int across_o = add_point(mix(p0, t.a, p01, t.b)), diagonal = add_point(p0), across_l = add_point(mix(p0, s.a, p10, s.b));
      // Entries in wedge order N, W, S, E (t_mesh.hpp): wedge `outward` (two entries), then `next` (one).
      xv.block = next == 0 ? std::vector<int>{across_l, across_o, diagonal} : std::vector<int>{across_o, diagonal, across_l};
    } else {
      fail(v, "has " + std::to_string(a) + " degrees of faces" + (a == 270 ? " (a concave corner)" : "") +
                  "; a crease boundary is converted at straight and convex boundary vertices");
    }
  }
  return x;
}

}  // namespace trivar
