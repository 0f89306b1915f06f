#include "trivar/cad/face_nurbs.hpp"

#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_ElementarySurface.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Line.hxx>
#include <Geom_Parabola.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "trivar/cad/occt_spline.hpp"
#include "trivar/cad/offset_fit.hpp"
#include "trivar/core/error.hpp"

namespace trivar::cad {

std::size_t DirectionMap::arc_of(double a) const {
  const std::size_t arcs = arc_ends.size() - 1;
  const double a0 = arc_ends.front(), d = (arc_ends.back() - a0) / static_cast<double>(arcs);
  return static_cast<std::size_t>(std::clamp(std::floor((a - a0) / d), 0.0, static_cast<double>(arcs - 1)));
}

double DirectionMap::operator()(double a) const {
  if (arc_ends.empty()) return a;
  const std::size_t i = arc_of(a);
  const double lo = arc_ends[i], hi = arc_ends[i + 1];
  return lo + (hi - lo) * 0.5 * (1 + std::tan(0.5 * (a - 0.5 * (lo + hi))) / std::tan(0.25 * (hi - lo)));
}

double DirectionMap::derivative(double a) const {
  if (arc_ends.empty()) return 1;
  const std::size_t i = arc_of(a);
  const double lo = arc_ends[i], hi = arc_ends[i + 1], c = std::cos(0.5 * (a - 0.5 * (lo + hi)));
  return (hi - lo) * 0.25 / (std::tan(0.25 * (hi - lo)) * c * c);
}

namespace {

// One direction's curve in the coordinates the surface is multi-affine in: the parameter itself (width 1,
// degree 1), (cos a, sin a) (width 2, rational quadratic arcs) or a curve's points (width 3). Cartesian points,
// weights apart.
struct Profile {
  KnotVector knots;
  int width = 1;
  std::vector<double> points;  // width values per control point, Cartesian
  std::vector<double> weights;
  DirectionMap map;
};

std::optional<Profile> linear_profile(double a, double b) {
  if (!(b > a)) return std::nullopt;
  return Profile{KnotVector(1, {a, a, b, b}), 1, {a, b}, {1, 1}, {}};
}

std::optional<Profile> angular_profile(double a, double b) {
  const double span = b - a;
  if (!(span > 0) || span > 2 * std::numbers::pi * (1 + 1e-12)) return std::nullopt;
  // Arcs split as the kernel's conversion (Convert_ElementarySurfaceToBSplineSurface) splits them, at most 150
  // degrees each (a full turn in three), so the surface is the one the kernel would make.
  const int arcs = static_cast<int>(1.2 * span / std::numbers::pi) + 1;
  Profile p;
  p.width = 2;
  std::vector<double> knots{a, a, a};
  for (int i = 0; i <= arcs; ++i) p.map.arc_ends.push_back(i == arcs ? b : a + span * i / arcs);
  for (int i = 1; i < arcs; ++i) knots.insert(knots.end(), 2, p.map.arc_ends[static_cast<std::size_t>(i)]);
  knots.insert(knots.end(), 3, b);
  p.knots = KnotVector(2, std::move(knots));
  const double half = 0.5 * span / arcs, w = std::cos(half);
  for (int j = 0; j <= 2 * arcs; ++j) {
    const double t = a + j * half, r = j % 2 ? 1 / w : 1.0;  // odd: the tangents' intersection
    p.points.insert(p.points.end(), {r * std::cos(t), r * std::sin(t)});
    p.weights.push_back(j % 2 ? w : 1.0);
  }
  return p;
}

// The surface S(u, v) = F(x(u), y(v)) with F affine in each argument: the tensor product of the profiles
// with control points F(x_i, y_j) and weights w_i w_j is exactly S (partition of unity of the rational basis).
TensorSpline<2> tensor_surface(const Profile& pu, const Profile& pv, const std::function<gp_XYZ(const double*, const double*)>& f) {
  const std::size_t nu = pu.weights.size(), nv = pv.weights.size();
  const auto weighted = [](const Profile& p) { return std::any_of(p.weights.begin(), p.weights.end(), [](double w) { return w != 1; }); };
  const bool rational = weighted(pu) || weighted(pv);
  std::vector<double> h;
  h.reserve(nu * nv * 4);
  for (std::size_t j = 0; j < nv; ++j)
    for (std::size_t i = 0; i < nu; ++i) {
      const gp_XYZ p = f(&pu.points[i * static_cast<std::size_t>(pu.width)], &pv.points[j * static_cast<std::size_t>(pv.width)]);
      const double w = pu.weights[i] * pv.weights[j];
      h.insert(h.end(), {w * p.X(), w * p.Y(), w * p.Z()});
      if (rational) h.push_back(w);
    }
  return TensorSpline<2>({pu.knots, pv.knots}, 3, rational, std::move(h));
}

std::optional<FaceNurbs> from_profiles(const std::optional<Profile>& pu, const std::optional<Profile>& pv,
                                       const std::function<gp_XYZ(const double*, const double*)>& f) {
  if (!pu || !pv) return std::nullopt;
  return FaceNurbs{tensor_surface(*pu, *pv, f), {pu->map, pv->map}};
}

// The analytic surface (plane, cylinder, cone, sphere, torus) offset by `d` along its unit normal
// Su x Sv / |Su x Sv| (d = 0: the surface itself), or nothing for other kinds. The offset of each is a surface
// of the same kind with the same parametrisation: with h = (x ^ y) . z (+1 for a right-handed position, -1 for a
// left-handed one) the normal is h e_r on a cylinder and sphere, h (cos v e_r + sin v z) on a torus (radius
// r + h d, minor radius r + h d), h (cos a e_r - sin a z) on a cone (where its radius r + v sin a > 0), and
// x ^ y on a plane.
std::optional<FaceNurbs> analytic_nurbs(const Handle(Geom_Surface)& s, const Box<2>& uv, double d) {
  const double u0 = uv.lo[0], u1 = uv.hi[0], v0 = uv.lo[1], v1 = uv.hi[1];
  const auto frame = [](const gp_Ax3& a) {
    return std::array<gp_XYZ, 4>{a.Location().XYZ(), a.XDirection().XYZ(), a.YDirection().XYZ(), a.Direction().XYZ()};
  };
  const auto handedness = [](const std::array<gp_XYZ, 4>& f) { return f[1].Crossed(f[2]).Dot(f[3]) > 0 ? 1.0 : -1.0; };
  // The offset radius; an offset that collapses the surface onto its axis or centre has no normal to carry.
  const auto offset_radius = [&](double r, const char* what) {
    const double out = r + d;
    require(std::abs(out) > 1e-12 * std::abs(r), [&] {
      return std::string("offset surface: the offset by ") + std::to_string(d) + " collapses the " + what + " of radius " +
             std::to_string(r) + " (no normal there)";
    });
    return out;
  };
  if (const auto pl = Handle(Geom_Plane)::DownCast(s); !pl.IsNull()) {
    const auto [o, x, y, z] = frame(pl->Position());
    const gp_XYZ c = o + d * x.Crossed(y);
    return from_profiles(linear_profile(u0, u1), linear_profile(v0, v1),
                         [&](const double* p, const double* q) { return c + p[0] * x + q[0] * y; });
  }
  if (const auto cy = Handle(Geom_CylindricalSurface)::DownCast(s); !cy.IsNull()) {
    const auto [o, x, y, z] = frame(cy->Position());
    const double h = handedness({o, x, y, z});
    const double r = h * offset_radius(h * cy->Radius(), "cylinder");
    return from_profiles(angular_profile(u0, u1), linear_profile(v0, v1),
                         [&](const double* p, const double* q) { return o + r * (p[0] * x + p[1] * y) + q[0] * z; });
  }
  if (const auto co = Handle(Geom_ConicalSurface)::DownCast(s); !co.IsNull()) {
    const auto [o, x, y, z] = frame(co->Position());
    const double h = handedness({o, x, y, z});
    const double r = co->RefRadius(), sa = std::sin(co->SemiAngle()), ca = std::cos(co->SemiAngle());
    // The kernel evaluates the offset of a cone on the cone's side of positive radius (r + v sin a > 0) on
    // both sides of the apex (its equivalent cone, Geom_OffsetSurface::Surface): so do we, the face's edges being
    // the kernel's.
    const double shift = h * d;
    if (d != 0) {
      const double a = r + v0 * sa, b = r + v1 * sa, eps = 1e-12 * (std::abs(r) + std::abs(v1 - v0));
      require((a > eps && b > eps) || (a < -eps && b < -eps),
              "offset surface: the face reaches the cone's apex, where the normal the offset needs is undefined");
    }
    return from_profiles(angular_profile(u0, u1), linear_profile(v0, v1), [&](const double* p, const double* q) {
      return o + (r + q[0] * sa + shift * ca) * (p[0] * x + p[1] * y) + (q[0] * ca - shift * sa) * z;
    });
  }
  if (const auto sp = Handle(Geom_SphericalSurface)::DownCast(s); !sp.IsNull()) {
    const auto [o, x, y, z] = frame(sp->Position());
    const double h = handedness({o, x, y, z});
    const double r = h * offset_radius(h * sp->Radius(), "sphere");
    return from_profiles(angular_profile(u0, u1), angular_profile(v0, v1), [&](const double* p, const double* q) {
      return o + r * q[0] * (p[0] * x + p[1] * y) + r * q[1] * z;
    });
  }
  if (const auto to = Handle(Geom_ToroidalSurface)::DownCast(s); !to.IsNull()) {
    const auto [o, x, y, z] = frame(to->Position());
    const double h = handedness({o, x, y, z});
    const double big = to->MajorRadius(), small = h * offset_radius(h * to->MinorRadius(), "torus tube");
    return from_profiles(angular_profile(u0, u1), angular_profile(v0, v1), [&](const double* p, const double* q) {
      return o + (big + small * q[0]) * (p[0] * x + p[1] * y) + small * q[1] * z;
    });
  }
  return std::nullopt;
}

Handle(Geom_Surface) without_trim(Handle(Geom_Surface) s) {
  for (auto rt = Handle(Geom_RectangularTrimmedSurface)::DownCast(s); !rt.IsNull(); rt = Handle(Geom_RectangularTrimmedSurface)::DownCast(s))
    s = rt->BasisSurface();
  return s;
}

// An offset surface whose basis has no analytic offset: it is fitted (offset_fit.hpp).
bool fitted_offset(const Handle(Geom_Surface)& s, Handle(Geom_Surface)& basis, double& distance) {
  const auto off = Handle(Geom_OffsetSurface)::DownCast(s);
  if (off.IsNull()) return false;
  basis = without_trim(off->BasisSurface());
  distance = off->Offset();
  return Handle(Geom_ElementarySurface)::DownCast(basis).IsNull();
}

// The curve over [a, b] (its own parameters) as a profile of width 3: a line and a parabola as polynomials, a
// circle and an ellipse as the angular profile under their affine frame (the angular map, as on a cylinder),
// B-spline and Bezier curves as they are (their whole domain, which must hold [a, b]). Nothing for other curves
// (hyperbolas, offset curves), which have no rational form in their own parameter.
std::optional<Profile> curve_profile(Handle(Geom_Curve) c, double a, double b) {
  for (auto t = Handle(Geom_TrimmedCurve)::DownCast(c); !t.IsNull(); t = Handle(Geom_TrimmedCurve)::DownCast(c)) c = t->BasisCurve();
  const auto framed = [](std::optional<Profile> p, const std::function<gp_XYZ(const double*)>& f) {
    if (!p) return p;
    std::vector<double> pts;
    for (std::size_t i = 0; i < p->weights.size(); ++i) {
      const gp_XYZ x = f(&p->points[i * static_cast<std::size_t>(p->width)]);
      pts.insert(pts.end(), {x.X(), x.Y(), x.Z()});
    }
    p->points = std::move(pts);
    p->width = 3;
    return p;
  };
  if (const auto l = Handle(Geom_Line)::DownCast(c); !l.IsNull()) {
    const gp_XYZ o = l->Position().Location().XYZ(), d = l->Position().Direction().XYZ();
    return framed(linear_profile(a, b), [&](const double* t) { return o + t[0] * d; });
  }
  if (const auto ci = Handle(Geom_Circle)::DownCast(c); !ci.IsNull()) {
    const gp_Ax2 f = ci->Position();
    const double r = ci->Radius();
    return framed(angular_profile(a, b), [&](const double* q) {
      return f.Location().XYZ() + r * q[0] * f.XDirection().XYZ() + r * q[1] * f.YDirection().XYZ();
    });
  }
  if (const auto el = Handle(Geom_Ellipse)::DownCast(c); !el.IsNull()) {
    const gp_Ax2 f = el->Position();
    const double ra = el->MajorRadius(), rb = el->MinorRadius();
    return framed(angular_profile(a, b), [&](const double* q) {
      return f.Location().XYZ() + ra * q[0] * f.XDirection().XYZ() + rb * q[1] * f.YDirection().XYZ();
    });
  }
  if (const auto pa = Handle(Geom_Parabola)::DownCast(c); !pa.IsNull()) {
    // O + t^2 / (4 f) X + t Y: one quadratic Bezier, its middle point where the end tangents meet.
    if (!(b > a) || !(pa->Focal() > 0)) return std::nullopt;
    const gp_Ax2 f = pa->Position();
    const double k = 1 / (4 * pa->Focal()), m = 0.5 * (a + b);
    const auto at = [&](double x, double y) { return f.Location().XYZ() + x * f.XDirection().XYZ() + y * f.YDirection().XYZ(); };
    const std::array<gp_XYZ, 3> q{at(k * a * a, a), at(k * a * b, m), at(k * b * b, b)};
    Profile p{KnotVector(2, {a, a, a, b, b, b}), 3, {}, {1, 1, 1}, {}};
    for (const gp_XYZ& x : q) p.points.insert(p.points.end(), {x.X(), x.Y(), x.Z()});
    return p;
  }
  if (Handle(Geom_BSplineCurve)::DownCast(c).IsNull() && Handle(Geom_BezierCurve)::DownCast(c).IsNull()) return std::nullopt;
  const TensorSpline<1> curve = to_spline(*GeomConvert::CurveToBSplineCurve(c));
  const Box<1> dom = curve.domain();
  const double slack = 1e-12 * (1 + dom.hi[0] - dom.lo[0]);
  if (a < dom.lo[0] - slack || b > dom.hi[0] + slack) return std::nullopt;
  Profile p{curve.knots(0), 3, {}, {}, {}};
  for (int i = 0; i < curve.num_coefs(); ++i) {
    const double* q = curve.coef(i);
    const double w = curve.weight(i);
    p.points.insert(p.points.end(), {q[0] / w, q[1] / w, q[2] / w});
    p.weights.push_back(w);
  }
  return p;
}

// The extrusion C(u) + v D: the curve's profile times a linear factor in v, with the kernel's parameters (or
// the angular map along a conic), so the face's curves carry over.
std::optional<FaceNurbs> extrusion_nurbs(const Geom_SurfaceOfLinearExtrusion& e, const Box<2>& uv) {
  const gp_XYZ d = e.Direction().XYZ();
  return from_profiles(curve_profile(e.BasisCurve(), uv.lo[0], uv.hi[0]), linear_profile(uv.lo[1], uv.hi[1]),
                       [&](const double* p, const double* q) { return gp_XYZ(p[0], p[1], p[2]) + q[0] * d; });
}

// The revolution of the meridian C(v) by the angle u about the axis (o, z), right-handed:
// o + ((C - o) . z) z + cos u (C - o - ((C - o) . z) z) + sin u z ^ (C - o), affine in (cos u, sin u) and in C,
// so the angular profile times the meridian's profile is exact. A meridian touching the axis gives a pole
// (coincident control points), as on a sphere.
std::optional<FaceNurbs> revolution_nurbs(const Geom_SurfaceOfRevolution& r, const Box<2>& uv) {
  const gp_XYZ o = r.Axis().Location().XYZ(), z = r.Axis().Direction().XYZ();
  return from_profiles(angular_profile(uv.lo[0], uv.hi[0]), curve_profile(r.BasisCurve(), uv.lo[1], uv.hi[1]),
                       [&](const double* p, const double* q) {
                         const gp_XYZ c = gp_XYZ(q[0], q[1], q[2]) - o, along = c.Dot(z) * z;
                         return o + along + p[0] * (c - along) + p[1] * z.Crossed(c);
                       });
}

}  // namespace

std::optional<FaceNurbs> face_nurbs(const TopoDS_Face& face, const Box<2>& uv, double tolerance) {
  Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  if (s.IsNull()) return std::nullopt;
  s = without_trim(s);
  if (const auto bs = Handle(Geom_BSplineSurface)::DownCast(s); !bs.IsNull()) return FaceNurbs{to_spline(*bs), {}};
  if (const auto bz = Handle(Geom_BezierSurface)::DownCast(s); !bz.IsNull())
    return FaceNurbs{to_spline(*GeomConvert::SurfaceToBSplineSurface(bz)), {}};
  if (const auto ex = Handle(Geom_SurfaceOfLinearExtrusion)::DownCast(s); !ex.IsNull()) return extrusion_nurbs(*ex, uv);
  if (const auto rv = Handle(Geom_SurfaceOfRevolution)::DownCast(s); !rv.IsNull()) return revolution_nurbs(*rv, uv);
  Handle(Geom_Surface) basis;
  double distance = 0;
  if (fitted_offset(s, basis, distance)) return FaceNurbs{fit_offset_surface(basis, distance, uv, tolerance).surface, {}};
  if (const auto off = Handle(Geom_OffsetSurface)::DownCast(s); !off.IsNull())
    return analytic_nurbs(without_trim(off->BasisSurface()), uv, off->Offset());
  return analytic_nurbs(s, uv, 0);
}

// The image of c under the map, as a C0 piecewise cubic (Bezier pieces) interpolating the image and its
// derivative at the ends of every piece, the pieces halved until the image is matched to 1e-11 of the
// parameter box at three inner points of each (the Hermite cubic's error falls as the fourth power of the
// piece length, away from the arc ends where the map's curvature jumps). A curve the map cannot follow within
// 4096 pieces is not mapped.
Handle(Geom2d_BSplineCurve) FaceNurbs::mapped_approximation(const Geom2d_BSplineCurve& c) const {
  const Box<2> box = surface.domain();
  const double tol = 1e-11 * (1 + box.extent(0) + box.extent(1));
  const auto image = [&](double t, gp_Pnt2d& p, gp_Vec2d& d) {
    gp_Pnt2d q;
    gp_Vec2d v;
    c.D1(t, q, v);
    p.SetCoord(map[0](q.X()), map[1](q.Y()));
    d.SetCoord(map[0].derivative(q.X()) * v.X(), map[1].derivative(q.Y()) * v.Y());
  };
  struct Node {
    double t;
    gp_Pnt2d p;
    gp_Vec2d d;
  };
  const auto node = [&](double t) {
    Node n{t, {}, {}};
    image(t, n.p, n.d);
    return n;
  };
  const auto bezier = [](const Node& a, const Node& b) {
    const double h = (b.t - a.t) / 3;
    return std::array<gp_Pnt2d, 4>{a.p, a.p.Translated(h * a.d), b.p.Translated(-h * b.d), b.p};
  };
  const auto fits = [&](const Node& a, const Node& b) {
    const std::array<gp_Pnt2d, 4> q = bezier(a, b);
    for (double x : {0.25, 0.5, 0.75}) {
      const double y = 1 - x;
      const gp_XY z = y * y * y * q[0].XY() + 3 * x * y * y * q[1].XY() + 3 * x * x * y * q[2].XY() + x * x * x * q[3].XY();
      gp_Pnt2d p;
      gp_Vec2d d;
      image(a.t + x * (b.t - a.t), p, d);
      if ((p.XY() - z).Modulus() > tol) return false;
    }
    return true;
  };
  // Start from the curve's own knots: the image is smooth between them except where an arc ends.
  std::vector<Node> done{node(c.FirstParameter())}, todo;
  for (int i = c.NbKnots(); i >= 1; --i)
    if (c.Knot(i) > c.FirstParameter() && c.Knot(i) <= c.LastParameter()) todo.push_back(node(c.Knot(i)));
  if (todo.empty() || todo.front().t < c.LastParameter()) todo.insert(todo.begin(), node(c.LastParameter()));
  while (!todo.empty()) {
    if (done.size() + todo.size() > 4096) return nullptr;
    const Node& a = done.back();
    const Node b = todo.back();
    if (fits(a, b)) {
      done.push_back(b);
      todo.pop_back();
    } else {
      todo.push_back(node(0.5 * (a.t + b.t)));
    }
  }
  const int n = static_cast<int>(done.size()) - 1;
  TColgp_Array1OfPnt2d poles(1, 3 * n + 1);
  TColStd_Array1OfReal knots(1, n + 1);
  TColStd_Array1OfInteger mults(1, n + 1);
  for (int i = 0; i < n; ++i) {
    const std::array<gp_Pnt2d, 4> q = bezier(done[static_cast<std::size_t>(i)], done[static_cast<std::size_t>(i) + 1]);
    for (int k = 0; k < 3; ++k) poles(3 * i + k + 1) = q[static_cast<std::size_t>(k)];
    if (i == n - 1) poles(3 * n + 1) = q[3];
  }
  for (int i = 0; i <= n; ++i) {
    knots(i + 1) = done[static_cast<std::size_t>(i)].t;
    mults(i + 1) = i == 0 || i == n ? 4 : 3;
  }
  return new Geom2d_BSplineCurve(poles, knots, mults, 3);
}

Handle(Geom2d_BSplineCurve) FaceNurbs::pcurve(const Handle(Geom2d_Curve)& c, double first, double last) const {
  const Handle(Geom2d_BSplineCurve) bc = Geom2dConvert::CurveToBSplineCurve(new Geom2d_TrimmedCurve(c, first, last));
  if (!map[0].angular() && !map[1].angular()) return bc;
  // Which coordinates vary along the curve (its control polygon's extent).
  std::array<double, 2> lo{bc->Pole(1).X(), bc->Pole(1).Y()}, hi = lo;
  for (int i = 2; i <= bc->NbPoles(); ++i)
    for (int k = 0; k < 2; ++k) {
      lo[static_cast<std::size_t>(k)] = std::min(lo[static_cast<std::size_t>(k)], bc->Pole(i).Coord(k + 1));
      hi[static_cast<std::size_t>(k)] = std::max(hi[static_cast<std::size_t>(k)], bc->Pole(i).Coord(k + 1));
    }
  std::array<bool, 2> varies{};
  bool bends = false;
  for (std::size_t k = 0; k < 2; ++k) {
    varies[k] = hi[k] - lo[k] > 1e-13 * (1 + std::abs(lo[k]));
    bends = bends || (varies[k] && map[k].angular());
  }
  Handle(Geom2d_Curve) base = c;
  for (auto t = Handle(Geom2d_TrimmedCurve)::DownCast(base); !t.IsNull(); t = Handle(Geom2d_TrimmedCurve)::DownCast(base))
    base = t->BasisCurve();
  const bool line = !Handle(Geom2d_Line)::DownCast(base).IsNull();
  // A line along one direction stays a line under that direction's (monotone) map; a curve whose angular
  // coordinates are constant keeps its shape; any other curve is approximated through the map.
  if (bends && !(line && varies[0] != varies[1])) return mapped_approximation(*bc);
  const auto mapped = [&](const gp_Pnt2d& p) {
    std::array<double, 2> q{p.X(), p.Y()};
    for (std::size_t k = 0; k < 2; ++k)
      if (map[k].angular()) q[k] = map[k](varies[k] ? q[k] : 0.5 * (lo[k] + hi[k]));
    return gp_Pnt2d(q[0], q[1]);
  };
  if (bends) {
    TColgp_Array1OfPnt2d poles(1, 2);
    poles(1) = mapped(c->Value(first));
    poles(2) = mapped(c->Value(last));
    TColStd_Array1OfReal knots(1, 2);
    knots(1) = first;
    knots(2) = last;
    TColStd_Array1OfInteger mults(1, 2);
    mults.Init(2);
    return new Geom2d_BSplineCurve(poles, knots, mults, 1);
  }
  for (int i = 1; i <= bc->NbPoles(); ++i) bc->SetPole(i, mapped(bc->Pole(i)));
  return bc;
}

bool maps_directly(const TopoDS_Face& face) {
  const TopoDS_Face fwd = TopoDS::Face(face.Oriented(TopAbs_FORWARD));
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(fwd, u0, u1, v0, v1);
  // A fitted offset keeps the basis's parameters (the identity map): only its curves need checking, and the
  // fit waits for the face's mapping.
  Handle(Geom_Surface) basis;
  double distance = 0;
  std::optional<FaceNurbs> form;
  if (fitted_offset(without_trim(BRep_Tool::Surface(fwd)), basis, distance))
    form.emplace();
  else
    try {
      form = face_nurbs(fwd, Box<2>{{u0, v0}, {u1, v1}}, 0);
    } catch (const Error&) {
      return false;
    }
  if (!form) return false;
  for (TopExp_Explorer e(fwd, TopAbs_EDGE); e.More(); e.Next()) {
    double f = 0, l = 0;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Current()), fwd, f, l);
    if (pc.IsNull() || form->pcurve(pc, f, l).IsNull()) return false;
  }
  return true;
}

}  // namespace trivar::cad
