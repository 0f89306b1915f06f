#pragma once
// The box mesh of a collection of LR B-splines given without one (STEP stores none): the union of the
// B-splines' knot lines. Per B-spline and direction, one rectangle per distinct local knot across its support,
// with that knot's local multiplicity. This is the mesh of every LR spline whose mesh lines all carry some
// B-spline's knot line (so the spline evaluates identically; the element partition can be coarser than the
// writer's where the writer's mesh had lines no B-spline uses).
//
// Per plane the pieces are merged into few maximal rectangles per multiplicity level (each knot line of a
// B-spline is typically shared by several B-splines); where pieces of several levels overlap the largest
// multiplicity counts, as in the mesh. The union of a plane is not a box in general, so a plane can come out
// as several rectangles that only together cross an element: the LRSpline constructor cuts by plane unions.
#include <span>
#include <vector>

#include "trivar/lr/lr_bspline.hpp"
#include "trivar/lr/mesh_rectangle.hpp"

namespace trivar {

template <int D>
std::vector<MeshRectangle<D>> knot_line_mesh(std::span<const LRBSpline<D>> basis);

extern template std::vector<MeshRectangle<2>> knot_line_mesh(std::span<const LRBSpline<2>>);
extern template std::vector<MeshRectangle<3>> knot_line_mesh(std::span<const LRBSpline<3>>);

}  // namespace trivar
