#pragma once
// Maps trivar objects to ISO 10303-42 entities in an exchange structure (the inverse of geometry_reader.hpp):
//   TensorSpline<1|2|3> polynomial -> B_SPLINE_{CURVE,SURFACE,VOLUME}_WITH_KNOTS (simple instance)
//                       rational   -> complex instance B_SPLINE_X + B_SPLINE_X_WITH_KNOTS + RATIONAL_B_SPLINE_X
//                                     + the supertypes (REPRESENTATION_ITEM, GEOMETRIC_REPRESENTATION_ITEM, ...)
//   LRSpline<2|3>                  -> LOCALLY_REFINED_SPLINE_{SURFACE,VOLUME} or, rational,
//                                     RATIONAL_LOCALLY_REFINED_SPLINE_{SURFACE,VOLUME} (simple instances: each
//                                     is a single leaf of its supertype chain), with shared LOCAL_B_SPLINEs
//                                     (1-based knot indices), type .LR_B_SPLINE., linearly_independent
//                                     .NOT_TESTED.
//   HierarchicalSpline<2|3>        -> the same entities with type .HIERARCHICAL_B_SPLINE.: the HB basis (each
//                                     active function a B-spline of its level, scaling factor 1) with the HB
//                                     coefficients; a THB spline is written as the same function in the HB basis
//                                     of its hierarchy (truncated functions are no scaled B-splines).
// Control grids are written u outermost. Knots, polynomial control points, weights and scaling factors are
// the stored doubles, so they read back bit-identical. Rational control points are written Cartesian
// (x = (w x) / w, one rounding per coordinate) because STEP stores points and weights; reading multiplies
// again, so homogeneous values can differ by an ulp and evaluation agrees to about 1e-15 relative.
// Informational logicals (closed, self_intersect) are written .U.; forms .UNSPECIFIED..
// Control dimensions 1 to 3 (CARTESIAN_POINT holds at most three coordinates); others are an error.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "trivar/io/step/exchange_file.hpp"
#include "trivar/hier/any_hierarchical_spline.hpp"
#include "trivar/lr/any_lr_spline.hpp"
#include "trivar/spline/any_spline.hpp"

namespace trivar::io::step {

// Adds the object (and its points and local B-splines) to `file`; returns the id of the spline instance.
std::uint64_t add_spline(ExchangeFile& file, const AnySpline& spline, const std::string& name = "");
std::uint64_t add_lr_spline(ExchangeFile& file, const AnyLRSpline& spline, const std::string& name = "");
std::uint64_t add_hierarchical_spline(ExchangeFile& file, const AnyHierarchicalSpline& spline, const std::string& name = "");
// A LOCALLY_REFINED_SPLINE_SURFACE (RATIONAL_... when rational: homogeneous control values) of any collection
// of scaled B-splines with the given locally_refined_spline_type (e.g. "STANDARD_T_SPLINE").
std::uint64_t add_locally_refined_surface(ExchangeFile& file, const Ints<2>& degrees, std::span<const LRBSpline<2>> basis,
                                          const Box<2>& domain, int dim, bool rational, const std::string& type,
                                          const std::string& name = "");

// Adds millimetre, radian and steradian SI units and the complex context
// GEOMETRIC_REPRESENTATION_CONTEXT(dimension) + GLOBAL_UNIT_ASSIGNED_CONTEXT + REPRESENTATION_CONTEXT;
// returns the context id.
std::uint64_t add_geometric_context(ExchangeFile& file, int dimension = 3);

struct GeometryFileOptions {
  std::string representation_name = "trivar";
  // The schema written to FILE_SCHEMA (AP242 edition 1 long form by default).
  std::string schema = "AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }";
  std::string description = "trivar geometry";
  // Names of the objects, splines first, then LR splines, then hierarchical splines; missing entries are
  // written ''.
  std::vector<std::string> names;
};

// A complete exchange structure: header, context and a SHAPE_REPRESENTATION holding every object. The context
// is 3-D unless all objects have a smaller control dimension (then the largest one). Throws trivar::Error when
// there is no object or an object's control dimension is outside 1..3.
ExchangeFile geometry_exchange_file(const std::vector<AnySpline>& splines, const std::vector<AnyLRSpline>& lr_splines,
                                    const GeometryFileOptions& options = {});
ExchangeFile geometry_exchange_file(const std::vector<AnySpline>& splines, const std::vector<AnyLRSpline>& lr_splines,
                                    const std::vector<AnyHierarchicalSpline>& hierarchical,
                                    const GeometryFileOptions& options = {});

}  // namespace trivar::io::step
