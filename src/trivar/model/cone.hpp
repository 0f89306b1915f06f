#pragma once
// Solid frustum (truncated cone) as five non-singular cells.
#include "trivar/model/primitives.hpp"

namespace trivar {

// disk_cells() at the bottom (radius bottom_radius, z = 0) ruled to the same layout at the top (top_radius,
// z = height): directions (disk u, disk v, z), degree 1 along z. Every horizontal section at height z is the
// bottom layout scaled by r(z) = bottom_radius + (top_radius - bottom_radius) z / height, so the lateral
// surface is exact. [0] is the core cell, [1..4] the outer cells on the +x, +y, -x, -y sides. Throws
// trivar::Error unless both radii and the height are positive and finite and 0 < core < 1 (see ConeSpec for
// why top_radius = 0 is excluded).
CellComplex make_cone(const ConeSpec& spec);

}  // namespace trivar
