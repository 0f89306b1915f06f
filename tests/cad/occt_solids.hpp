#pragma once
// Test solids built with OpenCASCADE and written to STEP by it: the independent source of the cad tests.
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <Bnd_Box.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace trivar::test {

inline const double kPi = 3.14159265358979323846;

// A through hole of a plate along z: centre and radius.
struct PlateHole {
  double x, y, r;
};

// The walls of through holes of a plate 0 <= z <= height (the lateral faces of cylinders, facing the hole's
// axis), added to `shell`. Returns each hole's bottom and top circle, for the loops of the plate's faces.
inline std::vector<std::pair<TopoDS_Edge, TopoDS_Edge>> add_hole_walls(TopoDS_Shell& shell, const std::vector<PlateHole>& holes,
                                                                       double height) {
  BRep_Builder bb;
  std::vector<std::pair<TopoDS_Edge, TopoDS_Edge>> circles;
  for (const PlateHole& h : holes) {
    const TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(h.x, h.y, 0), gp_Dir(0, 0, 1)), h.r, height).Shape();
    for (TopExp_Explorer f(cyl, TopAbs_FACE); f.More(); f.Next()) {
      if (BRepAdaptor_Surface(TopoDS::Face(f.Current())).GetType() != GeomAbs_Cylinder) continue;
      bb.Add(shell, f.Current().Reversed());
      std::pair<TopoDS_Edge, TopoDS_Edge> c;
      for (TopExp_Explorer e(f.Current(), TopAbs_EDGE); e.More(); e.Next()) {
        const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
        if (BRep_Tool::IsClosed(edge, TopoDS::Face(f.Current()))) continue;  // the seam
        (BRep_Tool::Pnt(TopExp::FirstVertex(edge)).Z() > height / 2 ? c.second : c.first) = edge;
      }
      circles.push_back(c);
    }
  }
  return circles;
}

// 40 x 30 x 20 block with two through holes of radius 4 along z.
inline TopoDS_Shape box_with_holes() {
  TopoDS_Shape s = BRepPrimAPI_MakeBox(40, 30, 20).Shape();
  for (double x : {12.0, 28.0})
    s = BRepAlgoAPI_Cut(s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, 15, -1), gp_Dir(0, 0, 1)), 4, 22).Shape()).Shape();
  return s;
}

// 30 x 20 x 10 block with every edge rounded (radius 2): planes, cylinders and spheres meet tangentially.
inline TopoDS_Shape filleted_block() {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(30, 20, 10).Shape();
  BRepFilletAPI_MakeFillet f(box);
  for (TopExp_Explorer e(box, TopAbs_EDGE); e.More(); e.Next()) f.Add(2.0, TopoDS::Edge(e.Current()));
  return f.Shape();
}

// A stepped profile with a slanted side revolved once about z: planes, cylinders and a cone.
inline TopoDS_Shape revolved_part() {
  BRepBuilderAPI_MakePolygon p;
  for (auto [r, z] : {std::pair{3.0, 0.0}, {10.0, 0.0}, {10.0, 4.0}, {6.0, 8.0}, {6.0, 12.0}, {3.0, 12.0}})
    p.Add(gp_Pnt(r, 0, z));
  p.Close();
  const TopoDS_Face profile = BRepBuilderAPI_MakeFace(p.Wire());
  return BRepPrimAPI_MakeRevol(profile, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))).Shape();
}

// A 20 x 20 x 10 block fused with a cylinder of radius 6 standing on its top, off-centre.
inline TopoDS_Shape fused_box_cylinder() {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(20, 20, 10).Shape();
  const TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(12, 9, 5), gp_Dir(0, 0, 1)), 6, 15).Shape();
  return BRepAlgoAPI_Fuse(box, cyl).Shape();
}

inline TopoDS_Shape ball() { return BRepPrimAPI_MakeSphere(gp_Pnt(1, 2, 3), 5).Shape(); }

// The faces of the shape lying wholly at or above the height z (to 1e-6): a top to remove when hollowing.
inline TopTools_ListOfShape faces_above(const TopoDS_Shape& s, double z) {
  TopTools_ListOfShape out;
  for (TopExp_Explorer f(s, TopAbs_FACE); f.More(); f.Next()) {
    Bnd_Box b;
    BRepBndLib::Add(f.Current(), b);
    double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
    b.Get(x0, y0, z0, x1, y1, z1);
    if (z0 > z - 1e-6) out.Append(f.Current());
  }
  return out;
}

inline double occt_volume(const TopoDS_Shape& s) {
  GProp_GProps g;
  BRepGProp::VolumeProperties(s, g, 1e-10, true);
  return g.Mass();
}

// Writes the shape as AP214 into `dir` and returns the path.
inline std::string write_step(const TopoDS_Shape& s, const std::filesystem::path& dir, const std::string& name) {
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));  // quiet writer
  std::filesystem::create_directories(dir);
  const std::string path = (dir / (name + ".stp")).string();
  STEPControl_Writer w;
  w.Transfer(s, STEPControl_AsIs);
  if (w.Write(path.c_str()) != IFSelect_RetDone) throw std::runtime_error("cannot write " + path);
  return path;
}

inline std::filesystem::path temp_dir(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("trivar_cad_" + name + "_" + std::to_string(::getpid()));
}

}  // namespace trivar::test
