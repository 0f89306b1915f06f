#pragma once
// The analysis space of a planar T-mesh with star points (extraordinary vertices): one bicubic patch per face
// (t_mesh_patches with no subdivision levels: the T-spline on exact faces, the Catmull-Clark limit surface on
// the faces near a star point, the constructed corner patch on the faces at one), each refined into n x n
// elements, as a C0 multipatch space (multipatch_space.hpp). Neighbouring faces share whole sides, so the
// refined control points of a shared side coincide; basis functions on patch sides are identified by position,
// which also joins the N patch corners at a star point. The space is C0 across face edges and Cp-1 inside a
// face; its geometry is the exported one (within the corner patches' deviation of the limit surface, which
// analysis takes as the domain).
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar {

struct TMeshSpaceReport {
  int faces = 0, corner_patches = 0;
  double deviation = 0;  // of the corner patches from the limit surface
};

// Throws trivar::Error when the mesh is not planar (z not constant), a face is more than one Bezier element
// (T-junction extensions cross it), a patch side is matched only in part (a T-junction: the sides do not
// conform), or subdivisions < 1.
MultipatchSpace<2> t_mesh_space(const TMeshSurface& surface, int subdivisions, TMeshSpaceReport* report = nullptr);

}  // namespace trivar
