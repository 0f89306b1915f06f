#pragma once
// The boundary of a glued V-model as a watertight triangle mesh (for STL, 3MF, AMF), each vertex traced back
// to its cell and cell parameters so attributes such as material fractions can be evaluated there.
#include <vector>

#include "trivar/model/boundary_tessellation.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar {

struct ModelTessellation {
  TriangleMesh mesh;            // closed and oriented outwards when the model's boundary is closed
  std::vector<int> cell;        // per vertex: the cell it was evaluated on
  std::vector<Param<3>> param;  // per vertex: its parameters in that cell
};

// Tessellates model_boundary(model) (shared faces are inside and left out) with tessellate(); the boundary
// topology is rebuilt from the faces with the model's gluing tolerance. Throws trivar::Error when the model
// is not glued or its boundary is not closed.
ModelTessellation tessellate_boundary(const VModel& model, const TessellationOptions& opts = {});

}  // namespace trivar
