#pragma once
// A crack-free triangulation of a T-spline surface to a chordal tolerance. The Bezier elements are the cells
// of one grid (all knot values), so neighbouring elements share whole sides: every grid column and row gets one
// subdivision count, and the sample points form one lattice shared by all elements (no T-vertices, so no
// cracks at T-junctions). Counts come from the Bezier nets: on a patch with second differences D_uu, D_uv, D_vv
// (degree-scaled, in element units) the bilinear interpolant of n_u x n_v sub-cells deviates by at most
// (D_uu / n_u^2 + 2 D_uv / (n_u n_v) + D_vv / n_v^2) / 8 (the rational patch is estimated by its Cartesian net).
#include <array>
#include <vector>

#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {

struct TSplineTriangulation {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<double, 2>> params;   // (s, t) of every point
  std::vector<std::array<int, 3>> triangles;   // counter-clockwise in (s, t)
};

// tolerance > 0 (model units); max_per_element bounds the subdivision of one element side.
TSplineTriangulation tessellate(const TSplineSurface& surface, double tolerance, int max_per_element = 64,
                                int threads = 0);

}  // namespace trivar
