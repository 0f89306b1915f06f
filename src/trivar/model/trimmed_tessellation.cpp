#include "trivar/model/trimmed_tessellation.hpp"

#include <algorithm>
#include <map>

#include "trivar/core/error.hpp"
#include "trivar/model/trimmed_interfaces.hpp"

namespace trivar {

bool has_trimmed_cells(const VModel& model) {
  return std::any_of(model.cells().begin(), model.cells().end(), [](const VCell& c) { return c.is_trimmed(); });
}

ModelTessellation trimmed_boundary_mesh(const VModel& model) {
  for (int ci = 0; ci < model.num_cells(); ++ci)
    require(model.cell(ci).is_trimmed(), [&] {
      return "trimmed boundary: cell " + std::to_string(ci) + " is not trimmed (models mixing trimmed and untrimmed "
             "cells have no boundary mesh)";
    });
  // Triangles a face between two cells gives both of them are inside the model and drop out.
  std::vector<long> first;
  const std::vector<long> twin = paired_trimming_triangles(model, first);
  // Vertices are merged by their exact coordinates (the first cell using one names it).
  std::map<std::array<double, 3>, int> ids;
  ModelTessellation t;
  for (int ci = 0; ci < model.num_cells(); ++ci) {
    const TriangleMesh& m = model.cell(ci).trim()->boundary().mesh;
    for (std::size_t k = 0; k < m.triangles.size(); ++k) {
      if (twin[static_cast<std::size_t>(first[static_cast<std::size_t>(ci)]) + k] >= 0) continue;
      std::array<int, 3> out;
      for (int c = 0; c < 3; ++c) {
        const auto& x = m.vertices[static_cast<std::size_t>(m.triangles[k][c])];
        const auto [it, fresh] = ids.try_emplace(x, static_cast<int>(t.mesh.vertices.size()));
        if (fresh) {
          t.mesh.vertices.push_back(x);
          t.cell.push_back(ci);
          t.param.push_back(x);
        }
        out[c] = it->second;
      }
      t.mesh.triangles.push_back(out);
    }
  }
  return t;
}

}  // namespace trivar
