#pragma once
// VTK XML UnstructuredGrid (.vtu, binary and zlib-compressed: vtu_file.hpp) output of locally refined splines
// (LR splines; HB and THB splines, whose elements are the leaves of their hierarchical mesh) for ParaView, one
// <Piece> per object:
//  - bezier (default): one VTK_BEZIER_QUADRILATERAL / _HEXAHEDRON (types 77 / 79) per element of the LR mesh,
//    exact up to rounding: the element's Bezier control points (lr_bezier_extraction.hpp) in VTK's point order,
//    cell data "HigherOrderDegrees" and, for rational splines, point data "RationalWeights". Elements do not
//    share points (LR meshes have T-junctions). Needs degree >= 1 in every direction.
//  - sampled: every element of the LR mesh is sampled on its own (n+1)^D grid of parameters
//    (n = samples_per_element) and cut into n^D VTK_QUAD / VTK_HEXAHEDRON cells, points not shared.
//  - parametric_mesh: the mesh itself, one VTK_QUAD / VTK_HEXAHEDRON per element with its corners at the
//    parameters (u, v, 0) / (u, v, w).
// A node on an element's upper face inside the domain is evaluated one ulp below it, so it takes the element's
// own polynomial piece (also where the spline is discontinuous); its "param" is the exact face parameter.
// Cell data: "element" (the element id) and "support" (the number of B-splines whose support contains the
// element, which shows overloading). Point data: "param" (u, v, w; w = 0 for surfaces). Points take the first
// three control components (zeros when dim < 3); further components go to point data "higher_components".
// Callers add point fields (VtkPointField, vtk_writer.hpp: value(piece, u, out) is called at the parameter
// the point is evaluated at, so one ulp inside the element as above; in Bezier mode the file holds the Bezier
// coefficients interpolating those values, exact for a spline field on the geometry's B-splines) and cell
// fields (one value per element, repeated on the element's VTK cells), e.g. a solution on the mesh and
// per-element error indicators.
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "trivar/hier/any_hierarchical_spline.hpp"
#include "trivar/io/vtk_writer.hpp"
#include "trivar/lr/any_lr_spline.hpp"

namespace trivar::io {

enum class LRVtkCells { bezier, sampled, parametric_mesh };

struct LRVtkOptions {
  LRVtkCells cells = LRVtkCells::bezier;
  int samples_per_element = 4;  // n >= 1, sampled mode
  // The elements written: the contiguous run of element ids [first_element, last_element) of every object
  // (one process's share of a parallel output); last_element < 0 means up to the last element.
  int first_element = 0, last_element = -1;
  // When not empty: one run [first, last) per object instead (a process's share of a multi-block model, whose
  // run of the element list covers parts of several blocks).
  std::vector<std::pair<int, int>> runs{};
};

// An extra cell-data array: value(piece, element, out) writes `components` values for element `element` (the
// LR element id) of object number `piece`. Called serially.
struct LRVtkCellField {
  std::string name;
  int components = 1;
  std::function<void(int piece, int element, std::span<double> out)> value;
};

// Throws trivar::Error (nothing written) for samples_per_element < 1 when sampled, degree 0 in Bezier mode, an
// empty list, an element run outside an object's elements (or runs not one per object), a field without name or value function, with a
// duplicate or reserved name, or a write failure.
void write_lr_vtu(const std::string& path, const AnyLRSpline& s, const LRVtkOptions& opts = {},
                  const std::vector<VtkPointField>& point_fields = {},
                  const std::vector<LRVtkCellField>& cell_fields = {});
void write_lr_vtu(const std::string& path, const std::vector<AnyLRSpline>& objects, const LRVtkOptions& opts = {},
                  const std::vector<VtkPointField>& point_fields = {},
                  const std::vector<LRVtkCellField>& cell_fields = {});

// The same for hierarchical splines (element = leaf id, "support" = active functions non-zero on the leaf).
void write_hierarchical_vtu(const std::string& path, const std::vector<AnyHierarchicalSpline>& objects,
                            const LRVtkOptions& opts = {}, const std::vector<VtkPointField>& point_fields = {},
                            const std::vector<LRVtkCellField>& cell_fields = {});

}  // namespace trivar::io
