#pragma once
// Internal to the cad layer (includes OpenCASCADE): the kernel's solids as trivar TrimmedBoundaries and back.
//
// SolidMapper maps one solid whose faces carry the kernel's triangulation and whose surfaces have an exact NURBS
// form (face_nurbs: analytic and B-spline surfaces; BRepBuilderAPI_NurbsConvert's output where a face's
// trimming curves do not follow the analytic map): every face an exact NURBS patch with its trimming loops, the mesh made
// watertight by identifying the nodes on shared edges. Faces triangulated once for several solids (a general
// fuse of cells) give the same triangles to each, so neighbouring cells' meshes conform.
//
// kernel_solid() goes the other way: the closed solid of a V-cell (the six boundary faces of its trivariate,
// or the exact faces and loops of its trimming boundary), sewn with a tolerance relative to its size.
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Solid.hxx>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "trivar/cad/intersection_edge.hpp"
#include "trivar/model/trimmed_boundary.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar::cad {

struct FaceNurbs;

class SolidMapper {
public:
  SolidMapper(const TopoDS_Shape& solid, double chordal);

  // Maps one face; `kind` and `name` describe the face as read. Returns an empty string or why it failed.
  std::string add_face(const TopoDS_Face& face, const std::string& kind, const std::string& name);
  // The boundary of the faces added (triangles collapsed by poles dropped).
  TrimmedBoundary take();

private:
  TopTools_IndexedMapOfShape edges_, vertices_;
  TrimmedBoundary boundary_;
  std::vector<bool> edge_done_;
  std::map<std::pair<int, int>, int> edge_nodes_;  // (edge, polygon position) -> mesh vertex
  std::map<int, int> vertex_nodes_;                // topological vertex -> mesh vertex
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces_;
  double scale_ = 0;  // the solid's size
  // Per edge where two faces meet off the exact intersection of their surfaces: the edge solved onto it
  // (intersection_edge.hpp) and the face its first parameter-space curve lies on.
  struct Solved {
    std::optional<IntersectionEdge> edge;
    TopoDS_Shape first_face;
  };
  std::map<int, Solved> solved_;

  int mesh_vertex_of(const TopoDS_Shape& vertex);
  const Solved& solved_edge(const TopoDS_Edge& edge, int index, const TopoDS_Face& face);
  std::string add_mesh(const TopoDS_Face& face, int face_index, const FaceNurbs& form);
};

// The closed solid of a cell, outward oriented. Throws trivar::Error naming `what` when the faces do not sew
// into a valid closed solid (a singular trivariate whose faces collapse, a trimming boundary the kernel
// cannot rebuild).
TopoDS_Solid kernel_solid(const VCell& cell, const std::string& what);

// The solids of all cells of a model, outward oriented. For a glued model of untrimmed cells every V-surface is
// one kernel face used by the cells on both sides (and their edges are shared), so a general fuse need not
// find coincident faces within the model (shared_faces); trimmed cells are made one by one (kernel_solid).
struct OperandSolids {
  std::vector<TopoDS_Solid> solids;
  bool shared_faces = false;
};
OperandSolids operand_solids(const VModel& model, const std::string& what);

}  // namespace trivar::cad
