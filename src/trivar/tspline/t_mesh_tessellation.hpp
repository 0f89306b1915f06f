#pragma once
// A watertight triangulation of a T-mesh surface (TMeshSurface: star points, no global (s, t)). Every edge of
// the mesh carries one list of sample points, evaluated once and shared by the faces on both sides; a face is
// triangulated on the tensor grid of the samples of its sides, and samples are carried across faces (a
// T-junction face passes the samples of its long side to the short sides opposite) until every side's samples
// are the grid lines of its face: no T-vertices, so no cracks. Edges and vertices are those of the mesh as given
// (TMeshSurface::face_mesh: the mesh as given, or its refinement by global steps), so a sharp crease's two sides
// share their points too. Counts come from second differences of the
// surface on a 9 x 9 grid per face (the bilinear interpolant of n x n sub-cells deviates by about
// D / (8 n^2)).
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

namespace trivar {

// tolerance > 0 (model units); max_per_face bounds the subdivision of one face side. `params` of the result
// are the face-local (u, v) of the face that evaluated the point.
TSplineTriangulation tessellate(const TMeshSurface& surface, double tolerance, int max_per_face = 64);

}  // namespace trivar
