#include "trivar/cad/occt_spline.hpp"

#include <TColStd_Array1OfReal.hxx>

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

}  // namespace

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
