#pragma once
// Analysis on a V-model of trimmed cells (the result of a Boolean or a split, or an imported part): one tensor
// B-spline space of degree p on the box around all cells (the identity geometry, as for one trimmed cell,
// trimmed_space.hpp), detrimmed cell by cell. Each element integrates its piece in every cell it meets with
// that cell's detrimmed rule, so the cells partition the quadrature exactly; the trimming boundary is the
// model's boundary only: faces two cells share (trimmed_interfaces.hpp) carry no boundary terms, and faces in
// a side plane of the box are the sides of the domain, where strong Dirichlet conditions go.
//
// Coupling across the interior V-surfaces: the cells share one spline space, so the solution is continuous
// (C^(p-1)) across the faces between cells and no interface terms are needed. That is the exact coupling for
// cells of one material; where the material jumps between cells, the exact solution's gradient has a kink on
// the shared face that the smooth splines resolve only to first order near it (cells carry their materials
// through cell_at; per-cell spaces coupled weakly across the face, e.g. by Nitsche's method, are not built).
#include <functional>
#include <vector>

#include "trivar/iga/trimmed_space.hpp"
#include "trivar/model/trimmed_interfaces.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar {

struct TrimmedModelSpace {
  RefinedSpace<3> space;
  Box<3> box;                        // the analysis box: the union of the cells' analysis boxes
  std::vector<Face> sides;           // sides of the box that hold a face of some cell (Dirichlet candidates)
  TrimmedInterfaces interfaces;      // the faces the cells share
  std::vector<std::vector<int>> element_cells;  // per element: the cells holding its quadrature points
  int cut = 0, outside = 0;          // elements cut by some trimming face, elements outside every cell
  // The cell containing the model point x (-1 when none): the element's one cell, or the cell among the
  // element's cells whose solid contains x. Thread-safe; valid while this object and the model live.
  int cell_at(const double* x) const;
  double volume() const;             // the sum of the quadrature weights
  const VModel* model = nullptr;
};

// The analysis space of a model whose cells are all trimmed. Throws trivar::Error for an untrimmed cell, faces
// only partly shared between cells (trimmed_interfaces' non-conforming ones), and what trimmed_space throws.
TrimmedModelSpace trimmed_model_space(const VModel& model, int degree, int elements, int threads = 0,
                                      const TrimmedSpaceOptions& opts = {});

}  // namespace trivar
