#include "trivar/cad/brep_mapping.hpp"

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <Bnd_Box.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ShapeFix_Shell.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Vertex.hxx>
#include <Precision.hxx>
#include <gp_Trsf.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <TopoDS_Compound.hxx>
#include <GProp_GProps.hxx>
#include <GeomConvert.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <ShapeFix_Shape.hxx>
#include <ShapeFix_Solid.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <optional>
#include <cmath>

#include "trivar/cad/face_nurbs.hpp"
#include "trivar/cad/occt_spline.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/iso_extraction.hpp"

namespace trivar::cad {

namespace {

// Offset surfaces of free-form bases are fitted within this fraction of the solid's size: the volume error is
// at most the faces' area times the deviation, far below the 1e-6 relative an import must reach.
constexpr double kOffsetFitTolerance = 1e-9;

// Signed area of a trimming loop in its face's parameter plane (positive: counter-clockwise).
double loop_area(const TrimLoop& loop) {
  static const QuadratureRule rule = gauss_legendre(8);
  double a = 0;
  for (const TrimCurve& c : loop.curves) {
    const std::vector<double> br = c.pcurve.knots(0).breakpoints();
    for (std::size_t s = 0; s + 1 < br.size(); ++s)
      for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
        double d[4];
        c.pcurve.eval_derivs({br[s] + rule.nodes[q] * (br[s + 1] - br[s])}, 1, d);
        a += 0.5 * rule.weights[q] * (br[s + 1] - br[s]) * (d[0] * d[3] - d[1] * d[2]);
      }
  }
  return a;
}

TensorSpline<1> reversed(const Handle(Geom2d_BSplineCurve)& c) {
  Handle(Geom2d_BSplineCurve) r = Handle(Geom2d_BSplineCurve)::DownCast(c->Copy());
  r->Reverse();
  return to_spline(*r);
}

TensorSpline<1> reverse_curve(const TensorSpline<1>& c) {
  const KnotVector& k = c.knots(0);
  std::vector<double> t(k.knots().rbegin(), k.knots().rend());
  const double a = k.knots().front(), b = k.knots().back();
  for (double& x : t) x = a + b - x;
  std::vector<double> coefs(c.coefs().size());
  const int s = c.stride(), n = c.num_coefs();
  for (int i = 0; i < n; ++i)
    std::copy(c.coef(n - 1 - i), c.coef(n - 1 - i) + s, coefs.begin() + static_cast<std::ptrdiff_t>(i) * s);
  return TensorSpline<1>({KnotVector(k.degree(), std::move(t))}, c.dim(), c.is_rational(), std::move(coefs));
}

// The face's surface as a B-spline, null when it is none.
Handle(Geom_BSplineSurface) bspline_surface(const TopoDS_Face& face) {
  Handle(Geom_Surface) surf = BRep_Tool::Surface(face);
  if (const auto rt = Handle(Geom_RectangularTrimmedSurface)::DownCast(surf); !rt.IsNull()) surf = rt->BasisSurface();
  return Handle(Geom_BSplineSurface)::DownCast(surf);
}

}  // namespace

SolidMapper::SolidMapper(const TopoDS_Shape& solid, double chordal) {
  TopExp::MapShapes(solid, TopAbs_EDGE, edges_);
  TopExp::MapShapes(solid, TopAbs_VERTEX, vertices_);
  TopExp::MapShapesAndAncestors(solid, TopAbs_EDGE, TopAbs_FACE, edge_faces_);
  Bnd_Box box;
  BRepBndLib::Add(solid, box, false);
  scale_ = box.IsVoid() ? 1.0 : std::sqrt(box.SquareExtent());
  boundary_.chordal_tolerance = chordal;
  boundary_.edges.resize(static_cast<std::size_t>(edges_.Extent()));
  edge_done_.assign(boundary_.edges.size(), false);
}

std::string SolidMapper::add_face(const TopoDS_Face& face, const std::string& kind, const std::string& name) {
  TrimmedFace tf;
  tf.kind = kind;
  tf.name = name;
  tf.reversed = face.Orientation() == TopAbs_REVERSED;
  tf.tolerance = BRep_Tool::Tolerance(face);
  const TopoDS_Face fwd = TopoDS::Face(face.Oriented(TopAbs_FORWARD));
  // The face's parameter box once: the wire explorer would otherwise compute it over all loops for each loop.
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(fwd, u0, u1, v0, v1);
  std::optional<FaceNurbs> form;
  try {
    form = face_nurbs(face, Box<2>{{u0, v0}, {u1, v1}}, kOffsetFitTolerance * scale_);
  } catch (const Error& e) {
    return e.what();
  }
  if (!form) return "the surface (" + std::string(BRep_Tool::Surface(face)->DynamicType()->Name()) + ") has no exact NURBS form";
  tf.surface = form->surface;
  for (TopExp_Explorer w(fwd, TopAbs_WIRE); w.More(); w.Next()) {
    TrimLoop loop;
    BRepTools_WireExplorer we;
    for (we.Init(TopoDS::Wire(w.Current()), fwd, u0, u1, v0, v1); we.More(); we.Next()) {
      const TopoDS_Edge& e = we.Current();
      double f = 0, l = 0;
      const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, fwd, f, l);
      if (pc.IsNull()) return "an edge has no parameter-space curve on the face";
      const Handle(Geom2d_BSplineCurve) bc = form->pcurve(pc, f, l);
      if (bc.IsNull()) return "a parameter-space curve is no iso-line of the surface's angular direction";
      TrimCurve tc;
      tc.edge_reversed = e.Orientation() == TopAbs_REVERSED;
      tc.edge = BRep_Tool::Degenerated(e) ? -1 : edges_.FindIndex(e) - 1;
      const Solved* solved = tc.edge >= 0 && !BRep_Tool::IsClosed(e, fwd) ? &solved_edge(e, tc.edge, fwd) : nullptr;
      if (solved && solved->edge) {
        const TensorSpline<1>& on = solved->first_face.IsSame(fwd) ? solved->edge->on_first : solved->edge->on_second;
        tc.pcurve = tc.edge_reversed ? reverse_curve(on) : on;
      } else {
        tc.pcurve = tc.edge_reversed ? reversed(bc) : to_spline(*bc);
      }
      if (tc.edge >= 0 && !edge_done_[tc.edge]) {
        double cf = 0, cl = 0;
        const Handle(Geom_Curve) c3 = BRep_Tool::Curve(e, cf, cl);
        if (c3.IsNull()) return "an edge has no 3D curve";
        boundary_.edges[tc.edge] = {solved && solved->edge ? solved->edge->curve
                                                           : to_spline(*GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(c3, cf, cl))),
                                    BRep_Tool::Tolerance(e)};
        edge_done_[tc.edge] = true;
      }
      loop.curves.push_back(std::move(tc));
    }
    if (!loop.curves.empty()) tf.loops.push_back(std::move(loop));
  }
  if (tf.loops.empty()) return "the face has no trimming loop";
  // The face's region must lie left of its loops: the largest loop counter-clockwise.
  std::size_t outer = 0;
  std::vector<double> areas;
  for (const TrimLoop& l : tf.loops) areas.push_back(loop_area(l));
  for (std::size_t i = 1; i < areas.size(); ++i)
    if (std::abs(areas[i]) > std::abs(areas[outer])) outer = i;
  if (areas[outer] < 0)
    for (TrimLoop& l : tf.loops) {
      std::reverse(l.curves.begin(), l.curves.end());
      for (TrimCurve& c : l.curves) {
        c.pcurve = reverse_curve(c.pcurve);
        c.edge_reversed = !c.edge_reversed;
      }
    }
  if (std::string why = add_mesh(face, static_cast<int>(boundary_.faces.size()), *form); !why.empty()) return why;
  boundary_.faces.push_back(std::move(tf));
  return {};
}

const SolidMapper::Solved& SolidMapper::solved_edge(const TopoDS_Edge& e, int index, const TopoDS_Face& face) {
  const auto [it, fresh] = solved_.try_emplace(index);
  if (!fresh) return it->second;
  Solved& s = it->second;
  s.first_face = face;
  // The other face along the edge, its surface and the edge's curves on both, over one parameter range.
  TopoDS_Face other;
  for (const TopoDS_Shape& f : edge_faces_.FindFromKey(e))
    if (!f.IsSame(face)) other = TopoDS::Face(f.Oriented(TopAbs_FORWARD));
  if (other.IsNull()) return s;
  const Handle(Geom_BSplineSurface) s1 = bspline_surface(face), s2 = bspline_surface(other);
  double f1 = 0, l1 = 0, f2 = 0, l2 = 0, f3 = 0, l3 = 0;
  const Handle(Geom2d_Curve) c1 = BRep_Tool::CurveOnSurface(e, face, f1, l1);
  const Handle(Geom2d_Curve) c2 = BRep_Tool::CurveOnSurface(e, other, f2, l2);
  const Handle(Geom_Curve) c3 = BRep_Tool::Curve(e, f3, l3);
  if (s1.IsNull() || s2.IsNull() || c1.IsNull() || c2.IsNull() || c3.IsNull()) return s;
  const double span = std::abs(l1 - f1);
  if (std::abs(f2 - f1) > 1e-12 * span || std::abs(l2 - l1) > 1e-12 * span || std::abs(f3 - f1) > 1e-12 * span ||
      std::abs(l3 - l1) > 1e-12 * span)
    return s;
  // Edges already on both surfaces (those of the operands, lines on planes) are kept as they are.
  constexpr int kProbes = 7;
  double gap = 0;
  for (int k = 0; k < kProbes; ++k) {
    const double t = f1 + (l1 - f1) * (k + 0.5) / kProbes;
    const gp_Pnt2d a = c1->Value(t), b = c2->Value(t);
    gap = std::max(gap, s1->Value(a.X(), a.Y()).Distance(s2->Value(b.X(), b.Y())));
  }
  if (gap <= 1e-10 * scale_) return s;
  s.edge = solve_intersection_edge(s1, c1, s2, c2, c3, f1, l1, scale_);
  return s;
}

TrimmedBoundary SolidMapper::take() {
  // Drop the triangles a pole collapsed.
  TriangleMesh& m = boundary_.mesh;
  std::size_t k = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) continue;
    m.triangles[k] = tri;
    boundary_.triangle_face[k] = boundary_.triangle_face[t];
    boundary_.triangle_uv[k] = boundary_.triangle_uv[t];
    ++k;
  }
  m.triangles.resize(k);
  boundary_.triangle_face.resize(k);
  boundary_.triangle_uv.resize(k);
  return std::move(boundary_);
}

int SolidMapper::mesh_vertex_of(const TopoDS_Shape& v) {
  const int id = vertices_.FindIndex(v);
  auto [it, fresh] = vertex_nodes_.try_emplace(id, static_cast<int>(boundary_.mesh.vertices.size()));
  if (fresh) {
    const gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(v));
    boundary_.mesh.vertices.push_back({p.X(), p.Y(), p.Z()});
  }
  return it->second;
}

// The face's triangulation, its nodes on edges identified with the edges' shared discretisation so that
// neighbouring faces use the same mesh vertices.
std::string SolidMapper::add_mesh(const TopoDS_Face& face, int face_index, const FaceNurbs& form) {
  TopLoc_Location loc;
  const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
  if (tri.IsNull() || tri->NbTriangles() == 0 || !tri->HasUVNodes()) return "the kernel did not tessellate the face";
  std::vector<int> node(static_cast<std::size_t>(tri->NbNodes()) + 1, -1);
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(x.Current());
    const Handle(Poly_PolygonOnTriangulation) poly = BRep_Tool::PolygonOnTriangulation(e, tri, loc);
    if (poly.IsNull()) return "the kernel's tessellation of an edge is missing";
    const TColStd_Array1OfInteger& nodes = poly->Nodes();
    TopoDS_Vertex v0, v1;
    TopExp::Vertices(TopoDS::Edge(e.Oriented(TopAbs_FORWARD)), v0, v1);
    const int n = nodes.Length();
    const int eid = edges_.FindIndex(e);
    const bool degenerate = BRep_Tool::Degenerated(e);
    for (int k = 0; k < n; ++k) {
      int& target = node[static_cast<std::size_t>(nodes(nodes.Lower() + k))];
      if (degenerate || k == 0)
        target = mesh_vertex_of(k == n - 1 && !degenerate ? v1 : v0);
      else if (k == n - 1)
        target = mesh_vertex_of(v1);
      else {
        auto [it, fresh] = edge_nodes_.try_emplace({eid, k}, static_cast<int>(boundary_.mesh.vertices.size()));
        if (fresh) {
          const gp_Pnt p = tri->Node(nodes(nodes.Lower() + k)).Transformed(loc.Transformation());
          boundary_.mesh.vertices.push_back({p.X(), p.Y(), p.Z()});
        }
        target = it->second;
      }
    }
  }
  for (int i = 1; i <= tri->NbNodes(); ++i)
    if (node[static_cast<std::size_t>(i)] < 0) {
      node[static_cast<std::size_t>(i)] = static_cast<int>(boundary_.mesh.vertices.size());
      const gp_Pnt p = tri->Node(i).Transformed(loc.Transformation());
      boundary_.mesh.vertices.push_back({p.X(), p.Y(), p.Z()});
    }
  const bool flip = face.Orientation() == TopAbs_REVERSED;
  for (int t = 1; t <= tri->NbTriangles(); ++t) {
    int n[3];
    tri->Triangle(t).Get(n[0], n[1], n[2]);
    if (flip) std::swap(n[1], n[2]);
    std::array<int, 3> ids;
    std::array<Param<2>, 3> uv;
    for (int k = 0; k < 3; ++k) {
      ids[k] = node[static_cast<std::size_t>(n[k])];
      const gp_Pnt2d p = tri->UVNode(n[k]);
      uv[k] = form(p.X(), p.Y());
    }
    boundary_.mesh.triangles.push_back(ids);
    boundary_.triangle_face.push_back(face_index);
    boundary_.triangle_uv.push_back(uv);
  }
  return {};
}

namespace {

// The solid bounded by a closed shell, its shell turned when it faced inwards (a reversed solid would be the
// complement of the region to the kernel's Booleans).
TopoDS_Solid outward_solid(TopoDS_Shell shell, const std::string& what) {
  BRep_Builder b;
  const auto make = [&] {
    TopoDS_Solid s;
    b.MakeSolid(s);
    b.Add(s, shell);
    return s;
  };
  TopoDS_Solid solid = make();
  GProp_GProps g;
  BRepGProp::VolumeProperties(solid, g);
  if (g.Mass() < 0) {
    shell.Reverse();
    solid = make();
  }
  require(BRepCheck_Analyzer(solid).IsValid(), what + ": the kernel reports the solid of the boundary faces invalid");
  return solid;
}

// Sews faces into a closed solid and orients it outwards; throws naming `what`.
TopoDS_Solid sew_solid(const std::vector<TopoDS_Face>& faces, double tolerance, const std::string& what) {
  BRepBuilderAPI_Sewing sew(tolerance);
  for (const TopoDS_Face& f : faces) sew.Add(f);
  sew.Perform();
  const TopoDS_Shape sewn = sew.SewedShape();
  TopExp_Explorer shells(sewn, TopAbs_SHELL);
  require(shells.More() && sew.NbFreeEdges() == 0,
          what + ": the boundary faces do not close a solid (" + std::to_string(sew.NbFreeEdges()) + " free edges after sewing)");
  const TopoDS_Shell shell = TopoDS::Shell(shells.Current());
  shells.Next();
  require(!shells.More(), what + ": the boundary faces form more than one shell");
  return outward_solid(shell, what);
}

// The six faces of the trivariate, each an untrimmed B-spline face.
std::vector<TopoDS_Face> trivariate_faces(const TensorSpline<3>& g) {
  std::vector<TopoDS_Face> faces;
  for (const TensorSpline<2>& f : boundary_faces(g)) faces.push_back(BRepBuilderAPI_MakeFace(to_occt(f), 1e-9).Face());
  return faces;
}

// One face per trimmed face: the surface bounded by its loops, each trim curve an edge on the surface.
std::vector<TopoDS_Face> trimmed_faces(const TrimmedBoundary& b, double tolerance, const std::string& what) {
  std::vector<TopoDS_Face> faces;
  for (std::size_t i = 0; i < b.faces.size(); ++i) {
    const TrimmedFace& tf = b.faces[i];
    const Handle(Geom_BSplineSurface) surface = to_occt(tf.surface);
    std::vector<TopoDS_Wire> wires;
    for (const TrimLoop& loop : tf.loops) {
      // The curves' ends on the surface: where a curve meets the next, the two ends differ by the accuracy of the
      // pcurves the kernel computed (intersection curves of an earlier Boolean are approximations, 1e-6 and more
      // apart at their ends). One vertex at each junction, its tolerance covering both ends, joins them; edges
      // made on their own would each get vertices of the default tolerance, too small to connect them.
      const std::size_t n = loop.curves.size();
      std::vector<Handle(Geom2d_BSplineCurve)> pcs;
      std::vector<std::array<gp_Pnt, 2>> ends;
      for (const TrimCurve& c : loop.curves) {
        pcs.push_back(to_occt_2d(c.pcurve));
        const auto at = [&](double t) {
          const gp_Pnt2d q = pcs.back()->Value(t);
          return surface->Value(q.X(), q.Y());
        };
        ends.push_back({at(pcs.back()->FirstParameter()), at(pcs.back()->LastParameter())});
      }
      std::vector<TopoDS_Vertex> junction(n);  // junction k: the start of curve k, the end of curve k - 1
      BRep_Builder builder;
      for (std::size_t k = 0; k < n; ++k) {
        const gp_Pnt& p0 = ends[(k + n - 1) % n][1];
        const gp_Pnt& p1 = ends[k][0];
        const double gap = p0.Distance(p1);
        require(gap <= tolerance, what + ": face " + std::to_string(i) + ": a trimming loop is not connected within the tolerance (gap " +
                                      std::to_string(gap) + " > " + std::to_string(tolerance) + ")");
        builder.MakeVertex(junction[k], gp_Pnt((p0.XYZ() + p1.XYZ()) / 2), std::max(Precision::Confusion(), 0.5 * gap * (1 + 1e-3)));
      }
      // A curve closed in space (a full circle beside a seam, a pole) starts and ends at one vertex: the kernel
      // refuses two there. Junctions joined by such curves become the first of them.
      for (std::size_t k = 0; k < n; ++k) {
        if (ends[k][0].Distance(ends[k][1]) > Precision::Confusion()) continue;
        const std::size_t to = (k + 1) % n;
        if (junction[to].IsSame(junction[k])) continue;
        const gp_Pnt p = BRep_Tool::Pnt(junction[k]);
        const double t = std::max(BRep_Tool::Tolerance(junction[k]),
                                  BRep_Tool::Tolerance(junction[to]) + p.Distance(BRep_Tool::Pnt(junction[to])));
        builder.UpdateVertex(junction[k], t);
        const TopoDS_Vertex old = junction[to];
        for (TopoDS_Vertex& v : junction)
          if (v.IsSame(old)) v = junction[k];
      }
      BRepBuilderAPI_MakeWire wire;
      for (std::size_t k = 0; k < n; ++k) {
        BRepBuilderAPI_MakeEdge edge(pcs[k], surface, junction[k], junction[(k + 1) % n], pcs[k]->FirstParameter(),
                                     pcs[k]->LastParameter());
        require(edge.IsDone(), what + ": face " + std::to_string(i) + ": a trimming curve is no edge on its surface");
        TopoDS_Edge e = edge.Edge();
        if (loop.curves[k].edge < 0) builder.Degenerated(e, true);
        wire.Add(e);
        require(wire.IsDone(), what + ": face " + std::to_string(i) + ": a trimming loop is not connected");
      }
      wires.push_back(wire.Wire());
    }
    BRepBuilderAPI_MakeFace make(surface, wires.front(), true);
    for (std::size_t w = 1; w < wires.size(); ++w) make.Add(wires[w]);
    require(make.IsDone(), what + ": face " + std::to_string(i) + ": the kernel cannot bound the surface by its loops");
    TopoDS_Face face = make.Face();
    BRepLib::BuildCurves3d(face, 1e-3 * tolerance, GeomAbs_C1, 14, 0);
    ShapeFix_Shape fix(face);
    fix.Perform();
    face = TopoDS::Face(fix.Shape());
    // The face's region lies left of its loops in (u, v), so it is the kernel's forward face; the outward
    // normal is S_u x S_v unless the face is reversed.
    if (tf.reversed) face.Reverse();
    faces.push_back(face);
  }
  return faces;
}

}  // namespace

TopoDS_Solid kernel_solid(const VCell& cell, const std::string& what) {
  try {
    if (!cell.is_trimmed()) {
      const Box<3> box = [&] {
        Box<3> b;
        cell.geometry().control_bounds(b.lo.data(), b.hi.data());
        return b;
      }();
      return sew_solid(trivariate_faces(cell.geometry()), 1e-7 * box.diagonal(), what);
    }
    const TrimmedBoundary& b = cell.trim()->boundary();
    double tol = 1e-6 * cell.trim()->bounding_box().diagonal();
    for (const TrimmedFace& f : b.faces) tol = std::max(tol, 2 * f.tolerance);
    for (const TrimEdge& e : b.edges) tol = std::max(tol, 2 * e.tolerance);
    return sew_solid(trimmed_faces(b, tol, what), tol, what);
  } catch (const Standard_Failure& e) {
    throw Error(what + ": the geometry kernel failed: " + std::string(e.GetMessageString()));
  }
}

OperandSolids operand_solids(const VModel& model, const std::string& what) {
  OperandSolids out;
  const auto one_by_one = [&] {
    out.shared_faces = false;
    out.solids.clear();
    for (int c = 0; c < model.num_cells(); ++c) out.solids.push_back(kernel_solid(model.cell(c), what + ": cell " + std::to_string(c)));
    return out;
  };
  const bool trimmed = std::any_of(model.cells().begin(), model.cells().end(), [](const VCell& c) { return c.is_trimmed(); });
  if (trimmed || !model.is_glued()) return one_by_one();
  out.shared_faces = true;
  try {
    const VTopology& t = model.topology();
    // The faces are sewn about the model's centre and the solids moved back: sewing all faces of a ball of
    // cells away from the origin left pairs of coincident edges unsewn, about the origin it does not.
    const std::array<double, 3> centre = model.bounding_box().center();
    std::vector<std::array<TensorSpline<2>, 6>> cell_faces;
    for (const VCell& c : model.cells())
      cell_faces.push_back(boundary_faces(transform(c.geometry(), Eigen::Matrix3d::Identity(), -Eigen::Vector3d(centre[0], centre[1], centre[2]))));
    gp_Trsf back;
    back.SetTranslation(gp_Vec(centre[0], centre[1], centre[2]));
    // One kernel face per V-surface, all sewn at once, so the cells' solids share their faces and edges.
    BRepBuilderAPI_Sewing sew(1e-7 * model.bounding_box().diagonal(), true, true, false, true);
    std::vector<TopoDS_Face> faces(t.surfaces.size());
    for (std::size_t s = 0; s < t.surfaces.size(); ++s) {
      const HalfVSurface& h = t.halves[static_cast<std::size_t>(t.surfaces[s].halves[0])];
      faces[s] = BRepBuilderAPI_MakeFace(to_occt(cell_faces[static_cast<std::size_t>(h.cell)][static_cast<std::size_t>(h.face)]), 1e-9).Face();
      sew.Add(faces[s]);
    }
    sew.Perform();
    for (int c = 0; c < model.num_cells(); ++c) {
      const std::string cw = what + ": cell " + std::to_string(c);
      BRep_Builder b;
      TopoDS_Shell shell;
      b.MakeShell(shell);
      for (int f = 0; f < 6; ++f) {
        const HalfVSurface& h = t.halves[static_cast<std::size_t>(6 * c + f)];
        // A face glued to another face of the same cell (a ring closing on itself) is inside the cell.
        if (h.degenerate || h.surface < 0 || (h.twin >= 0 && h.twin / 6 == c)) continue;
        b.Add(shell, sew.Modified(faces[static_cast<std::size_t>(h.surface)]));
      }
      ShapeFix_Shell fix(shell);
      fix.Perform();
      shell = fix.Shell();
      // Sewing many faces at once occasionally leaves a pair of coincident edges apart; the cells are then made
      // one by one (the fuse finds their coincident faces, at a higher cost).
      if (!BRep_Tool::IsClosed(shell)) return one_by_one();
      out.solids.push_back(outward_solid(shell, cw));
    }
    // Moved back as one shape with copied geometry, so the solids keep sharing their faces (the mapping of
    // pieces reads geometry and triangulations as stored, without locations).
    BRep_Builder b;
    TopoDS_Compound all;
    b.MakeCompound(all);
    for (const TopoDS_Solid& solid : out.solids) b.Add(all, solid);
    const TopoDS_Shape moved = BRepBuilderAPI_Transform(all, back, true).Shape();
    out.solids.clear();
    for (TopExp_Explorer x(moved, TopAbs_SOLID); x.More(); x.Next()) out.solids.push_back(TopoDS::Solid(x.Current()));
    require(static_cast<int>(out.solids.size()) == model.num_cells(), what + ": the kernel lost a cell's solid when moving it");
  } catch (const Standard_Failure& e) {
    throw Error(what + ": the geometry kernel failed: " + std::string(e.GetMessageString()));
  }
  return out;
}

}  // namespace trivar::cad
