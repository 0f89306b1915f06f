#include "trivar/cad/trimmed_form.hpp"

#include <string>

#include "trivar/core/error.hpp"

namespace trivar::cad {

VModel trimmed_form(const VModel& model, const BooleanOptions& options) {
  VModel untrimmed, trimmed;
  for (const VCell& c : model.cells()) (c.is_trimmed() ? trimmed : untrimmed).add_cell(c);
  if (untrimmed.num_cells() == 0 || trimmed.num_cells() == 0) return model;
  untrimmed.glue();
  BooleanReport rep;
  VModel out = boolean(untrimmed, trimmed, BooleanOp::unite, options, &rep);
  require(rep.pieces_both == 0, "trimmed form: " + std::to_string(rep.pieces_both) +
                                    " pieces lie in an untrimmed and a trimmed cell at once (the cells overlap)");
  out.set_materials(model.materials());
  return out;
}

}  // namespace trivar::cad
