#pragma once
// Cell attributes (materials, densities, fields): a constant vector, a spline field over the cell's parameter
// domain, or per-component expressions in model coordinates (x, y, z) or cell parameters (u, v, w).
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/model/expression.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

class Attribute {
public:
  enum class Kind { constant, field, expression };
  // Variables of an expression attribute: model coordinates x, y, z of the cell's geometry at the parameter,
  // or the cell parameters u, v, w themselves.
  enum class Space { model, parametric };

  // At least one value, all finite. Throws trivar::Error otherwise.
  static Attribute constant(std::vector<double> values);
  // A trivariate with any control dimension and its own knots. Its domain is mapped affinely onto the cell's
  // domain, so a field on [0, 1]^3 serves any cell. Throws trivar::Error on an empty spline.
  static Attribute field(TensorSpline<3> spline);
  // One expression per component in the variables of `space` (x,y,z or u,v,w). Throws trivar::Error (from the
  // parser) on a malformed component or on an empty list.
  static Attribute expression(const std::vector<std::string>& components, Space space);

  Kind kind() const { return kind_; }
  Space space() const { return space_; }
  int components() const;
  const std::vector<double>& values() const { return values_; }
  // The field (Kind::field) and the expressions (Kind::expression); empty for other kinds.
  const TensorSpline<3>* spline() const { return field_.get(); }
  const std::vector<Expression>& expressions() const { return expressions_; }

  // components() values at parameter u of a cell with geometry `geometry` (control dimension 3; used for the
  // cell's domain and, for model-space expressions, for x(u)). u outside the cell's domain is clamped.
  void eval(const TensorSpline<3>& geometry, const Param<3>& u, double* out) const;
  // As eval() for a u inside the cell's domain whose model point geometry(u) the caller has already
  // evaluated (point inversion ends with it): a model-space expression uses `point` instead of evaluating the
  // geometry again, so the result is the same as eval()'s when point is geometry.eval(u).
  void eval_at(const TensorSpline<3>& geometry, const Param<3>& u, const double* point, double* out) const;
  // eval_at() at u.size() parameters of one cell: points[3 i..3 i+2] = geometry(u[i]) (read only when
  // uses_model_point()), out[components() i + c] gets component c at u[i]. Expressions run over all points at
  // once (Expression::eval_many), so this is the per-pixel path of the slicer; results equal eval_at()'s.
  void eval_many(const TensorSpline<3>& geometry, std::span<const Param<3>> u, const double* points, double* out) const;
  // A model-space expression (uses_model_point()) at points.size() / 3 model points x, y, z: out[components() i
  // + c] gets component c at point i. The slicer's path: its points are geometry(u) of parameters inside the
  // cell, where eval_at() and eval_many() give the same values. Throws for other attributes.
  void eval_model_points(std::span<const double> points, double* out) const;
  // Model-space expressions read the cell's model point x(u).
  bool uses_model_point() const { return kind_ == Kind::expression && space_ == Space::model; }

private:
  Kind kind_ = Kind::constant;
  Space space_ = Space::model;
  std::vector<double> values_;
  std::shared_ptr<const TensorSpline<3>> field_;  // shared: attributes are copied with cells, fields are immutable
  std::vector<Expression> expressions_;
};

}  // namespace trivar
