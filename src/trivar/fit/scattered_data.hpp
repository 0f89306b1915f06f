#pragma once
// ScatteredData<D>: points in a D-dimensional parameter box, each with `dim` values: terrain (x, y; z) is
// D = 2, dim = 1; a volumetric scalar field (x, y, z; f) is D = 3, dim = 1; sampled material fractions
// (x, y, z; m fractions) are D = 3, dim = m. The coordinates are the parameters of the fitted spline (a height
// field or a field over the box), so no parametrisation step is needed.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "trivar/core/box.hpp"

namespace trivar {

template <int D>
struct ScatteredData {
  int dim = 1;                    // values per point
  std::vector<Param<D>> params;   // one per point
  std::vector<double> values;     // dim per point, point-major

  std::size_t size() const { return params.size(); }
  const double* value(std::size_t i) const { return values.data() + i * static_cast<std::size_t>(dim); }
  // Bounding box of the parameters.
  Box<D> bounding_box() const;
};

// A table of numbers read from a point file: `columns` values per row, row-major.
struct PointTable {
  int columns = 0;
  std::vector<double> values;
  std::size_t rows() const { return columns ? values.size() / static_cast<std::size_t>(columns) : 0; }
};

// The first D columns are the parameters, the others the values. Validates what a fit needs, throwing
// trivar::Error with a one-line message naming `source` and the row (1-based) at fault: at least D + 1 columns,
// every number finite, at least `min_points` rows, and points that span the box (not all on a line in 2D or a
// plane in 3D: the smallest principal axis of the parameters is above 1e-5 of the largest).
template <int D>
ScatteredData<D> scattered_data(const PointTable& table, const std::string& source, std::size_t min_points = 0);

// The same check for data built in memory (source names it in messages).
template <int D>
void validate(const ScatteredData<D>& data, const std::string& source, std::size_t min_points = 0);

extern template struct ScatteredData<2>;
extern template struct ScatteredData<3>;

}  // namespace trivar
