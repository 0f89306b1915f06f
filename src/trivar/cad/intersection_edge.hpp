#pragma once
// Internal to the cad layer (includes OpenCASCADE). An edge where two faces meet transversally lies on the
// intersection of their surfaces; the kernel's general fuse approximates intersection curves (its pcurves sit
// up to a few 1e-7 off the exact intersection of B-spline patches), which costs volumes 1e-8 and more. This
// rebuilds such an edge from points solved onto the exact intersection: at each node t, Newton's method on
// S1(u1, v1) = S2(u2, v2) with the point held in the plane through the kernel's edge point normal to the
// intersection's direction. The parameter-space curves on both faces and the 3D curve are interpolated per
// span as Bezier pieces (degree 6, C0 at span ends, the kernel's parameter t kept), spans halved until the
// pieces meet the solved points between the nodes to the tolerance.
#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>

#include <optional>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar::cad {

struct IntersectionEdge {
  TensorSpline<1> on_first, on_second;  // control dimension 2: (u, v) on each surface, over the edge's [t0, t1]
  TensorSpline<1> curve;                // control dimension 3
  double deviation = 0;                 // largest distance found between the pieces and the solved points
};

// The edge over [t0, t1] given by its 3D curve and its curves on both surfaces. Empty when the surfaces meet
// at an angle below about 1 degree somewhere (tangent contact: no transversal intersection to solve for) or
// Newton's method fails. `scale`: the model's size (the pieces meet the solved points to 1e-11 of it).
std::optional<IntersectionEdge> solve_intersection_edge(const Handle(Geom_Surface)& s1, const Handle(Geom2d_Curve)& c1,
                                                        const Handle(Geom_Surface)& s2, const Handle(Geom2d_Curve)& c2,
                                                        const Handle(Geom_Curve)& c3, double t0, double t1, double scale);

}  // namespace trivar::cad
