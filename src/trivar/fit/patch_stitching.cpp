#include "trivar/fit/patch_stitching.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"

namespace trivar {

namespace {

// The LR surface with new parameters: new direction k takes old direction src[k], every value mapped by
// map(k, value); reversed[k] when that map decreases.
LRSpline<2> remap(const LRSpline<2>& s, std::array<int, 2> src, std::array<bool, 2> reversed,
                  const std::function<double(int, double)>& map) {
  int to_new[2];
  for (int k = 0; k < 2; ++k) to_new[src[static_cast<std::size_t>(k)]] = k;
  std::vector<LRBSpline<2>> basis;
  basis.reserve(static_cast<std::size_t>(s.num_basis()));
  for (const LRBSpline<2>& b : s.basis_functions()) {
    LRBSpline<2> n = b;
    for (int k = 0; k < 2; ++k) {
      auto& t = n.knots[static_cast<std::size_t>(k)];
      t = b.knots[static_cast<std::size_t>(src[static_cast<std::size_t>(k)])];
      for (double& x : t) x = map(k, x);
      if (reversed[static_cast<std::size_t>(k)]) std::reverse(t.begin(), t.end());
    }
    basis.push_back(std::move(n));
  }
  std::vector<MeshRectangle<2>> mesh;
  for (const MeshRectangle<2>& r : s.mesh()) {
    const int k = to_new[r.dir], o = 1 - k, old_o = src[static_cast<std::size_t>(o)];
    double lo = map(o, r.extent.lo[old_o]), hi = map(o, r.extent.hi[old_o]);
    if (lo > hi) std::swap(lo, hi);
    Param<2> a{}, b{};
    a[o] = lo;
    b[o] = hi;
    mesh.push_back(MeshRectangle<2>::make(k, map(k, r.value), a, b, r.multiplicity));
  }
  const Ints<2> degrees{s.degree(src[0]), s.degree(src[1])};
  return LRSpline<2>(degrees, s.dim(), s.is_rational(), std::move(basis), std::move(mesh));
}

// The exact map (permutation and sign changes only) taking `seam` of s to the side u = hi, orientation kept.
struct Canonical {
  std::array<int, 2> src{0, 1};
  std::array<bool, 2> negate{};
};

Canonical canonical(DomainSide seam) {
  Canonical c;
  c.src = {seam.dir, 1 - seam.dir};
  c.negate[0] = seam.end == 0;
  c.negate[1] = c.negate[0] != (seam.dir == 1);  // a swap of directions reverses the orientation
  return c;
}

bool identity(const Canonical& c) { return c.src[0] == 0 && !c.negate[0] && !c.negate[1]; }

LRSpline<2> to_canonical(const LRSpline<2>& s, const Canonical& c) {
  if (identity(c)) return s;
  return remap(s, c.src, c.negate, [&](int k, double x) { return c.negate[static_cast<std::size_t>(k)] ? -x : x; });
}

LRSpline<2> from_canonical(const LRSpline<2>& s, const Canonical& c) {
  if (identity(c)) return s;
  std::array<int, 2> src{};
  std::array<bool, 2> negate{};
  for (int k = 0; k < 2; ++k) {
    src[static_cast<std::size_t>(c.src[static_cast<std::size_t>(k)])] = k;
    negate[static_cast<std::size_t>(c.src[static_cast<std::size_t>(k)])] = c.negate[static_cast<std::size_t>(k)];
  }
  return remap(s, src, negate, [&](int k, double x) { return negate[static_cast<std::size_t>(k)] ? -x : x; });
}

// x in [f0, f1] to [g0, g1], the ends exactly.
double lerp_exact(double x, double f0, double f1, double g0, double g1) {
  if (x == f0) return g0;
  if (x == f1) return g1;
  return g0 + (x - f0) / (f1 - f0) * (g1 - g0);
}

Param<2> side_point(const LRSpline<2>& s, DomainSide side, double t01) {
  const int a = side.along();
  return side_param(s, side, s.domain().lo[a] + t01 * (s.domain().hi[a] - s.domain().lo[a]));
}

double distance(const double* x, const double* y, int dim) {
  double d = 0;
  for (int i = 0; i < dim; ++i) d += (x[i] - y[i]) * (x[i] - y[i]);
  return std::sqrt(d);
}

struct SideMatch {
  DomainSide a, b;
  bool reversed = false;  // b's side runs against a's
  double gap = HUGE_VAL, ends_gap = HUGE_VAL;
};

// The pair of sides (and direction along them) closest as curves: largest distance at 33 corresponding points.
SideMatch closest_sides(const LRSpline<2>& A, const LRSpline<2>& B) {
  constexpr int n = 33;
  const int dim = A.dim();
  std::vector<double> pa(static_cast<std::size_t>(dim * n)), pb(pa.size());
  SideMatch best;
  for (int sa = 0; sa < 4; ++sa) {
    const DomainSide da{sa / 2, sa % 2};
    for (int i = 0; i < n; ++i) A.eval(side_point(A, da, i / double(n - 1)), pa.data() + i * dim);
    for (int sb = 0; sb < 4; ++sb) {
      const DomainSide db{sb / 2, sb % 2};
      for (int i = 0; i < n; ++i) B.eval(side_point(B, db, i / double(n - 1)), pb.data() + i * dim);
      for (int rev = 0; rev < 2; ++rev) {
        SideMatch m{da, db, rev == 1, 0.0, 0.0};
        for (int i = 0; i < n; ++i) {
          const double d = distance(pa.data() + i * dim, pb.data() + (rev ? n - 1 - i : i) * dim, dim);
          m.gap = std::max(m.gap, d);
          if (i == 0 || i == n - 1) m.ends_gap = std::max(m.ends_gap, d);
        }
        if (m.gap < best.gap) best = m;
      }
    }
  }
  return best;
}

const char* side_name(DomainSide s) {
  static const char* names[2][2] = {{"u = lo", "u = hi"}, {"v = lo", "v = hi"}};
  return names[s.dir][s.end];
}

// The first rows on both sides of the seam of two canonical patches (first's seam at u = hi, second's at
// u = lo), matched by their knots along the seam.
struct Column {
  std::array<int, 2> a{-1, -1}, b{-1, -1};  // [row]: ids in first / second
};

std::vector<Column> seam_columns(const LRSpline<2>& A, const LRSpline<2>& B, int rows) {
  std::map<std::vector<double>, Column> columns;
  for (int r = 0; r < rows; ++r) {
    for (int id : side_row(A, {0, 1}, r)) columns[A.basis_function(id).knots[1]].a[static_cast<std::size_t>(r)] = id;
    for (int id : side_row(B, {0, 0}, r)) columns[B.basis_function(id).knots[1]].b[static_cast<std::size_t>(r)] = id;
  }
  std::vector<Column> out;
  for (const auto& [knots, c] : columns) {
    for (int r = 0; r < rows; ++r)
      require(c.a[static_cast<std::size_t>(r)] >= 0 && c.b[static_cast<std::size_t>(r)] >= 0,
              "stitch: the B-splines next to the seam do not pair up across it after matching the knot lines (a "
              "locally refined seam neighbourhood whose rows differ along the seam is not supported)");
    if (rows == 2) {
      const auto& ua = A.basis_function(c.a[1]).knots[0];
      const auto& ub = B.basis_function(c.b[1]).knots[0];
      require(ua[1] == A.basis_function(c.a[0]).knots[0][0] && ub[ub.size() - 2] == B.basis_function(c.b[0]).knots[0].back(),
              "stitch: the two rows next to the seam have different knot spans across it (locally refined seam "
              "neighbourhood); C1 stitching needs them equal along each column");
    }
    out.push_back(c);
  }
  return out;
}

std::vector<LRBSpline<2>> basis_copy(const LRSpline<2>& s) {
  return {s.basis_functions().begin(), s.basis_functions().end()};
}

LRSpline<2> rebuilt(const LRSpline<2>& s, std::vector<LRBSpline<2>> basis) {
  return LRSpline<2>(s.degrees(), s.dim(), s.is_rational(), std::move(basis), s.mesh());
}

}  // namespace

Stitched stitch(const LRSpline<2>& first, const LRSpline<2>& second, const StitchOptions& options) {
  require(first.is_rational() == second.is_rational(),
          "stitch: one patch is rational and the other is not (give both as NURBS, weights 1 where polynomial)");
  // C1 of the homogeneous surfaces is not C1 of the rational ones (two exact circular arcs meeting tangentially
  // have opposite weight derivatives at the joint), and enforcing it would move the geometry; a Moebius
  // reparametrisation that matches the weight derivatives first would be needed.
  require(!first.is_rational() || options.continuity == Continuity::C0,
          "stitch: C1 stitching of rational patches is not supported (C0 is)");
  require(first.dim() == second.dim(), [&] {
    return "stitch: the patches have " + std::to_string(first.dim()) + " and " + std::to_string(second.dim()) +
           " coordinates";
  });
  const double tol = options.tolerance > 0 ? options.tolerance
                                           : 1e-8 * std::max({control_net_diagonal(first), control_net_diagonal(second), 1e-300});
  const SideMatch m = closest_sides(first, second);
  require(m.gap <= tol, [&] {
    if (m.ends_gap <= tol)
      return "stitch: the sides " + std::string(side_name(m.a)) + " of the first patch and " + side_name(m.b) +
             " of the second meet at both ends but differ in between by " + format_number(m.gap) +
             " (different curves, or parametrisations that do not correspond linearly)";
    return "stitch: the patches share no side (closest sides differ by " + format_number(m.gap) +
           ", tolerance " + format_number(tol) + ")";
  });
  const int pa = first.degree(m.a.along()), pb = second.degree(m.b.along());
  const int qa = first.degree(m.a.dir), qb = second.degree(m.b.dir);
  require(pa == pb && qa == qb, [&] {
    return "stitch: degrees differ: the first patch has degree " + std::to_string(pa) + " along the shared side and " +
           std::to_string(qa) + " across it, the second " + std::to_string(pb) + " and " + std::to_string(qb) +
           " (elevate one first)";
  });
  const Canonical ca = canonical(m.a);
  LRSpline<2> A = to_canonical(first, ca);
  const double a1 = A.domain().hi[0], c0 = A.domain().lo[1], c1 = A.domain().hi[1];

  // The second patch beyond u = a1, its side on A's side point by point, scaled across the seam by 1 / lambda.
  const int bd = m.b.dir, ba = m.b.along();
  const double blo = second.domain().lo[bd], bhi = second.domain().hi[bd], len = bhi - blo;
  // Where A's canonical v = c0 lies on the second's side: the first patch's side runs from its lo along-end to
  // its hi along-end; canonical v increases along it unless negated.
  const bool a_along_negated = ca.negate[1];
  const bool b_start_at_c0 = a_along_negated == m.reversed;  // b's lo along-end sits at canonical v = c0
  const bool across_reversed = m.b.end == 1, along_reversed = !b_start_at_c0;
  const bool swapped = bd == 1;
  require((swapped != across_reversed) == along_reversed, [&] {
    return "stitch: the second patch has the opposite orientation to the first along their shared side (its "
           "normal points the other way); reverse one of its parameter directions first";
  });
  auto place = [&](double length) {
    const double g_end = a1 + length;
    return remap(second, {bd, ba}, {across_reversed, along_reversed}, [&, g_end](int k, double x) {
      if (k == 0) return across_reversed ? lerp_exact(x, blo, bhi, g_end, a1) : lerp_exact(x, blo, bhi, a1, g_end);
      const double slo = second.domain().lo[ba], shi = second.domain().hi[ba];
      return b_start_at_c0 ? lerp_exact(x, slo, shi, c0, c1) : lerp_exact(x, slo, shi, c1, c0);
    });
  };
  // lambda: the factor by which the second patch's derivative across the seam (in its own parameter, at
  // canonical v) must be scaled to best match the first's; the second is then placed with length len / lambda.
  double lambda = 1.0;
  {
    constexpr int n = 17;
    const int dim = A.dim();
    const double slo = second.domain().lo[ba], shi = second.domain().hi[ba];
    std::vector<double> da(3 * static_cast<std::size_t>(dim)), db(da.size());
    double ab = 0, bb = 0;
    for (int i = 0; i < n; ++i) {
      const double f = static_cast<double>(i) / (n - 1);
      A.eval_first_derivatives({a1, c0 + (c1 - c0) * f}, da.data());
      second.eval_first_derivatives(side_param(second, m.b, b_start_at_c0 ? slo + (shi - slo) * f : shi - (shi - slo) * f),
                                    db.data());
      const double sign = across_reversed ? -1.0 : 1.0;
      for (int j = 0; j < dim; ++j) {
        const double x = da[static_cast<std::size_t>(dim + j)], y = sign * db[static_cast<std::size_t>((1 + bd) * dim + j)];
        ab += x * y;
        bb += y * y;
      }
    }
    lambda = ab / bb;
    const bool usable = bb > 0 && std::isfinite(lambda) && lambda > 0;
    require(usable || options.continuity == Continuity::C0,
            "stitch: the derivatives across the shared side point against each other (the patches fold back "
            "onto each other); C1 stitching is impossible, C0 is not");
    if (!usable) lambda = 1.0;
  }
  LRSpline<2> B = place(len / lambda);

  // Adapt the knot lines of each side to the other's over the rows the continuity involves.
  const int rows = options.continuity == Continuity::C1 ? 2 : 1;
  const auto ka = side_trace_knots(A, {0, 1});
  const auto kb = side_trace_knots(B, {0, 0});
  insert_side_knot_lines(A, {0, 1}, kb, rows);
  insert_side_knot_lines(B, {0, 0}, ka, rows);
  require(side_trace_knots(A, {0, 1}) == side_trace_knots(B, {0, 0}),
          "stitch: the knot lines of the shared side could not be matched");

  const std::vector<Column> cols = seam_columns(A, B, rows);
  std::vector<LRBSpline<2>> ba_ = basis_copy(A), bb_ = basis_copy(B);
  // Rational patches (C0): equal homogeneous (w x, w) seam values give equal rational ones, and a rational
  // surface keeps its geometry when all its weights are scaled by one factor; so the second patch's weights are
  // first scaled to meet the first's along the seam (least squares over the seam B-splines; the same curve has
  // proportional weights), then the seam values are averaged in homogeneous form.
  const int dim = A.dim(), stride = dim + (A.is_rational() ? 1 : 0);
  if (A.is_rational()) {
    double ab = 0, bb = 0, wmax = 0;
    for (const Column& c : cols) {
      const LRBSpline<2>& Ea = ba_[static_cast<std::size_t>(c.a[0])];
      const LRBSpline<2>& Eb = bb_[static_cast<std::size_t>(c.b[0])];
      const double wa = Ea.gamma * Ea.coef[static_cast<std::size_t>(dim)], wb = Eb.gamma * Eb.coef[static_cast<std::size_t>(dim)];
      ab += wa * wb;
      bb += wb * wb;
      wmax = std::max(wmax, std::abs(wa));
    }
    const double factor = ab / bb;
    for (const Column& c : cols) {
      const LRBSpline<2>& Ea = ba_[static_cast<std::size_t>(c.a[0])];
      const LRBSpline<2>& Eb = bb_[static_cast<std::size_t>(c.b[0])];
      const double wa = Ea.gamma * Ea.coef[static_cast<std::size_t>(dim)], wb = Eb.gamma * Eb.coef[static_cast<std::size_t>(dim)];
      require(std::abs(wa - factor * wb) <= 1e-8 * wmax, [&] {
        return "stitch: the weights along the shared side are not proportional (" + format_number(wa) + " against " +
               format_number(factor * wb) + " after scaling): the sides are different rational curves";
      });
    }
    for (LRBSpline<2>& f : bb_)
      for (double& x : f.coef) x *= factor;
  }
  double moved = 0;
  auto set = [&](LRBSpline<2>& f, const std::vector<double>& d) {  // d: gamma-weighted values
    for (int j = 0; j < stride; ++j) {
      const double c = d[static_cast<std::size_t>(j)] / f.gamma;
      moved = std::max(moved, std::abs(c - f.coef[static_cast<std::size_t>(j)]));
      f.coef[static_cast<std::size_t>(j)] = c;
    }
  };
  std::vector<double> dE(static_cast<std::size_t>(stride)), dFa(dE.size()), dFb(dE.size());
  for (const Column& c : cols) {
    LRBSpline<2>& Ea = ba_[static_cast<std::size_t>(c.a[0])];
    LRBSpline<2>& Eb = bb_[static_cast<std::size_t>(c.b[0])];
    for (int j = 0; j < stride; ++j)
      dE[static_cast<std::size_t>(j)] = 0.5 * (Ea.gamma * Ea.coef[static_cast<std::size_t>(j)] +
                                               Eb.gamma * Eb.coef[static_cast<std::size_t>(j)]);
    set(Ea, dE);
    set(Eb, dE);
    if (rows < 2) continue;
    LRBSpline<2>& Fa = ba_[static_cast<std::size_t>(c.a[1])];
    LRBSpline<2>& Fb = bb_[static_cast<std::size_t>(c.b[1])];
    const double hA = a1 - Ea.knots[0].front(), hB = Eb.knots[0].back() - a1;
    const double al = hB / (hA + hB), be = hA / (hA + hB), n = al * al + be * be;
    for (int j = 0; j < stride; ++j) {
      const auto J = static_cast<std::size_t>(j);
      const double fa = Fa.gamma * Fa.coef[J], fb = Fb.gamma * Fb.coef[J];
      const double r = dE[J] - al * fa - be * fb;
      dFa[J] = fa + al * r / n;
      dFb[J] = fb + be * r / n;
    }
    set(Fa, dFa);
    set(Fb, dFb);
  }
  Stitched out{from_canonical(rebuilt(A, std::move(ba_)), ca), from_canonical(rebuilt(B, std::move(bb_)), ca), m.a,
               options.continuity, m.gap, moved};
  return out;
}

LRSpline<2> merge(const Stitched& s) {
  const Canonical ca = canonical(s.seam);
  const LRSpline<2> A = to_canonical(s.first, ca), B = to_canonical(s.second, ca);
  const double a1 = A.domain().hi[0];
  require(B.domain().lo[0] == a1 && B.domain().lo[1] == A.domain().lo[1] && B.domain().hi[1] == A.domain().hi[1] &&
              A.degrees() == B.degrees(),
          "merge: the patches are not stitched along a common side");
  const int rows = s.continuity == Continuity::C1 ? 2 : 1, p = A.degree(0);
  const std::vector<Column> cols = seam_columns(A, B, rows);
  std::vector<char> drop_a(static_cast<std::size_t>(A.num_basis()), 0), drop_b(static_cast<std::size_t>(B.num_basis()), 0);
  for (const Column& c : cols)
    for (int r = 0; r < rows; ++r) {
      drop_a[static_cast<std::size_t>(c.a[static_cast<std::size_t>(r)])] = 1;
      drop_b[static_cast<std::size_t>(c.b[static_cast<std::size_t>(r)])] = 1;
    }
  std::vector<LRBSpline<2>> basis;
  for (int i = 0; i < A.num_basis(); ++i)
    if (!drop_a[static_cast<std::size_t>(i)]) basis.push_back(A.basis_function(i));
  for (int i = 0; i < B.num_basis(); ++i)
    if (!drop_b[static_cast<std::size_t>(i)]) basis.push_back(B.basis_function(i));
  // The B-splines across the seam: the knots of both sides with p (C0) or p - 1 (C1) copies of the seam.
  for (const Column& c : cols) {
    const LRBSpline<2>& Ea = A.basis_function(c.a[0]);
    const LRBSpline<2>& Eb = B.basis_function(c.b[0]);
    if (rows == 1) {
      LRBSpline<2> f = Ea;
      f.knots[0].assign(static_cast<std::size_t>(p), a1);
      f.knots[0].insert(f.knots[0].begin(), Ea.knots[0].front());
      f.knots[0].push_back(Eb.knots[0].back());
      basis.push_back(std::move(f));
      continue;
    }
    const LRBSpline<2>& Fa = A.basis_function(c.a[1]);
    const LRBSpline<2>& Fb = B.basis_function(c.b[1]);
    LRBSpline<2> f = Fa, g = Fb;
    f.knots[0] = {Fa.knots[0][0], Fa.knots[0][1]};
    f.knots[0].insert(f.knots[0].end(), static_cast<std::size_t>(p - 1), a1);
    f.knots[0].push_back(Eb.knots[0].back());
    g.knots[0] = {Ea.knots[0].front()};
    g.knots[0].insert(g.knots[0].end(), static_cast<std::size_t>(p - 1), a1);
    g.knots[0].push_back(Fb.knots[0][static_cast<std::size_t>(p)]);
    g.knots[0].push_back(Fb.knots[0][static_cast<std::size_t>(p + 1)]);
    basis.push_back(std::move(f));
    basis.push_back(std::move(g));
  }
  std::vector<MeshRectangle<2>> mesh;
  for (const auto* side : {&A, &B})
    for (const MeshRectangle<2>& r : side->mesh())
      if (!(r.dir == 0 && r.value == a1)) mesh.push_back(r);
  const int seam_mult = rows == 1 ? p : p - 1;
  if (seam_mult > 0)
    mesh.push_back(MeshRectangle<2>::make(0, a1, {a1, A.domain().lo[1]}, {a1, A.domain().hi[1]}, seam_mult));
  return from_canonical(LRSpline<2>(A.degrees(), A.dim(), A.is_rational(), std::move(basis), std::move(mesh)), ca);
}

}  // namespace trivar
