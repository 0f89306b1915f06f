#pragma once
// Solid circular cylinder as five non-singular cells.
#include "trivar/model/primitives.hpp"

namespace trivar {

// The frustum of make_cone() with equal radii: a core cell over the square and four ruled cells out to the
// quarter arcs, extruded from z = 0 to z = height (directions (disk u, disk v, z), degree 1 along z). Throws
// trivar::Error unless radius and height are positive and finite and 0 < core < 1.
CellComplex make_cylinder(const CylinderSpec& spec);

}  // namespace trivar
