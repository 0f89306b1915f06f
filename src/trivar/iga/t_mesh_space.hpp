#pragma once
// The analysis space of a planar T-mesh with star points (extraordinary vertices) and T-junctions: the Bezier
// patches of its faces (t_mesh_patches with no subdivision levels: the T-spline's Bezier elements on exact faces,
// the Catmull-Clark limit surface on the faces near a star point, the constructed corner patch on the faces at
// one), cut along the T-junctions' extensions until every side meets its neighbours whole (conforming_split),
// each refined into n x n elements, as a C0 multipatch space (multipatch_space.hpp). Basis functions on shared
// sides are identified by position, which also joins the N patch corners at a star point. The space is C0
// across patch sides and Cp-1 inside a patch; its geometry is the exported one (within the corner patches'
// deviation of the limit surface, which analysis takes as the domain).
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar {

struct TMeshSpaceReport {
  int faces = 0, patches = 0, corner_patches = 0;  // patches: after the cuts that make the sides conform
  double deviation = 0;  // of the corner patches from the limit surface
};

// Throws trivar::Error when the mesh is not planar (z not constant), a patch side without a neighbour is not on
// the mesh's boundary (the patches do not tile the domain), or subdivisions < 1.
MultipatchSpace<2> t_mesh_space(const TMeshSurface& surface, int subdivisions, TMeshSpaceReport* report = nullptr);

// The same on a T-mesh surface in space (curved, open or closed), for surface PDEs (surface_poisson.hpp): sides
// identified by their control points in space; the space's patch geometries carry only the knots and weights
// (their coordinates are the surface's (x, y)), `surfaces` the refined patches in space.
struct TMeshSurfaceSpace {
  MultipatchSpace<2> space;
  std::vector<TensorSpline<2>> surfaces;  // per patch, dim 3, the knots and weights of the space's patch
};
TMeshSurfaceSpace t_mesh_surface_space(const TMeshSurface& surface, int subdivisions, TMeshSpaceReport* report = nullptr);

}  // namespace trivar
