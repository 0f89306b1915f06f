#pragma once
// Maps ISO 10303-42 spline entities of a parsed exchange structure to trivar objects:
//   curves   B_SPLINE_CURVE_WITH_KNOTS, BEZIER_CURVE, UNIFORM_CURVE, QUASI_UNIFORM_CURVE, and complex
//            instances of B_SPLINE_CURVE with one of those and/or RATIONAL_B_SPLINE_CURVE   -> TensorSpline<1>
//   surfaces the same for B_SPLINE_SURFACE(_WITH_KNOTS), BEZIER/UNIFORM/QUASI_UNIFORM_SURFACE,
//            RATIONAL_B_SPLINE_SURFACE                                                         -> TensorSpline<2>
//   volumes  B_SPLINE_VOLUME(_WITH_KNOTS), BEZIER/UNIFORM/QUASI_UNIFORM_VOLUME, RATIONAL_B_SPLINE_VOLUME
//            (no knot_spec on volumes)                                                         -> TensorSpline<3>
//   LOCALLY_REFINED_SPLINE_SURFACE / _VOLUME and RATIONAL_LOCALLY_REFINED_SPLINE_SURFACE / _VOLUME (simple
//            or complex instances) with their LOCAL_B_SPLINEs                                  -> LRSpline<2|3>
//   LOCALLY_REFINED_SPLINE_CURVE and its rational form: exactly the B-spline curve on the union of the local
//            knot vectors (a univariate LR space is a tensor space)                            -> TensorSpline<1>
// Uniform, quasi-uniform and Bezier forms get the knots Part 42 defines for them (spacing 1; uniform starts at
// -degree with simple knots; quasi-uniform starts at 0 with end multiplicity degree + 1; Bezier is quasi-uniform
// with interior multiplicity degree). Control grids are listed u outermost in STEP and stored u fastest here.
// Rational entities give Cartesian points and weights; trivar stores w * x, one rounding per coordinate.
//
// LR splines. The B-splines' local knot indices may be 0- or 1-based (the published text is inconsistent): an
// index 0 anywhere in the entity means 0-based, otherwise 1-based. STEP stores no box mesh; it is rebuilt as the
// union of the B-splines' knot lines (knot_line_mesh, trivar/lr/knot_line_mesh.hpp).
//
// Every rule of the standard is checked (knot sums, multiplicities, strictly increasing knots, weights > 0,
// grid shapes, local multiplicities summing to degree + 2, scaling factors in (0, 1], domain) and every failure
// is one trivar::Error "file:line:column: #id: KEYWORD: message". A reference to an instance of the wrong type
// or to no instance is an error of the same form.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "trivar/io/step/exchange_file.hpp"
#include "trivar/lr/any_lr_spline.hpp"
#include "trivar/spline/any_spline.hpp"

namespace trivar::io::step {

enum class GeometryKind { none, curve, surface, volume, lr_curve, lr_surface, lr_volume };

// "curve", "surface", "volume", "lr_curve", "lr_surface", "lr_volume" ("none" for none).
const char* to_string(GeometryKind kind);

// What an instance is, by its keywords alone (no validation). LOCAL_B_SPLINE and CARTESIAN_POINT are parts,
// not objects: none.
GeometryKind geometry_kind(const Instance& instance);

// The keywords the mapper reads (spline entities, their parts, CARTESIAN_POINT); a ReadOptions::keep filter.
bool is_geometry_keyword(std::string_view keyword);

// The parts of a locally refined surface or volume (homogeneous control values when rational) and its
// locally_refined_spline_type, for kinds whose B-splines need not sum to one (T-splines, hierarchical
// B-splines).
template <int D>
struct LocallyRefinedParts {
  Ints<D> degrees{};
  int dim = 0;
  bool rational = false;
  std::vector<LRBSpline<D>> basis;
  std::string type;  // e.g. "STANDARD_T_SPLINE"
};
using LocallyRefinedSurfaceParts = LocallyRefinedParts<2>;

class GeometryReader {
public:
  // `file_name` prefixes messages; the instances' line and column come from the parser.
  GeometryReader(const ExchangeFile& file, std::string file_name);

  // Throws trivar::Error (as above) when the instance is not a valid spline of that kind.
  // Tensor kinds and locally refined curves.
  AnySpline tensor_spline(const Instance& instance) const;
  AnyLRSpline lr_spline(const Instance& instance) const;
  // A locally refined surface's B-splines and type, validated like lr_spline except for the partition of unity.
  LocallyRefinedSurfaceParts locally_refined_surface_parts(const Instance& instance) const;
  LocallyRefinedParts<3> locally_refined_volume_parts(const Instance& instance) const;
  // The locally_refined_spline_type of a locally refined surface or volume as written (empty when absent or
  // not an enumeration; lr_spline reports that), without reading the rest.
  std::string locally_refined_type(const Instance& instance) const;
  // The representation_item name (first parameter of the simple instance or of REPRESENTATION_ITEM).
  std::string name(const Instance& instance) const;

private:
  const ExchangeFile& file_;
  std::string file_name_;

  template <int D>
  TensorSpline<D> read_tensor(const Instance& in) const;
  template <int D>
  LRSpline<D> read_lr(const Instance& in) const;
  TensorSpline<1> read_lr_curve(const Instance& in) const;
};

}  // namespace trivar::io::step
