#pragma once
// Quadrature over the part of a box inside a trimmed solid and over the solid's trimmed faces: what analysis on
// trimmed V-cells (detrimming, seed 000 section 8) integrates with. A box the boundary stays out of gets the
// tensor Gauss rule or nothing; a cut box is split into octants down to a depth, and each cut leaf is
// integrated line by line: Gauss lines along the axis the boundary is most transversal to there, each cut at
// its exact crossings with the faces (TrimmedSolid::axis_crossings) and integrated by Gauss on every inside
// interval. The rule is exact on polynomials wherever the boundary is a graph over the leaf's other two axes
// with smooth height, so it converges at high order on smooth faces and algebraically (in the depth) across
// sharp edges and silhouettes. Faces are integrated on the mesh's parameter triangles mapped by the exact
// surface (collapsed Gauss rules): exact up to the chordal tolerance of the trimming curves in the parameter
// plane (none for trims that are straight there, as on planes, cylinders and cones cut by planes).
#include <array>
#include <vector>

#include "trivar/model/trimmed_solid.hpp"

namespace trivar {

struct TrimmedQuadratureOptions {
  int points = 3;  // Gauss points per direction (and per inside interval of a line)
  int depth = 2;   // octant splits of a cut box before the leaves are integrated line by line
};

struct VolumePoint {
  std::array<double, 3> x;
  double weight;
};

enum class BoxPlacement { inside, outside, cut };

// Appends to `out` the quadrature of box ∩ solid when the boundary may pass through the box (and returns cut);
// otherwise appends nothing and returns inside or outside.
BoxPlacement trimmed_box_quadrature(const TrimmedSolid& solid, const Box<3>& box, const TrimmedQuadratureOptions& opts,
                                    std::vector<VolumePoint>& out);

struct SurfacePoint {
  std::array<double, 3> x;
  std::array<double, 3> normal;  // unit, outward
  double weight;                 // area element times Gauss weight
};

// Quadrature of one face over its trimmed domain, `points`^2 per mesh triangle, appended to `out`.
void trimmed_face_quadrature(const TrimmedSolid& solid, int face, int points, std::vector<SurfacePoint>& out);

}  // namespace trivar
