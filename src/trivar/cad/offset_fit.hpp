#pragma once
// Internal to the cad layer (includes OpenCASCADE): the NURBS form of an offset surface P + d N whose basis is
// not an analytic surface (a B-spline or Bezier surface, a surface of revolution or extrusion). Its unit normal
// carries a square root, so the offset has no rational form in general and is fitted, with the basis's
// parametrisation (the face's parameter-space curves carry over unchanged).
//
// Written here because the kernel's conversion (GeomConvert's approximation of Geom_OffsetSurface) stops at a
// fixed 1e-4 model units, far above the 1e-6 relative volume an import must reach.
//
// The fit is C0 piecewise quintic: on each cell of a tensor grid the biquintic interpolating the exact offset at
// the 6 x 6 points of the cell's fifths (adjacent cells share their edge's points, so the patches meet exactly).
// Cells start at the basis's breakpoints (the offset is smooth between them); a cell whose deviation from the
// exact offset at the tenths of the cell (the 96 points midway between interpolation nodes) exceeds half the
// tolerance is halved in the direction(s) whose iso-lines carry the error, until every cell passes. (The
// interpolation error peaks near those midpoints: the half leaves the margin for the tolerance to hold
// everywhere.)
#include <Geom_Surface.hxx>

#include "trivar/core/box.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar::cad {

struct OffsetFit {
  TensorSpline<2> surface;  // degree 5 x 5, non-rational, control dimension 3, over the box given
  double deviation = 0;     // the largest deviation found at the check points of the last grid
};

// The offset `distance` along the unit normal Su x Sv / |Su x Sv| of `basis` over `uv`, within `tolerance`
// (model units). Throws trivar::Error when the basis's normal is undefined at a point of
// the box (a collapsed edge, a cusp) or when the fit would need more than 2^18 control points.
OffsetFit fit_offset_surface(const Handle(Geom_Surface)& basis, double distance, const Box<2>& uv, double tolerance);

}  // namespace trivar::cad
