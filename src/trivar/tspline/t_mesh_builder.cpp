#include "trivar/tspline/t_mesh_builder.hpp"

#include <algorithm>
#include <map>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

TImage t_image_from_segments(std::span<const KnotSegment> segments) {
  // Vertices: end points and crossings.
  std::map<std::array<double, 2>, int> vid;
  TImage im;
  const auto vertex = [&](double s, double t) {
    auto [it, fresh] = vid.try_emplace({s, t}, static_cast<int>(im.vertices.size()));
    if (fresh) im.vertices.push_back({s, t, {-1, -1, -1, -1}});
    return it->second;
  };
  for (const KnotSegment& g : segments)
    require((g.from[0] == g.to[0]) != (g.from[1] == g.to[1]),
            "T-mesh: a knot segment is not axis-parallel or has no length");
  std::vector<std::vector<std::pair<double, int>>> on(segments.size());
  for (std::size_t a = 0; a < segments.size(); ++a) {
    const KnotSegment& g = segments[a];
    const int k = g.from[0] == g.to[0] ? 1 : 0;  // varying parameter
    const double lo = std::min(g.from[k], g.to[k]), hi = std::max(g.from[k], g.to[k]), c = g.from[1 - k];
    const auto add = [&](double x) {
      std::array<double, 2> p;
      p[k] = x;
      p[1 - k] = c;
      on[a].push_back({x, vertex(p[0], p[1])});
    };
    add(lo);
    add(hi);
    for (const KnotSegment& h : segments) {
      const int kh = h.from[0] == h.to[0] ? 1 : 0;
      const double hlo = std::min(h.from[kh], h.to[kh]), hhi = std::max(h.from[kh], h.to[kh]), hc = h.from[1 - kh];
      if (kh == k) {  // collinear overlapping segments share their end points
        if (hc == c)
          for (double x : {hlo, hhi})
            if (x > lo && x < hi) add(x);
      } else if (hc >= lo && hc <= hi && c >= hlo && c <= hhi) {
        add(hc);
      }
    }
  }
  std::map<std::array<int, 2>, int> edge_link;
  for (auto& list : on) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    for (std::size_t i = 0; i + 1 < list.size(); ++i) {
      const int a = list[i].second, b = list[i + 1].second;
      if (edge_link.count({a, b})) continue;
      const int l = add_edge(im, a, b);
      edge_link[{a, b}] = l;
      edge_link[{b, a}] = l + 1;
    }
  }
  connect_vertex_links(im);
  // Faces: from every link not yet used, keep the face on the left (turn left where possible, else straight,
  // else right); counter-clockwise loops are faces, the clockwise one is the outer boundary.
  std::vector<char> used(im.links.size(), 0);
  const auto dir = [&](int l) {
    const TVertex& a = im.vertices[static_cast<std::size_t>(im.link_start(l))];
    const TVertex& b = im.vertices[static_cast<std::size_t>(im.link_end(l))];
    return a.s == b.s ? (b.t > a.t ? 0 : 2) : (b.s > a.s ? 3 : 1);
  };
  for (int l0 = 0; l0 < static_cast<int>(im.links.size()); ++l0) {
    if (used[static_cast<std::size_t>(l0)]) continue;
    TFace f;
    int l = l0, turns = 0;
    do {
      used[static_cast<std::size_t>(l)] = 1;
      f.loop.push_back(l);
      const int d = dir(l);
      const TVertex& v = im.vertices[static_cast<std::size_t>(im.link_end(l))];
      int next = -1;
      for (int turn : {1, 0, 3}) {
        next = v.links[static_cast<std::size_t>((d + turn) % 4)];
        if (next >= 0) {
          turns += turn == 3 ? -1 : turn;
          break;
        }
      }
      require(next >= 0, "T-mesh: a knot segment ends without meeting another (dangling end inside a face)");
      l = next;
    } while (l != l0);
    if (turns == 4) im.faces.push_back(std::move(f));
  }
  validate(im);
  return im;
}

TSpline t_spline_from_segments(const Ints<2>& degrees, std::span<const KnotSegment> segments,
                               const std::function<RationalPoint(double, double, int, int)>& point) {
  for (int k = 0; k < 2; ++k)
    require(degrees[k] >= 1 && degrees[k] <= kMaxDegree, "T-mesh: degree " + std::to_string(degrees[k]) + " out of range");
  TSpline ts;
  ts.degrees = degrees;
  ts.image = t_image_from_segments(segments);
  const Box<2> dom = ts.image.domain();
  // Candidate anchors: vertices, edges (their forward link), faces, each a box. Per direction k the anchor
  // holds nodes when its width fits the parity (odd: zero width, with (p - 1) / 2 more layers on a boundary
  // line; even: positive width, or zero width on a boundary line with p / 2 layers of that end's repeated
  // knots); the layers step inwards from the boundary.
  struct Anchor {
    TAnchorKind kind;
    int id;
    Box<2> box;
  };
  std::vector<Anchor> anchors;
  for (int v = 0; v < static_cast<int>(ts.image.vertices.size()); ++v) {
    const TVertex& x = ts.image.vertices[static_cast<std::size_t>(v)];
    anchors.push_back({TAnchorKind::vertex, v, Box<2>{{x.s, x.t}, {x.s, x.t}}});
  }
  for (int l = 0; l < static_cast<int>(ts.image.links.size()); ++l)
    if (ts.image.links[static_cast<std::size_t>(l)].sense)
      anchors.push_back({TAnchorKind::link, l, ts.image.edge_box(ts.image.links[static_cast<std::size_t>(l)].edge)});
  for (int f = 0; f < static_cast<int>(ts.image.faces.size()); ++f)
    anchors.push_back({TAnchorKind::face, f, ts.image.face_box(f)});
  for (const Anchor& an : anchors) {
    std::array<int, 2> lo{0, 0}, hi{0, 0};
    bool fits = true;
    for (int k = 0; k < 2; ++k) {
      const int p = degrees[k];
      const bool width = an.box.hi[k] > an.box.lo[k];
      const bool at_lo = !width && an.box.lo[k] == dom.lo[k], at_hi = !width && an.box.lo[k] == dom.hi[k];
      const int layers = p % 2 == 1 ? (p - 1) / 2 : p / 2 - 1;
      if (p % 2 == 1 ? width : !width && !at_lo && !at_hi) fits = false;
      if (at_lo) hi[k] = layers;
      if (at_hi) lo[k] = -layers;
    }
    if (!fits) continue;
    std::map<std::array<int, 2>, int> at;
    for (int b = lo[1]; b <= hi[1]; ++b)
      for (int a = lo[0]; a <= hi[0]; ++a) {
        const int id = static_cast<int>(ts.connect.nodes.size());
        at[{a, b}] = id;
        TNode n;
        n.kind = an.kind;
        n.anchor = an.id;
        n.point = id;
        ts.connect.nodes.push_back(n);
        ts.pointset.points.push_back(
            point(0.5 * (an.box.lo[0] + an.box.hi[0]), 0.5 * (an.box.lo[1] + an.box.hi[1]), std::abs(a), std::abs(b)));
      }
    static constexpr std::array<std::array<int, 2>, 4> step{{{0, 1}, {-1, 0}, {0, -1}, {1, 0}}};
    for (const auto& [pos, id] : at)
      for (int d = 0; d < 4; ++d) {
        auto it = at.find({pos[0] + step[static_cast<std::size_t>(d)][0], pos[1] + step[static_cast<std::size_t>(d)][1]});
        if (it != at.end()) ts.connect.nodes[static_cast<std::size_t>(id)].neighbours[static_cast<std::size_t>(d)] = it->second;
      }
  }
  validate(ts);
  return ts;
}

}  // namespace trivar
