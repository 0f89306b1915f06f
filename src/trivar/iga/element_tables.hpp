#pragma once
// Per-direction quadrature tables of a tensor patch: for every element of one knot vector, the Gauss points,
// their weights (scaled to the element) and the p+1 B-splines active there with their first derivatives at
// those points. A tensor element's basis is the product of one element per direction, so these 1-D tables
// are all the basis data that sum-factorised assembly needs.
#include <vector>

#include "trivar/spline/knot_vector.hpp"

namespace trivar {

struct DirectionTable {
  int degree = 0;
  int points = 0;                 // Gauss points per element
  std::vector<int> first;         // per element: index of its first active B-spline
  std::vector<double> lo, hi;     // per element: parameter interval
  std::vector<double> u;          // [e * points + q]: parameters of the points
  std::vector<double> weight;     // [e * points + q]: Gauss weight times element length
  std::vector<double> val, der;   // [(e * (degree + 1) + i) * points + q]: B-spline first[e] + i and its derivative

  int elements() const { return static_cast<int>(first.size()); }
  int functions() const { return degree + 1; }
  const double* values(int e) const { return val.data() + static_cast<std::size_t>(e) * functions() * points; }
  const double* derivatives(int e) const { return der.data() + static_cast<std::size_t>(e) * functions() * points; }
};

// Tables for the non-empty knot spans of kv with `points` Gauss-Legendre points each (points >= 1).
DirectionTable direction_table(const KnotVector& kv, int points);

}  // namespace trivar
