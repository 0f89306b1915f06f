#pragma once
// What kind of T-spline a T-spline is, and what follows for analysis:
//   T-junctions and their extensions (Scott, Li, Sederberg, Hughes 2012 for odd degrees; Beirao da Veiga, Buffa,
//   Sangalli, Vazquez 2013 for any degree): for a T-junction whose missing edge points along s (t likewise), the
//   face extension runs from it in the missing edge's direction until it has crossed ceil(p_s / 2) knot lines,
//   the edge extension the other way until floor(p_s / 2); the T-mesh is analysis-suitable when no s-extension
//   meets a t-extension. Beirao da Veiga et al. prove, for any degrees on a rectangle, analysis-suitable <=>
//   dual-compatible: every two blending functions whose supports overlap have, in at least one direction, local
//   knot vectors that are windows of one knot vector; dual compatibility gives a dual basis, hence linear
//   independence, on any domain (checked here from the blending functions, independently of the extensions).
//   On a domain that is not a rectangle the theory does not give a partition of unity (at concave corners or
//   holes with Bezier end conditions the sums reach 1.08 on Rhino's mouse model with no crossing extensions), so
//   there a T-mesh is called analysis-suitable when its extensions do not cross, its blending functions are
//   dual-compatible and they sum to one: the properties analysis relies on.
//   standard: the blending functions sum to one; semi-standard: sum w_i B_i is one (Sederberg et al. 2004);
//   read off the Bezier coefficients of the sums, exactly up to rounding.
//   Linear independence by lr/linear_independence (peeling, then the exact rank of the Bezier extraction).
// The Part 42 locally_refined_spline_type written for a T-spline (part42_type): ANALYSIS_SUITABLE_T_SPLINE when
// analysis-suitable, else SEMI_STANDARD_T_SPLINE when semi-standard, else STANDARD_T_SPLINE (the general rational
// T-spline of Sederberg et al. 2003, whose blending functions need not sum to one).
#include <array>
#include <string>
#include <vector>

#include "trivar/lr/linear_independence.hpp"
#include "trivar/tspline/t_spline.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {

struct TJunctionExtension {
  int vertex = -1;     // the T-junction
  int direction = -1;  // of its missing edge (north, west, south, east)
  int axis = 0;        // the extension runs along s (0) or t (1)
  double line = 0;     // at this t (axis 0) or s (axis 1)
  double lo = 0, hi = 0;
};

// Every T-junction (a vertex with a missing edge whose continuation lies inside a face) and its extension,
// except the pairs of T-junctions facing each other across a gap that no ray crosses (the missing edge ends at a
// vertex missing the edge back, and no T-node's anchor lies strictly between the two): the blending functions
// are then those of the T-mesh with the edge, which has neither T-junction, so the extensions of the pair say
// nothing about them (the Rhino fan model: four such gaps on two crossing lines, whose closed extensions all
// meet at one vertex, over blending functions that are the tensor-product B-splines). `gap_junctions` counts
// the T-junctions left out.
std::vector<TJunctionExtension> t_junction_extensions(const TSpline& ts, int* gap_junctions = nullptr);

struct DualCompatibility {
  bool compatible = true;
  int failing_pairs = 0;                // pairs of overlapping supports with no overlapping knot vectors
  std::array<int, 2> first_pair{-1, -1};
};
DualCompatibility dual_compatibility(const TSplineSurface& surface);

struct TSplineClass {
  int t_junctions = 0;
  int gap_junctions = 0;                  // of those, facing each other across gaps no ray crosses (no extension)
  bool analysis_suitable = false;
  int crossing_extensions = 0;            // pairs of an s- and a t-extension that meet
  bool rectangular_domain = true;         // the faces fill their bounding box
  bool standard = false;                  // sum B_i = 1
  bool semi_standard = false;             // sum w_i B_i = 1
  Independence independence = Independence::not_tested;
  DualCompatibility dual;
  std::string part42_type() const;
};

// `exact`: the exact rank test when peeling is inconclusive (otherwise independence may stay not_tested).
TSplineClass classify(const TSpline& ts, const TSplineSurface& surface, bool exact = true);

}  // namespace trivar
