#pragma once

#include <TopoDS_Shape.hxx>

namespace trivar::cad {

// Faces with more loops than this are checked by groups of loops (see is_valid_solid).
inline constexpr int crowded_face_loops = 32;

// OpenCASCADE's validity verdict (BRepCheck_Analyzer) on a solid, in time near-linear in the loops of a face.
// The kernel classifies every pair of loops of a face against each other, quadratic in its loops: a plate with
// hundreds of holes spent most of its import there. A face with more than crowded_face_loops loops is given to
// the kernel's analyzer as smaller faces on its surface instead: its outer loop with each group of up to
// crowded_face_loops - 1 other loops, neighbours in u (each loop closed, oriented as a hole, inside the outer
// loop, crossing neither it nor the group's loops), and its outer loop with each pair of loops of different
// groups whose parameter-space boxes overlap (disjoint, not nested), found by a sweep in u; loops whose boxes
// are apart can neither cross nor nest. The other faces (with their edges and vertices) go to the analyzer
// together, and the shells and the solid to the kernel's shell and solid checks. Without crowded faces this is
// the analyzer on the solid.
bool is_valid_solid(const TopoDS_Shape& solid);

}  // namespace trivar::cad
