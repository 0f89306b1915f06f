#pragma once
// A model mixing trimmed and untrimmed cells with every cell trimmed, for what reads trimmed cells only (the
// detrimmed analysis of iga/trimmed_model_space). Each untrimmed cell becomes a trimmed cell of the same
// region: the union (boolean.hpp) of the untrimmed cells with the trimmed ones, which do not overlap, so one
// general fuse meshes every face between two cells once and the cells share those faces as a Boolean's do.
// Attributes are carried as the Boolean carries those of one operand (constants and model-space formulas
// exactly, fields and parametric formulas of untrimmed cells as fitted spline fields).
#include "trivar/cad/boolean.hpp"

namespace trivar::cad {

// The model itself when no cell is untrimmed or none is trimmed; otherwise its cells (in an order of the
// kernel's choosing) all trimmed. Throws trivar::Error when cells overlap (the union would merge them).
VModel trimmed_form(const VModel& model, const BooleanOptions& options = {});

}  // namespace trivar::cad
