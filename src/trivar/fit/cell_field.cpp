#include "trivar/fit/cell_field.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/fit/least_squares.hpp"
#include "trivar/lr/tensor_expansion.hpp"
#include "trivar/spline/point_inversion.hpp"

namespace trivar {

CellField fit_cell_field(const VCell& cell, const ScatteredData<3>& samples, const CellFieldOptions& options) {
  validate(samples, "cell field");
  const TensorSpline<3>& geometry = cell.geometry();
  const Box<3> domain = geometry.domain();
  // Each sample's cell parameter, or a flag that its point lies outside the cell.
  std::vector<Param<3>> u(samples.size());
  std::vector<char> inside(samples.size(), 0);
  if (cell.is_trimmed()) {  // the trivariate is the identity on its box; the trimming surfaces bound the solid
    for (std::size_t i = 0; i < samples.size(); ++i) {
      u[i] = samples.params[i];
      bool in = true;
      for (int k = 0; k < 3; ++k) in = in && domain.lo[k] <= u[i][k] && u[i][k] <= domain.hi[k];
      inside[i] = in && cell.contains_param(u[i]);
    }
  } else {
    InversionOptions precise;  // the samples are exact to rounding: their parameters should be too
    precise.tolerance = 1e-13;
    const PointInverter<3> inverter(geometry, precise);
    parallel_for(static_cast<std::ptrdiff_t>(samples.size()), options.fit.threads, [&](std::ptrdiff_t i) {
      const auto I = static_cast<std::size_t>(i);
      const double x[3] = {samples.params[I][0], samples.params[I][1], samples.params[I][2]};
      const InversionResult<3> r = inverter.invert(x);
      inside[I] = r.found && r.converged;
      u[I] = r.param;
    });
  }
  ScatteredData<3> data;
  data.dim = samples.dim;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!inside[i]) continue;
    data.params.push_back(u[i]);
    data.values.insert(data.values.end(), samples.value(i), samples.value(i) + samples.dim);
  }
  const std::size_t used = data.size(), outside = samples.size() - used;
  require(used >= 4, "cell field: " + std::to_string(used) + " of " + std::to_string(samples.size()) +
                         " samples lie in the cell, at least 4 needed");
  Approximation<3> fit = approximate(data, options.fit, {}, &domain);
  LRSpline<3> field = fit.spline;
  double clamped = 0.0;
  if (options.fractions) {
    std::vector<double> coefs;
    coefs.reserve(static_cast<std::size_t>(field.num_basis() * field.dim()));
    for (const LRBSpline<3>& b : field.basis_functions()) {
      // Negative fractions raised to 0 and the others scaled to keep the B-spline's sum: the fit of fractions
      // summing to 1 sums to 1 (the fit is linear and reproduces constants), and so does the clamped field.
      double sum = 0.0, positive = 0.0;
      for (double c : b.coef) {
        sum += c;
        positive += std::max(c, 0.0);
        clamped = std::max(clamped, -c);
      }
      const double scale = positive > 0.0 && sum > 0.0 ? sum / positive : 1.0;
      for (double c : b.coef) coefs.push_back(std::max(c, 0.0) * scale);
    }
    if (clamped > 0.0) field = with_coefficients(field, field.dim(), coefs);
  }
  std::vector<double> values(data.values.size());
  field.eval_many(std::span<const Param<3>>(data.params), values, options.fit.threads);
  double max_error = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) max_error = std::max(max_error, std::abs(values[i] - data.values[i]));
  return CellField{Attribute::field(tensor_expansion(field)), std::move(fit), used, outside, clamped, max_error};
}

}  // namespace trivar
