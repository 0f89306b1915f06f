#include "trivar/tspline/t_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "trivar/core/error.hpp"

namespace trivar {

int TMesh::first_corner(int f) const {
  for (int l : faces[static_cast<std::size_t>(f)])
    if (links[static_cast<std::size_t>(l)].flag == 0) return l;
  throw Error("T-mesh: face " + std::to_string(f) + " has no corner");
}

int straight_link(const TMesh& m, int l) {
  const auto L = [&](int x) -> const TMeshLink& { return m.links[static_cast<std::size_t>(x)]; };
  const auto rot = [&](int x) { return x < 0 || L(x).face < 0 ? -1 : L(L(x).prev).opp; };
  std::array<int, 4> r{L(l).opp, -1, -1, -1};  // back, right, straight, left
  for (std::size_t i = 1; i < 4; ++i) r[i] = rot(r[i - 1]);
  if (r[3] < 0 || rot(r[3]) != r[0]) return -1;
  for (int x : r)
    if (L(x).face < 0 || m.faces[static_cast<std::size_t>(L(x).face)].size() != 4) return -1;
  return r[2];
}

VertexAngles vertex_angles(const TMesh& m) {
  VertexAngles r{std::vector<int>(m.vertices.size(), 0), std::vector<char>(m.vertices.size(), 0)};
  for (const TMeshLink& k : m.links) {
    if (k.vertex < 0) continue;
    if (k.face >= 0 && m.live_face(k.face))
      r.degrees[static_cast<std::size_t>(k.vertex)] += 90 * (k.flag + 1);
    else
      r.boundary[static_cast<std::size_t>(k.vertex)] = 1;
  }
  return r;
}

std::vector<int> star_points(const TMesh& m) {
  const VertexAngles angles = vertex_angles(m);
  std::vector<int> stars;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const int a = angles.degrees[v];
    if (a == 0 || (angles.boundary[v] ? a <= 270 : a == 360)) continue;
    stars.push_back(static_cast<int>(v));
  }
  return stars;
}

bool has_closed_strip(const TMesh& m) {
  const int nl = static_cast<int>(m.links.size());
  // Each link of a live face: its side (0..3 from the face's first corner). A strip in the face entered through
  // link l leaves through the links of the opposite side into the faces beyond them: a directed graph on the
  // links, whose cycles are the closed strips.
  std::vector<int> side(static_cast<std::size_t>(nl), -1);
  std::vector<std::array<std::vector<int>, 4>> sides(m.faces.size());
  for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
    if (!m.live_face(f)) continue;
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    const std::size_t start = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), m.first_corner(f)) - loop.begin());
    int k = -1;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int l = loop[(start + i) % loop.size()];
      if (m.links[static_cast<std::size_t>(l)].flag == 0) ++k;
      side[static_cast<std::size_t>(l)] = k;
      sides[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)].push_back(l);
    }
  }
  const auto successors = [&](int l) -> const std::vector<int>& {
    const TMeshLink& k = m.links[static_cast<std::size_t>(l)];
    return sides[static_cast<std::size_t>(k.face)][static_cast<std::size_t>((side[static_cast<std::size_t>(l)] + 2) % 4)];
  };
  // Depth-first search for a cycle (0 unvisited, 1 on the path, 2 done), without recursion.
  std::vector<char> state(static_cast<std::size_t>(nl), 0);
  for (int root = 0; root < nl; ++root) {
    if (side[static_cast<std::size_t>(root)] < 0 || state[static_cast<std::size_t>(root)]) continue;
    std::vector<std::pair<int, std::size_t>> path{{root, 0}};
    state[static_cast<std::size_t>(root)] = 1;
    while (!path.empty()) {
      auto& [l, i] = path.back();
      const std::vector<int>& out = successors(l);
      if (i == out.size()) {
        state[static_cast<std::size_t>(l)] = 2;
        path.pop_back();
        continue;
      }
      const int n = m.links[static_cast<std::size_t>(out[i++])].opp;
      if (side[static_cast<std::size_t>(n)] < 0) continue;  // the strip leaves the mesh
      if (state[static_cast<std::size_t>(n)] == 1) return true;
      if (state[static_cast<std::size_t>(n)] == 0) {
        state[static_cast<std::size_t>(n)] = 1;
        path.push_back({n, 0});
      }
    }
  }
  return false;
}

TChart t_spline_chart(const TMesh& m, std::span<const int> faces, int seed, bool all_connected) {
  const int nf = static_cast<int>(m.faces.size()), nl = static_cast<int>(m.links.size()),
            nv = static_cast<int>(m.vertices.size()), ne = static_cast<int>(m.intervals.size());
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  std::vector<char> in_set(static_cast<std::size_t>(nf), 0);
  if (faces.empty()) {
    for (int f = 0; f < nf; ++f) in_set[static_cast<std::size_t>(f)] = m.live_face(f) ? 1 : 0;
  } else {
    for (int f : faces) in_set[static_cast<std::size_t>(f)] = 1;
  }
  // Link directions: turn left at every corner; opposite links point the other way.
  std::vector<int> dir(static_cast<std::size_t>(nl), -1);
  const auto set_dir = [&](int l, int d) {
    int& x = dir[static_cast<std::size_t>(l)];
    if (x == -1) x = d;
    require(x == d, [&] {
      return "link " + std::to_string(l) + " gets two directions: a star point (extraordinary vertex) or a closed strip of faces near vertex " +
             std::to_string(L(l).vertex);
    });
  };
  set_dir(m.first_corner(seed), 3);
  std::vector<char> reached(static_cast<std::size_t>(nf), 0);
  reached[static_cast<std::size_t>(seed)] = 1;
  std::vector<int> stack{seed};
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    std::size_t start = 0;
    while (dir[static_cast<std::size_t>(loop[start])] < 0) ++start;
    int d = dir[static_cast<std::size_t>(loop[start])];
    for (std::size_t i = 1; i <= loop.size(); ++i) {
      const int l = loop[(start + i) % loop.size()];
      if (L(l).flag == 0) d = (d + 1) % 4;
      set_dir(l, d);
    }
    for (int l : loop) {
      set_dir(L(l).opp, (dir[static_cast<std::size_t>(l)] + 2) % 4);
      const int g = L(L(l).opp).face;
      if (g >= 0 && in_set[static_cast<std::size_t>(g)] && !reached[static_cast<std::size_t>(g)]) {
        reached[static_cast<std::size_t>(g)] = 1;
        stack.push_back(g);
      }
    }
  }
  if (all_connected)
    for (int f = 0; f < nf; ++f)
      require(!in_set[static_cast<std::size_t>(f)] || reached[static_cast<std::size_t>(f)], [&] {
        return "face " + std::to_string(f) + " is not connected to face " + std::to_string(seed) + " (one T-spline per file)";
      });
  // Vertex parameters: sums of knot intervals along the directed links from the seed's corner.
  std::vector<std::vector<int>> out_links(static_cast<std::size_t>(nv));
  double extent = 0;
  for (int l = 0; l < nl; ++l)
    if (dir[static_cast<std::size_t>(l)] >= 0) {
      out_links[static_cast<std::size_t>(L(l).vertex)].push_back(l);
      extent += m.intervals[static_cast<std::size_t>(L(l).edge)];
    }
  const double tol = 1e-9 * std::max(extent, 1e-300);
  std::vector<std::array<double, 2>> param(static_cast<std::size_t>(nv));
  std::vector<char> placed(static_cast<std::size_t>(nv), 0);
  const int v0 = L(m.first_corner(seed)).vertex;
  placed[static_cast<std::size_t>(v0)] = 1;
  std::vector<int> vstack{v0};
  while (!vstack.empty()) {
    const int v = vstack.back();
    vstack.pop_back();
    for (int l : out_links[static_cast<std::size_t>(v)]) {
      const int d = dir[static_cast<std::size_t>(l)];
      const int w = L(L(l).opp).vertex;
      std::array<double, 2> p = param[static_cast<std::size_t>(v)];
      p[static_cast<std::size_t>(tdir_axis(d))] += tdir_sign(d) * m.intervals[static_cast<std::size_t>(L(l).edge)];
      if (!placed[static_cast<std::size_t>(w)]) {
        placed[static_cast<std::size_t>(w)] = 1;
        param[static_cast<std::size_t>(w)] = p;
        vstack.push_back(w);
      } else {
        const auto& q = param[static_cast<std::size_t>(w)];
        require(std::abs(p[0] - q[0]) <= tol && std::abs(p[1] - q[1]) <= tol, [&] {
          return "contradictory knot intervals: vertex " + std::to_string(w) + " gets two different (s, t) through edge " +
                 std::to_string(L(l).edge);
        });
      }
    }
  }
  // Merge parameter values that agree up to rounding (interval sums are rounded).
  for (int k = 0; k < 2; ++k) {
    std::vector<std::pair<double, int>> vals;
    for (int v = 0; v < nv; ++v)
      if (placed[static_cast<std::size_t>(v)]) vals.push_back({param[static_cast<std::size_t>(v)][static_cast<std::size_t>(k)], v});
    std::sort(vals.begin(), vals.end());
    double rep = vals.front().first;
    const double base = vals.front().first;
    for (auto& [x, v] : vals) {
      if (x - rep > tol) rep = x;
      param[static_cast<std::size_t>(v)][static_cast<std::size_t>(k)] = rep - base;
    }
  }
  TChart out;
  out.vertex.assign(static_cast<std::size_t>(nv), -1);
  out.face.assign(static_cast<std::size_t>(nf), -1);
  out.link_dir = dir;
  TSpline& ts = out.spline;
  ts.degrees = {m.degree, m.degree};
  ts.force_bezier = m.force_bezier;
  TImage& im = ts.image;
  for (int v = 0; v < nv; ++v)
    if (placed[static_cast<std::size_t>(v)]) {
      out.vertex[static_cast<std::size_t>(v)] = static_cast<int>(im.vertices.size());
      im.vertices.push_back({param[static_cast<std::size_t>(v)][0], param[static_cast<std::size_t>(v)][1], {-1, -1, -1, -1}});
    }
  // Edges run in increasing parameter: from the vertex of their link going north or east.
  std::vector<int> emap(static_cast<std::size_t>(ne), -1), lmap(static_cast<std::size_t>(nl), -1);
  std::vector<int> forward(static_cast<std::size_t>(ne), -1);
  for (int l = 0; l < nl; ++l) {
    const int d = dir[static_cast<std::size_t>(l)];
    if (d == 0 || d == 3) forward[static_cast<std::size_t>(L(l).edge)] = l;
  }
  for (int e = 0; e < ne; ++e) {
    const int l = forward[static_cast<std::size_t>(e)];
    if (l < 0) continue;
    emap[static_cast<std::size_t>(e)] = static_cast<int>(im.edges.size());
    im.edges.push_back({out.vertex[static_cast<std::size_t>(L(l).vertex)], out.vertex[static_cast<std::size_t>(L(L(l).opp).vertex)]});
  }
  for (int l = 0; l < nl; ++l) {
    const int d = dir[static_cast<std::size_t>(l)];
    if (d < 0) continue;
    lmap[static_cast<std::size_t>(l)] = static_cast<int>(im.links.size());
    im.links.push_back({emap[static_cast<std::size_t>(L(l).edge)], d == 0 || d == 3});
  }
  for (int f = 0; f < nf; ++f) {
    if (!reached[static_cast<std::size_t>(f)]) continue;
    out.face[static_cast<std::size_t>(f)] = static_cast<int>(im.faces.size());
    TFace face;
    for (int l : m.faces[static_cast<std::size_t>(f)]) face.loop.push_back(lmap[static_cast<std::size_t>(l)]);
    im.faces.push_back(std::move(face));
  }
  for (const auto& [e, flag] : m.conditions)
    if (emap[static_cast<std::size_t>(e)] >= 0) im.conditions.push_back({emap[static_cast<std::size_t>(e)], flag != 0});
  connect_vertex_links(im);
  validate(im);
  // Nodes: per vertex its own node at block position (0, 0) and the block's nodes at (a, b) (a east, b north),
  // the block's wedges turned from the vertex frame into the chart's.
  ts.pointset.points = m.points;
  static constexpr std::array<std::array<int, 2>, 4> step{{{0, 1}, {-1, 0}, {0, -1}, {1, 0}}};
  for (int v = 0; v < nv; ++v) {
    const TMeshVertex& x = m.vertices[static_cast<std::size_t>(v)];
    if (!placed[static_cast<std::size_t>(v)] || x.primary < 0) continue;
    std::map<std::array<int, 2>, int> node_at;
    const auto add_node = [&](std::array<int, 2> pos, int point) {
      node_at[pos] = static_cast<int>(ts.connect.nodes.size());
      ts.connect.nodes.push_back({TAnchorKind::vertex, out.vertex[static_cast<std::size_t>(v)], point, {-1, -1, -1, -1}});
    };
    add_node({0, 0}, x.primary);
    if (!x.block.empty()) {
      int rot = -1;
      for (int l : out_links[static_cast<std::size_t>(v)])
        if (L(l).frame >= 0) rot = (dir[static_cast<std::size_t>(l)] - L(l).frame + 4) % 4;
      require(rot >= 0, [&] { return "vertex " + std::to_string(v) + ": its end-condition block has no frame"; });
      std::size_t gi = 0;
      for (int k = 0; k < 4; ++k) {
        const auto& a = step[static_cast<std::size_t>((k + rot) % 4)];
        const auto& c = step[static_cast<std::size_t>((k + 1 + rot) % 4)];
        for (int i = 1; i <= x.block_dims[static_cast<std::size_t>(k)]; ++i)
          for (int j = 0; j <= x.block_dims[static_cast<std::size_t>((k + 1) % 4)]; ++j) {
            const int g = x.block[gi++];
            if (g >= 0) add_node({i * a[0] + j * c[0], i * a[1] + j * c[1]}, g);
          }
      }
    }
    for (const auto& [pos, id] : node_at)
      for (int d = 0; d < 4; ++d) {
        auto it = node_at.find({pos[0] + step[static_cast<std::size_t>(d)][0], pos[1] + step[static_cast<std::size_t>(d)][1]});
        if (it != node_at.end()) ts.connect.nodes[static_cast<std::size_t>(id)].neighbours[static_cast<std::size_t>(d)] = it->second;
      }
  }
  validate(ts);
  return out;
}

}  // namespace trivar
