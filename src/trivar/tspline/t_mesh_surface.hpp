#pragma once
// The surface of a T-mesh with star points (extraordinary vertices), evaluated face by face in each face's own
// frame (u, v) in [0, 1]^2 (u along its first corner link, v turning left):
//   exact          faces whose neighbourhood of p + 1 face rings holds no star point: the T-spline itself,
//                  evaluated in the chart of that neighbourhood (t_spline_chart), where the T-spline rules
//                  (local knot vectors by rays, end-condition blocks) apply unchanged. A chart is accepted only
//                  when no blending function nonzero on its faces has a knot vector cut by the chart's border
//                  inside the mesh (else it grows by a ring), so this is the global T-spline's surface wherever
//                  one exists (tested face by face to 1e-12, also starting from one-ring charts). Charts are
//                  shared: as large as their layout in the plane allows (exact_chart), else by clusters of faces.
//   bicubic        the other faces without a star corner: the bicubic B-spline patch of their 4 x 4 control
//                  points on the knots of the mesh's lines through the face (uniform when the intervals are
//                  equal), which is the T-spline there (no T-junction nearby).
//   star           the faces at a star point: the Catmull-Clark limit surface of their 2N + 8 control points,
//                  evaluated exactly (catmull_clark_patch, Stam 1998).
//   non_uniform    the faces of the two face rings of a star point with unequal knot intervals on its three rings
//                  of faces (the faces whose 4 x 4 points hold the star point): non-uniform Catmull-Clark
//                  (non_uniform_catmull_clark: knot-interval-weighted rules, which are knot insertion of the
//                  bicubic B-spline away from the star point and uniform Catmull-Clark for equal intervals),
//                  evaluated exactly as B-spline cells of the subdivision levels. It needs the three rings to be
//                  quadrilaterals without T-junctions around vertices of four faces, off the boundary.
//   subdivided     faces with several star corners, or whose corner's neighbours are star points (star points
//                  joined by an edge; coarse cages such as a cube of one face per side): one uniform
//                  Catmull-Clark step of the face's two rings (subdivided_face), each quarter of the face a
//                  bicubic or star patch of the subdivided points (u, v in [0, 1/2]^2 etc. mapped to the
//                  sub-face's [0, 1]^2, derivatives times 2); exactly the limit surface still. Equal knot
//                  intervals only (unequal ones: crease, below).
//   crease         in a subdivision-crease mesh, the faces within p + 1 rings of an irregular vertex of a crease
//                  boundary (irregular_crease_vertices: a crease vertex of other than two faces, a corner of other
//                  than one; boundary star points among them; darts, where a crease ends inside the mesh and is
//                  cut open up to that vertex, smooth over its whole fan; cone points, creased vertices inside
//                  the mesh on no crease, interior corners), and faces near star points too close to a crease
//                  boundary for the patches above: repeated local Catmull-Clark subdivision with the crease rules
//                  of the mesh cut open along its creases (crease_face), exactly the limit surface. Quadrilaterals
//                  without T-junctions in their two face rings; unequal knot intervals take the non-uniform rules
//                  (NURCC with crease_ends' natural end at the crease: knot insertion of the exact surface where
//                  the neighbourhood is regular), as do, in such a mesh, the faces whose 4 x 4 points hold a star
//                  point with unequal intervals nearby but without NonUniformStar's three regular rings.
//                  In meshes without creases the same local subdivision, the smooth (NURCC) rule at every
//                  vertex, takes the faces that the methods above refuse for unequal knot intervals: faces with
//                  several star corners or next to star points joined by an edge, and faces whose 4 x 4 points
//                  hold a star point without NonUniformStar's three regular rings (another star point within
//                  them) or in the cells of two star points; where the global steps (see the constructor) do
//                  not apply (open meshes, T-junctions away from the star points). Their two face rings must be
//                  quadrilaterals without T-junctions inside the mesh, with one interval per strip and one point per
//                  vertex.
// At degree 1 every face is exact, star point or not: the T-spline of the chart of the face and the faces across its
// T-junctions (bilinear pieces, C0).
// At odd degrees above 3 the faces within p + 2 rings of a star point are averaging faces (averaging_face: the
// uniform B-spline of degree p where the mesh is a regular grid, the same subdivision rules at star points) when
// their (p + 1) / 2 face rings are quadrilaterals inside the mesh with equal knot intervals.
// At degree 3 the faces within p + 2 rings of a star point (bicubic and star) need, and are checked to have,
// no T-junction and no boundary within (p + 1) / 2 rings of them, control points
// without repeated-knot nodes, and at most one star corner per face or else equal intervals (subdivided).
// Weights other than 1 are rational Catmull-Clark: the rules act on the homogeneous points (w x, w) and the
// limit is projected, which on faces without a star corner is the rational uniform bicubic B-spline
// sum w P B / sum w B, i.e. the T-spline (the
// rules are linear, so Stam's evaluation of the homogeneous mesh is exact; projection keeps C1 across edges and
// the tangent plane at the star point). A face more than p rings from
// the star points' faces that fails these (a boundary, a T-junction or unequal intervals nearby) is exact
// instead when a chart of p up to (its distance - 1) rings around it holds its knot vectors (so a star point
// needs 7 faces to the boundary, not 8); otherwise the face's reason is the error (what is still refused:
// T-junctions (in creased meshes or with end-condition nodes off their vertices: others complete their lines
// first, t_junction_lines) and
// repeated knots within two rings of a star point's faces, unequal intervals, T-junctions or
// corners with a side of one edge near a star point on the boundary, unequal intervals near star points whose
// faces have a boundary (a Bezier end condition, which has no subdivision rule) within their two face rings,
// at degrees above 3 T-junctions, a boundary or unequal intervals within an averaging face's rings). Close star points with unequal intervals in closed quadrilateral meshes without creases
// are first moved apart by global non-uniform Catmull-Clark steps (see the constructor), after which their
// faces are NonUniformStar's, Stam's or bicubic cells; elsewhere they are crease faces. A star point on a Bezier
// end-condition boundary is an interior one of the mesh with a ghost layer along the boundary (boundary_ghosts:
// the Bezier end condition as a uniform bicubic net, round corners as the tensor product of the two clamped ends), so its
// faces are star faces of valence K + 2 and the faces near it bicubic faces of that mesh, the T-spline wherever
// their points avoid it. The surface there
// is then the Catmull-Clark limit surface of the control mesh, which on faces without a star corner is the
// uniform bicubic B-spline = the T-spline. Continuity: C2 across every edge away from star points
// (T-spline and uniform B-spline pieces meet as one spline); C1 across the edges at a star point except at the
// point itself, where the surface is G1 (tangent-plane continuous; the face parametrisations are singular there
// for valence != 4). tests/tspline/star_point_test.cpp measures positions, normals and first derivatives across
// every edge; tests/tspline/non_uniform_star_test.cpp the same for non-uniform star points, whose faces meet C2
// away from the star point and have a common tangent plane at it (normal spread 1.7e-5 rad at 1e-6 from a
// valence-5 star point with intervals 0.6 to 2.5).
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "trivar/tspline/averaging_face.hpp"
#include "trivar/tspline/crease_face.hpp"
#include "trivar/tspline/subdivided_face.hpp"
#include "trivar/tspline/t_junction_lines.hpp"
#include "trivar/tspline/t_mesh.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {

enum class FaceMethod { none, exact, bicubic, star, non_uniform, subdivided, crease, averaging };
const char* face_method_name(FaceMethod m);

// The frame of a Catmull-Clark patch starting at corner c (0..3, counter-clockwise from the face's first corner)
// in the face's (u, v): (u, v) = origin + u' a + v' b with a, b orthonormal (so u' = a . ((u, v) - origin)).
struct CornerFrame {
  std::array<double, 2> origin, a, b;
};
CornerFrame corner_frame(int corner);

class TMeshSurface {
public:
  // threads for the charts' builds (parallel_for; <= 0: all). A crease boundary (subd_creases), or a Bezier
  // boundary without block points (Fusion's MULTIPLE_KNOTS without grip map), is evaluated as its Bezier end
  // conditions with block points (crease_ends), but near a crease boundary's irregular vertices by local
  // subdivision (crease faces); mesh() is that mesh.
  // Star points fewer than kStarsApart edges apart with unequal knot intervals around one of them (closed
  // quadrilateral meshes, nurcc_step's scope): the mesh is first refined by global non-uniform Catmull-Clark steps
  // (non_uniform_subdivision) until they are that far apart, which leaves the limit surface unchanged; mesh() and
  // the faces are then the refined mesh's (face F lies in face F >> 2 global_steps() of the mesh as given;
  // eval_source evaluates the faces as given).
  // global_steps >= 0 forces that many steps.
  // T-junctions within p + 2 rings of a star point's faces, p + 3 of an irregular crease vertex's, and on the face
  // at a corner of a crease boundary: their lines are completed first (t_junction_lines), and the completed mesh is
  // the one refined and evaluated; its faces are pieces of the faces as given (eval_source and refined_point map
  // between them).
  static constexpr int kStarsApart = 7;
  explicit TMeshSurface(const TMesh& mesh, int threads = 0, int global_steps = -1);
  ~TMeshSurface();
  TMeshSurface(TMeshSurface&&) noexcept;

  const TMesh& mesh() const { return mesh_; }
  // The mesh as given (a crease boundary, sharp creases or a boundary without block points as read, for writing
  // it back and for the topology its tessellation welds); mesh() when no conversion was needed.
  const TMesh& source_mesh() const { return source_ ? *source_ : mesh_; }
  // The mesh whose faces are the surface's faces, with the edges and vertices they share (for welding a
  // tessellation): source_mesh() (whose faces mesh() keeps), or mesh() after global steps or T-junction lines (in a
  // mesh cut along sharp creases, with the creases' sides joined again).
  const TMesh& face_mesh() const {
    if (lines_ && !lines_->welded.faces.empty()) return lines_->welded;
    return steps_ > 0 || lines_ ? mesh_ : source_mesh();
  }
  // Global non-uniform Catmull-Clark steps applied to the mesh as given, or to its completed T-junction lines (each
  // face became 4^steps faces).
  int global_steps() const { return steps_; }
  int source_face(int face) const {
    const int g = face >> (2 * steps_);
    return lines_ ? lines_->pieces[static_cast<std::size_t>(g)].source : g;
  }
  // The T-junction lines completed before the evaluation (none: nullptr); its mesh is not kept (its welded mesh is).
  const CompletedLines* completed_lines() const { return lines_ ? &*lines_ : nullptr; }
  // A point (u, v) in [0, 1]^2 of face `face` of the mesh as given (source_mesh()'s ids and frames): the face of
  // the surface that holds it, the point in that face's frame, and that frame's d(u)/d(u as given) and
  // d(v)/d(v as given) (2^steps, times the inverse size of a piece of a completed T-junction line; a point on a
  // side between two faces is taken by the one above it).
  struct FacePoint {
    int face;
    double u, v;
    std::array<double, 2> scale;
  };
  FacePoint refined_point(int source_face, double u, double v) const;
  // eval on a face of the mesh as given (its (u, v) and derivatives): what users of the file name a face by.
  void eval_source(int source_face, double u, double v, double* out) const;
  int num_faces() const { return static_cast<int>(faces_.size()); }  // mesh face ids (deleted faces: none)
  FaceMethod method(int face) const { return faces_[static_cast<std::size_t>(face)].method; }
  int count(FaceMethod m) const;
  // The faces at a star point on the boundary (Catmull-Clark of the mesh with its ghost layer: Stam's patches, or
  // local non-uniform subdivision with unequal knot intervals nearby).
  int boundary_star_faces() const;
  const std::vector<int>& stars() const { return stars_; }
  int valence(int star) const;  // faces around a star point
  // The corners of a face (its first corner link's vertex, then counter-clockwise), for quads and T-faces.
  std::array<int, 4> corners(int face) const;
  // Value, d/du, d/dv (9 values) at (u, v) in [0, 1]^2 of the face.
  void eval(int face, double u, double v, double* out) const;

  // An exact face: the chart's T-spline and the face in it, (u, v) -> origin + u axis_u + v axis_v.
  struct ChartFrame {
    const TSplineSurface* chart = nullptr;
    std::array<double, 2> origin{}, axis_u{}, axis_v{};
  };
  ChartFrame chart_frame(int face) const;
  // A bicubic or star face: its control points in the catmull_clark_patch layout (a bicubic face: 16, the
  // regular case) and the corner of the face they start at; the patch's (u', v') maps to the face's (u, v) by
  // corner_frame.
  std::vector<std::array<double, 3>> patch_points(int face) const;
  // The same face in its patch frame (u', v'): the homogeneous limit surface (w x, w y, w z, w) and its d/du',
  // d/dv' (12 values: value, d/du', d/dv', four each; at a star point the derivatives are directions). A
  // subdivided face's patch frame is the face's own (u, v).
  void eval_patch_homogeneous(int face, double up, double vp, double* out) const;
  bool rational_patch(int face) const { return faces_[static_cast<std::size_t>(face)].rational; }
  int patch_corner(int face) const { return faces_[static_cast<std::size_t>(face)].corner; }
  // A non-uniform Catmull-Clark face: true when the star point is its patch corner (a face of the star's one-ring
  // of faces); the others lie in the second ring (their four quarters are bicubic B-spline cells).
  bool star_corner(int face) const { return faces_[static_cast<std::size_t>(face)].cell == std::array<int, 2>{0, 0}; }
  // Star points evaluated by non-uniform Catmull-Clark (unequal knot intervals around them).
  int non_uniform_stars() const { return static_cast<int>(nurcc_.size()); }
  // A subdivided face: its four quarters after one local Catmull-Clark step.
  const SubdividedFace& subdivided(int face) const;
  // A face evaluated by local subdivision: near an irregular vertex of a crease boundary, or near star points with
  // unequal knot intervals that NonUniformStar and Stam's patches do not take.
  const CreaseFace& crease_face(int face) const;
  // A face near a star point of odd degree above 3 (averaging subdivision).
  const AveragingFace& averaging_face(int face) const;

private:
  struct Face {
    FaceMethod method = FaceMethod::none;
    int chart = -1;                // exact: index into charts_
    std::array<double, 2> origin{}, axis_u{}, axis_v{};  // exact: the face's first corner and sides in the chart
    int corner = 0;                // star: the star point's corner (0..3)
    std::vector<int> points;       // bicubic: 16, star: 2N + 8 control points (catmull_clark_patch layout)
    // Their homogeneous coordinates, split for the evaluation of the linear rules: w x and (w, 0, 0).
    std::vector<std::array<double, 3>> wx, w;
    bool rational = false;         // a weight other than 1
    // bicubic with unequal knot intervals: the knots of the cell [0, 1] (patch frame), six per direction
    std::optional<std::array<std::array<double, 6>, 2>> knots;
    int nurcc = -1, sector = 0;    // non_uniform: index into nurcc_, the sector and the face's cell in it
    std::array<int, 2> cell{-1, -1};
    bool boundary_star = false;    // star or crease: a corner is a star point on the boundary
    int subdivided = -1;           // subdivided: index into subdivided_
    int crease = -1;               // crease: index into crease_faces_
    int averaging = -1;            // averaging: index into averaging_faces_
  };
  // `cut`: the mesh cut open along its sharp creases (split_creases) when it has any, for its T-junction lines,
  // its Bezier end-condition form and its crease faces.
  TMeshSurface(const TMesh& mesh, std::unique_ptr<TMesh> cut, int threads, int global_steps);
  struct Nurcc;  // a star point evaluated by non-uniform Catmull-Clark: its subdivision and homogeneous points
  std::optional<CompletedLines> lines_;  // its mesh emptied once mesh_ is built from it
  std::vector<std::vector<int>> pieces_of_;  // per face as given: its pieces after the lines were completed
  int steps_ = 0;
  TMesh mesh_;
  std::unique_ptr<TMesh> source_;  // the mesh as given, when mesh_ is its Bezier end-condition form
  std::vector<int> stars_;
  std::vector<Face> faces_;
  std::vector<std::unique_ptr<TSplineSurface>> charts_;
  std::vector<std::unique_ptr<Nurcc>> nurcc_;
  std::vector<SubdividedFace> subdivided_;
  std::vector<CreaseFace> crease_faces_;
  std::vector<AveragingFace> averaging_faces_;
  std::unique_ptr<TMesh> ghosted_;  // with star points on the boundary: the mesh with their ghost layers
  // The control mesh of the Catmull-Clark faces (bicubic and star: their `points` are its vertices).
  const TMesh& cc_mesh() const { return ghosted_ ? *ghosted_ : mesh_; }
};

}  // namespace trivar
