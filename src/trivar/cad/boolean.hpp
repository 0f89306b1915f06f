#pragma once
// Booleans of V-models (seed 001, "extended Booleans for V-rep"): union, difference and intersection of two
// models, whose result is again a V-model of trimmed cells carrying the operands' attributes, blended where
// the operands overlap.
//
// The boundary work is the geometry kernel's: every cell of both operands becomes a closed solid (the six
// faces of its trivariate, or its trimming faces), and one general fuse of all of them splits space into
// pieces whose shared faces are shared, with one triangulation. Which piece lies in which operand cell, which
// pieces the operation keeps, their trims, attributes and neighbours are trivar's: a kept piece becomes a
// trimmed cell (the identity trivariate on its box, trimmed by the piece's exact NURBS faces), so info,
// export, slice and the trimmed analysis read the result as they read an imported part, and it can be an
// operand again. Nothing of OpenCASCADE appears in this header.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "trivar/model/attribute_fit.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar::cad {

// split: every piece of A, inside and outside B, becomes a cell of its own with A's attributes (B is the tool
// of split.hpp and contributes nothing but the cut).
enum class BooleanOp { unite, subtract, intersect, split };

// How an attribute is valued in the overlap of a cell of A and a cell of B.
enum class BlendRule {
  take_a,    // A's value
  take_b,    // B's value
  average,   // (A + B) / 2
  formula,   // (1 - w) A + w B with a weight w(x, y, z) given as a formula
  distance,  // (d_A A + d_B B) / (d_A + d_B), d_A the distance to the part of A's boundary inside B and d_B to
             // the part of B's boundary inside A (seed 001, Eq. 2): continuous across both boundaries
};

struct AttributeRule {
  BlendRule rule = BlendRule::take_a;
  std::string weight;  // formula: w in x, y, z (0 gives A, 1 gives B)
};

struct BooleanOptions {
  AttributeRule default_rule;                  // for attributes without their own rule
  std::map<std::string, AttributeRule> rules;  // per attribute name
  // Largest distance of the result cells' meshes from their faces; 0 picks 1e-3 of the diagonal of the box
  // around both operands.
  double chordal_tolerance = 0;
  double angular_tolerance = 0.5;
  // Distance, relative to that diagonal, under which the kernel treats faces and edges as coincident.
  double fuzzy = 1e-9;
  // Spline fields for the attributes that have no closed form on a result cell (distance blends, fields and
  // parametric formulas of untrimmed operand cells).
  FieldFit field;
};

struct BooleanReport {
  int cells_a = 0, cells_b = 0;
  int pieces = 0;         // solids of the general fuse
  int pieces_a_only = 0, pieces_b_only = 0, pieces_both = 0;
  int cells = 0;          // of the result
  int exact_attributes = 0, fitted_attributes = 0;  // over result cells
  // Faces between two result cells, and per result cell its neighbours across them.
  int interior_faces = 0;
  std::vector<std::vector<int>> neighbours;
  int boundary_faces = 0;  // faces of exactly one result cell
};

// The Boolean of two models. Cells of one operand must not overlap one another (they may share faces).
// Empty results (an intersection of disjoint operands, a difference that removes everything) throw
// trivar::Error, since a V-model has at least one cell; so do cells the kernel cannot make a solid of and
// attributes whose component counts differ between the operands where they must be blended. Weight formulas
// that do not parse throw before any geometry is computed.
VModel boolean(const VModel& a, const VModel& b, BooleanOp op, const BooleanOptions& options = {},
               BooleanReport* report = nullptr);

// "union" -> unite, "difference" -> subtract, "intersection" -> intersect; throws trivar::Error otherwise.
BooleanOp boolean_op(const std::string& name);
// "a", "b", "average", "formula", "distance"; throws trivar::Error otherwise.
BlendRule blend_rule(const std::string& name);

}  // namespace trivar::cad
