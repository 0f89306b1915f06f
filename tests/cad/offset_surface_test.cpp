// Offset surfaces (Geom_OffsetSurface) in trivar's NURBS form, against the kernel's exact evaluation of the
// offset: the offset of a plane, cylinder, cone, sphere or torus is exact (to rounding, either handedness of the
// frame), any other offset is fitted within the tolerance asked for at random points. Solids with offset faces
// made by OpenCASCADE and written to STEP by it are read back with volumes from closed forms (the offset of a
// cylinder wall, a sphere, a torus, a cone frustum, and the offset of a B-spline cylinder, which takes the
// fit) and from the kernel's mass properties on the exact offsets.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepOffsetAPI_MakeOffsetShape.hxx>
#include <BRepOffsetAPI_MakeThickSolid.hxx>
#include <TopTools_ListOfShape.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <functional>
#include <numbers>
#include <random>

#include "cad/occt_solids.hpp"
#include "trivar/cad/face_nurbs.hpp"
#include "trivar/cad/offset_fit.hpp"
#include "trivar/cad/step_import.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/model/trimmed_check.hpp"

using namespace trivar;

namespace {

constexpr double kOffsetTurn = 2 * std::numbers::pi;

gp_Ax3 offset_frame(bool left_handed) {
  gp_Ax3 a(gp_Pnt(-1.5, 2.25, 4.0), gp_Dir(-0.2, 0.6, 0.7), gp_Dir(1, 0, 0));
  if (left_handed) a.YReverse();
  return a;
}

struct OffsetCase {
  std::string name;
  Handle(Geom_Surface) basis;
  Box<2> uv;
};

std::vector<OffsetCase> analytic_bases() {
  std::vector<OffsetCase> v;
  for (bool left : {false, true}) {
    const gp_Ax3 a = offset_frame(left);
    const std::string h = left ? " (left-handed)" : "";
    v.push_back({"plane" + h, new Geom_Plane(a), {{-4, 1}, {3, 6}}});
    v.push_back({"cylinder" + h, new Geom_CylindricalSurface(a, 2.5), {{0, -1}, {kOffsetTurn, 3}}});
    v.push_back({"cone" + h, new Geom_ConicalSurface(a, 0.4, 1.5), {{0.3, -2}, {5.0, 2}}});
    v.push_back({"cone below its apex" + h, new Geom_ConicalSurface(a, 0.4, 1.5), {{0, -9}, {kOffsetTurn, -5}}});
    v.push_back({"sphere" + h, new Geom_SphericalSurface(a, 3), {{0, -kOffsetTurn / 4}, {kOffsetTurn, kOffsetTurn / 4}}});
    v.push_back({"torus" + h, new Geom_ToroidalSurface(a, 5, 1.25), {{0, 0}, {kOffsetTurn, kOffsetTurn}}});
  }
  return v;
}

TopoDS_Face offset_face(const Handle(Geom_Surface)& s, const Box<2>& uv) {
  return BRepBuilderAPI_MakeFace(s, uv.lo[0], uv.hi[0], uv.lo[1], uv.hi[1], 1e-9).Face();
}

// The largest distance between the kernel's offset point at (u, v) and trivar's surface at the mapped
// parameters, over n random parameters in the box.
double offset_deviation(const Handle(Geom_Surface)& exact, const cad::FaceNurbs& form, const Box<2>& uv, int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> t(0, 1);
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    const double u = uv.lo[0] + t(rng) * (uv.hi[0] - uv.lo[0]), v = uv.lo[1] + t(rng) * (uv.hi[1] - uv.lo[1]);
    double x[3];
    form.surface.eval(form(u, v), x);
    worst = std::max(worst, exact->Value(u, v).Distance(gp_Pnt(x[0], x[1], x[2])));
  }
  return worst;
}

// A wavy bicubic B-spline patch over [0, 4] x [0, 3] (4 x 3 spans, simple knots: C2).
Handle(Geom_BSplineSurface) wavy_patch() {
  TColgp_Array2OfPnt poles(1, 7, 1, 6);
  for (int i = 1; i <= 7; ++i)
    for (int j = 1; j <= 6; ++j) poles(i, j) = gp_Pnt(1.5 * i, 1.2 * j + 0.3 * i, 0.8 * std::sin(1.3 * i) * std::cos(0.9 * j));
  TColStd_Array1OfReal ku(1, 5), kv(1, 4);
  TColStd_Array1OfInteger mu(1, 5), mv(1, 4);
  for (int i = 1; i <= 5; ++i) {
    ku(i) = i - 1;
    mu(i) = i == 1 || i == 5 ? 4 : 1;
  }
  for (int i = 1; i <= 4; ++i) {
    kv(i) = i - 1;
    mv(i) = i == 1 || i == 4 ? 4 : 1;
  }
  return new Geom_BSplineSurface(poles, ku, kv, mu, mv, 3, 3);
}

// The extrusion along (0.2, 0.1, 1) of a planar cubic Bezier with an inflection.
Handle(Geom_Surface) extruded_bezier() {
  TColgp_Array1OfPnt poles(1, 4);
  poles(1) = gp_Pnt(0, 0, 0);
  poles(2) = gp_Pnt(4, 4, 0);
  poles(3) = gp_Pnt(-2, 6, 0);
  poles(4) = gp_Pnt(2, 10, 0);
  return new Geom_SurfaceOfLinearExtrusion(new Geom_BezierCurve(poles), gp_Dir(0.2, 0.1, 1));
}

// A copy of the solid whose faces `pick` accepts get the surface `replace` makes of theirs (the same points at
// the same parameters, e.g. an offset surface of a smaller basis), their edges' parameter-space curves carried
// over (they are stored per surface).
TopoDS_Shape with_surfaces_replaced(const TopoDS_Shape& solid, const std::function<Handle(Geom_Surface)(const Handle(Geom_Surface)&)>& replace) {
  const TopoDS_Shape copy = BRepBuilderAPI_Copy(solid).Shape();
  BRep_Builder b;
  for (TopExp_Explorer f(copy, TopAbs_FACE); f.More(); f.Next()) {
    const TopoDS_Face face = TopoDS::Face(f.Current().Oriented(TopAbs_FORWARD));
    TopLoc_Location loc;
    const Handle(Geom_Surface) old = BRep_Tool::Surface(face, loc);
    const Handle(Geom_Surface) fresh = replace(old);
    if (fresh.IsNull()) continue;
    struct Curves {
      TopoDS_Edge edge;
      Handle(Geom2d_Curve) c1, c2;
      double first, last;
    };
    std::vector<Curves> curves;
    for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
      const TopoDS_Edge edge = TopoDS::Edge(e.Current());
      Curves c{edge, nullptr, nullptr, 0, 0};
      c.c1 = BRep_Tool::CurveOnSurface(TopoDS::Edge(edge.Oriented(TopAbs_FORWARD)), face, c.first, c.last);
      if (BRep_Tool::IsClosed(edge, face)) c.c2 = BRep_Tool::CurveOnSurface(TopoDS::Edge(edge.Oriented(TopAbs_REVERSED)), face, c.first, c.last);
      curves.push_back(c);
    }
    b.UpdateFace(face, fresh, loc, BRep_Tool::Tolerance(face));
    for (const Curves& c : curves) {
      if (c.c2.IsNull())
        b.UpdateEdge(c.edge, c.c1, face, BRep_Tool::Tolerance(c.edge));
      else
        b.UpdateEdge(c.edge, c.c1, c.c2, face, BRep_Tool::Tolerance(c.edge));
      b.Range(c.edge, face, c.first, c.last);
    }
  }
  return copy;
}

// Imports the solid through STEP: one solid, every face mapped, a valid trim, a watertight boundary; returns
// trivar's volume.
double offset_import(const TopoDS_Shape& s, const std::string& name) {
  const std::string path = test::write_step(s, test::temp_dir("offset"), name);
  const cad::StepImport im = cad::import_step(path);
  EXPECT_GT(im.report.faces_by_kind.count("offset") ? im.report.faces_by_kind.at("offset") : 0, 0) << "no offset face";
  EXPECT_TRUE(im.report.unmapped.empty()) << (im.report.unmapped.empty() ? "" : im.report.unmapped[0].reason);
  EXPECT_EQ(im.solids.size(), 1u);
  std::filesystem::remove_all(test::temp_dir("offset"));
  if (im.solids.size() != 1 || !im.solids[0].solid) return 0;
  const TrimCheck c = check_trim(*im.solids[0].solid);
  EXPECT_TRUE(c.valid) << (c.defects.empty() ? "" : c.defects[0]);
  EXPECT_TRUE(c.watertight);
  return im.solids[0].solid->volume();
}

// The surface itself as the offset by d of the same kind of surface (radius r - d, or the plane moved back).
Handle(Geom_Surface) as_analytic_offset(const Handle(Geom_Surface)& s, double d) {
  if (const auto c = Handle(Geom_CylindricalSurface)::DownCast(s); !c.IsNull())
    return new Geom_OffsetSurface(new Geom_CylindricalSurface(c->Position(), c->Radius() - d), d);
  if (const auto sp = Handle(Geom_SphericalSurface)::DownCast(s); !sp.IsNull())
    return new Geom_OffsetSurface(new Geom_SphericalSurface(sp->Position(), sp->Radius() - d), d);
  if (const auto t = Handle(Geom_ToroidalSurface)::DownCast(s); !t.IsNull())
    return new Geom_OffsetSurface(new Geom_ToroidalSurface(t->Position(), t->MajorRadius(), t->MinorRadius() - d), d);
  if (const auto co = Handle(Geom_ConicalSurface)::DownCast(s); !co.IsNull()) {
    // The cone offset by d along (cos a e_r - sin a z) from a cone whose frame sits d sin a up the axis.
    gp_Ax3 a = co->Position();
    const double sa = std::sin(co->SemiAngle()), ca = std::cos(co->SemiAngle());
    a.Translate(gp_Vec(a.Direction()) * (d * sa));
    return new Geom_OffsetSurface(new Geom_ConicalSurface(a, co->SemiAngle(), co->RefRadius() - d * ca), d);
  }
  return nullptr;
}

// The prism (height 4) over a profile bounded by x = 0, y = 0, y = 9 and a cubic Bezier with an inflection.
struct BezierPrism {
  Handle(Geom_BezierCurve) side;
  TopoDS_Shape solid;
};
BezierPrism bezier_prism() {
  TColgp_Array1OfPnt poles(1, 4);
  poles(1) = gp_Pnt(6, 0, 0);
  poles(2) = gp_Pnt(8, 3, 0);
  poles(3) = gp_Pnt(5, 6, 0);
  poles(4) = gp_Pnt(7, 9, 0);
  const Handle(Geom_BezierCurve) bezier = new Geom_BezierCurve(poles);
  BRepBuilderAPI_MakeWire w;
  w.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(6, 0, 0)).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(bezier).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(7, 9, 0), gp_Pnt(0, 9, 0)).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 9, 0), gp_Pnt(0, 0, 0)).Edge());
  return {bezier, BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(w.Wire(), true).Face(), gp_Vec(0, 0, 4)).Shape()};
}

// The area of the profile's offset by d <= 0 (inwards, sharp corners): oint x dy over the offset curve c + d n
// (Gauss-Legendre on 64 pieces, exact to rounding) and the straight sides x = -d, y = -d, y = 9 + d.
double offset_profile_area(const Geom_BezierCurve& bezier, double d) {
  // The offset curve's point and derivative at t (the outward normal of the counter-clockwise profile is
  // (y', -x') / |c'|).
  const auto curve = [&](double t, gp_XY& p, gp_XY& dp) {
    gp_Pnt c;
    gp_Vec v, a;
    bezier.D2(t, c, v, a);
    const double m = std::hypot(v.X(), v.Y());
    const gp_XY n(v.Y() / m, -v.X() / m), dn = (gp_XY(a.Y(), -a.X()) - n * (n * gp_XY(a.Y(), -a.X()))) / m;
    p = gp_XY(c.X(), c.Y()) + d * n;
    dp = gp_XY(v.X(), v.Y()) + d * dn;
  };
  // Where the offset curve meets the offset lines y = -d and y = 9 + d (bisection).
  const auto meets = [&](double level, double lo, double hi) {
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      gp_XY p, dp;
      curve(mid, p, dp);
      (p.Y() < level ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  const double t0 = d == 0 ? 0 : meets(-d, 0, 0.5), t1 = d == 0 ? 1 : meets(9 + d, 0.5, 1);
  double area = -d * (-d - (9 + d));  // x dy along x = -d, from y = 9 + d down to y = -d
  const QuadratureRule r = gauss_legendre(20);
  for (int piece = 0; piece < 64; ++piece)
    for (std::size_t q = 0; q < r.nodes.size(); ++q) {
      const double h = (t1 - t0) / 64, t = t0 + (piece + r.nodes[q]) * h;
      gp_XY p, dp;
      curve(t, p, dp);
      area += h * r.weights[q] * p.X() * dp.Y();
    }
  return area;
}

}  // namespace

TEST(OffsetSurface, OffsetsOfAnalyticSurfacesAreExact) {
  for (const OffsetCase& k : analytic_bases())
    for (double d : {0.7, -0.4}) {
      SCOPED_TRACE(k.name + " offset " + std::to_string(d));
      const Handle(Geom_Surface) exact = new Geom_OffsetSurface(k.basis, d);
      const std::optional<cad::FaceNurbs> form = cad::face_nurbs(offset_face(exact, k.uv), k.uv, 1e-9);
      ASSERT_TRUE(form);
      EXPECT_LT(offset_deviation(exact, *form, k.uv, 2000), 1e-13 * 16);  // coordinates up to 16
      // Exact means no more control points than the basis's own form.
      const std::optional<cad::FaceNurbs> plain = cad::face_nurbs(offset_face(k.basis, k.uv), k.uv, 1e-9);
      ASSERT_TRUE(plain);
      EXPECT_EQ(form->surface.num_coefs(), plain->surface.num_coefs());
      if (k.name.find("apex") == std::string::npos) {
        EXPECT_TRUE(cad::maps_directly(offset_face(exact, k.uv)));
      }
    }
}

TEST(OffsetSurface, OffsetsThatLoseTheNormalAreRefusedWithAReason) {
  const gp_Ax3 a = offset_frame(false);
  const auto refused = [](const Handle(Geom_Surface)& s, const Box<2>& uv, const std::string& why) {
    TopoDS_Face f;
    BRep_Builder().MakeFace(f, s, 1e-9);  // the surface alone: face_nurbs reads nothing else
    try {
      cad::face_nurbs(f, uv, 1e-9);
      ADD_FAILURE() << "accepted; expected: " << why;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  // A cylinder of radius 2.5 offset inwards by 2.5 is its axis.
  refused(new Geom_OffsetSurface(new Geom_CylindricalSurface(a, 2.5), -2.5), {{0, 0}, {1, 1}}, "collapses the cylinder");
  // A cone face through its apex (ref radius 1.5, half-angle 0.4: the apex at v = -3.85).
  refused(new Geom_OffsetSurface(new Geom_ConicalSurface(a, 0.4, 1.5), 0.2), {{0, -5}, {1, 1}}, "apex");
  // A B-spline sphere cap reaching the pole, where its v-derivative vanishes.
  const Handle(Geom_BSplineSurface) cap = GeomConvert::SurfaceToBSplineSurface(
      new Geom_RectangularTrimmedSurface(new Geom_SphericalSurface(a, 3), 0, 1.5, 0.5, std::numbers::pi / 2));
  refused(new Geom_OffsetSurface(cap, 0.3), {{0, 0.5}, {1.5, std::numbers::pi / 2}}, "degenerate");
  // A tolerance no fit of 2^18 control points reaches.
  try {
    cad::fit_offset_surface(wavy_patch(), 0.5, {{0, 0}, {4, 3}}, 1e-30);
    ADD_FAILURE() << "an impossible tolerance was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("control points"), std::string::npos) << e.what();
  }
}

TEST(OffsetSurface, FreeFormOffsetsAreFittedWithinTheTolerance) {
  const std::vector<OffsetCase> cases{{"B-spline patch", wavy_patch(), {{0, 0}, {4, 3}}},
                                      {"B-spline patch part", wavy_patch(), {{0.6, 1.1}, {2.7, 2.4}}},
                                      {"extruded Bezier", extruded_bezier(), {{0, -1}, {1, 4}}}};
  for (const OffsetCase& k : cases)
    for (double d : {0.5, -0.3})
      for (double tol : {1e-6, 1e-9}) {
        SCOPED_TRACE(k.name + " offset " + std::to_string(d) + " tolerance " + std::to_string(tol));
        const Handle(Geom_Surface) exact = new Geom_OffsetSurface(k.basis, d);
        const std::optional<cad::FaceNurbs> form = cad::face_nurbs(offset_face(exact, k.uv), k.uv, tol);
        ASSERT_TRUE(form);
        EXPECT_FALSE(form->map[0].angular() || form->map[1].angular());  // the basis's parameters
        const Box<2> dom = form->surface.domain();
        for (int i = 0; i < 2; ++i) {
          EXPECT_DOUBLE_EQ(dom.lo[i], k.uv.lo[i]);
          EXPECT_DOUBLE_EQ(dom.hi[i], k.uv.hi[i]);
        }
        EXPECT_LT(offset_deviation(exact, *form, k.uv, 3000), tol);
        EXPECT_TRUE(cad::maps_directly(offset_face(exact, k.uv)));
      }
  // Along the extrusion the offset is a straight line: the fit never splits that direction.
  const cad::OffsetFit fit = cad::fit_offset_surface(extruded_bezier(), 0.5, {{0, -1}, {1, 4}}, 1e-9);
  EXPECT_EQ(fit.surface.knots(1).unique().size(), 5u);  // the four starting cells
  EXPECT_GT(fit.surface.knots(0).unique().size(), 5u);
}

TEST(OffsetSurface, SolidsWithAnalyticOffsetFacesHaveClosedFormVolumes) {
  const double pi = std::numbers::pi;
  struct Solid {
    std::string name;
    TopoDS_Shape shape;
    double exact;
  };
  const std::vector<Solid> solids{
      {"cylinder", BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(1, 2, 3), gp_Dir(0, 0, 1)), 4, 7).Shape(), pi * 16 * 7},
      {"torus", BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 1, 0)), 6, 1.5).Shape(), 2 * pi * pi * 6 * 1.5 * 1.5},
      {"cone frustum", BRepPrimAPI_MakeCone(2, 5, 6).Shape(), pi * 6 / 3 * (25 + 10 + 4)}};
  for (const Solid& s : solids)
    for (double d : {0.75, -1.0}) {
      SCOPED_TRACE(s.name + " offset " + std::to_string(d));
      const TopoDS_Shape shape = with_surfaces_replaced(s.shape, [&](const Handle(Geom_Surface)& g) { return as_analytic_offset(g, d); });
      EXPECT_NEAR(test::occt_volume(shape), s.exact, 1e-8 * s.exact);  // the kernel on the exact offsets
      EXPECT_NEAR(offset_import(shape, "analytic_offset"), s.exact, 1e-9 * s.exact);
    }
}

TEST(OffsetSurface, KernelOffsetOfAPrismWithABezierSideHasTheExactVolume) {
  // Offset inwards by the kernel with sharp (intersection) joins: the prism of height 4 - 2 |d| over the
  // profile's inward offset, whose Bezier side becomes the offset of the extrusion (fitted by trivar).
  const BezierPrism prism = bezier_prism();
  for (double d : {-0.3, -0.6}) {
    SCOPED_TRACE("offset " + std::to_string(d));
    const double exact = offset_profile_area(*prism.side, d) * (4 + 2 * d);
    BRepOffsetAPI_MakeOffsetShape offset;
    offset.PerformByJoin(prism.solid, d, 1e-7, BRepOffset_Skin, false, false, GeomAbs_Intersection);
    ASSERT_TRUE(offset.IsDone());
    EXPECT_NEAR(offset_import(offset.Shape(), "kernel_offset"), exact, 1e-9 * exact);
    // The kernel's own mass properties of the same solid meet the 1e-6 target, not much more.
    EXPECT_NEAR(test::occt_volume(offset.Shape()), exact, 1e-6 * exact);
  }
}

TEST(OffsetSurface, KernelShellOfAPrismWithABezierSideHasTheExactVolume) {
  // The prism hollowed by the kernel (its top removed, walls 0.4 thick inwards, sharp joins): the prism less
  // the cavity, the prism of height 4 - 0.4 over the profile's inward offset by 0.4.
  const BezierPrism prism = bezier_prism();
  const TopTools_ListOfShape top = test::faces_above(prism.solid, 4);
  ASSERT_EQ(top.Extent(), 1);
  BRepOffsetAPI_MakeThickSolid shell;
  shell.MakeThickSolidByJoin(prism.solid, top, -0.4, 1e-7, BRepOffset_Skin, false, false, GeomAbs_Intersection);
  ASSERT_TRUE(shell.IsDone());
  const double exact = offset_profile_area(*prism.side, 0) * 4 - offset_profile_area(*prism.side, -0.4) * 3.6;
  EXPECT_NEAR(offset_import(shell.Shape(), "kernel_shell"), exact, 1e-9 * exact);
}
