#pragma once
// OpenSubdiv (Pixar's reference implementation of Catmull-Clark subdivision with creases and boundary rules) as an
// independent reference for the Catmull-Clark limit surfaces of the tests. Linked into test_tspline only, used
// through its public API: Far builds the topology, Bfr evaluates each base face's limit surface.
//
// Face parametrisation (Bfr's): a quadrilateral's (u, v) in [0, 1]^2 has its first vertex at (0, 0), the second at
// (1, 0), the third at (1, 1) and the fourth at (0, 1) (u along the edge from the first vertex to the second). An
// N-gon (N != 4) is split into N quadrilateral sub-faces, one per corner (the corner, its edges' midpoints and the
// centroid), laid out side by side in (u, v); eval_ngon_corner takes a sub-face's normalised (s, t) in [0, 1]^2
// with (0, 0) at corner i, s along the half edge towards corner i + 1 and t along the half edge towards corner i - 1
// (checked by the reference's own test).
//
// Exactness: Bfr represents the limit surface of a face as B-spline patches of the refined mesh wherever that is
// regular, so it is exact (to rounding) there; only the sub-patches touching an extraordinary vertex (or an
// irregular feature) at the last refinement level L are approximated, within 2^-L of the extraordinary corner in
// the face's (u, v). They interpolate the exact limit point; their derivatives there converge with L (measured
// with this API at L = 10: the tangents leave the limit tangent plane by 8e-7 rad at a valence-3 vertex, 3e-10
// rad at valence 5, 3e-11 rad at valence 8). Measured with OpenSubdiv 3.5 against trivar's exact evaluation:
// levels above 10 refine further only round an extraordinary vertex at a face's first corner (elsewhere the
// surface stays approximated within 2^-10), and an evaluation some levels inside the approximated region of a
// corner other than the first read out of bounds (Bfr's irregular patch evaluation). So L = 10, and samples
// either at such a corner or farther than 2^-10 from it.
#include <array>
#include <memory>
#include <vector>

namespace trivar::test {

// A polygonal control mesh: faces as vertex loops, all oriented the same way.
struct PolyMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<int>> faces;
  std::vector<std::array<int, 2>> sharp_edges;  // infinitely sharp creases (end vertices)
  std::vector<int> sharp_vertices;              // infinitely sharp (corner) vertices
  // Boundary rule: every boundary edge is an infinitely sharp crease (Sdc::Options::VTX_BOUNDARY_EDGE_ONLY), and
  // with sharp_corners also every boundary vertex of a single face is a sharp corner, interpolated
  // (VTX_BOUNDARY_EDGE_AND_CORNER).
  bool sharp_corners = true;
};

struct LimitSample {
  std::array<double, 3> p{}, du{}, dv{};
};

class OsdLimitSurface {
public:
  // Bfr's refinement level for smooth and sharp irregular features is 10 (see above).
  explicit OsdLimitSurface(const PolyMesh& mesh);
  ~OsdLimitSurface();
  OsdLimitSurface(const OsdLimitSurface&) = delete;
  OsdLimitSurface& operator=(const OsdLimitSurface&) = delete;

  // The limit surface of a face at Bfr's (u, v), position and first derivatives.
  LimitSample eval(int face, double u, double v) const;
  // An N-gon's (N != 4) sub-face at `corner`, at its normalised (s, t); derivatives by s and t.
  LimitSample eval_ngon_corner(int face, int corner, double s, double t) const;
  // The limit positions of the mesh's vertices and two tangent directions spanning the limit tangent plane (exact
  // limit masks of Far::PrimvarRefiner::Limit after one uniform step; the tangents' lengths belong to no face's
  // parametrisation). After `levels` uniform steps: at a dart (one sharp edge inside the mesh) Far's mask is the
  // smooth vertex's, which is not the limit there (the midpoint rule on the sharp edge moves it), so its error
  // shrinks with the levels only (geometrically: Aitken's extrapolation of three levels gives the limit).
  std::vector<LimitSample> vertex_limits(int levels = 1) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace trivar::test
