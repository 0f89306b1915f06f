#pragma once
// Internal to the cad layer (includes OpenCASCADE): the exact NURBS form of a face's surface built directly
// from its analytic definition (plane, cylinder, cone, sphere, torus; B-spline and Bezier surfaces as they
// are; offsets of these; extrusions and revolutions of lines, circles, ellipses, parabolas, B-spline and
// Bezier curves), with the map from the kernel's surface parameters to the NURBS parameters.
//
// Written here rather than taken from the kernel's BRepBuilderAPI_NurbsConvert because the kernel re-projects
// every parameter-space curve of a converted periodic face onto the new surface (an approximation, and most
// of an import's time for parts with many holes). Here the map is closed form: a linear direction keeps its
// parameter; an angular direction (cos a, sin a) becomes equal rational quadratic arcs (as many as the
// kernel's own conversion makes, so the surface is the kernel's) whose knots sit at their end angles, so on the arc between knot angles a0 and a1 = a0 + d the NURBS
// parameter is  s = a0 + d (1 + tan((a - am) / 2) / tan(d / 4)) / 2,  am = a0 + d / 2  (the stereographic
// parametrisation of a circle: the rational quadratic arc with middle weight cos(d / 2) is linear in
// tan((a - am) / 2)). Iso-lines stay iso-lines (a line u = const or v = const maps to a line), so the trimming
// curves of prismatic, turned and filleted features map exactly; other curves on an angular direction are
// approximated through the closed-form map (far closer than the kernel's re-projection, which approximates
// them too).
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Curve.hxx>
#include <TopoDS_Face.hxx>

#include <array>
#include <optional>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar::cad {

// One parameter direction of a face: the identity, or an angle whose NURBS form is a chain of arcs.
struct DirectionMap {
  std::vector<double> arc_ends;  // empty: the identity; else the knot angles a0 < a1 < ... (equal arcs)
  bool angular() const { return !arc_ends.empty(); }
  double operator()(double a) const;
  double derivative(double a) const;

private:
  std::size_t arc_of(double a) const;
};

struct FaceNurbs {
  TensorSpline<2> surface;         // control dimension 3, in model space (the face's location applied)
  std::array<DirectionMap, 2> map;  // kernel (u, v) -> surface parameters
  Param<2> operator()(double u, double v) const { return {map[0](u), map[1](v)}; }
  // The curve (u, v)(t), t in [first, last], in the surface's parameters with the same orientation: exact for
  // iso-lines and for curves whose angular coordinates are constant; other curves on an angular direction
  // (a helix, the intersection with an oblique plane) are approximated through the map to 1e-11 of the
  // parameter box (null when that takes more than 4096 cubic pieces).
  Handle(Geom2d_BSplineCurve) pcurve(const Handle(Geom2d_Curve)& c, double first, double last) const;

private:
  Handle(Geom2d_BSplineCurve) mapped_approximation(const Geom2d_BSplineCurve& c) const;
};

// The face's surface (orientation ignored) over the parameter box `uv` (the face's UV bounds), or nothing
// when the surface kind is not handled (sweeps of hyperbolas or offset curves, ...) or an angular
// direction spans more than a full turn. A circle or ellipse swept into a face keeps the angular map in its
// direction, as a cylinder's or torus's angles do. Offset surfaces keep their basis's parametrisation: the offset of a plane, cylinder, cone, sphere
// or torus is exact (the same kind with a changed radius or position); any other offset is fitted to
// `tolerance` (model units, offset_fit.hpp). Throws trivar::Error when an offset is undefined on the face (a
// degenerate basis, an offset collapsing the surface) or its fit too large.
std::optional<FaceNurbs> face_nurbs(const TopoDS_Face& face, const Box<2>& uv, double tolerance);

// Whether face_nurbs applies to the face and maps every parameter-space curve of its loops (exactly, or for
// curves across an angular direction, to 1e-11 of the parameter box). Offsets that need a fit are not fitted
// here.
bool maps_directly(const TopoDS_Face& face);

}  // namespace trivar::cad
