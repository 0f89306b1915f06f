#include "trivar/model/trimmed_tessellation.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"

namespace trivar {

bool has_trimmed_cells(const VModel& model) {
  return std::any_of(model.cells().begin(), model.cells().end(), [](const VCell& c) { return c.is_trimmed(); });
}

ModelTessellation trimmed_boundary_mesh(const VModel& model) {
  ModelTessellation t;
  for (int ci = 0; ci < model.num_cells(); ++ci) {
    const VCell& c = model.cell(ci);
    require(c.is_trimmed(), [&] {
      return "trimmed boundary: cell " + std::to_string(ci) + " is not trimmed (models mixing trimmed and untrimmed "
             "cells have no boundary mesh)";
    });
    const TriangleMesh& m = c.trim()->boundary().mesh;
    const int offset = static_cast<int>(t.mesh.vertices.size());
    for (const auto& v : m.vertices) {
      t.mesh.vertices.push_back(v);
      t.cell.push_back(ci);
      t.param.push_back(v);
    }
    for (const auto& tri : m.triangles) t.mesh.triangles.push_back({tri[0] + offset, tri[1] + offset, tri[2] + offset});
  }
  return t;
}

}  // namespace trivar
