#pragma once
// Analysis on a trimmed V-cell (seed 000 section 8, detrimming): the tensor B-splines of degree p on a box
// around the solid, as a RefinedSpace (refined_space.hpp) whose elements know how much of them is inside. An
// element the boundary stays out of keeps its Gauss rule or is marked outside; an element cut by the trimming
// boundary gets the quadrature of its inside part (trimmed_quadrature.hpp: octree subdivision to a depth, then
// lines cut at the exact crossings), and the points of the solid's faces inside it on the same lines become its
// trimming boundary points. So the one element loop (refined_assembly.hpp), the Dirichlet projection and the error norms
// serve trimmed cells unchanged; functions without support in the solid are fixed at zero by the solvers.
//
// Boundary conditions: the trimming boundary is a Neumann boundary (the problem's flux, or natural). Faces of
// the solid lying in a side plane of the box are not trimming boundary: they are that side of the domain, where
// strong Dirichlet conditions are projected over the whole side (so the data must be defined on all of it) and
// Neumann loads would be integrated over all of it (not supported: give Dirichlet conditions there).
#include "trivar/iga/tensor_space.hpp"
#include "trivar/iga/refined_space.hpp"
#include "trivar/model/trimmed_quadrature.hpp"

namespace trivar {

struct TrimmedSpaceOptions {
  int depth = 2;         // octant splits of a cut element (trimmed_quadrature.hpp)
  int extra_points = 1;  // Gauss points per direction on cut elements and faces: p + 1 + extra_points
};

// The tightest box around the solid whose side planes hold the solid's plane faces exactly: the box of the
// mesh, grown by the chordal tolerance on the sides where no mesh triangle lies in the side plane.
Box<3> analysis_box(const TrimmedSolid& solid);

// The identity x(u) = u on the box: degree `degree`, `elements` equal elements per direction (control points
// at the Greville abscissae). The geometry of the space below, and of its solution files.
TensorSpline<3> identity_geometry(const Box<3>& box, int degree, int elements);

// The space of degree `degree` with `elements` equal elements per direction on `box` (which must contain the
// solid), the identity geometry. Throws trivar::Error for degree < 1, elements < 1, a box not holding the solid
// or a solid the box leaves no element of.
RefinedSpace<3> trimmed_space(const TrimmedSolid& solid, const Box<3>& box, int degree, int elements, int threads = 0,
                              const TrimmedSpaceOptions& opts = {});

// One part of a domain made of several trimmed solids that meet only on their faces (the cells of a Boolean):
// the solid and the faces of it that are not trimming boundary (faces in a side plane of the box, faces shared
// with another part), per face of its boundary (empty: none).
struct TrimmedPart {
  const TrimmedSolid* solid = nullptr;
  std::vector<char> skip_faces;
};

// The space on the union of the parts: an element inside one part keeps its Gauss rule; otherwise its rule is
// the parts' detrimmed rules together (each part integrates its own piece of the element) and its trimming
// boundary points those of the parts' faces not skipped. `element_parts` (when given) receives per element the
// parts holding its quadrature points (ascending; empty outside). Throws as the one-solid form.
RefinedSpace<3> trimmed_space(const std::vector<TrimmedPart>& parts, const Box<3>& box, int degree, int elements,
                              int threads = 0, const TrimmedSpaceOptions& opts = {},
                              std::vector<std::vector<int>>* element_parts = nullptr);

// The faces of the solid that lie in a side plane of the box (all their mesh vertices there): sides of the
// domain rather than trimming boundary.
std::vector<int> faces_on_box_sides(const TrimmedSolid& solid, const Box<3>& box);
// The sides of the box (as faces of the domain: dir, side) that hold such a face.
std::vector<Face> box_sides_with_faces(const TrimmedSolid& solid, const Box<3>& box);

}  // namespace trivar
