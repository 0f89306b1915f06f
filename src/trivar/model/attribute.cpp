#include "trivar/model/attribute.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"

namespace trivar {

Attribute Attribute::constant(std::vector<double> values) {
  require(!values.empty(), "constant attribute: no values");
  for (std::size_t k = 0; k < values.size(); ++k)
    require(std::isfinite(values[k]), "constant attribute: value " + std::to_string(k) + " is not finite");
  Attribute a;
  a.kind_ = Kind::constant;
  a.values_ = std::move(values);
  return a;
}

Attribute Attribute::field(TensorSpline<3> spline) {
  require(spline.num_coefs() > 0 && spline.dim() > 0, "field attribute: empty spline");
  Attribute a;
  a.kind_ = Kind::field;
  a.field_ = std::make_shared<const TensorSpline<3>>(std::move(spline));
  return a;
}

Attribute Attribute::expression(const std::vector<std::string>& components, Space space) {
  require(!components.empty(), "expression attribute: no components");
  Attribute a;
  a.kind_ = Kind::expression;
  a.space_ = space;
  const std::vector<std::string> vars =
      space == Space::model ? std::vector<std::string>{"x", "y", "z"} : std::vector<std::string>{"u", "v", "w"};
  for (const auto& c : components) a.expressions_.push_back(Expression::parse(c, vars));
  return a;
}

int Attribute::components() const {
  switch (kind_) {
    case Kind::constant: return static_cast<int>(values_.size());
    case Kind::field: return field_->dim();
    case Kind::expression: return static_cast<int>(expressions_.size());
  }
  return 0;
}

void Attribute::eval(const TensorSpline<3>& geometry, const Param<3>& u, double* out) const {
  const Box<3> cell = geometry.domain();
  Param<3> t;
  for (int k = 0; k < 3; ++k) t[k] = std::clamp(u[k], cell.lo[k], cell.hi[k]);
  switch (kind_) {
    case Kind::constant: std::copy(values_.begin(), values_.end(), out); return;
    case Kind::field: {
      const Box<3> f = field_->domain();
      Param<3> s;
      for (int k = 0; k < 3; ++k) s[k] = f.lo[k] + (t[k] - cell.lo[k]) / cell.extent(k) * f.extent(k);
      field_->eval(s, out);
      return;
    }
    case Kind::expression: {
      double vars[3] = {t[0], t[1], t[2]};
      if (space_ == Space::model) {
        // The message is built only on failure: this runs once per slicer pixel.
        require(geometry.dim() == 3,
                [] { return std::string("expression attribute in x, y, z: cell geometry is not in 3-space"); });
        geometry.eval(t, vars);
      }
      for (std::size_t c = 0; c < expressions_.size(); ++c) out[c] = expressions_[c].eval(vars);
      return;
    }
  }
}

}  // namespace trivar
