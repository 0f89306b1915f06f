#pragma once
// The boundary of a V-model of trimmed cells as one triangle mesh: the cells' watertight trimming meshes with
// the faces two cells share left out (cells of a Boolean share the triangulation of the faces between them),
// each vertex traced back to its cell and parameters (a trimmed cell's parameters are model coordinates), so
// exporters colour it by the cells' attributes like any other model boundary.
#include "trivar/model/model_tessellation.hpp"

namespace trivar {

// True when some cell of the model is trimmed.
bool has_trimmed_cells(const VModel& model);

// Throws trivar::Error when a cell is untrimmed (a model mixing both kinds has no common boundary mesh yet).
ModelTessellation trimmed_boundary_mesh(const VModel& model);

}  // namespace trivar
