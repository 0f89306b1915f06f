#include "trivar/cad/occt_spline.hpp"

#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>

namespace trivar::cad {

namespace {

KnotVector flat_knots(int degree, const TColStd_Array1OfReal& seq) {
  std::vector<double> k(static_cast<std::size_t>(seq.Length()));
  for (int i = seq.Lower(); i <= seq.Upper(); ++i) k[static_cast<std::size_t>(i - seq.Lower())] = seq(i);
  return KnotVector(degree, std::move(k));
}

template <class Curve, int N>
TensorSpline<1> curve_to_spline(const Curve& in) {
  Handle(Curve) c = Handle(Curve)::DownCast(in.Copy());
  if (c->IsPeriodic()) c->SetNotPeriodic();
  TColStd_Array1OfReal seq(1, c->NbPoles() + c->Degree() + 1);
  c->KnotSequence(seq);
  std::vector<double> pts, w;
  for (int i = 1; i <= c->NbPoles(); ++i) {
    const auto p = c->Pole(i);
    pts.push_back(p.X());
    pts.push_back(p.Y());
    if constexpr (N == 3) pts.push_back(p.Coord(3));
    if (c->IsRational()) w.push_back(c->Weight(i));
  }
  return TensorSpline<1>::from_cartesian({flat_knots(c->Degree(), seq)}, N, pts, w);
}

// Distinct knots and their multiplicities, as the kernel stores them.
void knots_and_mults(const KnotVector& k, TColStd_Array1OfReal& knots, TColStd_Array1OfInteger& mults) {
  const std::vector<double> u = k.unique();
  const std::vector<int> m = k.multiplicities();
  knots.Resize(1, static_cast<int>(u.size()), false);
  mults.Resize(1, static_cast<int>(u.size()), false);
  for (std::size_t i = 0; i < u.size(); ++i) {
    knots(static_cast<int>(i) + 1) = u[i];
    mults(static_cast<int>(i) + 1) = m[i];
  }
}

}  // namespace

Handle(Geom_BSplineSurface) to_occt(const TensorSpline<2>& s) {
  const int nu = s.count(0), nv = s.count(1);
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int l = s.linear_index({i, j});
      double x[3];
      s.control_point(l, x);
      poles(i + 1, j + 1) = gp_Pnt(x[0], x[1], x[2]);
      weights(i + 1, j + 1) = s.weight(l);
    }
  TColStd_Array1OfReal uk(1, 1), vk(1, 1);
  TColStd_Array1OfInteger um(1, 1), vm(1, 1);
  knots_and_mults(s.knots(0), uk, um);
  knots_and_mults(s.knots(1), vk, vm);
  if (!s.is_rational()) return new Geom_BSplineSurface(poles, uk, vk, um, vm, s.degree(0), s.degree(1));
  return new Geom_BSplineSurface(poles, weights, uk, vk, um, vm, s.degree(0), s.degree(1));
}

Handle(Geom2d_BSplineCurve) to_occt_2d(const TensorSpline<1>& c) {
  const int n = c.count(0);
  TColgp_Array1OfPnt2d poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i) {
    double x[2];
    c.control_point(i, x);
    poles(i + 1) = gp_Pnt2d(x[0], x[1]);
    weights(i + 1) = c.weight(i);
  }
  TColStd_Array1OfReal k(1, 1);
  TColStd_Array1OfInteger m(1, 1);
  knots_and_mults(c.knots(0), k, m);
  if (!c.is_rational()) return new Geom2d_BSplineCurve(poles, k, m, c.degree(0));
  return new Geom2d_BSplineCurve(poles, weights, k, m, c.degree(0));
}

TensorSpline<2> to_spline(const Geom_BSplineSurface& in) {
  Handle(Geom_BSplineSurface) s = Handle(Geom_BSplineSurface)::DownCast(in.Copy());
  if (s->IsUPeriodic()) s->SetUNotPeriodic();
  if (s->IsVPeriodic()) s->SetVNotPeriodic();
  const int nu = s->NbUPoles(), nv = s->NbVPoles();
  TColStd_Array1OfReal useq(1, nu + s->UDegree() + 1), vseq(1, nv + s->VDegree() + 1);
  s->UKnotSequence(useq);
  s->VKnotSequence(vseq);
  const bool rational = s->IsURational() || s->IsVRational();
  std::vector<double> pts, w;
  pts.reserve(static_cast<std::size_t>(3 * nu * nv));
  for (int j = 1; j <= nv; ++j)
    for (int i = 1; i <= nu; ++i) {
      const gp_Pnt p = s->Pole(i, j);
      pts.insert(pts.end(), {p.X(), p.Y(), p.Z()});
      if (rational) w.push_back(s->Weight(i, j));
    }
  return TensorSpline<2>::from_cartesian({flat_knots(s->UDegree(), useq), flat_knots(s->VDegree(), vseq)}, 3, pts, w);
}

TensorSpline<1> to_spline(const Geom_BSplineCurve& c) { return curve_to_spline<Geom_BSplineCurve, 3>(c); }
TensorSpline<1> to_spline(const Geom2d_BSplineCurve& c) { return curve_to_spline<Geom2d_BSplineCurve, 2>(c); }

}  // namespace trivar::cad
