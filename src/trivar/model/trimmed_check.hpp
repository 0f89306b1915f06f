#pragma once
// Validity of a trimmed boundary beyond what TrimmedSolid's constructor enforces (a watertight, outward mesh):
// the exact faces must agree with it. Every trimming loop closes (consecutive curves meet on the surface),
// every trimming curve stays in its surface's domain and starts and ends on its 3D edge, the faces' orientation
// flags agree with the mesh (the exact volume is positive and within the mesh's chordal band of the mesh
// volume). A solid that passes encloses what its mesh shows, so volumes, slices and quadrature are right.
#include <string>
#include <vector>

#include "trivar/model/trimmed_solid.hpp"

namespace trivar {

struct TrimCheck {
  bool valid = true;
  std::vector<std::string> defects;  // one line each, naming the face / loop / curve
  double largest_loop_gap = 0;       // model units, between consecutive curve ends mapped onto the surface
  double largest_edge_gap = 0;       // model units, between a trimming curve's ends and its edge's ends
  double exact_volume = 0, mesh_volume = 0;
  double volume_band = 0;            // the largest |exact - mesh| volume difference the chordal tolerance allows
  bool watertight = false;
};

// `tolerance`: the largest gap accepted, in model units (0: 1e-6 of the box diagonal, or a face's own
// tolerance when larger).
TrimCheck check_trim(const TrimmedSolid& solid, double tolerance = 0);

}  // namespace trivar
