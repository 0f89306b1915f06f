#pragma once
// A T-spline surface for ParaView: one exact rational Bezier quadrilateral (VTK_BEZIER_QUADRILATERAL) per Bezier
// element, with RationalWeights, HigherOrderDegrees and per cell the element id and the number of blending
// functions on it; or, from a tessellation, plain triangles with their (s, t).
#include <string>

#include "trivar/tspline/t_spline_surface.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

namespace trivar::io {

void write_t_spline_vtu(const std::string& path, const TSplineSurface& surface);
void write_triangulation_vtu(const std::string& path, const TSplineTriangulation& mesh);
// Wavefront OBJ (v, vt = (s, t), f with 1-based v/vt), written atomically.
void write_triangulation_obj(const std::string& path, const TSplineTriangulation& mesh);

}  // namespace trivar::io
