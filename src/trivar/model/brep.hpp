#pragma once
// Brep: the boundary of a solid as spline faces glued along shared curves and vertices (topology only; the
// geometry is the faces' own). Built by brep_from_surfaces (or from a V-model's boundary), consumed by
// tessellate.
#include <array>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// A face side lies on a boundary curve. Sides are numbered like boundary_faces() of a surface: 0 u = lo,
// 1 u = hi, 2 v = lo, 3 v = hi. `reversed` means the side's increasing parameter runs from the curve's end
// vertex to its start vertex.
struct FaceSide {
  int curve = -1;
  bool reversed = false;
};

struct BrepFace {
  TensorSpline<2> surface;  // control dimension 3
  std::array<FaceSide, 4> sides;
  bool flip = false;  // the outward normal is S_v x S_u instead of S_u x S_v
};

// A curve's start and end vertex ids (equal for a closed curve).
struct BrepCurve {
  std::array<int, 2> vertices{};
};

struct Brep {
  std::vector<BrepFace> faces;
  std::vector<BrepCurve> curves;
  int num_vertices = 0;
};

// Parameters of side `side` of s at t in [0, 1] along the side's increasing parameter.
inline Param<2> side_parameters(const TensorSpline<2>& s, int side, double t) {
  const Box<2> d = s.domain();
  const int fixed = side / 2, run = 1 - fixed;
  Param<2> p;
  p[fixed] = side % 2 ? d.hi[fixed] : d.lo[fixed];
  p[run] = d.lo[run] + t * (d.hi[run] - d.lo[run]);
  return p;
}

// The point of side `side` of s (control dimension 3) at t in [0, 1].
inline std::array<double, 3> side_point(const TensorSpline<2>& s, int side, double t) {
  std::array<double, 3> x;
  s.eval(side_parameters(s, side, t), x.data());
  return x;
}

}  // namespace trivar
