#include "trivar/cad/step_import.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomConvert.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Shape.hxx>
#include <Standard_Failure.hxx>
#include <StepData_StepModel.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <cmath>
#include <filesystem>
#include <map>

#include "trivar/cad/occt_spline.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"

namespace trivar::cad {

namespace {

// The kernel reports progress and warnings on stdout; trivar's output is its own.
void silence_kernel() {
  static const bool done = [] {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    m->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    return true;
  }();
  (void)done;
}

std::string surface_kind(const TopoDS_Face& f) {
  switch (BRepAdaptor_Surface(f, false).GetType()) {
    case GeomAbs_Plane: return "plane";
    case GeomAbs_Cylinder: return "cylinder";
    case GeomAbs_Cone: return "cone";
    case GeomAbs_Sphere: return "sphere";
    case GeomAbs_Torus: return "torus";
    case GeomAbs_BezierSurface: return "bezier";
    case GeomAbs_BSplineSurface: return "bspline";
    case GeomAbs_SurfaceOfRevolution: return "revolution";
    case GeomAbs_SurfaceOfExtrusion: return "extrusion";
    case GeomAbs_OffsetSurface: return "offset";
    default: return "other";
  }
}

// "StepShape_AdvancedFace" -> "ADVANCED_FACE".
std::string step_keyword(const char* type_name) {
  std::string n = type_name, r;
  if (const auto p = n.find('_'); p != std::string::npos) n = n.substr(p + 1);
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (i > 0 && std::isupper(static_cast<unsigned char>(n[i]))) r += '_';
    r += static_cast<char>(std::toupper(static_cast<unsigned char>(n[i])));
  }
  return r;
}

class Namer {
public:
  explicit Namer(const STEPControl_Reader& reader) : reader_(reader) {}
  // "#812 ADVANCED_FACE", or `fallback` when the shape has no STEP instance.
  std::string operator()(const TopoDS_Shape& s, const std::string& fallback) const {
    const Handle(XSControl_WorkSession) ws = reader_.WS();
    if (ws.IsNull() || ws->TransferReader().IsNull()) return fallback;
    const Handle(Standard_Transient) e = ws->TransferReader()->EntityFromShapeResult(s, 1);
    const Handle(StepData_StepModel) model = Handle(StepData_StepModel)::DownCast(ws->Model());
    if (e.IsNull() || model.IsNull()) return fallback;
    std::string n = "#";
    n += std::to_string(model->IdentLabel(e));
    n += ' ';
    n += step_keyword(e->DynamicType()->Name());
    return n;
  }

private:
  const STEPControl_Reader& reader_;
};

int count_unique(const TopoDS_Shape& s, TopAbs_ShapeEnum kind) {
  TopTools_IndexedMapOfShape m;
  TopExp::MapShapes(s, kind, m);
  return m.Extent();
}

// Edges of a shell used by one face only (seams, used twice by one face, and degenerate edges excepted).
int free_edges(const TopoDS_Shape& shell) {
  TopTools_IndexedDataMapOfShapeListOfShape m;
  TopExp::MapShapesAndAncestors(shell, TopAbs_EDGE, TopAbs_FACE, m);
  int n = 0;
  for (int i = 1; i <= m.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(m.FindKey(i));
    if (BRep_Tool::Degenerated(e)) continue;
    const TopTools_ListOfShape& faces = m.FindFromIndex(i);
    if (faces.Extent() == 1 && !BRep_Tool::IsClosed(e, TopoDS::Face(faces.First()))) ++n;
  }
  return n;
}

std::string plural(int n, const char* word) { return std::to_string(n) + " " + word + (n == 1 ? "" : "s"); }

// What lies outside every solid, one line per kind.
std::vector<std::string> outside_solids(const TopoDS_Shape& shape) {
  std::vector<std::string> out;
  int shells = 0, open = 0, open_edges = 0;
  for (TopExp_Explorer x(shape, TopAbs_SHELL, TopAbs_SOLID); x.More(); x.Next()) {
    ++shells;
    if (const int fe = free_edges(x.Current()); fe > 0) {
      ++open;
      open_edges += fe;
    }
  }
  if (shells > 0)
    out.push_back(plural(shells, "shell") + " outside solids" +
                  (open > 0 ? " (" + std::to_string(open) + " open: " + plural(open_edges, "free edge") + ")" : ""));
  int faces = 0, edges = 0, vertices = 0;
  for (TopExp_Explorer x(shape, TopAbs_FACE, TopAbs_SHELL); x.More(); x.Next()) ++faces;
  for (TopExp_Explorer x(shape, TopAbs_EDGE, TopAbs_FACE); x.More(); x.Next()) ++edges;
  for (TopExp_Explorer x(shape, TopAbs_VERTEX, TopAbs_EDGE); x.More(); x.Next()) ++vertices;
  if (faces > 0) out.push_back(plural(faces, "face") + " outside shells");
  if (edges > 0) out.push_back(plural(edges, "edge") + " outside faces (wires, curves)");
  if (vertices > 0) out.push_back(plural(vertices, "vertex") + " outside edges (points)");
  return out;
}

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

// Builds the trimmed boundary of one (converted, meshed) solid. Throws a message naming the face on a
// missing pcurve or a surface that is no B-spline after conversion.
class SolidMapper {
public:
  SolidMapper(const TopoDS_Shape& solid, double chordal) : solid_(solid) {
    TopExp::MapShapes(solid, TopAbs_EDGE, edges_);
    TopExp::MapShapes(solid, TopAbs_VERTEX, vertices_);
    boundary_.chordal_tolerance = chordal;
    boundary_.edges.resize(static_cast<std::size_t>(edges_.Extent()));
    edge_done_.assign(boundary_.edges.size(), false);
  }

  // Maps one face; `kind` and `name` describe the face as read. Returns an empty string or why it failed.
  std::string add_face(const TopoDS_Face& face, const std::string& kind, const std::string& name) {
    TrimmedFace tf;
    tf.kind = kind;
    tf.name = name;
    tf.reversed = face.Orientation() == TopAbs_REVERSED;
    tf.tolerance = BRep_Tool::Tolerance(face);
    Handle(Geom_Surface) surf = BRep_Tool::Surface(face);
    if (const auto rt = Handle(Geom_RectangularTrimmedSurface)::DownCast(surf); !rt.IsNull()) surf = rt->BasisSurface();
    const Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(surf);
    if (bs.IsNull()) return "the surface (" + std::string(surf->DynamicType()->Name()) + ") has no exact NURBS form";
    tf.surface = to_spline(*bs);
    const TopoDS_Face fwd = TopoDS::Face(face.Oriented(TopAbs_FORWARD));
    for (TopExp_Explorer w(fwd, TopAbs_WIRE); w.More(); w.Next()) {
      TrimLoop loop;
      for (BRepTools_WireExplorer we(TopoDS::Wire(w.Current()), fwd); we.More(); we.Next()) {
        const TopoDS_Edge& e = we.Current();
        double f = 0, l = 0;
        const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, fwd, f, l);
        if (pc.IsNull()) return "an edge has no parameter-space curve on the face";
        const Handle(Geom2d_BSplineCurve) bc = Geom2dConvert::CurveToBSplineCurve(new Geom2d_TrimmedCurve(pc, f, l));
        TrimCurve tc;
        tc.edge_reversed = e.Orientation() == TopAbs_REVERSED;
        tc.pcurve = tc.edge_reversed ? reversed(bc) : to_spline(*bc);
        tc.edge = BRep_Tool::Degenerated(e) ? -1 : edges_.FindIndex(e) - 1;
        if (tc.edge >= 0 && !edge_done_[tc.edge]) {
          double cf = 0, cl = 0;
          const Handle(Geom_Curve) c3 = BRep_Tool::Curve(e, cf, cl);
          if (c3.IsNull()) return "an edge has no 3D curve";
          boundary_.edges[tc.edge] = {to_spline(*GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(c3, cf, cl))),
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
    if (std::string why = add_mesh(face, static_cast<int>(boundary_.faces.size())); !why.empty()) return why;
    boundary_.faces.push_back(std::move(tf));
    return {};
  }

  TrimmedBoundary take() {
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

private:
  const TopoDS_Shape& solid_;
  TopTools_IndexedMapOfShape edges_, vertices_;
  TrimmedBoundary boundary_;
  std::vector<bool> edge_done_;
  std::map<std::pair<int, int>, int> edge_nodes_;  // (edge, polygon position) -> mesh vertex
  std::map<int, int> vertex_nodes_;                // topological vertex -> mesh vertex

  static TensorSpline<1> reverse_curve(const TensorSpline<1>& c) {
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

  int mesh_vertex_of(const TopoDS_Vertex& v) {
    const int id = vertices_.FindIndex(v);
    auto [it, fresh] = vertex_nodes_.try_emplace(id, static_cast<int>(boundary_.mesh.vertices.size()));
    if (fresh) {
      const gp_Pnt p = BRep_Tool::Pnt(v);
      boundary_.mesh.vertices.push_back({p.X(), p.Y(), p.Z()});
    }
    return it->second;
  }

  // The face's triangulation, its nodes on edges identified with the edges' shared discretisation so that
  // neighbouring faces use the same mesh vertices.
  std::string add_mesh(const TopoDS_Face& face, int face_index) {
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
        uv[k] = {p.X(), p.Y()};
      }
      boundary_.mesh.triangles.push_back(ids);
      boundary_.triangle_face.push_back(face_index);
      boundary_.triangle_uv.push_back(uv);
    }
    return {};
  }
};

// The kernel's fixed Gauss rule: a cross-check for reports, a fifth of the adaptive rule's time.
double kernel_volume(const TopoDS_Shape& s) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(s, props, true);
  return props.Mass();
}

}  // namespace

StepImport import_step(const std::string& path, const ImportOptions& opts) {
  silence_kernel();
  require(opts.chordal_tolerance >= 0 && opts.angular_tolerance > 0,
          "STEP import: the chordal tolerance must be >= 0 and the angular tolerance > 0");
  std::error_code ec;
  require(std::filesystem::is_regular_file(path, ec), path + ": no such file");
  StepImport out;
  BrepReport& r = out.report;
  r.file = path;
  STEPControl_Reader reader;
  try {
    require(reader.ReadFile(path.c_str()) == IFSelect_RetDone, path + ": not a readable STEP file");
    require(reader.TransferRoots() > 0, path + ": the STEP file holds no shape the kernel can transfer");
    const TopoDS_Shape shape = reader.OneShape();
    require(!shape.IsNull(), path + ": the STEP file holds no shape");
    const Namer name(reader);
    r.solids = count_unique(shape, TopAbs_SOLID);
    r.shells = count_unique(shape, TopAbs_SHELL);
    r.faces = count_unique(shape, TopAbs_FACE);
    r.edges = count_unique(shape, TopAbs_EDGE);
    r.vertices = count_unique(shape, TopAbs_VERTEX);
    {
      TopTools_IndexedMapOfShape faces;
      TopExp::MapShapes(shape, TopAbs_FACE, faces);
      for (int i = 1; i <= faces.Extent(); ++i) ++r.faces_by_kind[surface_kind(TopoDS::Face(faces(i)))];
    }
    r.not_solid = outside_solids(shape);
    Bnd_Box bb;
    BRepBndLib::Add(shape, bb);
    const double diag = bb.IsVoid() ? 1.0 : std::sqrt(bb.SquareExtent());
    const double chordal = opts.chordal_tolerance > 0 ? opts.chordal_tolerance : 1e-3 * diag;

    int index = 0;
    for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next(), ++index) {
      TopoDS_Shape solid = x.Current();
      const std::string sname = name(solid, "solid " + std::to_string(index));
      ImportedSolid imported{sname, nullptr, 0};
      if (!BRepCheck_Analyzer(solid).IsValid()) {
        ShapeFix_Shape fix(solid);
        fix.Perform();
        solid = fix.Shape();
        require(BRepCheck_Analyzer(solid).IsValid(), path + ": " + sname + " is not a valid solid and could not be repaired");
        r.repairs.push_back(sname + ": invalid as read (e.g. missing parameter-space curves, tolerances); repaired by shape healing");
      }
      if (const int fe = free_edges(solid); fe > 0)
        throw Error(path + ": " + sname + " is not closed (" + plural(fe, "free edge") + ")");
      imported.kernel_volume = kernel_volume(solid);
      require(imported.kernel_volume > 0, path + ": " + sname + " is inside out or encloses nothing (volume " +
                                              std::to_string(imported.kernel_volume) + ")");
      BRepBuilderAPI_NurbsConvert conv(solid, true);
      const TopoDS_Shape nurbs = conv.Shape();
      BRepMesh_IncrementalMesh mesh(nurbs, chordal, false, opts.angular_tolerance, true);
      SolidMapper mapper(nurbs, chordal);
      // Faces as they sit in the converted solid (with their orientation there), named after the faces read.
      TopTools_IndexedMapOfShape converted;
      std::vector<TopoDS_Face> originals;
      for (TopExp_Explorer f(solid, TopAbs_FACE); f.More(); f.Next()) {
        const TopoDS_Shape mod = conv.ModifiedShape(f.Current());
        if (converted.Add(mod) > static_cast<int>(originals.size())) originals.push_back(TopoDS::Face(f.Current()));
      }
      int fi = 0;
      bool complete = true;
      for (TopExp_Explorer f(nurbs, TopAbs_FACE); f.More(); f.Next(), ++fi) {
        const TopoDS_Face& face = TopoDS::Face(f.Current());
        const int oi = converted.FindIndex(face);
        const TopoDS_Face orig = oi > 0 ? originals[static_cast<std::size_t>(oi - 1)] : face;
        const std::string fname = name(orig, sname + " face " + std::to_string(fi));
        if (std::string why = mapper.add_face(face, surface_kind(orig), fname); !why.empty()) {
          r.unmapped.push_back({fname, why});
          complete = false;
        }
      }
      if (complete) {
        try {
          imported.solid = std::make_shared<const TrimmedSolid>(mapper.take());
        } catch (const Error& e) {
          throw Error(path + ": " + sname + ": " + e.what());
        }
      }
      out.solids.push_back(std::move(imported));
    }
  } catch (const Standard_Failure& e) {
    throw Error(path + ": the geometry kernel failed: " + std::string(e.GetMessageString()));
  }
  return out;
}

}  // namespace trivar::cad
