#pragma once
// VTK XML UnstructuredGrid (.vtu) output of splines for ParaView (binary, zlib-compressed: vtu_file.hpp), in
// three modes:
//  - bezier (default): one VTK_BEZIER_CURVE / _QUADRILATERAL / _HEXAHEDRON (types 75 / 77 / 79) per
//    element, exact up to rounding: its Bezier control points (Cartesian) in VTK's higher-order point order
//    (corners, edges, faces, interior), cell data "HigherOrderDegrees" and, when some object is rational,
//    point data "RationalWeights". Elements share the Bezier points of common boundaries where the spline is
//    continuous. Needs degree >= 1 in every direction.
//  - sampled: every element is sampled on an (n+1)^D grid of parameters (n = samples_per_element)
//    and cut into VTK_LINE / VTK_QUAD / VTK_HEXAHEDRON cells. Neighbouring elements share their boundary
//    samples unless the spline is discontinuous there (interior knot of multiplicity degree + 1), in which
//    case each side gets its own points, the left one evaluated at the largest double below the knot.
//  - control_net: the control net instead of the geometry: Cartesian control points joined by VTK_LINE cells
//    along every direction ("param" = Greville abscissae, cell data "direction" = 0, 1, 2 for u, v, w).
// Point data "param" holds the parameter (u, v, w) of every point, padded with zeros for curves and surfaces
// (for Bezier points: the equally spaced Bezier node parameters). Points take the first three control
// components (padded with zeros when dim < 3); further components go to point data "higher_components".
// Cell data "element" is the index of the spline element (u fastest) a cell belongs to (sampled, Bezier).
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/any_spline.hpp"

namespace trivar::io {

// An extra point-data array: value(piece, u, out) writes `components` values at parameter u (one value per
// parametric direction) of object number `piece` (0 for write_vtu of a single spline). Called serially.
// In Bezier mode it is called at the element's equally spaced node parameters and the file holds the Bezier
// coefficients interpolating those values in the element's (rational) Bernstein basis
// (spline/bernstein_interpolation.hpp): a spline field on the object's knots and weights, such as a solution,
// is shown exactly, any other field is interpolated at the nodes.
struct VtkPointField {
  std::string name;
  int components = 1;
  std::function<void(int piece, std::span<const double> u, std::span<double> out)> value;
};

// The parameter point of a field's u (D values).
template <int D>
Param<D> param_of(std::span<const double> u) {
  Param<D> p;
  for (int k = 0; k < D; ++k) p[k] = u[static_cast<std::size_t>(k)];
  return p;
}

enum class VtkCells { bezier, sampled, control_net };

struct VtkOptions {
  VtkCells cells = VtkCells::bezier;
  int samples_per_element = 4;  // n >= 1, sampled mode
};

// Throws trivar::Error (nothing written) for an empty spline, samples_per_element < 1, a degree-0 direction
// in Bezier mode, or a field without name or value function, with a duplicate or reserved name.
void write_vtu(const std::string& path, const AnySpline& s, const VtkOptions& opts = {},
               const std::vector<VtkPointField>& fields = {});
// Several objects, one <Piece> each (ParaView shows them as one data set).
void write_vtu(const std::string& path, const std::vector<AnySpline>& objects, const VtkOptions& opts = {},
               const std::vector<VtkPointField>& fields = {});

}  // namespace trivar::io
