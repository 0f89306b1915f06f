#include "trivar/fit/patch_stitching.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <iterator>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/fit/seam_weights.hpp"

namespace trivar {

namespace {

// The LR spline with new parameters: new direction k takes old direction src[k], every value mapped by
// map(k, value); reversed[k] when that map decreases.
template <int D>
LRSpline<D> remap(const LRSpline<D>& s, std::array<int, D> src, std::array<bool, D> reversed,
                  const std::function<double(int, double)>& map) {
  std::array<int, D> to_new{};
  for (int k = 0; k < D; ++k) to_new[static_cast<std::size_t>(src[static_cast<std::size_t>(k)])] = k;
  std::vector<LRBSpline<D>> basis;
  basis.reserve(static_cast<std::size_t>(s.num_basis()));
  for (const LRBSpline<D>& b : s.basis_functions()) {
    LRBSpline<D> n = b;
    for (int k = 0; k < D; ++k) {
      auto& t = n.knots[static_cast<std::size_t>(k)];
      t = b.knots[static_cast<std::size_t>(src[static_cast<std::size_t>(k)])];
      for (double& x : t) x = map(k, x);
      if (reversed[static_cast<std::size_t>(k)]) std::reverse(t.begin(), t.end());
    }
    basis.push_back(std::move(n));
  }
  std::vector<MeshRectangle<D>> mesh;
  for (const MeshRectangle<D>& r : s.mesh()) {
    const int k = to_new[static_cast<std::size_t>(r.dir)];
    Param<D> a{}, b{};
    for (int o = 0; o < D; ++o) {
      if (o == k) continue;
      const int old_o = src[static_cast<std::size_t>(o)];
      double lo = map(o, r.extent.lo[old_o]), hi = map(o, r.extent.hi[old_o]);
      if (lo > hi) std::swap(lo, hi);
      a[o] = lo;
      b[o] = hi;
    }
    mesh.push_back(MeshRectangle<D>::make(k, map(k, r.value), a, b, r.multiplicity));
  }
  Ints<D> degrees{};
  for (int k = 0; k < D; ++k) degrees[k] = s.degree(src[static_cast<std::size_t>(k)]);
  return LRSpline<D>(degrees, s.dim(), s.is_rational(), std::move(basis), std::move(mesh));
}

// True when the permutation is odd.
template <std::size_t N>
bool odd(const std::array<int, N>& perm) {
  bool o = false;
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = i + 1; j < N; ++j) o = o != (perm[i] > perm[j]);
  return o;
}

// The exact map (permutation and sign changes only) taking `seam` of s to the side u = hi, orientation kept:
// directions rotated cyclically so that the seam's comes first, the seam's and (if the rotation is odd) the
// first along it negated.
template <int D>
struct Canonical {
  std::array<int, D> src{};
  std::array<bool, D> negate{};
};

template <int D>
Canonical<D> canonical(DomainSide seam) {
  Canonical<D> c;
  for (int k = 0; k < D; ++k) c.src[static_cast<std::size_t>(k)] = (seam.dir + k) % D;
  c.negate[0] = seam.end == 0;
  c.negate[1] = c.negate[0] != odd(c.src);
  return c;
}

template <int D>
bool identity(const Canonical<D>& c) {
  for (int k = 0; k < D; ++k)
    if (c.src[static_cast<std::size_t>(k)] != k || c.negate[static_cast<std::size_t>(k)]) return false;
  return true;
}

template <int D>
LRSpline<D> to_canonical(const LRSpline<D>& s, const Canonical<D>& c) {
  if (identity(c)) return s;
  return remap<D>(s, c.src, c.negate, [&](int k, double x) { return c.negate[static_cast<std::size_t>(k)] ? -x : x; });
}

template <int D>
LRSpline<D> from_canonical(const LRSpline<D>& s, const Canonical<D>& c) {
  if (identity(c)) return s;
  std::array<int, D> src{};
  std::array<bool, D> negate{};
  for (int k = 0; k < D; ++k) {
    src[static_cast<std::size_t>(c.src[static_cast<std::size_t>(k)])] = k;
    negate[static_cast<std::size_t>(c.src[static_cast<std::size_t>(k)])] = c.negate[static_cast<std::size_t>(k)];
  }
  return remap<D>(s, src, negate, [&](int k, double x) { return negate[static_cast<std::size_t>(k)] ? -x : x; });
}

// x in [f0, f1] to [g0, g1], the ends exactly.
double lerp_exact(double x, double f0, double f1, double g0, double g1) {
  if (x == f0) return g0;
  if (x == f1) return g1;
  return g0 + (x - f0) / (f1 - f0) * (g1 - g0);
}

// How the second patch's side corresponds to the first's: the first's i-th direction along its side (ascending)
// is the second's perm[i]-th along its side, reversed[i] when they run against each other.
template <int D>
struct SideMatch {
  DomainSide a, b;
  std::array<int, D - 1> perm{};
  std::array<bool, D - 1> reversed{};
  double gap = HUGE_VAL, ends_gap = HUGE_VAL;
};

// The side's values on an n^(D-1) grid (first along direction fastest).
template <int D>
std::vector<double> side_grid(const LRSpline<D>& s, DomainSide side, int n) {
  const auto along = along_directions<D>(side);
  int total = 1;
  for (int i = 0; i < D - 1; ++i) total *= n;
  std::vector<double> out(static_cast<std::size_t>(total * s.dim()));
  for (int g = 0; g < total; ++g) {
    Param<D> u{};
    u[side.dir] = side.value(s);
    for (int i = 0, r = g; i < D - 1; ++i, r /= n) {
      const int a = along[static_cast<std::size_t>(i)];
      u[a] = s.domain().lo[a] + (r % n) / double(n - 1) * (s.domain().hi[a] - s.domain().lo[a]);
    }
    s.eval(u, out.data() + static_cast<std::ptrdiff_t>(g) * s.dim());
  }
  return out;
}

// The pair of sides (and correspondence along them) closest as curves or surfaces: largest distance at
// corresponding grid points.
template <int D>
SideMatch<D> closest_sides(const LRSpline<D>& A, const LRSpline<D>& B) {
  const int n = D == 2 ? 33 : 9, dim = A.dim();
  int total = 1;
  for (int i = 0; i < D - 1; ++i) total *= n;
  std::array<int, D - 1> perm{};
  for (int i = 0; i < D - 1; ++i) perm[static_cast<std::size_t>(i)] = i;
  std::vector<std::array<int, D - 1>> perms;
  do perms.push_back(perm);
  while (std::next_permutation(perm.begin(), perm.end()));
  SideMatch<D> best;
  for (int sa = 0; sa < 2 * D; ++sa) {
    const DomainSide da{sa / 2, sa % 2};
    const std::vector<double> pa = side_grid(A, da, n);
    for (int sb = 0; sb < 2 * D; ++sb) {
      const DomainSide db{sb / 2, sb % 2};
      const std::vector<double> pb = side_grid(B, db, n);
      for (const auto& pm : perms)
        for (int rev = 0; rev < (1 << (D - 1)); ++rev) {
          SideMatch<D> m{da, db, pm, {}, 0.0, 0.0};
          for (int i = 0; i < D - 1; ++i) m.reversed[static_cast<std::size_t>(i)] = (rev >> i) & 1;
          for (int g = 0; g < total; ++g) {
            int gb = 0, stride = 1;
            std::array<int, D - 1> gbi{};
            bool corner = true;
            for (int i = 0, r = g; i < D - 1; ++i, r /= n) {
              const int x = r % n;
              corner = corner && (x == 0 || x == n - 1);
              gbi[static_cast<std::size_t>(pm[static_cast<std::size_t>(i)])] = m.reversed[static_cast<std::size_t>(i)] ? n - 1 - x : x;
            }
            for (int i = 0; i < D - 1; ++i, stride *= n) gb += gbi[static_cast<std::size_t>(i)] * stride;
            const double d = point_distance(pa.data() + static_cast<std::ptrdiff_t>(g) * dim, pb.data() + static_cast<std::ptrdiff_t>(gb) * dim, dim);
            m.gap = std::max(m.gap, d);
            if (corner) m.ends_gap = std::max(m.ends_gap, d);
          }
          if (m.gap < best.gap) best = m;
        }
    }
  }
  return best;
}

const char* side_name(DomainSide s) {
  static const char* names[3][2] = {{"u = lo", "u = hi"}, {"v = lo", "v = hi"}, {"w = lo", "w = hi"}};
  return names[s.dir][s.end];
}

// The first rows on both sides of the seam of two canonical patches (first's seam at u = hi, second's at
// u = lo), matched by their knots along the seam.
struct Column {
  std::array<int, 2> a{-1, -1}, b{-1, -1};  // [row]: ids in first / second
};

template <int D>
std::vector<double> knots_along_seam(const LRBSpline<D>& f) {
  std::vector<double> key;
  for (int k = 1; k < D; ++k) key.insert(key.end(), f.knots[static_cast<std::size_t>(k)].begin(), f.knots[static_cast<std::size_t>(k)].end());
  return key;
}

template <int D>
std::vector<Column> seam_columns(const LRSpline<D>& A, const LRSpline<D>& B, int rows) {
  std::map<std::vector<double>, Column> columns;
  for (int r = 0; r < rows; ++r) {
    for (int id : side_row(A, {0, 1}, r)) columns[knots_along_seam(A.basis_function(id))].a[static_cast<std::size_t>(r)] = id;
    for (int id : side_row(B, {0, 0}, r)) columns[knots_along_seam(B.basis_function(id))].b[static_cast<std::size_t>(r)] = id;
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

template <int D>
std::vector<LRBSpline<D>> basis_copy(const LRSpline<D>& s) {
  return {s.basis_functions().begin(), s.basis_functions().end()};
}

template <int D>
LRSpline<D> rebuilt(const LRSpline<D>& s, std::vector<LRBSpline<D>> basis) {
  return LRSpline<D>(s.degrees(), s.dim(), s.is_rational(), std::move(basis), s.mesh());
}

// The weight function of a rational LR spline, as a polynomial one with one coordinate (same B-splines).
template <int D>
LRSpline<D> weight_function(const LRSpline<D>& s) {
  std::vector<LRBSpline<D>> basis = basis_copy(s);
  for (LRBSpline<D>& f : basis) f.coef = {f.coef[static_cast<std::size_t>(s.dim())]};
  return LRSpline<D>(s.degrees(), 1, false, std::move(basis), s.mesh());
}

// Both sides' trace knots in each direction, the larger multiplicity where both hold a value.
template <int D>
SideKnots<D> knot_union(const SideKnots<D>& x, const SideKnots<D>& y) {
  SideKnots<D> out;
  for (int k = 0; k < D; ++k) {
    std::map<double, int> m;
    for (const auto* side : {&x, &y})
      for (const auto& [value, mult] : (*side)[static_cast<std::size_t>(k)]) m[value] = std::max(m[value], mult);
    out[static_cast<std::size_t>(k)].assign(m.begin(), m.end());
  }
  return out;
}

}  // namespace

template <int D>
Stitched<D> stitch(const LRSpline<D>& first, const LRSpline<D>& second, const StitchOptions& options) {
  require(first.is_rational() == second.is_rational(),
          "stitch: one patch is rational and the other is not (give both as NURBS, weights 1 where polynomial)");
  // Rational C1 keeps the weights and enforces C1 on the homogeneous coordinates w x (seam_weights.hpp), which is
  // C1 of the rational map only when the weights are C1 across the seam already: pieces of one NURBS are. C1 of
  // the homogeneous patches alone is not C1 of the rational ones (two exact circular arcs meeting tangentially
  // have opposite weight derivatives at the joint), and moving the weights would move the geometry elsewhere; a
  // Moebius reparametrisation that matches the weight derivatives first would be needed. So weights that are not
  // C1 across the seam are refused, naming the jump.
  const bool rational_c1 = first.is_rational() && options.continuity == Continuity::C1;
  require(first.dim() == second.dim(), [&] {
    return "stitch: the patches have " + std::to_string(first.dim()) + " and " + std::to_string(second.dim()) +
           " coordinates";
  });
  const double tol = options.tolerance > 0 ? options.tolerance
                                           : 1e-8 * std::max({control_net_diagonal(first), control_net_diagonal(second), 1e-300});
  const SideMatch<D> m = closest_sides(first, second);
  require(m.gap <= tol, [&] {
    if (m.ends_gap <= tol)
      return "stitch: the sides " + std::string(side_name(m.a)) + " of the first patch and " + side_name(m.b) +
             " of the second meet at the corners but differ in between by " + format_number(m.gap) +
             " (different curves or surfaces, or parametrisations that do not correspond linearly)";
    return "stitch: the patches share no side (closest sides differ by " + format_number(m.gap) +
           ", tolerance " + format_number(tol) + ")";
  });
  const auto along_a = along_directions<D>(m.a), along_b = along_directions<D>(m.b);
  for (int i = 0; i < D - 1; ++i) {
    const int pa = first.degree(along_a[static_cast<std::size_t>(i)]);
    const int pb = second.degree(along_b[static_cast<std::size_t>(m.perm[static_cast<std::size_t>(i)])]);
    const int qa = first.degree(m.a.dir), qb = second.degree(m.b.dir);
    require(pa == pb && qa == qb, [&] {
      return "stitch: degrees differ: the first patch has degree " + std::to_string(pa) + " along the shared side and " +
             std::to_string(qa) + " across it, the second " + std::to_string(pb) + " and " + std::to_string(qb) +
             " (elevate one first)";
    });
  }
  const Canonical<D> ca = canonical<D>(m.a);
  LRSpline<D> A = to_canonical(first, ca);
  const double a1 = A.domain().hi[0];

  // The second patch beyond u = a1, its side on A's side point by point, scaled across the seam by 1 / lambda.
  // Canonical direction k >= 1 is first's original direction ca.src[k], the i-th along its side, which is the
  // second's along_b[perm[i]].
  const int bd = m.b.dir;
  const double blo = second.domain().lo[bd], bhi = second.domain().hi[bd], len = bhi - blo;
  const bool across_reversed = m.b.end == 1;
  std::array<int, D> src{};
  std::array<bool, D> flip{};
  src[0] = bd;
  flip[0] = across_reversed;
  for (int k = 1; k < D; ++k) {
    const auto i = static_cast<std::size_t>(
        std::find(along_a.begin(), along_a.end(), ca.src[static_cast<std::size_t>(k)]) - along_a.begin());
    src[static_cast<std::size_t>(k)] = along_b[static_cast<std::size_t>(m.perm[i])];
    flip[static_cast<std::size_t>(k)] = m.reversed[i] != ca.negate[static_cast<std::size_t>(k)];
  }
  bool orientation_flipped = odd(src);
  for (bool f : flip) orientation_flipped = orientation_flipped != f;
  require(!orientation_flipped, [&] {
    return std::string("stitch: the second patch has the opposite orientation to the first along their shared side (") +
           (D == 2 ? "its normal points the other way" : "its Jacobian has the other sign") +
           "); reverse one of its parameter directions first";
  });
  auto place = [&](double length) {
    const double g_end = a1 + length;
    return remap<D>(second, src, flip, [&, g_end](int k, double x) {
      if (k == 0) return across_reversed ? lerp_exact(x, blo, bhi, g_end, a1) : lerp_exact(x, blo, bhi, a1, g_end);
      const int o = src[static_cast<std::size_t>(k)];
      const double slo = second.domain().lo[o], shi = second.domain().hi[o];
      const double c0 = A.domain().lo[k], c1 = A.domain().hi[k];
      return flip[static_cast<std::size_t>(k)] ? lerp_exact(x, slo, shi, c1, c0) : lerp_exact(x, slo, shi, c0, c1);
    });
  };
  // lambda: the factor by which the second patch's derivative across the seam (placed with its own length) must
  // be scaled to best match the first's; the second is then placed with length len / lambda.
  double lambda = 1.0;
  {
    const LRSpline<D> B1 = place(len);
    const int n = D == 2 ? 17 : 7, dim = A.dim();
    int total = 1;
    for (int i = 0; i < D - 1; ++i) total *= n;
    std::vector<double> da(static_cast<std::size_t>((D + 1) * dim)), db(da.size());
    double ab = 0, bb = 0;
    for (int g = 0; g < total; ++g) {
      Param<D> u{};
      u[0] = a1;
      for (int k = 1, r = g; k < D; ++k, r /= n)
        u[k] = A.domain().lo[k] + (r % n) / double(n - 1) * (A.domain().hi[k] - A.domain().lo[k]);
      A.eval_first_derivatives(u, da.data());
      B1.eval_first_derivatives(u, db.data());
      for (int j = 0; j < dim; ++j) {
        const double x = da[static_cast<std::size_t>(dim + j)], y = db[static_cast<std::size_t>(dim + j)];
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
    if (rational_c1) {
      // Weights kept: the speed that makes them C1 is the only one under which the rational patches can be C1
      // (a bent first row would bias the geometric fit). Fitted like the geometric one, after the second's
      // weights are scaled to meet the first's along the seam; used when the weights' cross derivative is more
      // than rounding, the check below then decides.
      const LRSpline<D> Aw = weight_function(A), Bw = weight_function(B1);
      double w[D + 1], wab = 0, wbb = 0, gab = 0, gbb = 0, wmax = 0, gmax = 0;
      for (int g = 0; g < total; ++g) {
        Param<D> u{};
        u[0] = a1;
        for (int k = 1, r = g; k < D; ++k, r /= n)
          u[k] = A.domain().lo[k] + (r % n) / double(n - 1) * (A.domain().hi[k] - A.domain().lo[k]);
        Aw.eval_first_derivatives(u, w);
        const double wa = w[0], ga = w[1];
        Bw.eval_first_derivatives(u, w);
        wab += wa * w[0];
        wbb += w[0] * w[0];
        gab += ga * w[1];
        gbb += w[1] * w[1];
        wmax = std::max(wmax, std::abs(wa));
        gmax = std::max(gmax, std::abs(w[1]));
      }
      // factor * lw * (second's weight derivative) best matches the first's, factor scaling the weights.
      const double factor = wab / wbb, lw = gab / gbb / factor;
      if (gbb > 0 && std::isfinite(lw) && lw > 0 && factor * gmax * A.domain().extent(0) > 1e-10 * wmax) lambda = lw;
    }
  }
  LRSpline<D> B = place(len / lambda);

  // Adapt the knot lines of each side to the other's over the rows the continuity involves.
  const int rows = options.continuity == Continuity::C1 ? 2 : 1;
  const SideKnots<D> both = knot_union<D>(side_trace_knots(A, {0, 1}), side_trace_knots(B, {0, 0}));
  insert_side_knot_lines(A, {0, 1}, both, rows);
  insert_side_knot_lines(B, {0, 0}, both, rows);
  require(side_trace_knots(A, {0, 1}) == side_trace_knots(B, {0, 0}),
          "stitch: the knot lines of the shared side could not be matched");

  const std::vector<Column> cols = seam_columns(A, B, rows);
  std::vector<LRBSpline<D>> ba_ = basis_copy(A), bb_ = basis_copy(B);
  // Rational patches (C0): equal homogeneous (w x, w) seam values give equal rational ones, and a rational
  // patch keeps its geometry when all its weights are scaled by one factor; so the second patch's weights are
  // first scaled to meet the first's along the seam (least squares over the seam B-splines; the same curve has
  // proportional weights), then the seam values are averaged in homogeneous form.
  const int dim = A.dim(), stride = dim + (A.is_rational() ? 1 : 0);
  if (A.is_rational()) {
    double ab = 0, bb = 0, wmax = 0;
    for (const Column& c : cols) {
      const LRBSpline<D>& Ea = ba_[static_cast<std::size_t>(c.a[0])];
      const LRBSpline<D>& Eb = bb_[static_cast<std::size_t>(c.b[0])];
      const double wa = Ea.gamma * Ea.coef[static_cast<std::size_t>(dim)], wb = Eb.gamma * Eb.coef[static_cast<std::size_t>(dim)];
      ab += wa * wb;
      bb += wb * wb;
      wmax = std::max(wmax, std::abs(wa));
    }
    const double factor = ab / bb;
    for (const Column& c : cols) {
      const LRBSpline<D>& Ea = ba_[static_cast<std::size_t>(c.a[0])];
      const LRBSpline<D>& Eb = bb_[static_cast<std::size_t>(c.b[0])];
      const double wa = Ea.gamma * Ea.coef[static_cast<std::size_t>(dim)], wb = Eb.gamma * Eb.coef[static_cast<std::size_t>(dim)];
      require(std::abs(wa - factor * wb) <= 1e-8 * wmax, [&] {
        return "stitch: the weights along the shared side are not proportional (" + format_number(wa) + " against " +
               format_number(factor * wb) + " after scaling): the sides are different rational curves";
      });
    }
    for (LRBSpline<D>& f : bb_)
      for (double& x : f.coef) x *= factor;
  }
  // Rational C1: the weights must be C1 across the seam (per column, from the control values: the derivative
  // across of row 0 and 1's combination); the column furthest from it is named. The weights then stay as they
  // are and only w x moves.
  if (rational_c1) {
    const int p = A.degree(0);
    double worst = -1, out_of = 0, into = 0, weight = 0;
    for (const Column& c : cols) {
      const LRBSpline<D>& Ea = ba_[static_cast<std::size_t>(c.a[0])];
      const LRBSpline<D>& Eb = bb_[static_cast<std::size_t>(c.b[0])];
      const LRBSpline<D>& Fa = ba_[static_cast<std::size_t>(c.a[1])];
      const LRBSpline<D>& Fb = bb_[static_cast<std::size_t>(c.b[1])];
      const auto W = static_cast<std::size_t>(dim);
      const double hA = a1 - Ea.knots[0].front(), hB = Eb.knots[0].back() - a1;
      const double wE = Ea.gamma * Ea.coef[W];
      const double da = p * (wE - Fa.gamma * Fa.coef[W]) / hA, db = p * (Fb.gamma * Fb.coef[W] - Eb.gamma * Eb.coef[W]) / hB;
      const double excess = std::abs(da - db) / (std::abs(da) + std::abs(db) + std::abs(wE) / A.domain().extent(0));
      if (excess > worst) {
        worst = excess;
        out_of = da;
        into = db;
        weight = wE;
      }
    }
    require_weights_c1(out_of, into, weight, A.domain().extent(0), [] { return std::string("stitch"); },
                       "the shared side");
  }
  const int moving = rational_c1 ? dim : stride;  // the coordinates that move
  double moved = 0;
  auto set = [&](LRBSpline<D>& f, const std::vector<double>& d) {  // d: gamma-weighted values
    for (int j = 0; j < moving; ++j) {
      const double c = d[static_cast<std::size_t>(j)] / f.gamma;
      moved = std::max(moved, std::abs(c - f.coef[static_cast<std::size_t>(j)]));
      f.coef[static_cast<std::size_t>(j)] = c;
    }
  };
  std::vector<double> dE(static_cast<std::size_t>(stride)), dFa(dE.size()), dFb(dE.size());
  for (const Column& c : cols) {
    LRBSpline<D>& Ea = ba_[static_cast<std::size_t>(c.a[0])];
    LRBSpline<D>& Eb = bb_[static_cast<std::size_t>(c.b[0])];
    for (int j = 0; j < moving; ++j)
      dE[static_cast<std::size_t>(j)] = 0.5 * (Ea.gamma * Ea.coef[static_cast<std::size_t>(j)] +
                                               Eb.gamma * Eb.coef[static_cast<std::size_t>(j)]);
    set(Ea, dE);
    set(Eb, dE);
    if (rows < 2) continue;
    LRBSpline<D>& Fa = ba_[static_cast<std::size_t>(c.a[1])];
    LRBSpline<D>& Fb = bb_[static_cast<std::size_t>(c.b[1])];
    const double hA = a1 - Ea.knots[0].front(), hB = Eb.knots[0].back() - a1;
    const double al = hB / (hA + hB), be = hA / (hA + hB), n = al * al + be * be;
    for (int j = 0; j < moving; ++j) {
      const auto J = static_cast<std::size_t>(j);
      const double fa = Fa.gamma * Fa.coef[J], fb = Fb.gamma * Fb.coef[J];
      const double r = dE[J] - al * fa - be * fb;
      dFa[J] = fa + al * r / n;
      dFb[J] = fb + be * r / n;
    }
    set(Fa, dFa);
    set(Fb, dFb);
  }
  return Stitched<D>{from_canonical(rebuilt(A, std::move(ba_)), ca), from_canonical(rebuilt(B, std::move(bb_)), ca),
                     m.a, options.continuity, m.gap, moved};
}

template <int D>
LRSpline<D> merge(const Stitched<D>& s) {
  const Canonical<D> ca = canonical<D>(s.seam);
  const LRSpline<D> A = to_canonical(s.first, ca), B = to_canonical(s.second, ca);
  const double a1 = A.domain().hi[0];
  bool common = B.domain().lo[0] == a1 && A.degrees() == B.degrees();
  for (int k = 1; k < D; ++k)
    common = common && B.domain().lo[k] == A.domain().lo[k] && B.domain().hi[k] == A.domain().hi[k];
  require(common, "merge: the patches are not stitched along a common side");
  const int rows = s.continuity == Continuity::C1 ? 2 : 1, p = A.degree(0);
  const std::vector<Column> cols = seam_columns(A, B, rows);
  std::vector<char> drop_a(static_cast<std::size_t>(A.num_basis()), 0), drop_b(static_cast<std::size_t>(B.num_basis()), 0);
  for (const Column& c : cols)
    for (int r = 0; r < rows; ++r) {
      drop_a[static_cast<std::size_t>(c.a[static_cast<std::size_t>(r)])] = 1;
      drop_b[static_cast<std::size_t>(c.b[static_cast<std::size_t>(r)])] = 1;
    }
  std::vector<LRBSpline<D>> basis;
  for (int i = 0; i < A.num_basis(); ++i)
    if (!drop_a[static_cast<std::size_t>(i)]) basis.push_back(A.basis_function(i));
  for (int i = 0; i < B.num_basis(); ++i)
    if (!drop_b[static_cast<std::size_t>(i)]) basis.push_back(B.basis_function(i));
  // The B-splines across the seam: the knots of both sides with p (C0) or p - 1 (C1) copies of the seam.
  for (const Column& c : cols) {
    const LRBSpline<D>& Ea = A.basis_function(c.a[0]);
    const LRBSpline<D>& Eb = B.basis_function(c.b[0]);
    if (rows == 1) {
      LRBSpline<D> f = Ea;
      f.knots[0].assign(static_cast<std::size_t>(p), a1);
      f.knots[0].insert(f.knots[0].begin(), Ea.knots[0].front());
      f.knots[0].push_back(Eb.knots[0].back());
      basis.push_back(std::move(f));
      continue;
    }
    const LRBSpline<D>& Fa = A.basis_function(c.a[1]);
    const LRBSpline<D>& Fb = B.basis_function(c.b[1]);
    LRBSpline<D> f = Fa, g = Fb;
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
  std::vector<MeshRectangle<D>> mesh;
  for (const auto* side : {&A, &B})
    for (const MeshRectangle<D>& r : side->mesh())
      if (!(r.dir == 0 && r.value == a1)) mesh.push_back(r);
  const int seam_mult = rows == 1 ? p : p - 1;
  if (seam_mult > 0) mesh.push_back(MeshRectangle<D>::make(0, a1, A.domain().lo, A.domain().hi, seam_mult));
  return from_canonical(LRSpline<D>(A.degrees(), A.dim(), A.is_rational(), std::move(basis), std::move(mesh)), ca);
}

template Stitched<2> stitch(const LRSpline<2>&, const LRSpline<2>&, const StitchOptions&);
template Stitched<3> stitch(const LRSpline<3>&, const LRSpline<3>&, const StitchOptions&);
template LRSpline<2> merge(const Stitched<2>&);
template LRSpline<3> merge(const Stitched<3>&);

}  // namespace trivar
