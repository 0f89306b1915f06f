#pragma once
// VModel: a complex of V-cells (seed 001, Def. 3.3) with the topology built by gluing, and the queries of the
// V-rep data structure: neighbours, cells around a V-curve, relation of two cells, volume, mass, bounding box.
#include <string>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/model/glue.hpp"
#include "trivar/model/material_table.hpp"
#include "trivar/model/vcell.hpp"
#include "trivar/model/vtopology.hpp"

namespace trivar {

// How two cells touch, strongest first: sharing a V-surface, else a V-curve, else a V-point.
enum class CellRelation { none = 0, point = 1, curve = 2, face = 3 };

class VModel {
public:
  // Adds a cell and returns its index; the topology is dropped until the next glue().
  int add_cell(VCell cell);
  int num_cells() const { return static_cast<int>(cells_.size()); }
  const std::vector<VCell>& cells() const { return cells_; }
  const VCell& cell(int i) const;
  // Mutable access changes attributes only (a cell's geometry is immutable), so the topology stays valid.
  VCell& cell(int i);

  // The materials the cells' "material" attributes refer to, by component index (names and display colours
  // for slices, 3MF and AMF). Empty when the model has no material attribute.
  const MaterialTable& materials() const { return materials_; }
  void set_materials(MaterialTable m) { materials_ = std::move(m); }

  // Builds (replaces) the topology; see glue.hpp.
  const VTopology& glue(const GlueOptions& options = {});
  bool is_glued() const { return glued_; }
  // Throws trivar::Error when the model has not been glued since the last add_cell().
  const VTopology& topology() const;

  // Cells related to `cell` at least as strongly as `at_least` (face: sharing a V-surface), ascending,
  // without `cell` itself.
  std::vector<int> neighbours(int cell, CellRelation at_least = CellRelation::face) const;
  std::vector<int> cells_around_curve(int curve) const { return topology().cells_around_curve(curve); }
  CellRelation relation(int a, int b) const;

  // Box of all control points: contains the model (convex hull property, positive weights).
  Box<3> bounding_box() const;
  // Sum of the cells' volumes by Gauss quadrature with n points per element and direction; n = 0 picks
  // ceil(3 p / 2) + 1 for polynomial cells of maximal degree p (exact: det J has degree 3p - 1) and 2 p + 8 for
  // rational ones (det J is rational; the error decays spectrally: for a revolved annulus with one quarter-circle
  // segment per element, 8 points give 1e-11 relative, 12 give 2e-15).
  double volume(int n = 0) const;
  // Sum over cells of the integral of density * |det J|, where `density` names a scalar attribute every cell
  // has. Elements are the union of the geometry's and (for a field) the density field's knot spans, so a
  // field density is integrated exactly by the same rule as volume(); expressions are integrated to the
  // accuracy of the rule. Throws trivar::Error when a cell lacks the attribute or it is not scalar.
  double mass(const std::string& density, int n = 0) const;
  // The attribute's values at parameter u of a cell.
  void eval_attribute(int cell, const std::string& name, const Param<3>& u, double* out) const {
    this->cell(cell).eval_attribute(name, u, out);
  }

private:
  std::vector<VCell> cells_;
  MaterialTable materials_;
  VTopology topology_;
  bool glued_ = false;
};

}  // namespace trivar
