#pragma once
// Quad control meshes written as Rhino TSM text (#TS0200 records: f, e, v, l with the corner flags, ec, the
// grip map and the control points), for the star-point tests: a closed cube of n x n faces per side (eight
// valence-3 star points) or a box open at the bottom, a planar fan of N sectors of m x m faces around one star
// point of valence N, a half fan of K sectors around a star point on a straight boundary, a grid with a slit (two
// star points on the boundary), a cube with an edge turned (star points of valence 3 and 5 joined by edges), and
// a face split 2 x 2 (T-junctions on the faces round it).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace trivar::test {

struct QuadMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 4>> quads;  // counter-clockwise seen from outside
  // Faces with T-junctions, written after the quads: the vertex loop counter-clockwise from a corner, and per
  // vertex whether the face's angle there is 180 degrees (a neighbour's T-junction on its side).
  struct TFace {
    std::vector<int> loop;
    std::vector<char> straight;
  };
  std::vector<TFace> t_faces;
  std::map<std::array<int, 2>, double> intervals;  // knot intervals other than the default, by end vertices
};

// Every edge gets knot interval `interval` (or its entry in m.intervals); boundary links get the outside angle's flag
// (angle / 90 - 1: -1 after four faces at a boundary star point, -2 after five; 0 there with `clamp_outside_flags`); every boundary vertex
// gets the repeated-knot node block of Bezier end conditions (one layer outwards, its points on the vertex).
inline std::string tsm_text(const QuadMesh& m, double interval = 1.0, bool clamp_outside_flags = false) {
  struct Link {
    int prev, next, opp = -1, vertex, face, edge = -1, flag;
  };
  std::vector<Link> links;
  std::map<std::array<int, 2>, int> by_ends;
  std::vector<int> angle(m.points.size(), 0);  // the faces' angles at a vertex, in right angles
  std::vector<QuadMesh::TFace> faces;
  for (const auto& q : m.quads) faces.push_back({{q[0], q[1], q[2], q[3]}, {0, 0, 0, 0}});
  faces.insert(faces.end(), m.t_faces.begin(), m.t_faces.end());
  std::vector<int> face_link;
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    const auto& loop = faces[f].loop;
    const int n = static_cast<int>(loop.size()), base = static_cast<int>(links.size());
    face_link.push_back(base);
    for (int i = 0; i < n; ++i) {
      const int l = static_cast<int>(links.size());
      links.push_back({base + (i + n - 1) % n, base + (i + 1) % n, -1, loop[i], f, -1, faces[f].straight[i] ? 1 : 0});
      by_ends[{loop[i], loop[(i + 1) % n]}] = l;
      angle[loop[i]] += faces[f].straight[i] ? 2 : 1;
    }
  }
  const int inner = static_cast<int>(links.size());
  std::map<int, int> outside_from;  // boundary vertex -> outside link leaving it
  for (int l = 0; l < inner; ++l) {
    const int a = links[l].vertex, b = links[links[l].next].vertex;
    auto it = by_ends.find({b, a});
    if (it != by_ends.end()) {
      links[l].opp = it->second;
      continue;
    }
    const int o = static_cast<int>(links.size());
    links.push_back({-1, -1, l, b, -1, -1, clamp_outside_flags ? std::max(0, 3 - angle[b]) : 3 - angle[b]});
    links[l].opp = o;
    outside_from[b] = o;
  }
  for (int o = inner; o < static_cast<int>(links.size()); ++o) {
    const int end = links[links[o].opp].vertex;  // the outside link runs b -> a
    links[o].next = outside_from.at(end);
    links[outside_from.at(end)].prev = o;
  }
  int edges = 0;
  std::vector<int> edge_link;
  for (int l = 0; l < static_cast<int>(links.size()); ++l)
    if (links[l].edge < 0) {
      links[l].edge = links[links[l].opp].edge = edges++;
      edge_link.push_back(l);
    }
  std::vector<int> vertex_link(m.points.size(), -1);
  for (int l = 0; l < static_cast<int>(links.size()); ++l)
    if (vertex_link[links[l].vertex] < 0) vertex_link[links[l].vertex] = l;
  // Blocks: the outward directions in the vertex frame (link vertex_link[v] goes EAST; the next link
  // counter-clockwise turns by its face's angle); a straight boundary vertex one layer, a corner two and the
  // diagonal node.
  std::vector<std::string> blocks;
  std::vector<int> block_vertex;
  for (int o = inner; o < static_cast<int>(links.size()); ++o) {
    const int v = links[o].vertex;
    int l = vertex_link[v], frame = 3;
    while (l != o) {
      frame = ((frame + links[l].flag + 1) % 4 + 4) % 4;
      l = links[links[l].prev].opp;
    }
    std::array<int, 4> dims{0, 0, 0, 0};
    dims[(frame + 1) % 4] = 1;
    if (links[o].flag == 2) dims[(frame + 2) % 4] = 1;  // a convex corner: outwards across both sides
    if (angle[v] == 3) dims = {1, 1, 1, 1};              // a concave corner: a ring all round (as Rhino writes)
    std::ostringstream b;
    b << "0m cg " << v << " 4 " << dims[0] << ' ' << dims[1] << ' ' << dims[2] << ' ' << dims[3];
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < dims[k] * (dims[(k + 1) % 4] + 1); ++i) {
        b << ' ' << m.points.size() + block_vertex.size();
        block_vertex.push_back(v);
      }
    blocks.push_back(b.str());
  }
  std::ostringstream os;
  os.precision(17);
  os << "#TS0200\n\ndegree 3\ncap-type 1\nstar-smoothness 0\nunits 1 millimeters\nforce-bezier-end-conditions 1\n";
  for (int l : face_link) os << "f " << l << " 0\n";
  for (int e = 0; e < edges; ++e) {
    const Link& k = links[edge_link[e]];
    const int a = k.vertex, b = links[k.opp].vertex;
    auto it = m.intervals.find({a, b});
    if (it == m.intervals.end()) it = m.intervals.find({b, a});
    os << "e " << edge_link[e] << ' ' << (it == m.intervals.end() ? interval : it->second) << '\n';
  }
  for (int v : vertex_link) os << "v " << v << " EAST\n";
  for (const Link& k : links)
    os << "l " << k.prev << ' ' << k.next << ' ' << k.opp << ' ' << k.vertex << ' ' << k.face << ' ' << k.edge << ' ' << k.flag << '\n';
  for (int e = 0; e < edges; ++e)
    if (links[edge_link[e]].face < 0 || links[links[edge_link[e]].opp].face < 0) os << "ec " << e << " 0\n";
  os << "0m odd-grip-map\n";
  for (std::size_t v = 0; v < m.points.size(); ++v) os << "0m gvp " << v << '\n';
  for (int v : block_vertex) os << "0m gv " << v << '\n';
  for (const std::string& b : blocks) os << b << '\n';
  for (const auto& p : m.points) os << "0g " << p[0] << ' ' << p[1] << ' ' << p[2] << " 1\n";
  for (int v : block_vertex) os << "0g " << m.points[v][0] << ' ' << m.points[v][1] << ' ' << m.points[v][2] << " 1\n";
  os << "\ntol 1e-05\nver 1\n";
  return os.str();
}

// Unequal knot intervals round a star point: the mesh of sectors (nu x nv faces each, in the order built, as
// half_fan_mesh builds them) gets the interval u[i] on the edges along spoke k of its face (i, j) and u[j] on those
// along spoke k + 1, so each spoke carries the intervals u and every strip one interval, round the star point too.
inline void grade_by_ring(QuadMesh& q, const std::vector<std::array<int, 2>>& sectors, const std::vector<double>& u) {
  std::size_t f = 0;
  for (const auto& [nu, nv] : sectors)
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i, ++f) {
        const auto& c = q.quads[f];
        q.intervals[{c[0], c[1]}] = q.intervals[{c[3], c[2]}] = u[static_cast<std::size_t>(i)];
        q.intervals[{c[0], c[3]}] = q.intervals[{c[1], c[2]}] = u[static_cast<std::size_t>(j)];
      }
}

// The surface of the box of n[0] x n[1] x n[2] unit grid cells, scaled by 2 / n[0] with its lowest corner at
// (-1, -1, -1), without its bottom side (z lowest) when `open_bottom` (an open box whose rim is the boundary).
inline QuadMesh box_mesh(const std::array<int, 3>& n, bool open_bottom = false) {
  QuadMesh m;
  std::map<std::array<int, 3>, int> id;
  const auto vertex = [&](std::array<int, 3> g) {
    auto [it, fresh] = id.emplace(g, static_cast<int>(m.points.size()));
    if (fresh) m.points.push_back({-1 + 2.0 * g[0] / n[0], -1 + 2.0 * g[1] / n[0], -1 + 2.0 * g[2] / n[0]});
    return it->second;
  };
  for (int a = 0; a < 3; ++a)
    for (int side : {0, n[static_cast<std::size_t>(a)]}) {
      if (open_bottom && a == 2 && side == 0) continue;
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      for (int j = 0; j < n[static_cast<std::size_t>(c)]; ++j)
        for (int i = 0; i < n[static_cast<std::size_t>(b)]; ++i) {
          std::array<std::array<int, 3>, 4> q;
          const std::array<std::array<int, 2>, 4> ij{{{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
          for (int k = 0; k < 4; ++k) {
            q[k][a] = side;
            q[k][b] = ij[k][0];
            q[k][c] = ij[k][1];
          }
          std::array<int, 4> f{vertex(q[0]), vertex(q[1]), vertex(q[2]), vertex(q[3])};
          if (side == 0) std::swap(f[1], f[3]);
          m.quads.push_back(f);
        }
    }
  return m;
}

// Quad f of q split 2 x 2: new points at its sides' midpoints (counter-clockwise from the side from its first
// vertex) and its centre, each lifted by `lift` along z; the quads across its sides become T-faces (a side on the
// boundary keeps its midpoint as a boundary vertex).
inline QuadMesh split_face(const QuadMesh& q, std::size_t f, const std::array<double, 5>& lift) {
  QuadMesh r = q;
  const std::array<int, 4> c = q.quads[f];
  const auto interval = [&](int a, int b) {
    const auto it = q.intervals.find({a, b});
    return it != q.intervals.end() ? it->second : 1.0;
  };
  const auto point = [&](std::array<double, 3> p, double dz) {
    p[2] += dz;
    r.points.push_back(p);
    return static_cast<int>(r.points.size()) - 1;
  };
  std::array<int, 4> mid{};
  std::array<double, 3> centre{};
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& a = q.points[static_cast<std::size_t>(c[k])];
    const auto& b = q.points[static_cast<std::size_t>(c[(k + 1) % 4])];
    mid[k] = point({(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}, lift[k]);
    for (std::size_t i = 0; i < 3; ++i) centre[i] += a[i] / 4;
  }
  const int o = point(centre, lift[4]);
  std::vector<std::array<int, 4>> quads;
  std::vector<int> across(4, -1);  // the quad across side k
  for (std::size_t g = 0; g < q.quads.size(); ++g)
    for (std::size_t k = 0; k < 4; ++k)
      for (std::size_t i = 0; i < 4; ++i)
        if (q.quads[g][i] == c[(k + 1) % 4] && q.quads[g][(i + 1) % 4] == c[k]) across[k] = static_cast<int>(g);
  for (std::size_t g = 0; g < q.quads.size(); ++g)
    if (g != f && std::find(across.begin(), across.end(), static_cast<int>(g)) == across.end()) quads.push_back(q.quads[g]);
  for (std::size_t k = 0; k < 4; ++k) {
    const int a = c[k], b = c[(k + 1) % 4], before = mid[(k + 3) % 4];
    quads.push_back({a, mid[k], o, before});
    const double half = interval(a, b) / 2, inner = interval(c[(k + 1) % 4], c[(k + 2) % 4]) / 2;
    r.intervals[{a, mid[k]}] = r.intervals[{mid[k], a}] = r.intervals[{mid[k], b}] = r.intervals[{b, mid[k]}] = half;
    r.intervals[{mid[k], o}] = r.intervals[{o, mid[k]}] = inner;
    // The T-face across side k (none at the boundary): its loop with the midpoint between b and a.
    if (across[k] < 0) continue;
    const auto& n = q.quads[static_cast<std::size_t>(across[k])];
    QuadMesh::TFace t;
    for (std::size_t i = 0; i < 4; ++i) {
      t.loop.push_back(n[i]);
      t.straight.push_back(0);
      if (n[i] == b) {
        t.loop.push_back(mid[k]);
        t.straight.push_back(1);
      }
    }
    r.t_faces.push_back(std::move(t));
  }
  r.quads = std::move(quads);
  return r;
}

// The index of face (i, j) of the top side (z = 1) of box_mesh({n, n, n}) (`unbent`: its points as made).
inline std::size_t top_face(const std::vector<std::array<double, 3>>& unbent, const QuadMesh& box, int n, int i, int j) {
  for (std::size_t f = 0; f < box.quads.size(); ++f) {
    double x = 0, y = 0, z = 0;
    for (int v : box.quads[f]) {
      x += unbent[static_cast<std::size_t>(v)][0] / 4;
      y += unbent[static_cast<std::size_t>(v)][1] / 4;
      z += unbent[static_cast<std::size_t>(v)][2] / 4;
    }
    if (std::abs(z - 1) < 1e-12 && std::abs((x + 1) * n / 2 - (i + 0.5)) < 1e-9 && std::abs((y + 1) * n / 2 - (j + 0.5)) < 1e-9) return f;
  }
  throw std::runtime_error("no top face");
}

// The surface of the cube [-1, 1]^3 in n x n faces per side.
inline QuadMesh cube_mesh(int n) { return box_mesh({n, n, n}); }

// Splits 2 x 2 the face of the top side (z = 1) of box_mesh({n, n, n}) whose corners' mean is the centre of cell
// (i, j) of the side's grid refined `level` times (a face made by earlier splits, so splits nest), with new points
// at its sides' midpoints and centre (a side that already has its midpoint keeps it; a T-junction elsewhere on a
// side is not taken). Every face is kept as a loop in q.t_faces (quads are moved there first); `unbent` holds the
// points as made, for finding faces, and grows with q.points.
inline void split_top_face(QuadMesh& q, std::vector<std::array<double, 3>>& unbent, int n, int i, int j, int level) {
  for (const auto& f : q.quads) q.t_faces.push_back({{f[0], f[1], f[2], f[3]}, {0, 0, 0, 0}});
  q.quads.clear();
  const auto interval = [&](int a, int b) {
    const auto it = q.intervals.find({a, b});
    return it != q.intervals.end() ? it->second : 1.0;
  };
  const auto set_interval = [&](int a, int b, double d) { q.intervals[{a, b}] = q.intervals[{b, a}] = d; };
  const auto add_point = [&](const std::array<double, 3>& p, const std::array<double, 3>& u) {
    q.points.push_back(p);
    unbent.push_back(u);
    return static_cast<int>(q.points.size()) - 1;
  };
  const double cell = std::ldexp(1.0, -level);
  std::size_t at = q.t_faces.size();
  for (std::size_t f = 0; f < q.t_faces.size() && at == q.t_faces.size(); ++f) {
    std::array<double, 3> c{};
    for (std::size_t k = 0; k < q.t_faces[f].loop.size(); ++k)
      if (!q.t_faces[f].straight[k])
        for (std::size_t a = 0; a < 3; ++a) c[a] += unbent[static_cast<std::size_t>(q.t_faces[f].loop[k])][a] / 4;
    if (std::abs(c[2] - 1) < 1e-12 && std::abs((c[0] + 1) * n / 2 - (i + 0.5) * cell) < 1e-9 && std::abs((c[1] + 1) * n / 2 - (j + 0.5) * cell) < 1e-9)
      at = f;
  }
  if (at == q.t_faces.size()) throw std::runtime_error("no top face at that cell");
  const QuadMesh::TFace face = q.t_faces[at];
  q.t_faces.erase(q.t_faces.begin() + static_cast<std::ptrdiff_t>(at));
  std::vector<std::size_t> corner;
  for (std::size_t k = 0; k < face.loop.size(); ++k)
    if (!face.straight[k]) corner.push_back(k);
  if (corner.size() != 4 || corner[0] != 0) throw std::runtime_error("a face loop that does not start at one of 4 corners");
  std::array<int, 4> c{}, mid{};
  std::array<double, 4> length{};
  for (std::size_t k = 0; k < 4; ++k) c[k] = face.loop[corner[k]];
  for (std::size_t k = 0; k < 4; ++k) {
    const int a = c[k], b = c[(k + 1) % 4];
    const std::size_t first = corner[k] + 1, last = k == 3 ? face.loop.size() : corner[k + 1];
    if (last - first > 1) throw std::runtime_error("a side with several T-junctions");
    if (last - first == 1) {
      mid[k] = face.loop[first];
      length[k] = interval(a, mid[k]) + interval(mid[k], b);
      if (std::abs(interval(a, mid[k]) - interval(mid[k], b)) > 1e-12 * length[k]) throw std::runtime_error("a T-junction off a side's middle");
      continue;
    }
    length[k] = interval(a, b);
    std::array<double, 3> p{}, u{};
    for (std::size_t x = 0; x < 3; ++x) {
      p[x] = (q.points[static_cast<std::size_t>(a)][x] + q.points[static_cast<std::size_t>(b)][x]) / 2;
      u[x] = (unbent[static_cast<std::size_t>(a)][x] + unbent[static_cast<std::size_t>(b)][x]) / 2;
    }
    mid[k] = add_point(p, u);
    set_interval(a, mid[k], length[k] / 2);
    set_interval(mid[k], b, length[k] / 2);
    for (auto& g : q.t_faces)  // the face across gets the midpoint as a T-junction
      for (std::size_t x = 0; x < g.loop.size(); ++x)
        if (g.loop[x] == b && g.loop[(x + 1) % g.loop.size()] == a) {
          g.loop.insert(g.loop.begin() + static_cast<std::ptrdiff_t>(x) + 1, mid[k]);
          g.straight.insert(g.straight.begin() + static_cast<std::ptrdiff_t>(x) + 1, 1);
          break;
        }
  }
  std::array<double, 3> p{}, u{};
  for (int v : c)
    for (std::size_t x = 0; x < 3; ++x) {
      p[x] += q.points[static_cast<std::size_t>(v)][x] / 4;
      u[x] += unbent[static_cast<std::size_t>(v)][x] / 4;
    }
  const int o = add_point(p, u);
  for (std::size_t k = 0; k < 4; ++k) set_interval(mid[k], o, length[(k + 1) % 4] / 2);
  for (std::size_t k = 0; k < 4; ++k) q.t_faces.push_back({{c[k], mid[k], o, mid[(k + 3) % 4]}, {0, 0, 0, 0}});
}

// cube_mesh(4) with the edge between two adjacent quads inside one side turned: its ends drop to valence 3, the
// ends of the new diagonal rise to 5, each valence-3 point joined by an edge to a valence-5 one. The valence-3
// points move off the hexagon's centre (else the quads would have straight angles).
inline QuadMesh turned_edge_cube() {
  QuadMesh m = cube_mesh(4);
  const auto inside_side = [&](int v) {
    int on = 0;
    for (double x : m.points[static_cast<std::size_t>(v)]) on += std::abs(std::abs(x) - 1) < 1e-12;
    return on == 1;
  };
  for (std::size_t a = 0; a < m.quads.size(); ++a)
    for (std::size_t b = 0; b < m.quads.size(); ++b)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          auto A = m.quads[a], B = m.quads[b];
          std::rotate(A.begin(), A.begin() + i, A.end());
          std::rotate(B.begin(), B.begin() + j, B.end());
          if (A[0] != B[1] || A[1] != B[0]) continue;  // the edge p -> q of A is q -> p in B
          const std::array<int, 6> h{A[1], A[2], A[3], A[0], B[2], B[3]};  // the hexagon, counter-clockwise
          if (!std::all_of(h.begin(), h.end(), inside_side)) continue;
          m.quads[a] = {h[1], h[2], h[3], h[4]};
          m.quads[b] = {h[4], h[5], h[0], h[1]};
          std::array<double, 3> c{};
          for (int v : h)
            for (std::size_t k = 0; k < 3; ++k) c[k] += m.points[static_cast<std::size_t>(v)][k] / 6;
          for (int v : {h[0], h[3]})
            for (std::size_t k = 0; k < 3; ++k) {
              double& x = m.points[static_cast<std::size_t>(v)][k];
              x += 0.5 * (x - c[k]);
            }
          return m;
        }
  throw std::logic_error("turned_edge_cube: no two quads inside one side");
}

// N sectors of m x m faces around a star point of valence N at the origin; z = height(x, y).
template <class Height>
QuadMesh fan_mesh(int valence, int m, Height height) {
  QuadMesh q;
  std::map<std::array<int, 3>, int> id;  // (sector, i, j), with (k, 0, j) stored as (k - 1, j, 0)
  const auto vertex = [&](int k, int i, int j) {
    if (i == 0 && j == 0) k = 0;
    if (i == 0 && j > 0) {
      k = (k + 1) % valence;
      i = j;
      j = 0;
    }
    auto [it, fresh] = id.emplace(std::array<int, 3>{k, i, j}, static_cast<int>(q.points.size()));
    if (fresh) {
      const double a = 2 * std::numbers::pi * k / valence, b = 2 * std::numbers::pi * (k + 1) / valence;
      const double x = i * std::cos(a) + j * std::cos(b), y = i * std::sin(a) + j * std::sin(b);
      q.points.push_back({x, y, height(x, y)});
    }
    return it->second;
  };
  for (int k = 0; k < valence; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        q.quads.push_back({vertex(k, i, j), vertex(k, i + 1, j), vertex(k, i + 1, j + 1), vertex(k, i, j + 1)});
  return q;
}

// fan_mesh with knot interval interval(k, i) on the edges of the i-th strip along spoke k (so sector k's faces
// [i, i + 1] x [j, j + 1] have intervals interval(k, i) and interval(k + 1, j)): unequal between spokes and along
// them, as non-uniform Catmull-Clark takes them.
template <class Height, class Interval>
QuadMesh fan_mesh_with_intervals(int valence, int m, Height height, Interval interval) {
  QuadMesh q = fan_mesh(valence, m, height);
  for (int k = 0; k < valence; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const auto& f = q.quads[static_cast<std::size_t>(k * m * m + j * m + i)];
        q.intervals[{f[0], f[1]}] = q.intervals[{f[3], f[2]}] = interval(k, i);
        q.intervals[{f[1], f[2]}] = q.intervals[{f[0], f[3]}] = interval((k + 1) % valence, j);
      }
  return q;
}

// fan_mesh with T-junctions: in sector 0, the faces [i, i + 1] x [row, row + 1], first <= i < last, are split
// at row + 1/2 (edges of knot interval 1/2), which puts T-junctions on the sides of the faces first - 1 and last
// of that row (1 <= first < last < m).
template <class Height>
QuadMesh fan_mesh_with_t_junctions(int valence, int m, int row, int first, int last, Height height) {
  QuadMesh q = fan_mesh(valence, m, height);
  const auto quad = [&](int i) { return q.quads[static_cast<std::size_t>(row * m + i)]; };  // sector 0
  std::vector<int> mid;  // the new vertices (i, row + 1/2), first <= i <= last
  for (int i = first; i <= last; ++i) {
    const auto& a = q.points[static_cast<std::size_t>(i < last ? quad(i)[0] : quad(i - 1)[1])];
    const auto& b = q.points[static_cast<std::size_t>(i < last ? quad(i)[3] : quad(i - 1)[2])];
    const double x = 0.5 * (a[0] + b[0]), y = 0.5 * (a[1] + b[1]);
    mid.push_back(static_cast<int>(q.points.size()));
    q.points.push_back({x, y, height(x, y)});
  }
  std::vector<std::array<int, 4>> quads;
  for (int k = 0; k < static_cast<int>(q.quads.size()); ++k) {
    const int i = k - row * m;
    if (i >= first - 1 && i <= last && k < m * m) continue;
    quads.push_back(q.quads[static_cast<std::size_t>(k)]);
  }
  for (int i = first; i < last; ++i) {
    const auto c = quad(i);
    const int lo = mid[static_cast<std::size_t>(i - first)], hi = mid[static_cast<std::size_t>(i - first + 1)];
    quads.push_back({c[0], c[1], hi, lo});
    quads.push_back({lo, hi, c[2], c[3]});
    q.intervals[{c[0], lo}] = q.intervals[{lo, c[3]}] = 0.5;
    q.intervals[{c[1], hi}] = q.intervals[{hi, c[2]}] = 0.5;
  }
  const auto left = quad(first - 1), right = quad(last);
  q.t_faces.push_back({{left[0], left[1], mid.front(), left[2], left[3]}, {0, 0, 1, 0, 0}});
  q.t_faces.push_back({{right[0], right[1], right[2], right[3], mid.back()}, {0, 0, 0, 0, 1}});
  q.quads = std::move(quads);
  return q;
}

// K sectors of m x m faces around a star point at the origin on the boundary: spoke k at angle pi k / K, spokes 0
// and K along the boundary (the x axis); z = height(x, y). K = 2 is a regular boundary vertex.
template <class Height>
QuadMesh half_fan_mesh(int sectors, int m, Height height) {
  QuadMesh q;
  std::map<std::array<int, 2>, int> spoke;        // (spoke, i >= 1)
  std::map<std::array<int, 3>, int> inner;        // (sector, i, j >= 1)
  const auto make = [&](double x, double y) {
    q.points.push_back({x, y, height(x, y)});
    return static_cast<int>(q.points.size()) - 1;
  };
  const int star = make(0, 0);
  const auto dir = [&](int k) { return std::array<double, 2>{std::cos(std::numbers::pi * k / sectors), std::sin(std::numbers::pi * k / sectors)}; };
  const auto vertex = [&](int k, int i, int j) {
    if (i == 0 && j == 0) return star;
    if (j == 0 || i == 0) {
      const std::array<int, 2> key{j == 0 ? k : k + 1, j == 0 ? i : j};
      auto it = spoke.find(key);
      if (it != spoke.end()) return it->second;
      const auto d = dir(key[0]);
      return spoke[key] = make(key[1] * d[0], key[1] * d[1]);
    }
    auto it = inner.find({k, i, j});
    if (it != inner.end()) return it->second;
    const auto a = dir(k), b = dir(k + 1);
    return inner[{k, i, j}] = make(i * a[0] + j * b[0], i * a[1] + j * b[1]);
  };
  for (int k = 0; k < sectors; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        q.quads.push_back({vertex(k, i, j), vertex(k, i + 1, j), vertex(k, i + 1, j + 1), vertex(k, i, j + 1)});
  return q;
}

// The grid of w x h unit faces with a slit along the line y = row from x = first to x = last (its inner vertices
// doubled: the faces below it take copies at the same points), whose ends are star points of four faces on the
// boundary; z = height(x, y).
template <class Height>
QuadMesh slit_mesh(int w, int h, int row, int first, int last, Height height) {
  QuadMesh q;
  const auto id = [&](int i, int j) { return j * (w + 1) + i; };
  for (int j = 0; j <= h; ++j)
    for (int i = 0; i <= w; ++i) q.points.push_back({double(i), double(j), height(double(i), double(j))});
  std::map<int, int> below;  // slit vertex -> its copy for the faces below the slit
  for (int i = first + 1; i < last; ++i) {
    below[id(i, row)] = static_cast<int>(q.points.size());
    q.points.push_back(q.points[static_cast<std::size_t>(id(i, row))]);
  }
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      std::array<int, 4> f{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      if (j + 1 == row)
        for (int& v : f)
          if (below.count(v)) v = below.at(v);
      q.quads.push_back(f);
    }
  return q;
}

}  // namespace trivar::test
