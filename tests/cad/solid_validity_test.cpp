#include "trivar/cad/solid_validity.hpp"

#include <gtest/gtest.h>

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Face.hxx>
#include <TopExp.hxx>
#include <TopoDS_Iterator.hxx>
#include <gp_Circ.hxx>

#include <numbers>

#include "cad/occt_solids.hpp"
#include "trivar/cad/step_import.hpp"
#include "trivar/cad/step_transfer.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

// One loop added to a plate whose faces carry more loops than cad::crowded_face_loops.
enum class Defect { none, overlapping, outside, nested, reversed, open };

const char* defect_name(Defect d) {
  switch (d) {
    case Defect::none: return "none";
    case Defect::overlapping: return "overlapping";
    case Defect::outside: return "outside";
    case Defect::nested: return "nested";
    case Defect::reversed: return "reversed";
    case Defect::open: return "open";
  }
  return "";
}

constexpr double plate_side = 70, plate_height = 2, hole_radius = 2;
constexpr int grid_holes = 36;  // 6 x 6 holes on a 10 mm grid

// The face with its loops as stored, the loop holding `flip` reversed and `extra` added.
TopoDS_Face relooped(const TopoDS_Face& f, const TopoDS_Edge& flip, const TopoDS_Wire& extra) {
  const TopoDS_Face base = TopoDS::Face(f.Oriented(TopAbs_FORWARD));
  TopoDS_Face g = TopoDS::Face(base.EmptyCopied());
  BRep_Builder b;
  for (TopoDS_Iterator it(base, false, false); it.More(); it.Next()) {
    TopoDS_Shape w = it.Value();
    bool has_flip = false;
    for (TopExp_Explorer e(w, TopAbs_EDGE); e.More() && !flip.IsNull(); e.Next()) has_flip = has_flip || e.Current().IsSame(flip);
    b.Add(g, has_flip ? w.Reversed() : w);
  }
  if (!extra.IsNull()) b.Add(g, extra);
  g.Orientation(f.Orientation());
  return g;
}

// A 70 x 70 x 2 plate with 6 x 6 holes of radius 2 on a 10 mm grid and one more loop on its top and bottom
// faces, made face by face so that the loop can be wrong: crossing a hole, outside the plate, inside a hole,
// oriented as an outer loop, or open (on the top face only; its hole has no wall).
TopoDS_Shape holed_plate(Defect d) {
  std::vector<test::PlateHole> holes;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) holes.push_back({10.0 + 10 * i, 10.0 + 10 * j, hole_radius});
  switch (d) {
    // Crossing the hole at (60, 60); the check's groups of loops (31 a group by least u, u along x or y) put
    // the two apart.
    case Defect::overlapping: holes.push_back({58, 58, hole_radius}); break;
    case Defect::outside: holes.push_back({80, 35, hole_radius}); break;
    case Defect::nested: holes.push_back({10, 10, 1}); break;
    case Defect::none:
    case Defect::reversed: holes.push_back({65, 65, hole_radius}); break;
    case Defect::open: break;
  }
  BRep_Builder bb;
  TopoDS_Shell shell;
  bb.MakeShell(shell);
  const auto circles = test::add_hole_walls(shell, holes, plate_height);  // bottom, top
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(plate_side, plate_side, plate_height).Shape();
  for (TopExp_Explorer f(box, TopAbs_FACE); f.More(); f.Next()) {
    TopoDS_Face face = TopoDS::Face(f.Current());
    const gp_Pln plane = BRepAdaptor_Surface(face).Plane();
    if (std::abs(plane.Axis().Direction().Z()) > 0.5) {
      const bool top = plane.Location().Z() > 1;
      BRepBuilderAPI_MakeFace mk(face);
      for (const auto& [bottom, upper] : circles) mk.Add(BRepBuilderAPI_MakeWire(top ? upper : bottom).Wire());
      ShapeFix_Face fix(mk.Face());  // orients the hole loops only
      fix.FixOrientation();
      face = fix.Face();
      if (d == Defect::reversed) face = relooped(face, top ? circles.back().second : circles.back().first, {});
      if (d == Defect::open && top) {
        const gp_Circ c(gp_Ax2(gp_Pnt(65, 65, plate_height), gp_Dir(0, 0, 1)), hole_radius);
        face = relooped(face, {}, BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(c, 0, 1.5 * std::numbers::pi).Edge()).Wire());
      }
    }
    bb.Add(shell, face);
  }
  TopoDS_Solid solid;
  bb.MakeSolid(solid);
  bb.Add(solid, shell);
  return solid;
}

// The shape as the import reads it, before its validity check.
TopoDS_Shape read_step_file(const std::string& path) {
  STEPControl_Reader r;
  EXPECT_EQ(r.ReadFile(path.c_str()), IFSelect_RetDone);
  cad::transfer_roots(r);
  return r.OneShape();
}

std::vector<TopoDS_Face> crowded_faces(const TopoDS_Shape& s) {
  std::vector<TopoDS_Face> out;
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(s, TopAbs_FACE, faces);
  for (int i = 1; i <= faces.Extent(); ++i) {
    int loops = 0;
    for (TopoDS_Iterator it(faces(i)); it.More(); it.Next()) ++loops;
    if (loops > cad::crowded_face_loops) out.push_back(TopoDS::Face(faces(i)));
  }
  return out;
}

}  // namespace

// The verdict on each solid with a wrong loop, and on its crowded faces alone, is the kernel's own analyzer's
// on the same shape: as built, and as the import reads it back from STEP (where the transfer's healing may
// already have mended the loop). The import refuses or repairs a solid the kernel finds invalid.
TEST(SolidValidity, CrowdedFacesGetTheKernelsVerdict) {
  const auto dir = test::temp_dir("crowded_loops");
  const auto same_verdicts = [](const TopoDS_Shape& s) {
    const bool kernel = BRepCheck_Analyzer(s).IsValid();
    EXPECT_EQ(cad::is_valid_solid(s), kernel);
    for (const TopoDS_Face& f : crowded_faces(s)) EXPECT_EQ(cad::is_valid_solid(f), BRepCheck_Analyzer(f).IsValid());
    return kernel;
  };
  for (const Defect d : {Defect::none, Defect::overlapping, Defect::outside, Defect::nested, Defect::reversed, Defect::open}) {
    SCOPED_TRACE(defect_name(d));
    const TopoDS_Shape built = holed_plate(d);
    ASSERT_EQ(crowded_faces(built).size(), 2u);
    EXPECT_EQ(same_verdicts(built), d == Defect::none);
    const std::string path = test::write_step(built, dir, std::string("plate_") + defect_name(d));
    const TopoDS_Shape read = read_step_file(path);
    ASSERT_FALSE(crowded_faces(read).empty());
    bool all_valid = true;
    for (TopExp_Explorer x(read, TopAbs_SOLID); x.More(); x.Next()) all_valid = same_verdicts(x.Current()) && all_valid;
    try {
      const cad::StepImport im = cad::import_step(path);
      EXPECT_EQ(im.report.repairs.empty(), all_valid);
    } catch (const Error& e) {
      EXPECT_FALSE(all_valid) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}

// A valid plate with crowded faces imports without repair, its volume that of OpenCASCADE's mass properties and
// of the closed form.
TEST(SolidValidity, ValidCrowdedPlateKeepsItsVolume) {
  const auto dir = test::temp_dir("crowded_valid");
  const std::string path = test::write_step(holed_plate(Defect::none), dir, "plate");
  const cad::StepImport im = cad::import_step(path);
  ASSERT_EQ(im.solids.size(), 1u);
  ASSERT_TRUE(im.solids[0].solid);
  EXPECT_TRUE(im.report.repairs.empty());
  const double ref = test::occt_volume(read_step_file(path));
  EXPECT_NEAR(im.solids[0].solid->volume(), ref, 1e-6 * ref);
  const double closed = plate_height * (plate_side * plate_side - (grid_holes + 1) * std::numbers::pi * hole_radius * hole_radius);
  EXPECT_NEAR(im.solids[0].solid->volume(), closed, 1e-9 * closed);
  std::filesystem::remove_all(dir);
}
