#pragma once
// A crack-free triangulation of a T-spline surface to a chordal tolerance. The Bezier elements are the cells
// of one grid (all knot values), so neighbouring elements share whole sides. Each element gets its own
// subdivision n_u x n_v from its Bezier net: a rigorous bound D_uu, D_uv, D_vv on the second derivatives of
// its rational patch (element units) and the linear interpolation bound
// (D_uu / n_u^2 + 2 D_uv / (n_u n_v) + D_vv / n_v^2) / 8 <= tolerance, with the fewest sub-cells. Each side is
// sampled once, for both elements on it, as finely as the finer of them needs; an element whose sides are finer
// than its own lattice keeps the lattice one step inside and zips the ring between to the sides. No T-vertices,
// so no cracks, and every triangle spans at most one sub-cell of its element in each direction.
#include <array>
#include <vector>

#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {

struct TSplineTriangulation {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<double, 2>> params;   // (s, t) of every point
  std::vector<std::array<int, 3>> triangles;   // counter-clockwise in (s, t)
};

// tolerance > 0 (model units); max_per_element bounds the subdivision of one element side (an element that would
// need more is cut max_per_element times, and the tolerance is not met there).
TSplineTriangulation tessellate(const TSplineSurface& surface, double tolerance, int max_per_element = 64,
                                int threads = 0);

}  // namespace trivar
