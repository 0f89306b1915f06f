#pragma once
// Quadrature over the part of a box inside a trimmed solid and over the solid's trimmed faces: what analysis on
// trimmed V-cells (detrimming, seed 000 section 8) integrates with. A box the boundary stays out of gets the
// tensor Gauss rule or nothing; a cut box is split into octants down to a depth, and each cut leaf is
// integrated one dimension at a time: Gauss lines along the axis the boundary is most transversal to there,
// each cut at its exact crossings with the faces (TrimmedSolid::axis_crossings) and integrated by Gauss on
// every inside interval, the lines' base split where the boundary meets the leaf's faces (where the inside
// length has kinks). The rule converges at high order wherever the boundary is a smooth graph over the leaf's
// other two axes, and algebraically (in the depth) across sharp edges and silhouettes. The faces inside a cut
// leaf are integrated on the same lines (one point per crossing, see surface_line), so surface rules respect
// element boundaries too.
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

struct SurfacePoint {
  std::array<double, 3> x;
  std::array<double, 3> normal;  // unit, outward
  double weight;                 // area element times Gauss weight
};

// Appends to `volume` the quadrature of box ∩ solid when the boundary may pass through the box (and returns
// cut), and to `surface` (when given) that of the solid's faces inside the box, leaving out the faces flagged
// in skip_faces (indexed by face; empty: none); otherwise appends nothing and returns inside or outside.
BoxPlacement trimmed_box_quadrature(const TrimmedSolid& solid, const Box<3>& box, const TrimmedQuadratureOptions& opts,
                                    std::vector<VolumePoint>& volume, std::vector<SurfacePoint>* surface = nullptr,
                                    const std::vector<char>& skip_faces = {});

}  // namespace trivar
