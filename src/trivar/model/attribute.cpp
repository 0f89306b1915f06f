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

void Attribute::eval(const TensorSpline<3>& geometry, const Param<3>& u, double* out) const { eval_at(geometry, u, nullptr, out); }

void Attribute::eval_at(const TensorSpline<3>& geometry, const Param<3>& u, const double* point, double* out) const {
  if (kind_ == Kind::constant) {
    std::copy(values_.begin(), values_.end(), out);
    return;
  }
  const Box<3> cell = geometry.domain();
  Param<3> t;
  for (int k = 0; k < 3; ++k) t[k] = std::clamp(u[k], cell.lo[k], cell.hi[k]);
  if (kind_ == Kind::field) {
    const Box<3> f = field_->domain();
    Param<3> s;
    for (int k = 0; k < 3; ++k) s[k] = f.lo[k] + (t[k] - cell.lo[k]) / cell.extent(k) * f.extent(k);
    field_->eval(s, out);
    return;
  }
  double vars[3] = {t[0], t[1], t[2]};
  if (space_ == Space::model) {
    // The message is built only on failure: this runs once per slicer pixel.
    require(geometry.dim() == 3,
            [] { return std::string("expression attribute in x, y, z: cell geometry is not in 3-space"); });
    if (point && t == u) std::copy(point, point + 3, vars);
    else geometry.eval(t, vars);
  }
  for (std::size_t c = 0; c < expressions_.size(); ++c) out[c] = expressions_[c].eval(vars);
}

namespace {

// The expressions at n points whose variables fill(i, x) writes, by columns in blocks that stay in the L1 cache.
template <class Fill>
void eval_expression_columns(const std::vector<Expression>& expressions, std::size_t n, Fill&& fill, double* out) {
  const std::size_t m = expressions.size();
  constexpr std::size_t kBlock = 256;
  double columns[3][kBlock], values[kBlock];
  for (std::size_t first = 0; first < n; first += kBlock) {
    const std::size_t b = std::min(kBlock, n - first);
    for (std::size_t i = 0; i < b; ++i) {
      double x[3];
      fill(first + i, x);
      for (int k = 0; k < 3; ++k) columns[k][i] = x[k];
    }
    const double* const vars[3] = {columns[0], columns[1], columns[2]};
    for (std::size_t c = 0; c < m; ++c) {
      expressions[c].eval_many(vars, b, values);
      for (std::size_t i = 0; i < b; ++i) out[m * (first + i) + c] = values[i];
    }
  }
}

}  // namespace

void Attribute::eval_many(const TensorSpline<3>& geometry, std::span<const Param<3>> u, const double* points,
                          double* out) const {
  const auto n = u.size();
  const auto m = static_cast<std::size_t>(components());
  if (kind_ != Kind::expression) {
    for (std::size_t i = 0; i < n; ++i) eval_at(geometry, u[i], nullptr, out + m * i);
    return;
  }
  require(!uses_model_point() || geometry.dim() == 3,
          [] { return std::string("expression attribute in x, y, z: cell geometry is not in 3-space"); });
  const Box<3> cell = geometry.domain();
  const bool model = uses_model_point();
  eval_expression_columns(expressions_, n, [&](std::size_t i, double* x) {
    Param<3> t;
    for (int k = 0; k < 3; ++k) t[k] = std::clamp(u[i][k], cell.lo[k], cell.hi[k]);
    std::copy(t.begin(), t.end(), x);
    if (model) {
      if (t == u[i]) std::copy(points + 3 * i, points + 3 * i + 3, x);
      else geometry.eval(t, x);
    }
  }, out);
}

void Attribute::eval_model_points(std::span<const double> points, double* out) const {
  require(uses_model_point(),
          [] { return std::string("attribute: model points given to an attribute that is not a model-space expression"); });
  eval_expression_columns(expressions_, points.size() / 3,
                          [&](std::size_t i, double* x) { std::copy(&points[3 * i], &points[3 * i] + 3, x); }, out);
}

}  // namespace trivar
