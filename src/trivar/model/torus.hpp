#pragma once
// Solid ring torus as five non-singular cells of revolution.
#include "trivar/model/primitives.hpp"

namespace trivar {

// disk_cells(minor_radius) placed in the xz-plane about (major_radius, 0, 0) and revolved a full turn about
// the z-axis (revolve(): exact, degree 2 and four segments in the angle). Directions (disk u, disk v,
// angle); the disk is mirrored (z = -y) on placement so that every cell is positively oriented. Each cell is
// closed in the angle: its faces at angle 0 and 2 pi coincide. Throws trivar::Error unless
// 0 < minor_radius < major_radius (finite) and 0 < core < 1.
CellComplex make_torus(const TorusSpec& spec);

}  // namespace trivar
