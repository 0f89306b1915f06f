#pragma once
// VCell: a volumetric cell of a V-model (seed 001, Def. 3.2): the intersection of one or more trivariates,
// delineated by trimming surfaces, carrying named attributes. A cell is one trivariate (its geometry), untrimmed
// or trimmed by a closed boundary of trimming surfaces (trimmed_solid.hpp): the cell is then the part of the
// trivariate's image inside the boundary. A trimmed cell's trivariate is today the identity on an axis-aligned
// box around the boundary (x(u) = u), so its parameter and model points coincide and attributes in either
// space are evaluated at the same point. The list of trivariates keeps room for the general definition. The
// geometry is immutable after construction (the model's topology depends on it); attributes may change.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/model/attribute.hpp"
#include "trivar/model/trimmed_solid.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

class VCell {
public:
  // Throws trivar::Error unless the trivariate has control dimension 3.
  explicit VCell(TensorSpline<3> geometry) {
    require(geometry.dim() == 3, "V-cell: the trivariate must have control dimension 3, got " +
                                     std::to_string(geometry.dim()));
    trivariates_.push_back(std::move(geometry));
  }
  // A trimmed cell. Throws trivar::Error unless the trivariate is the identity on a box (every control point at
  // its Greville point) that contains the boundary's box.
  VCell(TensorSpline<3> geometry, std::shared_ptr<const TrimmedSolid> trim);

  bool is_trimmed() const { return trim_ != nullptr; }
  // The trimming boundary, or null for an untrimmed cell.
  const TrimmedSolid* trim() const { return trim_.get(); }
  const std::shared_ptr<const TrimmedSolid>& shared_trim() const { return trim_; }
  // Whether the cell parameter u lies in the cell (always for an untrimmed cell's domain).
  bool contains_param(const Param<3>& u) const;

  const TensorSpline<3>& geometry() const { return trivariates_.front(); }
  const std::vector<TensorSpline<3>>& trivariates() const { return trivariates_; }

  void set_attribute(const std::string& name, Attribute a) { attributes_.insert_or_assign(name, std::move(a)); }
  bool has_attribute(const std::string& name) const { return attributes_.count(name) != 0; }
  // Throws trivar::Error when the cell has no attribute of that name.
  const Attribute& attribute(const std::string& name) const {
    auto it = attributes_.find(name);
    require(it != attributes_.end(), "V-cell: no attribute '" + name + "'");
    return it->second;
  }
  const std::map<std::string, Attribute>& attributes() const { return attributes_; }
  // attribute(name).components() values at the cell parameter u.
  void eval_attribute(const std::string& name, const Param<3>& u, double* out) const {
    attribute(name).eval(geometry(), u, out);
  }

private:
  std::vector<TensorSpline<3>> trivariates_;
  std::shared_ptr<const TrimmedSolid> trim_;
  std::map<std::string, Attribute> attributes_;
};

// The trivariate of a trimmed cell: the identity x(u) = u on the box (degree 1, one element per direction).
TensorSpline<3> identity_box(const Box<3>& b);

}  // namespace trivar
