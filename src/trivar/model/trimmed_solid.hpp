#pragma once
// TrimmedSolid: the region enclosed by a TrimmedBoundary, with the queries every consumer of a trimmed V-cell
// needs: is a point inside, where does an axis-parallel line cross the boundary, how large is the region.
// Immutable after construction and thread-safe, so cells share one through a shared_ptr.
//
// Classification away from the boundary works on the watertight mesh with an exact-parity ray test (the point
// is perturbed symbolically, so a ray through a mesh vertex or edge, or one grazing the mesh tangentially, is
// counted the same way by every triangle around it); that answer is the exact one because the point is
// farther from the mesh than the mesh is from the faces. Within that band no ray is cast: of the faces whose
// triangles come that close, the one with the nearest exact closest point inside its trim decides, by the
// side of its outward normal the point lies on. So near-tangent rays, which may miss the inscribed mesh while
// crossing the true surface, never decide.
#include <array>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/model/trimmed_boundary.hpp"

namespace trivar {

struct LineCrossing {
  double t = 0;           // coordinate along the line's axis
  bool entering = false;  // the line, run towards +axis, enters the region here (leaves it otherwise)
  int face = -1;          // the boundary face crossed
  Param<2> uv{};          // its parameters on that face
};

class TrimmedSolid {
public:
  // Validates the boundary (faces of control dimension 3 and trimming loops of dimension 2, a watertight
  // outward-oriented mesh with per-triangle faces and parameters) and builds one search grid per axis.
  // Throws trivar::Error naming the first defect.
  explicit TrimmedSolid(TrimmedBoundary boundary);

  const TrimmedBoundary& boundary() const { return boundary_; }
  // Box around the boundary: the mesh's box grown by its chordal tolerance.
  const Box<3>& bounding_box() const { return box_; }

  // Whether x lies inside (points on the boundary may go either way; near a sharp edge, within the chordal
  // tolerance, the face of the nearest mesh triangle decides).
  bool contains(const std::array<double, 3>& x) const;

  // The crossings of the line through p parallel to coordinate axis `axis` (p[axis] is ignored) with the
  // boundary for t in (t_lo, t_hi), sorted by t: the crossings with the mesh, each moved onto its exact face.
  // Entering and leaving alternate; a line passing within the chordal tolerance of a silhouette may gain or
  // lose a pair of crossings there (contains() decides such points exactly). `out` is cleared first.
  void axis_crossings(int axis, const std::array<double, 3>& p, double t_lo, double t_hi,
                      std::vector<LineCrossing>& out) const;

  // Volume of the region from the exact faces (trimmed_integral.hpp), computed once at construction.
  double volume() const { return volume_; }

  // Whether the boundary may pass through the open box: false proves that the box lies wholly inside or wholly
  // outside (contains() at any of its points then decides). Conservative: the boxes of the mesh triangles,
  // grown by the chordal tolerance on curved faces (flat faces are meshed exactly), are tested, so a face lying
  // in a side plane of the box does not count.
  bool boundary_meets(const Box<3>& b) const;
  // The axis the boundary inside the box is most transversal to: the one whose smallest normal component over
  // the mesh triangles boundary_meets() finds there is largest (0 when there are none).
  int transversal_axis(const Box<3>& b) const;

  // The closed polygon in face `face`'s parameter plane that stands for its trimming loop `loop` when
  // parameter points are classified (straight spans as one chord, curved ones within a quarter of the chordal
  // tolerance in model space), and how far its chords stray from the curves in the parameter plane at most.
  const std::vector<std::array<double, 2>>& trim_polygon(int face, int loop) const {
    return trim_polygons_.at(static_cast<std::size_t>(face)).at(static_cast<std::size_t>(loop));
  }
  double trim_slack(int face) const { return trim_slack_.at(static_cast<std::size_t>(face)); }

private:
  // Triangles whose projection along an axis covers each cell of a uniform grid over the box's other two
  // coordinates (compressed rows).
  struct AxisGrid {
    int b = 0, c = 0;  // the projected coordinates
    int nb = 1, nc = 1;
    double lo_b = 0, lo_c = 0, inv_hb = 0, inv_hc = 0;
    std::vector<int> start, triangles;
  };
  TrimmedBoundary boundary_;
  Box<3> box_;
  std::array<AxisGrid, 3> grids_;
  // Triangles per cell of a uniform 3D grid over the box, for the near-boundary search.
  struct SpaceGrid {
    std::array<int, 3> n{1, 1, 1};
    std::array<double, 3> lo{}, inv_h{};
    std::vector<int> start, triangles;
    // Calls f(t) for the triangles listed in the cells that meet [from, to] (a triangle once per cell), until f
    // returns true; returns whether one did.
    template <class F>
    bool any_triangle_in(const std::array<double, 3>& from, const std::array<double, 3>& to, F&& f) const;
  } space_;
  // Per face its trimming loops as closed polygons in the parameter plane (trim_polygon).
  std::vector<std::vector<std::vector<std::array<double, 2>>>> trim_polygons_;
  std::vector<std::vector<Box<2>>> trim_boxes_;  // per face and loop: the polygon's box
  std::vector<double> trim_slack_;  // per face: how far its polygons may stray from the trimming curves
  std::vector<char> flat_;          // per face: all control points in one plane
  double volume_ = 0;

  // Calls f(t) for the mesh triangles whose boxes (grown as boundary_meets says) meet the open box, until f
  // returns true; returns whether one did.
  template <class F>
  bool any_triangle_meeting(const Box<3>& b, F&& f) const;
  void mesh_crossings(int axis, const std::array<double, 3>& p, std::vector<LineCrossing>& out) const;
  void refine(int axis, const std::array<double, 3>& p, LineCrossing& c) const;
  // Within `band` of the mesh: 1 inside, 0 outside by the nearest exact face; -1 farther than `band` or when
  // no close face has its closest point within its trim (then the mesh decides).
  bool inside_trim(int face, const Param<2>& uv) const;
  int classify_near(const std::array<double, 3>& x, double band) const;
};

}  // namespace trivar
