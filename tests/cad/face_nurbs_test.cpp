// The exact NURBS form of analytic and swept faces against the kernel's own surfaces: every point of the kernel's
// surface at (u, v) is the NURBS point at the mapped parameters (to rounding), iso-line trimming curves map to
// lines whose images stay on the kernel's curves, and curves the map would bend are refused.
#include "trivar/cad/face_nurbs.hpp"

#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom2d_Line.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Hyperbola.hxx>
#include <Geom_Line.hxx>
#include <Geom_Parabola.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_ToroidalSurface.hxx>

#include <numbers>

#include "trivar/cad/occt_spline.hpp"

using namespace trivar;

namespace {

constexpr double kTurn = 2 * std::numbers::pi;

// A skewed frame away from the origin; left-handed when asked (its y axis is x cross z then, not z cross x).
gp_Ax3 skewed_frame(bool left_handed) {
  gp_Ax3 a(gp_Pnt(3.5, -2.25, 7.0), gp_Dir(0.3, -0.5, 0.8), gp_Dir(0.8, 0.6, 0.0).Crossed(gp_Dir(0.3, -0.5, 0.8)));
  if (left_handed) a.YReverse();
  return a;
}

struct KernelSurface {
  std::string name;
  Handle(Geom_Surface) surface;
  Box<2> uv;
};

std::vector<KernelSurface> kernel_surfaces() {
  std::vector<KernelSurface> v;
  for (bool left : {false, true}) {
    const gp_Ax3 a = skewed_frame(left);
    const std::string h = left ? " (left-handed)" : "";
    v.push_back({"plane" + h, new Geom_Plane(a), {{-4, 1}, {3, 6}}});
    v.push_back({"cylinder" + h, new Geom_CylindricalSurface(a, 2.5), {{0, -1}, {kTurn, 3}}});
    v.push_back({"cylinder part" + h, new Geom_CylindricalSurface(a, 2.5), {{0.4, -1}, {2.9, 3}}});
    v.push_back({"cone" + h, new Geom_ConicalSurface(a, 0.4, 1.5), {{0, -2}, {kTurn, 2}}});
    v.push_back({"sphere" + h, new Geom_SphericalSurface(a, 3), {{0, -kTurn / 4}, {kTurn, kTurn / 4}}});
    v.push_back({"sphere band" + h, new Geom_SphericalSurface(a, 3), {{1, -0.3}, {5.5, 1.1}}});
    v.push_back({"torus" + h, new Geom_ToroidalSurface(a, 5, 1.25), {{0, 0}, {kTurn, kTurn}}});
    v.push_back({"torus quarter" + h, new Geom_ToroidalSurface(a, 5, 1.25), {{kTurn / 2, -1}, {3 * kTurn / 4, 2}}});
  }
  return v;
}

TopoDS_Face face_of(const KernelSurface& k) {
  return BRepBuilderAPI_MakeFace(k.surface, k.uv.lo[0], k.uv.hi[0], k.uv.lo[1], k.uv.hi[1], 1e-9).Face();
}

double distance(const gp_Pnt& p, const double* x) { return std::hypot(p.X() - x[0], p.Y() - x[1], p.Z() - x[2]); }

}  // namespace

TEST(FaceNurbs, SurfacesAreTheKernelsAnalyticSurfacesToRounding) {
  for (const KernelSurface& k : kernel_surfaces()) {
    SCOPED_TRACE(k.name);
    const std::optional<cad::FaceNurbs> form = cad::face_nurbs(face_of(k), k.uv, 1e-9);
    ASSERT_TRUE(form);
    const Box<2> dom = form->surface.domain();
    double worst = 0;
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; j <= 40; ++j) {
        const double u = k.uv.lo[0] + i / 40.0 * (k.uv.hi[0] - k.uv.lo[0]), v = k.uv.lo[1] + j / 40.0 * (k.uv.hi[1] - k.uv.lo[1]);
        const Param<2> st = (*form)(u, v);
        ASSERT_TRUE(dom.contains(st, 1e-12)) << u << " " << v;
        double x[3];
        form->surface.eval(st, x);
        worst = std::max(worst, distance(k.surface->Value(u, v), x));
      }
    EXPECT_LT(worst, 1e-13 * 16);  // coordinates up to 16: a few units in the last place
    // The kernel's own conversion of the same patch is the same spline: the same breakpoints (the arc ends)
    // and, unless the kernel made it periodic (a full turn, which trivar unrolls), the same control net.
    const Handle(Geom_BSplineSurface) kbs = GeomConvert::SurfaceToBSplineSurface(
        new Geom_RectangularTrimmedSurface(k.surface, k.uv.lo[0], k.uv.hi[0], k.uv.lo[1], k.uv.hi[1]));
    const TensorSpline<2> kernel = cad::to_spline(*kbs);
    ASSERT_EQ(kernel.is_rational(), form->surface.is_rational());
    // (The kernel shifts some angle ranges by a period: the torus quarter's v from -1 to 2 pi - 1.)
    const Box<2> kd = kernel.domain();
    if (std::abs(kd.lo[0] - dom.lo[0]) + std::abs(kd.lo[1] - dom.lo[1]) > 1e-12) continue;
    for (int d = 0; d < 2; ++d) {
      std::vector<double> a, b;
      for (double x : kernel.knots(d).unique())
        if (x >= dom.lo[d] - 1e-12 && x <= dom.hi[d] + 1e-12) a.push_back(x);
      b = form->surface.knots(d).unique();
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-14);
    }
    if (kbs->IsUPeriodic() || kbs->IsVPeriodic()) continue;
    ASSERT_EQ(kernel.num_coefs(), form->surface.num_coefs());
    for (std::size_t i = 0; i < kernel.coefs().size(); ++i) EXPECT_NEAR(kernel.coefs()[i], form->surface.coefs()[i], 1e-12 * 16);
  }
}

TEST(FaceNurbs, AngularMapIsMonotoneAndExactAtTheArcEnds) {
  const KernelSurface k = kernel_surfaces()[1];  // full cylinder
  const cad::FaceNurbs form = *cad::face_nurbs(face_of(k), k.uv, 1e-9);
  ASSERT_TRUE(form.map[0].angular());
  ASSERT_FALSE(form.map[1].angular());
  for (double a : form.map[0].arc_ends) EXPECT_DOUBLE_EQ(form.map[0](a), a);
  // The arc ends are the surface's knots: the NURBS parameter equals the angle there.
  for (double a : form.map[0].arc_ends) EXPECT_TRUE(form.surface.knots(0).multiplicity(a) >= 2) << a;
  double prev = -1;
  for (int i = 0; i <= 1000; ++i) {
    const double s = form.map[0](kTurn * i / 1000);
    EXPECT_GT(s, prev);
    prev = s;
  }
  EXPECT_DOUBLE_EQ(form.map[1](1.75), 1.75);
}

TEST(FaceNurbs, IsoLinesMapToLinesOnTheKernelsCurves) {
  for (const KernelSurface& k : kernel_surfaces()) {
    if (k.name.find("plane") != std::string::npos) continue;
    SCOPED_TRACE(k.name);
    const cad::FaceNurbs form = *cad::face_nurbs(face_of(k), k.uv, 1e-9);
    const double um = 0.3 * k.uv.lo[0] + 0.7 * k.uv.hi[0], vm = 0.6 * k.uv.lo[1] + 0.4 * k.uv.hi[1];
    // u = um (v running down) and v = vm (u running up), each over the whole face.
    const std::array<Handle(Geom2d_Line), 2> lines{new Geom2d_Line(gp_Pnt2d(um, 0), gp_Dir2d(0, -1)),
                                                  new Geom2d_Line(gp_Pnt2d(0, vm), gp_Dir2d(1, 0))};
    const std::array<std::array<double, 2>, 2> ranges{{{-k.uv.hi[1], -k.uv.lo[1]}, {k.uv.lo[0], k.uv.hi[0]}}};
    for (int d = 0; d < 2; ++d) {
      const Handle(Geom2d_BSplineCurve) c = form.pcurve(lines[d], ranges[d][0], ranges[d][1]);
      ASSERT_FALSE(c.IsNull());
      EXPECT_EQ(c->Degree(), 1);
      const TensorSpline<1> pc = cad::to_spline(*c);
      // The image of every point of the mapped line is a point of the kernel's iso-curve, in the same order.
      double last = -1e300;
      for (int i = 0; i <= 50; ++i) {
        const double t = ranges[d][0] + i / 50.0 * (ranges[d][1] - ranges[d][0]);
        double st[2], x[3];
        pc.eval({t}, st);
        form.surface.eval({st[0], st[1]}, x);
        // The kernel parameter of this point along the line: invert the monotone map by bisection.
        const int run = 1 - d;  // the direction the line runs along
        const cad::DirectionMap& m = form.map[static_cast<std::size_t>(run)];
        const double target = st[run];
        double lo = d == 0 ? k.uv.lo[1] : k.uv.lo[0], hi = d == 0 ? k.uv.hi[1] : k.uv.hi[0];
        for (int it = 0; it < 200; ++it) {
          const double mid = 0.5 * (lo + hi);
          (m(mid) < target ? lo : hi) = mid;
        }
        const double a = 0.5 * (lo + hi);
        const gp_Pnt ref = d == 0 ? k.surface->Value(um, a) : k.surface->Value(a, vm);
        EXPECT_LT(distance(ref, x), 1e-12) << t;
        const double along = d == 0 ? -a : a;  // the line runs down in v for d = 0
        EXPECT_GE(along, last - 1e-12);
        last = along;
      }
    }
  }
}

TEST(FaceNurbs, CurvesAcrossAnAngleFollowTheMapClosely) {
  for (const KernelSurface& k : {kernel_surfaces()[1], kernel_surfaces()[6]}) {  // cylinder, torus
    SCOPED_TRACE(k.name);
    const cad::FaceNurbs form = *cad::face_nurbs(face_of(k), k.uv, 1e-9);
    // A helix (a diagonal line) across the whole angle: no iso-line, so approximated through the map; every
    // point of it at kernel parameter t lands on the kernel's surface point of the line at t.
    const Handle(Geom2d_Line) helix = new Geom2d_Line(gp_Pnt2d(k.uv.lo[0], k.uv.lo[1]), gp_Dir2d(kTurn, k.uv.hi[1] - k.uv.lo[1]));
    const double len = std::hypot(kTurn, k.uv.hi[1] - k.uv.lo[1]);
    const Handle(Geom2d_BSplineCurve) c = form.pcurve(helix, 0, len);
    ASSERT_FALSE(c.IsNull());
    EXPECT_GT(c->NbKnots(), 2);
    const TensorSpline<1> pc = cad::to_spline(*c);
    double worst = 0;
    for (int i = 0; i <= 997; ++i) {
      const double t = len * i / 997;
      const gp_Pnt2d uv = helix->Value(t);
      double st[2], x[3];
      pc.eval({t}, st);
      form.surface.eval({st[0], st[1]}, x);
      worst = std::max(worst, distance(k.surface->Value(uv.X(), uv.Y()), x));
    }
    EXPECT_LT(worst, 1e-9);
  }
  // On a plane every curve keeps its shape (the map is the identity).
  const KernelSurface plane = kernel_surfaces()[0];
  const cad::FaceNurbs pf = *cad::face_nurbs(face_of(plane), plane.uv, 1e-9);
  const Handle(Geom2d_BSplineCurve) pl = pf.pcurve(new Geom2d_Line(gp_Pnt2d(0, 2), gp_Dir2d(1, 1)), 0, 2);
  ASSERT_FALSE(pl.IsNull());
  EXPECT_EQ(pl->NbPoles(), 2);
  // A face bounded by its iso-lines maps directly; an angle beyond a full turn is left to the kernel.
  EXPECT_TRUE(cad::maps_directly(face_of(kernel_surfaces()[1])));
  EXPECT_FALSE(cad::face_nurbs(face_of(kernel_surfaces()[1]), {{0, 0}, {kTurn + 0.1, 1}}, 1e-9));
}

TEST(FaceNurbs, BSplineSurfacesAreTakenAsTheyAre) {
  const KernelSurface k = kernel_surfaces()[4];  // sphere
  const Handle(Geom_BSplineSurface) bs =
      GeomConvert::SurfaceToBSplineSurface(new Geom_RectangularTrimmedSurface(k.surface, 0.5, 2.5, -1.0, 1.0));
  const TopoDS_Face f = BRepBuilderAPI_MakeFace(bs, 1e-9).Face();
  const std::optional<cad::FaceNurbs> form = cad::face_nurbs(f, {{0.5, -1}, {2.5, 1}}, 1e-9);
  ASSERT_TRUE(form);
  EXPECT_FALSE(form->map[0].angular() || form->map[1].angular());
  double x[3];
  form->surface.eval({1.3, 0.2}, x);
  EXPECT_LT(distance(bs->Value(1.3, 0.2), x), 1e-13);
}

// Surfaces of linear extrusion and of revolution of every kind of basis curve trivar converts, each over a
// parameter box inside its curve's range: a rational B-spline (a circle arc's conversion, weights != 1), a
// Bezier, a line, a circle, an ellipse, a parabola, a trimmed curve; revolutions also of a meridian touching
// the axis (a pole) and of a circle off the axis (a torus), over full and partial turns.
std::vector<KernelSurface> swept_surfaces() {
  TColgp_Array1OfPnt poles(1, 4);
  poles(1) = gp_Pnt(0, 0, 1);
  poles(2) = gp_Pnt(4, 4, 0);
  poles(3) = gp_Pnt(-2, 6, 2);
  poles(4) = gp_Pnt(2, 10, 0);
  const Handle(Geom_Curve) bezier = new Geom_BezierCurve(poles);
  const Handle(Geom_Curve) rational =
      GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(new Geom_Circle(gp_Ax2(gp_Pnt(1, 2, 3), gp_Dir(0, 0, 1)), 3), 0.2, 4.0));
  const gp_Ax2 tilted(gp_Pnt(1.5, -0.5, 2), gp_Dir(0.2, 0.9, 0.3), gp_Dir(1, 0, 0).Crossed(gp_Dir(0.2, 0.9, 0.3)));
  const Handle(Geom_Curve) line = new Geom_Line(gp_Pnt(2, 1, -1), gp_Dir(0.5, -0.2, 0.8));
  const Handle(Geom_Curve) circle = new Geom_Circle(tilted, 2.5);
  const Handle(Geom_Curve) ellipse = new Geom_Ellipse(tilted, 3, 1.25);
  const Handle(Geom_Curve) parabola = new Geom_Parabola(tilted, 0.8);
  const gp_Dir dir(0.2, 0.1, 1);
  std::vector<KernelSurface> v;
  const auto extrusion = [&](const std::string& n, const Handle(Geom_Curve)& c, double a, double b) {
    v.push_back({"extrusion of " + n, new Geom_SurfaceOfLinearExtrusion(c, dir), {{a, -1}, {b, 3}}});
  };
  extrusion("rational B-spline", rational, rational->FirstParameter(), rational->LastParameter());
  extrusion("Bezier part", bezier, 0.1, 0.8);
  extrusion("line", line, -2, 5);
  extrusion("circle", circle, 0, kTurn);
  extrusion("circle arc", circle, 1, 3.5);
  extrusion("ellipse arc", ellipse, -1, 2);
  extrusion("parabola", parabola, -2, 3);
  extrusion("trimmed circle", new Geom_TrimmedCurve(circle, 0.5, 2), 0.5, 2);
  // Revolutions about an oblique axis away from the origin; meridians in a plane through the axis or not.
  const gp_Ax1 axis(gp_Pnt(-1, 0.5, 0.25), gp_Dir(0.1, -0.2, 1));
  TColgp_Array1OfPnt mp(1, 4);  // a cubic meridian starting on the axis
  mp(1) = axis.Location().Translated(gp_Vec(axis.Direction()) * -2);
  mp(2) = gp_Pnt(2, 1, -1);
  mp(3) = gp_Pnt(3, -1, 2);
  mp(4) = gp_Pnt(1, 0.5, 4);
  const Handle(Geom_Curve) on_axis = new Geom_BezierCurve(mp);
  const gp_Ax2 meridian_plane(gp_Pnt(3, 0.5, 0.25), gp_Dir(0, 1, 0.2), gp_Dir(1, 0, 0));  // a plane through the axis
  const auto revolution = [&](const std::string& n, const Handle(Geom_Curve)& c, Box<2> uv) {
    v.push_back({"revolution of " + n, new Geom_SurfaceOfRevolution(c, axis), uv});
  };
  revolution("rational B-spline", rational, {{0, rational->FirstParameter()}, {kTurn, rational->LastParameter()}});
  revolution("Bezier, partly", bezier, {{0.7, 0.1}, {2.9, 0.9}});
  revolution("line (a cone)", line, {{0, -2}, {kTurn, 1}});
  revolution("line, partly", line, {{-1, -2}, {3, 1}});
  revolution("circle off the axis (a torus)", new Geom_Circle(meridian_plane, 1.5), {{0, 0}, {kTurn, kTurn}});
  revolution("circle arc, partly", new Geom_Circle(meridian_plane, 1.5), {{2, 0.5}, {4.5, 2}});
  revolution("ellipse", ellipse, {{0, -1}, {kTurn, 2}});
  revolution("parabola", parabola, {{0.5, -1}, {5, 2}});
  revolution("meridian from the axis (a pole)", on_axis, {{0, 0}, {kTurn, 1}});
  revolution("trimmed Bezier", new Geom_TrimmedCurve(bezier, 0.2, 0.6), {{0, 0.2}, {1.5, 0.6}});
  return v;
}

TEST(FaceNurbs, SweptSurfacesAreTheKernelsSurfacesToRounding) {
  for (const KernelSurface& k : swept_surfaces()) {
    SCOPED_TRACE(k.name);
    const std::optional<cad::FaceNurbs> form = cad::face_nurbs(face_of(k), k.uv, 1e-9);
    ASSERT_TRUE(form);
    const Box<2> dom = form->surface.domain();
    double worst = 0, size = 0;
    for (int i = 0; i <= 60; ++i)
      for (int j = 0; j <= 60; ++j) {
        const double u = k.uv.lo[0] + i / 60.0 * (k.uv.hi[0] - k.uv.lo[0]), v = k.uv.lo[1] + j / 60.0 * (k.uv.hi[1] - k.uv.lo[1]);
        const Param<2> st = (*form)(u, v);
        ASSERT_TRUE(dom.contains(st, 1e-12)) << u << " " << v;
        double x[3];
        form->surface.eval(st, x);
        gp_Pnt p;
        k.surface->D0(u, v, p);
        worst = std::max(worst, distance(p, x));
        size = std::max(size, p.XYZ().Modulus());
      }
    EXPECT_LT(worst, 1e-12 * size);
    // Bounded by its iso-lines (a pole's degenerate edge included), the face maps directly.
    EXPECT_TRUE(cad::maps_directly(face_of(k)));
  }
  // A hyperbola has no rational form in its own (hyperbolic) parameter: left to the kernel's conversion.
  const KernelSurface h{"extrusion of a hyperbola", new Geom_SurfaceOfLinearExtrusion(new Geom_Hyperbola(gp_Ax2(), 2, 1), gp_Dir(0, 0, 1)),
                        {{-1, 0}, {1, 1}}};
  EXPECT_FALSE(cad::face_nurbs(face_of(h), h.uv, 1e-9));
  EXPECT_FALSE(cad::maps_directly(face_of(h)));
}
