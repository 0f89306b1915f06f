#pragma once
// A T-spline as its control mesh, before any parametrisation: half-edge links as the Rhino T-Splines format
// stores them, a knot interval per edge, and per vertex its node's control point and the repeated-knot node
// block of Bezier end conditions. A T-mesh with star points (extraordinary vertices) has no global (s, t); each
// face still has local charts (`t_spline_chart`): the faces around it laid out in the plane by their knot
// intervals, where the T-spline rules apply wherever the chart holds no star point.
#include <array>
#include <span>
#include <vector>

#include "trivar/tspline/t_spline.hpp"

namespace trivar {

struct TMeshLink {
  int prev = -1, next = -1, opp = -1;  // in the face loop (counter-clockwise); the link of the same edge back
  int vertex = -1;                     // the vertex it leaves; -1: a deleted slot
  int face = -1;                       // -1: outside (a boundary link) or a deleted face
  int edge = -1;
  int flag = 0;                        // (angle of its face at `vertex`) / 90 - 1: 0 corner, 1 straight, 2 reflex
  int frame = -1;                      // its direction (north, west, south, east) in the vertex's own frame
};

// The subdivision rule of a vertex on a sharp crease of a subdivision-crease mesh: crease (two sharp edges: the
// crease curve runs through), corner (three or more, counting the boundary's, or a creased vertex: interpolated;
// inside the mesh on no crease a cone point), dart (one sharp edge inside the mesh: the crease ends there and the
// vertex moves by the smooth rule over all its faces).
enum class CreaseRule : unsigned char { none, crease, corner, dart };

struct TMeshVertex {
  bool live = true;
  int primary = -1;                // control point of the vertex's own node
  std::array<int, 4> block_dims{};  // Bezier end-condition block: dK node layers towards frame direction K
  std::vector<int> block;          // its points, wedge K = N, W, S, E holding dK x (d(K+1) + 1) entries; -1: none
  int split_from = -1;             // a side of a sharp crease vertex cut open (split_creases): that vertex
  CreaseRule crease_rule = CreaseRule::none;  // a vertex cut open by split_creases (every side): its rule
};

// How the surface ends at the mesh's boundary. bezier: Bezier end conditions (repeated knots, the boundary curve
// the B-spline of the end-condition block points; Rhino's force-bezier export, Fusion's MULTIPLE_KNOTS).
// subd_creases: the boundary as a subdivision crease (Fusion's SUBD_CREASES: the boundary curve the uniform cubic
// B-spline of the boundary control points, corners interpolated).
enum class EndConditions { bezier, subd_creases };

struct TMesh {
  int degree = 3;  // odd, both directions
  bool force_bezier = true;
  EndConditions end_conditions = EndConditions::bezier;
  std::vector<TMeshLink> links;
  std::vector<std::vector<int>> faces;  // link loops; empty: a deleted face (a hole)
  std::vector<double> intervals;        // per edge; 0: a deleted edge
  std::vector<TMeshVertex> vertices;
  std::vector<RationalPoint> points;
  std::vector<std::array<int, 2>> conditions;  // edge conditions (edge, flag); between two faces of a
                                               // subd_creases mesh, sharp creases (sharp_creases)
  // Fusion's crease lists (`100edges`, `100verts`): the edges and vertices its editor marks as creased, kept
  // as read for writing back; the crease edges are sharp creases of a subd_creases mesh (sharp_creases).
  std::vector<int> crease_edges, crease_vertices;

  bool live_face(int f) const { return !faces[static_cast<std::size_t>(f)].empty(); }
  // The face's first corner link (flag 0): its canonical frame starts at that link's vertex going east.
  int first_corner(int f) const;
};

// The link leaving the far end of link l straight on (the opposite of l's link there), when that vertex is an
// interior vertex of four quadrilaterals; -1 otherwise.
int straight_link(const TMesh& m, int l);

// The faces' angles at each vertex in degrees (90 (flag + 1) per corner of a live face) and whether it is on the
// boundary (a link of it outside the live faces).
struct VertexAngles {
  std::vector<int> degrees;
  std::vector<char> boundary;
};
VertexAngles vertex_angles(const TMesh& m);

// Face angle sums at the vertices: a star point is an interior vertex whose faces' angles do not sum to 360
// degrees, or a boundary vertex whose faces' angles exceed 270.
std::vector<int> star_points(const TMesh& m);

// Whether the mesh holds a closed strip: faces, each entered through one side and left through the opposite one,
// that come back to the first (round a torus or a tube). The knot intervals lay such a strip out along a straight
// line, so it cannot close in the plane: the mesh has no global (s, t) even without star points.
bool has_closed_strip(const TMesh& m);

// The chart of a set of faces (empty: all live faces): the faces reached from `seed` across shared edges, laid
// out by their knot intervals with the seed's first corner link going east and the smallest (s, t) at 0, and
// the T-spline on it (nodes of the chart's vertices, their end-condition blocks turned into the chart's frame).
// With `all_connected`, a face of the set not reached is an error. Throws trivar::Error when the layout
// contradicts itself (a star point inside the set, a closed strip, contradictory knot intervals).
struct TChart {
  TSpline spline;
  std::vector<int> vertex;    // mesh vertex -> T-image vertex, -1: not in the chart
  std::vector<int> face;      // mesh face -> T-image face, -1: not in the chart
  std::vector<int> link_dir;  // mesh link -> its compass direction in the chart, -1: not in the chart
};
TChart t_spline_chart(const TMesh& m, std::span<const int> faces, int seed, bool all_connected);

}  // namespace trivar
