#pragma once
// Local subdivision nets and surfaces with unequal knot intervals, for the tests of crease_face: a face's crease net
// written here from the mesh's links (independently of TMeshSurface's), Cartesian values of homogeneous ones, and
// derivatives per unit of knot interval.
#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

#include "trivar/tspline/crease_face.hpp"
#include "trivar/tspline/sharp_creases.hpp"
#include "trivar/tspline/t_mesh.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar::test {

// Cartesian value, d/du, d/dv (9) from a homogeneous one (12).
inline std::array<double, 9> cartesian(const double* h) {
  std::array<double, 9> o{};
  for (int c = 0; c < 3; ++c) {
    o[static_cast<std::size_t>(c)] = h[c] / h[3];
    for (int k = 1; k <= 2; ++k) o[static_cast<std::size_t>(3 * k + c)] = (h[4 * k + c] - o[static_cast<std::size_t>(c)] * h[4 * k + 3]) / h[3];
  }
  return o;
}

// The crease net of face f of a quad mesh without T-junctions and without sharp creases (its faces within two
// rings of f, f first from its first corner), written here from the mesh's links and boundary_rules.
inline CreaseNet net_of(const TMesh& m, int f) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const std::vector<CreaseRule> rules = boundary_rules(m);
  std::vector<std::vector<int>> at(m.vertices.size());
  for (const TMeshLink& k : m.links)
    if (k.vertex >= 0 && k.face >= 0) at[static_cast<std::size_t>(k.vertex)].push_back(k.face);
  std::vector<int> hood{f};
  std::set<int> in{f};
  for (int ring = 0; ring < 2; ++ring)
    for (int g : std::vector<int>(hood))
      for (int l : m.faces[static_cast<std::size_t>(g)])
        for (int h : at[static_cast<std::size_t>(L(l).vertex)])
          if (in.insert(h).second) hood.push_back(h);
  CreaseNet net;
  std::map<int, int> id;
  for (int g : hood) {
    auto loop = m.faces[static_cast<std::size_t>(g)];
    if (g == f) std::rotate(loop.begin(), std::find(loop.begin(), loop.end(), m.first_corner(f)), loop.end());
    std::array<int, 4> quad{};
    std::array<bool, 4> sharp{};
    std::array<double, 4> d{};
    for (std::size_t k = 0; k < 4; ++k) {
      const int v = L(loop[k]).vertex;
      sharp[k] = L(L(loop[k]).opp).face < 0;
      d[k] = m.intervals[static_cast<std::size_t>(L(loop[k]).edge)];
      if (!id.count(v)) {
        id[v] = static_cast<int>(net.points.size());
        const RationalPoint& p = m.points[static_cast<std::size_t>(m.vertices[static_cast<std::size_t>(v)].primary)];
        net.points.push_back({p.w * p.xyz[0], p.w * p.xyz[1], p.w * p.xyz[2], p.w});
        const CreaseRule r = rules[static_cast<std::size_t>(v)];
        net.rules.push_back(r == CreaseRule::none ? VertexRule::smooth : r == CreaseRule::crease ? VertexRule::crease : VertexRule::corner);
      }
      quad[k] = id[v];
    }
    net.quads.push_back(quad);
    net.sharp.push_back(sharp);
    net.intervals.push_back(d);
  }
  return net;
}

// A surface's eval with the derivatives per unit of knot interval (d/du over the interval of the face's side 0,
// d/dv over side 3's), in which B-spline pieces on different intervals meet C1.
inline auto knot_units(const TMeshSurface& s) {
  return [&s](int f, double u, double v, double* o) {
    const TMesh& m = s.face_mesh();
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    const std::size_t first = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), m.first_corner(f)) - loop.begin());
    const auto interval = [&](std::size_t k) { return m.intervals[static_cast<std::size_t>(m.links[static_cast<std::size_t>(loop[(first + k) % 4])].edge)]; };
    s.eval(f, u, v, o);
    for (int c = 0; c < 3; ++c) {
      o[3 + c] /= interval(0);
      o[6 + c] /= interval(3);
    }
  };
}

}  // namespace trivar::test
