#include "trivar/model/trimmed_vertices.hpp"

#include <algorithm>

#include "trivar/core/union_find.hpp"

namespace trivar {

namespace {

using P3 = std::array<double, 3>;

P3 curve_point(const TensorSpline<1>& c, double t) {
  P3 x;
  c.eval({t}, x.data());
  return x;
}

// The trim curve's point at parameter t on its face's surface.
P3 trim_point(const TrimmedFace& f, const TrimCurve& c, double t) {
  double uv[2];
  c.pcurve.eval({t}, uv);
  P3 x;
  f.surface.eval({uv[0], uv[1]}, x.data());
  return x;
}

}  // namespace

TrimmedVertices trimmed_vertices(const TrimmedBoundary& b) {
  const int ne = static_cast<int>(b.edges.size());
  TrimmedVertices r;
  r.edge_vertices.assign(b.edges.size(), {-1, -1});
  r.edge_faces.resize(b.edges.size());
  r.edge_ends.resize(b.edges.size());
  std::vector<char> used(b.edges.size(), 0);
  // Node 2 e is the start of edge e, 2 e + 1 its end. Where a loop passes from one curve to the next, the end
  // of the first (in the loop's direction) is the start of the next.
  UnionFind uf(2 * ne);
  const auto loop_start = [](const TrimCurve& c) { return 2 * c.edge + (c.edge_reversed ? 1 : 0); };
  const auto loop_end = [](const TrimCurve& c) { return 2 * c.edge + (c.edge_reversed ? 0 : 1); };
  int face_term = 0;
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    const TrimmedFace& face = b.faces[f];
    face_term += 2 - static_cast<int>(face.loops.size());
    for (const TrimLoop& loop : face.loops) {
      std::vector<const TrimCurve*> real;
      for (const TrimCurve& c : loop.curves)
        if (c.edge >= 0 && c.edge < ne) real.push_back(&c);
      for (std::size_t k = 0; k < real.size(); ++k) {
        const TrimCurve& c = *real[k];
        const auto e = static_cast<std::size_t>(c.edge);
        r.edge_faces[e].push_back(static_cast<int>(f));
        if (!used[e]) {
          used[e] = 1;
          if (b.edges[e].curve.num_coefs() > 0) {
            const Box<1> d = b.edges[e].curve.domain();
            r.edge_ends[e] = {curve_point(b.edges[e].curve, d.lo[0]), curve_point(b.edges[e].curve, d.hi[0])};
          } else {
            const Box<1> d = c.pcurve.domain();
            const P3 s = trim_point(face, c, d.lo[0]), t = trim_point(face, c, d.hi[0]);
            r.edge_ends[e] = c.edge_reversed ? std::array<P3, 2>{t, s} : std::array<P3, 2>{s, t};
          }
        }
        uf.unite(loop_end(c), loop_start(*real[(k + 1) % real.size()]));
      }
    }
  }
  std::vector<int> vertex(static_cast<std::size_t>(2 * ne), -1);
  std::vector<int> joined;  // per vertex: edge ends averaged into its position
  for (int e = 0; e < ne; ++e) {
    if (!used[static_cast<std::size_t>(e)]) continue;
    ++r.used_edges;
    std::sort(r.edge_faces[static_cast<std::size_t>(e)].begin(), r.edge_faces[static_cast<std::size_t>(e)].end());
    for (int s = 0; s < 2; ++s) {
      int& v = vertex[static_cast<std::size_t>(uf.find(2 * e + s))];
      if (v < 0) {
        v = static_cast<int>(r.positions.size());
        r.positions.push_back({0, 0, 0});
        joined.push_back(0);
      }
      r.edge_vertices[static_cast<std::size_t>(e)][static_cast<std::size_t>(s)] = v;
      const P3& x = r.edge_ends[static_cast<std::size_t>(e)][static_cast<std::size_t>(s)];
      for (int k = 0; k < 3; ++k) r.positions[static_cast<std::size_t>(v)][static_cast<std::size_t>(k)] += x[static_cast<std::size_t>(k)];
      ++joined[static_cast<std::size_t>(v)];
    }
  }
  for (std::size_t v = 0; v < r.positions.size(); ++v)
    for (double& x : r.positions[v]) x /= joined[v];
  r.euler_characteristic = static_cast<int>(r.positions.size()) - r.used_edges + face_term;
  return r;
}

}  // namespace trivar
