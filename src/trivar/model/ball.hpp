#pragma once
// Solid ball as seven non-singular cells with an exact spherical boundary.
#include "trivar/model/primitives.hpp"

namespace trivar {

// The unit sphere tiled by the six rational biquartic Bezier patches of the cube-sphere (Cobb 1988, "Tiling
// the sphere with rational Bezier patches", table 4): the patch over the face z > 0, with u along +x and v
// along +y, scaled by `radius` about the origin. Exact up to rounding (|S| = radius on the whole patch).
SplineSurface cube_sphere_patch(double radius);

// [0] the core cube [-a, a]^3 + center, a = core * radius / sqrt(3), as a degree (4, 4, 4) Bezier volume
// with unit weights; [1..6] the cells between the cube's faces +x, -x, +y, -y, +z, -z and the sphere
// patches above them, each ruled (ruled()) from the flat face (degree-elevated to 4) at w = 0 to the patch
// at w = 1, so w points outward. The six outer cells are the +z cell turned by rotations that only permute
// and negate coordinates, which keeps the sphere exact and the faces shared by neighbours identical.
// Throws trivar::Error unless radius > 0, center finite and 0 < core < 1.
CellComplex make_ball(const BallSpec& spec);

}  // namespace trivar
