// The closure defect of imported solids (model/closure_defect.hpp): the integral of the outward normal over the
// faces, zero for a closed boundary and minus the area vector of what is missing otherwise.
#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <TopoDS_Shell.hxx>

#include <cmath>
#include <cstdio>

#include "cad/occt_solids.hpp"
#include "trivar/cad/step_import.hpp"
#include "trivar/model/closure_defect.hpp"

using namespace trivar;

namespace {

// The solid of the kernel's shape as the import maps it from the kernel's own STEP file.
cad::StepImport import_written(const TopoDS_Shape& s, const std::string& name) {
  const auto dir = test::temp_dir("closure");
  const cad::StepImport im = cad::import_step(test::write_step(s, dir, name));
  std::filesystem::remove_all(dir);
  return im;
}

// The point at the middle of a face's parameter domain (for the box's planes: the face's centre).
std::array<double, 3> face_middle(const TrimmedFace& f) {
  const Box<2> d = f.surface.domain();
  std::array<double, 3> x;
  f.surface.eval({0.5 * (d.lo[0] + d.hi[0]), 0.5 * (d.lo[1] + d.hi[1])}, x.data());
  return x;
}

}  // namespace

// Closed solids from the kernel: the normal integrates to zero up to rounding, nothing is reported.
TEST(ClosureDefect, ClosedKernelSolidsCloseToRounding) {
  const std::pair<const char*, TopoDS_Shape> solids[] = {
      {"box", BRepPrimAPI_MakeBox(gp_Pnt(1, 2, 3), 40, 30, 20).Shape()},
      {"cylinder", BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-3, 1, 2), gp_Dir(1, 2, 2)), 5, 12).Shape()},
      {"ball", test::ball()}};
  for (const auto& [name, shape] : solids) {
    SCOPED_TRACE(name);
    const cad::StepImport im = import_written(shape, name);
    ASSERT_EQ(im.solids.size(), 1u);
    ASSERT_TRUE(im.solids[0].closure);
    const ClosureDefect& d = *im.solids[0].closure;
    std::printf("%s: area vector %.3g %.3g %.3g, relative %.3g, allowance %.3g\n", name, d.area_vector[0], d.area_vector[1],
                d.area_vector[2], d.relative, d.allowance);
    EXPECT_LE(d.relative, 1e-12);
    EXPECT_TRUE(d.closed());
    EXPECT_TRUE(im.report.open_boundaries.empty());
    // The mesh's area: within the chordal tolerance's share of the faces' (exact for the box).
    const double area = std::string(name) == "box" ? 2 * (40 * 30 + 40 * 20 + 30 * 20)
                        : std::string(name) == "cylinder" ? 2 * test::kPi * 25 + 2 * test::kPi * 5 * 12
                                                          : 4 * test::kPi * 25;
    EXPECT_NEAR(d.area, area, 1e-2 * area);
  }
}

// The box without one of its faces: the defect is minus that face's area times its outward normal, exactly
// (planar faces, exact rules), and the solid is reported open with the volume's dependence on the reference
// point.
TEST(ClosureDefect, BoxWithoutAFaceMissesItsAreaVector) {
  const double lo[3] = {1, 2, 3}, size[3] = {40, 30, 20};
  const cad::StepImport im = import_written(BRepPrimAPI_MakeBox(gp_Pnt(lo[0], lo[1], lo[2]), size[0], size[1], size[2]).Shape(), "box");
  const TrimmedBoundary& closed = im.solids.at(0).solid->boundary();
  ASSERT_EQ(closed.faces.size(), 6u);
  const double diagonal = std::hypot(size[0], size[1], size[2]);
  for (std::size_t i = 0; i < 6; ++i) {
    TrimmedBoundary open = closed;
    open.faces.erase(open.faces.begin() + static_cast<std::ptrdiff_t>(i));
    // The missing face's outward normal: the axis it is perpendicular to, towards the side of the box it is on.
    const std::array<double, 3> m = face_middle(closed.faces[i]);
    std::array<double, 3> missing{};
    for (int k = 0; k < 3; ++k) {
      const double side = std::abs(m[k] - lo[k]) < 1e-9 ? -1 : std::abs(m[k] - lo[k] - size[k]) < 1e-9 ? 1 : 0;
      missing[k] = side * size[(k + 1) % 3] * size[(k + 2) % 3];
    }
    const double area = std::hypot(missing[0], missing[1], missing[2]);
    ASSERT_GT(area, 0);
    const ClosureDefect d = closure_defect(open);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(d.area_vector[k], -missing[k], 1e-12 * area) << "face " << i << " component " << k;
    EXPECT_NEAR(d.norm, area, 1e-12 * area);
    EXPECT_NEAR(d.volume_uncertainty, area * diagonal, 1e-12 * area * diagonal);  // the mesh's box is exact here
    EXPECT_FALSE(d.closed());
    const std::string w = cad::open_boundary_warning("solid 0", d);
    EXPECT_EQ(w.rfind("solid 0: the boundary does not close", 0), 0u) << w;
    EXPECT_NE(w.find("the volume depends on the reference point"), std::string::npos) << w;
    EXPECT_EQ(w.find('\n'), std::string::npos);
  }
}

// A cylinder without its top disc: minus the disc's area vector, pi r^2 along the axis (rational faces: the
// quadrature converges to rounding); without its lateral face nothing, the lateral face's normals cancel.
TEST(ClosureDefect, CylinderWithoutItsTopMissesTheDisc) {
  const double r = 5, h = 12;
  const cad::StepImport im = import_written(BRepPrimAPI_MakeCylinder(r, h).Shape(), "cylinder");
  const TrimmedBoundary& closed = im.solids.at(0).solid->boundary();
  ASSERT_EQ(closed.faces.size(), 3u);
  const double disc = test::kPi * r * r;
  for (std::size_t i = 0; i < 3; ++i) {
    TrimmedBoundary open = closed;
    open.faces.erase(open.faces.begin() + static_cast<std::ptrdiff_t>(i));
    const std::string& kind = closed.faces[i].kind;
    const double z = face_middle(closed.faces[i])[2];
    const double expected_z = kind == "cylinder" ? 0 : z > h / 2 ? -disc : disc;
    const ClosureDefect d = closure_defect(open);
    SCOPED_TRACE(kind + " at z " + std::to_string(z));
    EXPECT_NEAR(d.area_vector[0], 0, 1e-12 * disc);
    EXPECT_NEAR(d.area_vector[1], 0, 1e-12 * disc);
    EXPECT_NEAR(d.area_vector[2], expected_z, 1e-12 * disc);
    EXPECT_EQ(d.closed(), kind == "cylinder");
  }
}

// The defect predicts how OpenCASCADE's own volume of the open box moves with its reference point c: by
// (c' - c) . A / 3 (its mass properties integrate (x - c) . n / 3 over the faces).
TEST(ClosureDefect, PredictsTheKernelsVolumeShift) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(1, 2, 3), 40, 30, 20).Shape();
  const cad::StepImport im = import_written(box, "box");
  TrimmedBoundary open = im.solids.at(0).solid->boundary();
  // Drop the top face (z = 23) from both.
  BRep_Builder bb;
  TopoDS_Shell shell;
  bb.MakeShell(shell);
  const TopTools_ListOfShape top = test::faces_above(box, 23);
  ASSERT_EQ(top.Extent(), 1);
  for (TopExp_Explorer f(box, TopAbs_FACE); f.More(); f.Next())
    if (!f.Current().IsSame(top.First())) bb.Add(shell, f.Current());
  std::erase_if(open.faces, [](const TrimmedFace& f) { return face_middle(f)[2] > 23 - 1e-9; });
  ASSERT_EQ(open.faces.size(), 5u);
  const ClosureDefect d = closure_defect(open);
  const auto kernel_volume = [&](const gp_Pnt& c) {
    GProp_GProps g(c);
    BRepGProp::VolumeProperties(shell, g, 1e-12, false);
    return g.Mass();
  };
  const gp_Pnt c(0, 0, 0), c2(7, -5, 11);
  const double predicted = ((c2.X() - c.X()) * d.area_vector[0] + (c2.Y() - c.Y()) * d.area_vector[1] +
                            (c2.Z() - c.Z()) * d.area_vector[2]) / 3;
  EXPECT_NEAR(kernel_volume(c) - kernel_volume(c2), predicted, 1e-9 * std::abs(predicted));
  EXPECT_NEAR(predicted, -11.0 * 1200 / 3, 1e-9 * 4400);
}
