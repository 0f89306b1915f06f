#pragma once
// A field sampled at scattered model points (material fractions measured or simulated for additive
// manufacturing, a density, a temperature) fitted over a V-cell and attached to it as a spline-field attribute,
// which slicing, 3MF/AMF export and analysis then read like any other. The samples are carried into the cell's
// parameters (point inversion of its trivariate; a trimmed cell's parameters are model coordinates), fitted there
// by the adaptive LR approximation on the cell's whole parameter box, and the LR volume is written exactly as a
// tensor spline (tensor_expansion), the form a field attribute takes.
#include <cstddef>

#include "trivar/fit/lr_approximation.hpp"
#include "trivar/model/vcell.hpp"

namespace trivar {

struct CellFieldOptions {
  ApproximationOptions fit;
  // Material fractions: coefficients below 0 are raised to 0 after the fit and the B-spline's other fractions
  // scaled to keep its sum, so by the convex hull property the field is >= 0 everywhere in the cell (what slicing
  // requires), not only at the samples, and fractions that sum to 1 still do.
  bool fractions = false;
};

struct CellField {
  Attribute attribute;           // Attribute::field over the cell's parameter box
  Approximation<3> fit;          // the LR fit in the cell's parameters (before any clamping)
  std::size_t used = 0;          // samples inside the cell
  std::size_t outside = 0;       // samples whose point is not in the cell (skipped)
  double clamped = 0.0;          // fractions: the largest amount a coefficient was raised by
  double max_error = 0.0;        // at the used samples, of the attached field (after clamping)
};

// samples: model points (x, y, z) with data.dim values. Throws trivar::Error naming the problem when fewer than
// the fit needs lie in the cell, or for bad options or values (as approximate).
CellField fit_cell_field(const VCell& cell, const ScatteredData<3>& samples, const CellFieldOptions& options);

}  // namespace trivar
