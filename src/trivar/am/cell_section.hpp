#pragma once
// Outline of a cell at height z: the section of its six boundary faces with the plane z = const, as line
// segments in xy forming closed polygons (every vertex is shared by exactly two segments, up to segments of
// zero length on collapsed faces).
//
// Method: each face is sampled once on a parameter grid (knot spans subdivided uniformly). Per height, every
// grid edge whose end heights straddle z gets its crossing refined on the spline by safeguarded regula falsi
// (Illinois) to rounding, marching squares connects the crossings inside each grid quad (saddles decided by
// the quad's mean height), and a segment is split at the section curve's point between its ends (projected
// onto the plane by Newton inside the face) until its chord deviates from the curve by at most `tolerance`.
//
// Closedness is exact, not approximate: all points are evaluated on the trivariate at the same parameter
// triple whichever face they belong to, and the grid in each cell direction is shared by the faces containing
// it, so the crossings on an edge of the cell are bit-identical for its two faces. An even-odd scanline fill
// therefore never sees a vertex twice or a crack. Cost per height: one comparison per grid edge, about ten
// spline evaluations per crossing and three per subdivision.
#include <array>
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar::am {

struct OutlineSegment {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int face = -1;  // cell face 0..5 (2 * direction + side, as in model/vtopology.hpp)
  // Cell parameters of the two ends: the slicer starts point inversion of a row's first pixel from them.
  Param<3> u0{}, u1{};
};

struct SectionOptions {
  int samples_per_span = 16;  // grid intervals per knot span and direction (>= 1)
  double tolerance = 1e-5;    // chord deviation from the section curve in the xy plane (model units, > 0)
  int max_depth = 24;         // halvings of one grid segment
};

class CellSection {
public:
  // Samples the six faces. Throws trivar::Error unless geometry has control dimension 3 and the options are
  // valid.
  explicit CellSection(const TensorSpline<3>& geometry, const SectionOptions& options = {});

  // Appends the outline at height z to `out` (nothing when z misses the cell). Thread-safe.
  void section(double z, std::vector<OutlineSegment>& out) const;

  // Height range of the control points: the cell lies inside it.
  double z_lo() const { return z_lo_; }
  double z_hi() const { return z_hi_; }
  const TensorSpline<3>& geometry() const { return geometry_; }

private:
  struct Face {
    int fixed_dir = 0;
    double fixed = 0;
    std::array<int, 2> dirs{};  // cell directions of the face parameters (s, t)
    std::vector<double> points;  // xyz per grid point, s fastest
  };
  void section_face(const Face& f, double z, std::vector<OutlineSegment>& out, int face) const;
  void emit(const Face& f, const Param<3>& pa, const double* a, const Param<3>& pb, const double* b, double z,
            int depth, int face, std::vector<OutlineSegment>& out) const;

  TensorSpline<3> geometry_;
  SectionOptions options_;
  std::array<std::vector<double>, 3> params_;  // grid parameters per cell direction
  std::array<Face, 6> faces_;
  double z_lo_ = 0, z_hi_ = 0;
  double z_eps_ = 0;  // height accuracy of crossings and projections (rounding level of the cell size)
};

}  // namespace trivar::am
