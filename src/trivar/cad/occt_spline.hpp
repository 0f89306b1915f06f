#pragma once
// Internal to the cad layer (includes OpenCASCADE): exact conversion of the kernel's B-spline curves and
// surfaces to trivar's TensorSpline (flat knot vectors, u-fastest control grids, homogeneous weights) and back.
#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar::cad {

// Periodic splines are unrolled to their clamped form first (the same geometry).
TensorSpline<2> to_spline(const Geom_BSplineSurface& s);
TensorSpline<1> to_spline(const Geom_BSplineCurve& c);    // control dimension 3
TensorSpline<1> to_spline(const Geom2d_BSplineCurve& c);  // control dimension 2

// The other way (exact): a surface of control dimension 3, a curve of control dimension 2.
Handle(Geom_BSplineSurface) to_occt(const TensorSpline<2>& s);
Handle(Geom2d_BSplineCurve) to_occt_2d(const TensorSpline<1>& c);

}  // namespace trivar::cad
