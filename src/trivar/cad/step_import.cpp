#include "trivar/cad/step_import.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <Geom_Plane.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Shape.hxx>
#include <Standard_Failure.hxx>
#include <StepData_StepModel.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TopoDS.hxx>
#include <TransferBRep.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <future>
#include <map>
#include <optional>

#include "trivar/cad/brep_mapping.hpp"
#include "trivar/cad/face_nurbs.hpp"
#include "trivar/cad/solid_validity.hpp"
#include "trivar/cad/step_transfer.hpp"
#include "trivar/core/error.hpp"

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

// STEP instance names of transferred shapes. The kernel's own lookup (EntityFromShapeResult) scans every
// transfer result per call, quadratic in the faces of a part; the same answer comes from one scan: the first
// result equal to the shape (orientation included), else the last one that is the same shape.
class Namer {
public:
  explicit Namer(const STEPControl_Reader& reader) {
    const Handle(XSControl_WorkSession) ws = reader.WS();
    if (ws.IsNull() || ws->TransferReader().IsNull()) return;
    const Handle(Transfer_TransientProcess) tp = ws->TransferReader()->TransientProcess();
    model_ = Handle(StepData_StepModel)::DownCast(ws->Model());
    if (tp.IsNull() || model_.IsNull()) return;
    for (int i = 1; i <= tp->NbMapped(); ++i) {
      const Handle(Standard_Transient) e = tp->Mapped(i);
      const TopoDS_Shape sh = TransferBRep::ShapeResult(tp, e);
      if (sh.IsNull()) continue;
      Found* f = found_.ChangeSeek(sh);
      if (f == nullptr) f = found_.Bound(sh, Found{});
      Handle(Standard_Transient)& exact = f->by_orientation[static_cast<int>(sh.Orientation())];
      if (exact.IsNull()) exact = e;
      f->same = e;
    }
  }
  // "#812 ADVANCED_FACE", or `fallback` when the shape has no STEP instance.
  std::string operator()(const TopoDS_Shape& s, const std::string& fallback) const {
    const Found* f = found_.Seek(s);
    if (f == nullptr) return fallback;
    const Handle(Standard_Transient)& exact = f->by_orientation[static_cast<int>(s.Orientation())];
    const Handle(Standard_Transient)& e = exact.IsNull() ? f->same : exact;
    std::string n = "#";
    n += std::to_string(model_->IdentLabel(e));
    n += ' ';
    n += step_keyword(e->DynamicType()->Name());
    return n;
  }

private:
  struct Found {
    Handle(Standard_Transient) by_orientation[4];
    Handle(Standard_Transient) same;
  };
  Handle(StepData_StepModel) model_;
  NCollection_DataMap<TopoDS_Shape, Found, TopTools_ShapeMapHasher> found_;
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

// An edge on a plane may come without its parameter-space curve (STEP writers often omit them: the kernel
// projects the 3D curve whenever one is asked for). A face with hundreds of hole loops asks for each of them
// once per pair of loops in the validity check and again in the NURBS conversion; projected once and stored,
// they cost a linear pass. The projection onto a plane is exact, so the solid is unchanged.
void store_plane_pcurves(const TopoDS_Shape& solid) {
  for (TopExp_Explorer f(solid, TopAbs_FACE); f.More(); f.Next()) {
    const TopoDS_Face& face = TopoDS::Face(f.Current());
    TopLoc_Location loc;
    if (Handle(Geom_Plane)::DownCast(BRep_Tool::Surface(face, loc)).IsNull()) continue;
    for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) BRepLib::BuildPCurveForEdgeOnPlane(TopoDS::Edge(e.Current()), face);
  }
}

// The kernel's adaptive rule to 1e-9 relative: a cross-check on request. Its fixed Gauss rule, five times
// cheaper, is off by 4.4e-4 on a SolidWorks part of cylinders and planes (tests/data/step/cad_systems).
double kernel_volume(const TopoDS_Shape& s) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(s, props, 1e-9, true);
  return props.Mass();
}

// The FILE_NAME header's originating system without surrounding blanks ("" when the file leaves it empty).
std::string originating_system(const STEPControl_Reader& reader) {
  const APIHeaderSection_MakeHeader header(reader.StepModel());
  if (!header.HasFn()) return {};
  const Handle(TCollection_HAsciiString) name = header.OriginatingSystem();
  if (name.IsNull()) return {};
  std::string s = name->ToCString();
  const std::size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// The solid's faces as exact NURBS patches with their loops and the kernel's tessellation, or the faces that
// could not be mapped.
struct MappedSolid {
  SolidMapper mapper;
  std::vector<UnmappedFace> unmapped;
};

MappedSolid map_solid(const TopoDS_Shape& solid, const Namer& name, const std::string& sname, double chordal, double angular) {
  // Faces whose surfaces and trimming curves trivar maps exactly itself (face_nurbs) keep the solid's geometry:
  // a copy of its topology is meshed, so the validity check reading the solid beside it is undisturbed. Else
  // the kernel converts the solid (re-projecting the trimming curves of periodic faces: most of the time of a
  // part with many holes when it is not needed).
  bool direct = true;
  for (TopExp_Explorer f(solid, TopAbs_FACE); f.More() && direct; f.Next()) direct = maps_directly(TopoDS::Face(f.Current()));
  std::optional<BRepBuilderAPI_NurbsConvert> conv;
  TopoDS_Shape target;
  if (direct)
    target = BRepBuilderAPI_Copy(solid, false, false).Shape();
  else {
    conv.emplace(solid, true);
    target = conv->Shape();
  }
  // Delaunay by Delabella: a planar face carrying hundreds of hole loops took most of the import with the
  // default (Watson) algorithm.
  IMeshTools_Parameters mp;
  mp.Deflection = chordal;
  mp.Angle = angular;
  mp.InParallel = true;
  mp.MeshAlgo = IMeshTools_MeshAlgoType_Delabella;
  BRepMesh_IncrementalMesh mesh(target, mp);
  MappedSolid out{SolidMapper(target, chordal), {}};
  // Faces as they sit in the mapped solid (with their orientation there), named after the faces read.
  TopTools_IndexedMapOfShape mapped;
  std::vector<TopoDS_Face> originals;
  for (TopExp_Explorer f(solid, TopAbs_FACE), g(target, TopAbs_FACE); f.More() && g.More(); f.Next(), g.Next()) {
    const TopoDS_Shape mod = conv ? conv->ModifiedShape(f.Current()) : g.Current();
    if (mapped.Add(mod) > static_cast<int>(originals.size())) originals.push_back(TopoDS::Face(f.Current()));
  }
  int fi = 0;
  for (TopExp_Explorer f(target, TopAbs_FACE); f.More(); f.Next(), ++fi) {
    const TopoDS_Face& face = TopoDS::Face(f.Current());
    const int oi = mapped.FindIndex(face);
    const TopoDS_Face orig = oi > 0 ? originals[static_cast<std::size_t>(oi - 1)] : face;
    const std::string fname = name(orig, sname + " face " + std::to_string(fi));
    if (std::string why = out.mapper.add_face(face, surface_kind(orig), fname); !why.empty()) out.unmapped.push_back({fname, why});
  }
  return out;
}

}  // namespace

std::string open_boundary_warning(const std::string& solid, const ClosureDefect& d) {
  const auto g = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return std::string(buf);
  };
  return solid + ": the boundary does not close (integral of the normal " + g(d.norm) + " = " + g(d.relative) +
         " of the area, above the " + g(d.allowance) + " its tolerances allow): the volume depends on the reference point of the divergence theorem by up to " +
         g(d.volume_uncertainty);
}

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
    r.originating_system = originating_system(reader);
    require(transfer_roots(reader) > 0, path + ": the STEP file holds no shape the kernel can transfer");
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
      ImportedSolid imported{sname, nullptr, std::nullopt, std::nullopt};
      store_plane_pcurves(solid);
      // The validity check (and the kernel's volume when asked for) runs beside the conversion, which reads the
      // same solid and builds a copy; an invalid solid discards the conversion and is converted again after
      // repair by the kernel's full shape healing (which includes the fixes of intersecting edges and loops the
      // transfer leaves out: step_transfer.hpp).
      const bool want_volume = opts.kernel_volume;
      auto checked = std::async(std::launch::async, [&solid, want_volume] {
        const bool valid = is_valid_solid(solid);
        return std::make_pair(valid, valid && want_volume ? std::optional<double>(kernel_volume(solid)) : std::nullopt);
      });
      std::optional<MappedSolid> mapped;
      std::exception_ptr failure;
      try {
        mapped = map_solid(solid, name, sname, chordal, opts.angular_tolerance);
      } catch (...) {
        failure = std::current_exception();
      }
      auto [valid, volume] = checked.get();
      if (!valid) {
        ShapeFix_Shape fix(solid);
        fix.Perform();
        solid = fix.Shape();
        require(is_valid_solid(solid), path + ": " + sname + " is not a valid solid and could not be repaired");
        r.repairs.push_back(sname + ": invalid as read (e.g. missing parameter-space curves, tolerances, intersecting loops); repaired by shape healing");
        if (want_volume) volume = kernel_volume(solid);
        failure = nullptr;
        mapped.reset();
      }
      if (const int fe = free_edges(solid); fe > 0)
        throw Error(path + ": " + sname + " is not closed (" + plural(fe, "free edge") + ")");
      // Without the kernel's volume an inside-out solid is refused by TrimmedSolid (its mesh encloses a
      // negative volume) once its faces are mapped.
      imported.kernel_volume = volume;
      if (volume)
        require(*volume > 0, path + ": " + sname + " is inside out or encloses nothing (volume " + std::to_string(*volume) + ")");
      if (failure) std::rethrow_exception(failure);
      if (!mapped) mapped = map_solid(solid, name, sname, chordal, opts.angular_tolerance);
      for (UnmappedFace& u : mapped->unmapped) r.unmapped.push_back(std::move(u));
      if (mapped->unmapped.empty()) {
        try {
          imported.solid = std::make_shared<const TrimmedSolid>(mapped->mapper.take());
        } catch (const Error& e) {
          throw Error(path + ": " + sname + ": " + e.what());
        }
        imported.closure = closure_defect(imported.solid->boundary());
        if (!imported.closure->closed()) r.open_boundaries.push_back(open_boundary_warning(sname, *imported.closure));
      }
      out.solids.push_back(std::move(imported));
    }
  } catch (const Standard_Failure& e) {
    throw Error(path + ": the geometry kernel failed: " + std::string(e.GetMessageString()));
  }
  return out;
}

}  // namespace trivar::cad
