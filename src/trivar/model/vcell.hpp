#pragma once
// VCell: a volumetric cell of a V-model (seed 001, Def. 3.2): the intersection of one or more trivariates,
// delineated by trimming surfaces, carrying named attributes. Trimming is not supported yet, so a cell is one
// untrimmed trivariate (its geometry); the list of trivariates keeps room for the general definition. The
// geometry is immutable after construction (the model's topology depends on it); attributes may change.
#include <map>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/model/attribute.hpp"
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
  std::map<std::string, Attribute> attributes_;
};

}  // namespace trivar
