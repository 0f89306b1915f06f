#include "trivar/model/trimmed_tessellation.hpp"

#include <algorithm>
#include <map>

#include "trivar/core/error.hpp"

namespace trivar {

bool has_trimmed_cells(const VModel& model) {
  return std::any_of(model.cells().begin(), model.cells().end(), [](const VCell& c) { return c.is_trimmed(); });
}

ModelTessellation trimmed_boundary_mesh(const VModel& model) {
  // Vertices are merged by their exact coordinates: cells cut from one another by a Boolean share the
  // triangulation of every face between them, so a shared face's triangles appear in both cells with the same
  // corners and opposite orientations. Such pairs are inside the model and cancel.
  std::map<std::array<double, 3>, int> ids;
  std::vector<std::array<double, 3>> vertices;
  std::vector<int> vertex_cell;
  struct Tri {
    std::array<int, 3> v;
    int cell;
  };
  std::vector<Tri> tris;
  for (int ci = 0; ci < model.num_cells(); ++ci) {
    const VCell& c = model.cell(ci);
    require(c.is_trimmed(), [&] {
      return "trimmed boundary: cell " + std::to_string(ci) + " is not trimmed (models mixing trimmed and untrimmed "
             "cells have no boundary mesh)";
    });
    const TriangleMesh& m = c.trim()->boundary().mesh;
    std::vector<int> local(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
      auto [it, fresh] = ids.try_emplace(m.vertices[i], static_cast<int>(vertices.size()));
      if (fresh) {
        vertices.push_back(m.vertices[i]);
        vertex_cell.push_back(ci);
      }
      local[i] = it->second;
    }
    for (const auto& tri : m.triangles) tris.push_back({{local[tri[0]], local[tri[1]], local[tri[2]]}, ci});
  }
  // A triangle by its corners in rotation-normalised order; the opposite orientation has the last two swapped.
  const auto key = [](std::array<int, 3> v) {
    std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
    return v;
  };
  std::map<std::array<int, 3>, std::vector<std::size_t>> by_key;
  for (std::size_t t = 0; t < tris.size(); ++t) by_key[key(tris[t].v)].push_back(t);
  std::vector<char> inside(tris.size(), 0);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (inside[t]) continue;
    const auto& v = tris[t].v;
    const auto it = by_key.find(key({v[0], v[2], v[1]}));
    if (it == by_key.end()) continue;
    for (std::size_t o : it->second)
      if (!inside[o] && tris[o].cell != tris[t].cell) {
        inside[t] = inside[o] = 1;
        break;
      }
  }
  ModelTessellation t;
  std::vector<int> used(vertices.size(), -1);
  for (std::size_t k = 0; k < tris.size(); ++k) {
    if (inside[k]) continue;
    std::array<int, 3> out;
    for (int c = 0; c < 3; ++c) {
      int& u = used[static_cast<std::size_t>(tris[k].v[c])];
      if (u < 0) {
        u = static_cast<int>(t.mesh.vertices.size());
        const auto& x = vertices[static_cast<std::size_t>(tris[k].v[c])];
        t.mesh.vertices.push_back(x);
        t.cell.push_back(vertex_cell[static_cast<std::size_t>(tris[k].v[c])]);
        t.param.push_back(x);
      }
      out[c] = u;
    }
    t.mesh.triangles.push_back(out);
  }
  return t;
}

}  // namespace trivar
