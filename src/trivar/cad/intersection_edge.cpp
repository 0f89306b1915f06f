#include "trivar/cad/intersection_edge.hpp"

#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "trivar/spline/bernstein_interpolation.hpp"

namespace trivar::cad {

namespace {

constexpr int kPieceDegree = 6;
constexpr int kMaxHalvings = 14;
// The end spans' share of the edge's parameter range.
constexpr double kEndSpan = 1e-6;
// Largest distance of the pieces from the solved points, relative to the model's size.
constexpr double kFitTolerance = 1e-11;
// sin of the smallest angle between the surfaces at which their intersection is solved for.
constexpr double kMinSine = 0.02;

// One point on both surfaces: (u1, v1, u2, v2) and the 3D point.
struct EdgePoint {
  double p[4];
  gp_Pnt x;
};

class EdgeSolver {
 public:
  EdgeSolver(const Handle(Geom_Surface)& s1, const Handle(Geom2d_Curve)& c1, const Handle(Geom_Surface)& s2,
             const Handle(Geom2d_Curve)& c2, const Handle(Geom_Curve)& c3, double scale)
      : s1_(s1), s2_(s2), c1_(c1), c2_(c2), c3_(c3), scale_(scale) {}

  // The exact intersection point near the kernel's edge point at t, in its normal plane.
  std::optional<EdgePoint> at(double t) const {
    const gp_Pnt2d a = c1_->Value(t), b = c2_->Value(t);
    const gp_Pnt x0 = c3_->Value(t);
    EdgePoint e{{a.X(), a.Y(), b.X(), b.Y()}, {}};
    gp_Vec dir;
    for (int it = 0; it < 30; ++it) {
      gp_Pnt p1, p2;
      gp_Vec d1u, d1v, d2u, d2v;
      s1_->D1(e.p[0], e.p[1], p1, d1u, d1v);
      s2_->D1(e.p[2], e.p[3], p2, d2u, d2v);
      const gp_Vec n1 = d1u.Crossed(d1v), n2 = d2u.Crossed(d2v);
      const gp_Vec tangent = n1.Crossed(n2);
      if (n1.Magnitude() == 0 || n2.Magnitude() == 0 || tangent.Magnitude() < kMinSine * n1.Magnitude() * n2.Magnitude())
        return std::nullopt;
      if (it == 0) dir = tangent.Normalized();
      Eigen::Matrix4d J;
      Eigen::Vector4d F;
      const gp_Vec r(p2, p1), q(x0, p1);
      for (int k = 0; k < 3; ++k) {
        J(k, 0) = d1u.Coord(k + 1), J(k, 1) = d1v.Coord(k + 1), J(k, 2) = -d2u.Coord(k + 1), J(k, 3) = -d2v.Coord(k + 1);
        F(k) = r.Coord(k + 1);
      }
      J(3, 0) = dir.Dot(d1u), J(3, 1) = dir.Dot(d1v), J(3, 2) = 0, J(3, 3) = 0;
      F(3) = dir.Dot(q);
      const Eigen::Vector4d step = J.partialPivLu().solve(-F);
      if (!step.allFinite()) return std::nullopt;
      for (int k = 0; k < 4; ++k) e.p[k] += step(k);
      if (step.norm() <= 1e-14 * (1 + std::abs(e.p[0]) + std::abs(e.p[1]) + std::abs(e.p[2]) + std::abs(e.p[3])) ||
          F.norm() <= 1e-15 * scale_) {
        e.x = s1_->Value(e.p[0], e.p[1]);
        return e;
      }
    }
    return std::nullopt;
  }

 private:
  Handle(Geom_Surface) s1_, s2_;
  Handle(Geom2d_Curve) c1_, c2_;
  Handle(Geom_Curve) c3_;
  double scale_;
};

// Bezier pieces over spans of [t0, t1], appended to the knot and coefficient lists of three curves.
struct Pieces {
  std::vector<double> breaks;
  std::vector<double> uv1, uv2, xyz;  // kPieceDegree + 1 coefficients per piece, C0 duplicates kept
};

double value(const double* coef, int dim, int k, double s) {
  // de Casteljau on one component of a degree kPieceDegree Bezier piece.
  double b[kPieceDegree + 1];
  for (int i = 0; i <= kPieceDegree; ++i) b[i] = coef[i * dim + k];
  for (int r = 1; r <= kPieceDegree; ++r)
    for (int i = 0; i <= kPieceDegree - r; ++i) b[i] = (1 - s) * b[i] + s * b[i + 1];
  return b[0];
}

}  // namespace

std::optional<IntersectionEdge> solve_intersection_edge(const Handle(Geom_Surface)& s1, const Handle(Geom2d_Curve)& c1,
                                                        const Handle(Geom_Surface)& s2, const Handle(Geom2d_Curve)& c2,
                                                        const Handle(Geom_Curve)& c3, double t0, double t1,
                                                        double scale) {
  const EdgeSolver solve(s1, c1, s2, c2, c3, scale);
  const double tolerance = kFitTolerance * scale;
  BernsteinInterpolation<1> interp({kPieceDegree});
  constexpr int n = kPieceDegree + 1;
  Pieces out;
  out.breaks.push_back(t0);
  double deviation = 0;
  // The ends stay where the kernel put them, so the loops through them stay closed in every face's parameters
  // (Green's theorem over a loop with a gap would miss the gap's term); the solved curve takes over within a
  // short end span, whose distance from the exact intersection (below the kernel's error, over 1e-6 of the
  // edge) costs nothing measurable.
  const auto kernel_point = [&](double t) {
    const gp_Pnt2d a = c1->Value(t), b = c2->Value(t);
    return EdgePoint{{a.X(), a.Y(), b.X(), b.Y()}, c3->Value(t)};
  };
  // Spans to do, last first: (a, b, halvings, at an end).
  struct Span {
    double a, b;
    int depth;
    bool end;
  };
  std::vector<Span> todo;
  constexpr int kStartSpans = 4;
  const double eps = kEndSpan * (t1 - t0);
  todo.push_back({t1 - eps, t1, 0, true});
  for (int i = kStartSpans - 1; i >= 0; --i)
    todo.push_back({t0 + eps + (t1 - t0 - 2 * eps) * i / kStartSpans, t0 + eps + (t1 - t0 - 2 * eps) * (i + 1) / kStartSpans, 0, false});
  todo.push_back({t0, t0 + eps, 0, true});
  while (!todo.empty()) {
    const Span sp = todo.back();
    todo.pop_back();
    std::vector<double> v1(2 * n), v2(2 * n), v3(3 * n);
    for (int i = 0; i < n; ++i) {
      const double t = sp.a + (sp.b - sp.a) * i / kPieceDegree;
      const std::optional<EdgePoint> e = (sp.end && i == 0 && sp.a == t0) || (sp.end && i == n - 1 && sp.b == t1)
                                             ? std::optional<EdgePoint>(kernel_point(i == 0 ? t0 : t1))
                                             : solve.at(t);
      if (!e) return std::nullopt;
      v1[2 * i] = e->p[0], v1[2 * i + 1] = e->p[1], v2[2 * i] = e->p[2], v2[2 * i + 1] = e->p[3];
      v3[3 * i] = e->x.X(), v3[3 * i + 1] = e->x.Y(), v3[3 * i + 2] = e->x.Z();
    }
    interp.apply(v1, 2, {});
    interp.apply(v2, 2, {});
    interp.apply(v3, 3, {});
    // The pieces against solved points between the nodes, in model units.
    double err = 0;
    for (int i = 0; i < kPieceDegree && !sp.end; ++i) {
      const double s = (i + 0.5) / kPieceDegree;
      const std::optional<EdgePoint> e = solve.at(sp.a + (sp.b - sp.a) * s);
      if (!e) return std::nullopt;
      const gp_Pnt q1 = s1->Value(value(v1.data(), 2, 0, s), value(v1.data(), 2, 1, s));
      const gp_Pnt q2 = s2->Value(value(v2.data(), 2, 0, s), value(v2.data(), 2, 1, s));
      const gp_Pnt q3(value(v3.data(), 3, 0, s), value(v3.data(), 3, 1, s), value(v3.data(), 3, 2, s));
      err = std::max({err, q1.Distance(e->x), q2.Distance(e->x), q3.Distance(e->x)});
    }
    if (err > tolerance && sp.depth < kMaxHalvings) {
      const double m = 0.5 * (sp.a + sp.b);
      todo.push_back({m, sp.b, sp.depth + 1, false});
      todo.push_back({sp.a, m, sp.depth + 1, false});
      continue;
    }
    deviation = std::max(deviation, err);
    out.breaks.push_back(sp.b);
    out.uv1.insert(out.uv1.end(), v1.begin(), v1.end());
    out.uv2.insert(out.uv2.end(), v2.begin(), v2.end());
    out.xyz.insert(out.xyz.end(), v3.begin(), v3.end());
  }
  // Pieces joined C0: interior breaks of multiplicity kPieceDegree, the shared end coefficient once (the pieces
  // meet at the same solved point).
  const std::size_t pieces = out.breaks.size() - 1;
  std::vector<double> knots(kPieceDegree + 1, t0);
  for (std::size_t k = 1; k < pieces; ++k) knots.insert(knots.end(), kPieceDegree, out.breaks[k]);
  knots.insert(knots.end(), kPieceDegree + 1, t1);
  const auto join = [&](const std::vector<double>& c, int dim) {
    std::vector<double> coefs;
    for (std::size_t k = 0; k < pieces; ++k)
      coefs.insert(coefs.end(), c.begin() + static_cast<std::ptrdiff_t>((k * n + (k == 0 ? 0 : 1)) * dim),
                   c.begin() + static_cast<std::ptrdiff_t>((k + 1) * n * dim));
    return TensorSpline<1>({KnotVector(kPieceDegree, knots)}, dim, false, std::move(coefs));
  };
  return IntersectionEdge{join(out.uv1, 2), join(out.uv2, 2), join(out.xyz, 3), deviation};
}

}  // namespace trivar::cad
