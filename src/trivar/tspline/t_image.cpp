#include "trivar/tspline/t_image.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"

namespace trivar {

int TImage::link_start(int l) const {
  const TLink& k = links[static_cast<std::size_t>(l)];
  const TEdge& e = edges[static_cast<std::size_t>(k.edge)];
  return k.sense ? e.start : e.end;
}

int TImage::link_end(int l) const {
  const TLink& k = links[static_cast<std::size_t>(l)];
  const TEdge& e = edges[static_cast<std::size_t>(k.edge)];
  return k.sense ? e.end : e.start;
}

Box<2> TImage::edge_box(int e) const {
  Box<2> b = Box<2>::empty();
  for (int v : {edges[static_cast<std::size_t>(e)].start, edges[static_cast<std::size_t>(e)].end}) {
    const TVertex& x = vertices[static_cast<std::size_t>(v)];
    const double p[2] = {x.s, x.t};
    b.extend(p);
  }
  return b;
}

Box<2> TImage::face_box(int f) const {
  Box<2> b = Box<2>::empty();
  for (int l : faces[static_cast<std::size_t>(f)].loop) {
    const TVertex& x = vertices[static_cast<std::size_t>(link_start(l))];
    const double p[2] = {x.s, x.t};
    b.extend(p);
  }
  return b;
}

Box<2> TImage::domain() const {
  Box<2> b = Box<2>::empty();
  for (const TVertex& x : vertices) {
    const double p[2] = {x.s, x.t};
    b.extend(p);
  }
  return b;
}

std::string describe_link(const TImage& image, int l) {
  return "link " + std::to_string(l) + " (vertex " + std::to_string(image.link_start(l)) + " -> vertex " +
         std::to_string(image.link_end(l)) + ")";
}

namespace {

// The compass direction of the link (north, west, south, east).
int link_direction(const TImage& im, int l) {
  const TVertex& a = im.vertices[static_cast<std::size_t>(im.link_start(l))];
  const TVertex& b = im.vertices[static_cast<std::size_t>(im.link_end(l))];
  if (a.s == b.s) return b.t > a.t ? 0 : 2;
  return b.s > a.s ? 3 : 1;
}

}  // namespace

void validate(const TImage& im) {
  const int nv = static_cast<int>(im.vertices.size()), ne = static_cast<int>(im.edges.size()),
            nl = static_cast<int>(im.links.size());
  for (int e = 0; e < ne; ++e) {
    const TEdge& x = im.edges[static_cast<std::size_t>(e)];
    require(x.start >= 0 && x.start < nv && x.end >= 0 && x.end < nv,
            [&] { return "T-image: edge " + std::to_string(e) + " names a vertex that does not exist"; });
    const TVertex& a = im.vertices[static_cast<std::size_t>(x.start)];
    const TVertex& b = im.vertices[static_cast<std::size_t>(x.end)];
    const bool horizontal = a.t == b.t && b.s > a.s, vertical = a.s == b.s && b.t > a.t;
    require(horizontal || vertical, [&] {
      return "T-image: edge " + std::to_string(e) + " from vertex " + std::to_string(x.start) + " to vertex " +
             std::to_string(x.end) + " is not an axis-parallel segment of positive length in increasing direction";
    });
  }
  for (int l = 0; l < nl; ++l)
    require(im.links[static_cast<std::size_t>(l)].edge >= 0 && im.links[static_cast<std::size_t>(l)].edge < ne,
            [&] { return "T-image: link " + std::to_string(l) + " names an edge that does not exist"; });
  for (int f = 0; f < static_cast<int>(im.faces.size()); ++f) {
    const auto& loop = im.faces[static_cast<std::size_t>(f)].loop;
    const auto where = [&] { return "T-image: face " + std::to_string(f) + ": "; };
    require(loop.size() >= 4, [&] { return where() + "a loop of " + std::to_string(loop.size()) + " links"; });
    for (int l : loop) require(l >= 0 && l < nl, [&] { return where() + "names a link that does not exist"; });
    int corners = 0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int l = loop[i], next = loop[(i + 1) % loop.size()];
      require(im.link_end(l) == im.link_start(next), [&] {
        return where() + "the loop is not closed: " + describe_link(im, l) + " is followed by " + describe_link(im, next);
      });
      const int turn = (link_direction(im, next) - link_direction(im, l) + 4) % 4;
      require(turn == 0 || turn == 1, [&] {
        return where() + "not a counter-clockwise rectangle (the loop turns right or back at vertex " +
               std::to_string(im.link_end(l)) + ")";
      });
      corners += turn;
    }
    require(corners == 4, [&] { return where() + "not a rectangle (" + std::to_string(corners) + " corners)"; });
  }
  for (int v = 0; v < nv; ++v)
    for (int d = 0; d < 4; ++d) {
      const int l = im.vertices[static_cast<std::size_t>(v)].links[static_cast<std::size_t>(d)];
      if (l < 0) continue;
      require(l < nl && im.link_start(l) == v && link_direction(im, l) == d, [&] {
        return "T-image: vertex " + std::to_string(v) + ": its " + kTDirNames[static_cast<std::size_t>(d)] +
               " link " + std::to_string(l) + " does not leave the vertex going " + kTDirNames[static_cast<std::size_t>(d)];
      });
    }
}

int add_edge(TImage& im, int a, int b) {
  const TVertex& x = im.vertices[static_cast<std::size_t>(a)];
  const TVertex& y = im.vertices[static_cast<std::size_t>(b)];
  const bool forward = y.s > x.s || y.t > x.t;
  const int e = static_cast<int>(im.edges.size());
  im.edges.push_back(forward ? TEdge{a, b} : TEdge{b, a});
  const int l = static_cast<int>(im.links.size());
  im.links.push_back({e, forward});
  im.links.push_back({e, !forward});
  return l;
}

void connect_vertex_links(TImage& im) {
  for (TVertex& v : im.vertices) v.links = {-1, -1, -1, -1};
  for (int l = 0; l < static_cast<int>(im.links.size()); ++l)
    im.vertices[static_cast<std::size_t>(im.link_start(l))].links[static_cast<std::size_t>(link_direction(im, l))] = l;
}

}  // namespace trivar
