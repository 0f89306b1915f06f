#include "trivar/fit/multiblock_space.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <type_traits>
#include <utility>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/iga/refined_quadrature.hpp"

namespace trivar {

namespace {

std::string where(int i, DomainSide s) {
  static const char* names[3][2] = {{"u = lo", "u = hi"}, {"v = lo", "v = hi"}, {"w = lo", "w = hi"}};
  return "block " + std::to_string(i) + " side " + names[s.dir][s.end];
}

// The point of the side at the face parameters of u (u[side.dir] is set to the side).
template <int D>
Param<D> on_face(const LRSpline<D>& s, DomainSide side, Param<D> u) {
  u[side.dir] = side.value(s);
  return u;
}

// The side's point closest to x (samples, then Gauss-Newton in the side's parameters); false when farther than
// tol. Parameters within rounding of the side's ends or its trace knots (`knots`) become those values exactly.
template <int D>
bool on_side(const LRSpline<D>& s, DomainSide side, const std::type_identity_t<SideKnots<D>>& knots, const double* x,
             double tol, Param<D>& u) {
  const auto dirs = along_directions<D>(side);
  const Box<D>& dom = s.domain();
  constexpr int n = D == 2 ? 65 : 17;
  int count = 1;
  for (int k = 1; k < D; ++k) count *= n;
  const int dim = s.dim();
  std::vector<double> buffer(static_cast<std::size_t>((D + 1) * dim));
  double* c = buffer.data();
  double best = HUGE_VAL;
  for (int g = 0; g < count; ++g) {
    Param<D> t = on_face(s, side, dom.lo);
    for (int k = 0, r = g; k < D - 1; ++k, r /= n) {
      const int a = dirs[static_cast<std::size_t>(k)];
      t[a] = dom.lo[a] + dom.extent(a) * (r % n) / (n - 1);
    }
    s.eval(t, c);
    const double d = point_distance(c, x, dim);
    if (d < best) best = d, u = t;
  }
  for (int it = 0; it < 30; ++it) {
    s.eval_first_derivatives(u, c);
    Eigen::Matrix<double, D - 1, D - 1> H;
    Eigen::Matrix<double, D - 1, 1> g;
    for (int k = 0; k < D - 1; ++k) {
      const double* dk = c + dim * (1 + dirs[static_cast<std::size_t>(k)]);
      g[k] = 0;
      for (int j = 0; j < dim; ++j) g[k] += (c[j] - x[j]) * dk[j];
      for (int l = 0; l < D - 1; ++l) {
        const double* dl = c + dim * (1 + dirs[static_cast<std::size_t>(l)]);
        H(k, l) = 0;
        for (int j = 0; j < dim; ++j) H(k, l) += dk[j] * dl[j];
      }
    }
    if (H.determinant() <= 0) break;
    const Eigen::Matrix<double, D - 1, 1> step = H.inverse() * g;
    Param<D> next = u;
    for (int k = 0; k < D - 1; ++k) {
      const int a = dirs[static_cast<std::size_t>(k)];
      next[a] = std::clamp(u[a] - step[k], dom.lo[a], dom.hi[a]);
    }
    if (next == u) break;
    u = next;
  }
  // A parameter within rounding of the side's ends or of one of its knots is that value exactly: a common part
  // found again on matched blocks must end on the very knots the first matching inserted.
  for (int a : dirs)
    for (const auto& [value, m] : knots[static_cast<std::size_t>(a)])
      if (std::abs(u[a] - value) <= 1e-10 * dom.extent(a)) u[a] = value;
  s.eval(u, c);
  return point_distance(c, x, dim) <= tol;
}

// A value within rounding of one of `knots` becomes that knot, so knots passed back and forth stay identical.
double snap(double t, const std::vector<std::pair<double, int>>& knots, double scale) {
  for (const auto& k : knots)
    if (std::abs(k.first - t) <= 1e-10 * scale) return k.first;
  return t;
}

// Direction a of side `from` and the direction of side `to` it runs along.
template <int D>
int to_dir(const BlockInterface<D>& f, int from, int a) {
  if (from == 0) return f.along[a];
  for (int b = 0; b < D; ++b)
    if (f.along[b] == a) return b;
  return -1;
}

// Parameter x in direction a of side `from` mapped to the corresponding direction of side `to`.
template <int D>
double map_value(const BlockInterface<D>& f, int from, int a, double x) {
  const int to = 1 - from, b = to_dir(f, from, a);
  const double l0 = f.lo[static_cast<std::size_t>(from)][a], h0 = f.hi[static_cast<std::size_t>(from)][a];
  const double l1 = f.lo[static_cast<std::size_t>(to)][b], h1 = f.hi[static_cast<std::size_t>(to)][b];
  if (x == l0) return l1;
  if (x == h0) return h1;
  return l1 + (x - l0) / (h0 - l0) * (h1 - l1);
}

template <int D>
Param<D> map_param(const BlockInterface<D>& f, int from, const Param<D>& x) {
  Param<D> y{};
  for (int a = 0; a < D; ++a) {
    if (a == f.side[static_cast<std::size_t>(from)].dir) continue;
    y[to_dir(f, from, a)] = map_value(f, from, a, x[a]);
  }
  y[f.side[static_cast<std::size_t>(1 - from)].dir] = f.lo[static_cast<std::size_t>(1 - from)][f.side[static_cast<std::size_t>(1 - from)].dir];
  return y;
}

// Faces that overlap with no corner of either on the other (a plus-shaped overlap: each crosses the other like
// the bars of a plus sign) share a part that no corner bounds; matching cannot find it, and leaving it out would
// make the blocks' boundary run through the model. Refused: interior points of face sj (a grid) that lie on face
// si inside its edges reveal it. Points outside si's control-net box (plus tol) are skipped cheaply.
template <int D>
void refuse_crossing_faces(const LRSpline<D>& A, int i, DomainSide si, const std::type_identity_t<SideKnots<D>>& knots_i,
                           const LRSpline<D>& C, int j, DomainSide sj, double tol) {
  const int dim = A.dim();
  std::vector<double> lo(static_cast<std::size_t>(dim), HUGE_VAL), hi(lo.size(), -HUGE_VAL);
  for (int id : side_row(A, si, 0))
    for (int k = 0; k < dim; ++k) {
      const double c = A.basis_function(id).coef[static_cast<std::size_t>(k)] / (A.is_rational() ? A.basis_function(id).coef.back() : 1.0);
      lo[static_cast<std::size_t>(k)] = std::min(lo[static_cast<std::size_t>(k)], c);
      hi[static_cast<std::size_t>(k)] = std::max(hi[static_cast<std::size_t>(k)], c);
    }
  const auto dc = along_directions<D>(sj), da = along_directions<D>(si);
  constexpr int n = 9;
  std::vector<double> x(static_cast<std::size_t>(dim));
  Param<D> t;
  for (int g = 0; g < n * n; ++g) {
    Param<D> u = on_face(C, sj, C.domain().lo);
    u[dc[0]] = C.domain().lo[dc[0]] + C.domain().extent(dc[0]) * (1 + g % n) / (n + 1);
    u[dc[1]] = C.domain().lo[dc[1]] + C.domain().extent(dc[1]) * (1 + g / n) / (n + 1);
    C.eval(u, x.data());
    bool near = true;
    for (int k = 0; k < dim; ++k)
      near = near && x[static_cast<std::size_t>(k)] >= lo[static_cast<std::size_t>(k)] - tol && x[static_cast<std::size_t>(k)] <= hi[static_cast<std::size_t>(k)] + tol;
    if (!near || !on_side(A, si, knots_i, x.data(), tol, t)) continue;
    bool inside = true;
    for (int a : da) inside = inside && t[a] > A.domain().lo[a] && t[a] < A.domain().hi[a];
    require(!inside, [&] {
      return "multiblock: " + where(i, si) + " and " + where(j, sj) + " overlap with no corner of either face on the "
             "other (a plus-shaped overlap); split one block at the other's edges";
    });
  }
}

// The common part of two sides, if they share one of positive measure. The corners of each side that lie on the
// other bound it (two diagonal corners at least: a side inside the other, sides offset along it); the directions
// correspond where the sides' tangents are parallel at such a corner, and the parametrisations must then agree
// linearly at every corner found and at interior points.
template <int D>
bool common_part(const std::vector<LRSpline<D>>& B, int i, DomainSide si, int j, DomainSide sj,
                 const std::type_identity_t<SideKnots<D>>& knots_i, const std::type_identity_t<SideKnots<D>>& knots_j,
                 double tol, BlockInterface<D>& out) {
  const LRSpline<D>& A = B[static_cast<std::size_t>(i)];
  const LRSpline<D>& C = B[static_cast<std::size_t>(j)];
  std::vector<std::pair<Param<D>, Param<D>>> hits;  // (on si, on sj)
  const int dim = A.dim();
  std::vector<double> xs(static_cast<std::size_t>((D + 1) * dim)), ys(xs.size());
  double* x = xs.data();
  double* y = ys.data();
  const auto corners = [](const LRSpline<D>& s, DomainSide side) {
    std::vector<Param<D>> cs;
    const auto dirs = along_directions<D>(side);
    for (int c = 0; c < (1 << (D - 1)); ++c) {
      Param<D> u = on_face(s, side, s.domain().lo);
      for (int k = 0; k < D - 1; ++k) {
        const int a = dirs[static_cast<std::size_t>(k)];
        u[a] = (c >> k) & 1 ? s.domain().hi[a] : s.domain().lo[a];
      }
      cs.push_back(u);
    }
    return cs;
  };
  Param<D> t;
  for (const Param<D>& c : corners(C, sj)) {
    C.eval(c, x);
    if (on_side(A, si, knots_i, x, tol, t)) hits.emplace_back(t, c);
  }
  for (const Param<D>& a : corners(A, si)) {
    A.eval(a, x);
    if (on_side(C, sj, knots_j, x, tol, t)) hits.emplace_back(a, t);
  }
  if (hits.size() < 2) {
    if (D == 3) refuse_crossing_faces(A, i, si, knots_i, C, j, sj, tol);
    return false;
  }
  const auto da = along_directions<D>(si), dc = along_directions<D>(sj);
  Param<D> lo = hits[0].first, hi = hits[0].first;
  for (const auto& h : hits)
    for (int a : da) lo[a] = std::min(lo[a], h.first[a]), hi[a] = std::max(hi[a], h.first[a]);
  for (int a : da)
    if (hi[a] - lo[a] <= 1e-9 * A.domain().extent(a)) return false;  // sides that touch along an edge or a corner
  // Corresponding directions: parallel tangents at the first corner found.
  out.block = {i, j};
  out.side = {si, sj};
  out.along[si.dir] = sj.dir;
  A.eval_first_derivatives(hits[0].first, x);
  C.eval_first_derivatives(hits[0].second, y);
  for (int a : da) {
    double best = 0;
    for (int c : dc) {
      const double* ta = x + dim * (1 + a);
      const double* tc = y + dim * (1 + c);
      double dot = 0, na = 0, nc = 0;
      for (int k = 0; k < dim; ++k) dot += ta[k] * tc[k], na += ta[k] * ta[k], nc += tc[k] * tc[k];
      const double cosine = std::abs(dot) / std::sqrt(na * nc);
      if (cosine > best) best = cosine, out.along[a] = c;
    }
  }
  const auto fail = [&] {
    return "multiblock: " + where(i, si) + " and " + where(j, sj) +
           " meet at the corners of a common part but differ in between (different curves or surfaces, or "
           "parametrisations that do not correspond linearly)";
  };
  // The corresponding corners: per direction, the other side's parameter at the smallest and largest hit.
  out.lo = {lo, on_face(C, sj, C.domain().lo)};
  out.hi = {hi, out.lo[1]};
  for (int a : da) {
    const int c = out.along[a];
    for (const auto& h : hits) {
      if (h.first[a] == lo[a]) out.lo[1][c] = h.second[c];
      if (h.first[a] == hi[a]) out.hi[1][c] = h.second[c];
    }
    require(out.lo[1][c] != out.hi[1][c], fail);
  }
  // Every corner found and interior points must correspond linearly.
  const double scale = std::max(A.domain().extent(da[0]), 1.0);
  for (const auto& h : hits) {
    const Param<D> m = map_param(out, 0, h.first);
    for (int c : dc) require(std::abs(m[c] - h.second[c]) <= 1e-8 * std::max(scale, C.domain().extent(c)), fail);
  }
  constexpr int n = D == 2 ? 16 : 6;
  int count = 1;
  for (int k = 1; k < D; ++k) count *= n - 1;
  for (int g = 0; g < count; ++g) {
    Param<D> u = lo;
    for (int k = 0, r = g; k < D - 1; ++k, r /= n - 1) {
      const int a = da[static_cast<std::size_t>(k)];
      u[a] = lo[a] + (hi[a] - lo[a]) * (1 + r % (n - 1)) / n;
    }
    A.eval(u, x);
    C.eval(map_param(out, 0, u), y);
    require(point_distance(x, y, dim) <= tol, fail);
  }
  for (int a : da)
    require(A.degree(a) == C.degree(out.along[a]), [&] {
      return "multiblock: " + where(i, si) + " and " + where(j, sj) + " have different degrees along their interface";
    });
  return true;
}

// Knot lines (planes) of the other side of interface f on the common part (side `to` receives them), and in
// `edges` the part's bounds where they lie inside the receiving side (a T-joint) with multiplicity p.
template <int D>
SideKnots<D> knots_for(const std::vector<LRSpline<D>>& B, const BlockInterface<D>& f, int to,
                       std::type_identity_t<SideKnots<D>>& edges) {
  const int from = 1 - to;
  const LRSpline<D>& R = B[static_cast<std::size_t>(f.block[static_cast<std::size_t>(to)])];
  const LRSpline<D>& S = B[static_cast<std::size_t>(f.block[static_cast<std::size_t>(from)])];
  const SideKnots<D> own = side_trace_knots(R, f.side[static_cast<std::size_t>(to)]);
  const SideKnots<D> theirs = side_trace_knots(S, f.side[static_cast<std::size_t>(from)]);
  SideKnots<D> out;
  for (int b : along_directions<D>(f.side[static_cast<std::size_t>(from)])) {
    const int a = to_dir(f, from, b);
    auto& k = out[static_cast<std::size_t>(a)];
    const double slo = std::min(f.lo[static_cast<std::size_t>(from)][b], f.hi[static_cast<std::size_t>(from)][b]);
    const double shi = std::max(f.lo[static_cast<std::size_t>(from)][b], f.hi[static_cast<std::size_t>(from)][b]);
    for (const auto& [s, m] : theirs[static_cast<std::size_t>(b)])
      if (s > slo && s < shi)
        k.emplace_back(snap(map_value(f, from, b, s), own[static_cast<std::size_t>(a)], R.domain().extent(a)), m);
    for (double e : {f.lo[static_cast<std::size_t>(to)][a], f.hi[static_cast<std::size_t>(to)][a]})
      edges[static_cast<std::size_t>(a)].emplace_back(e, R.degree(a));
  }
  return out;
}

// Where the neighbour's planes must reach on side `to` of interface f: across the supports of the B-splines of
// the first `rows` rows that meet the common part (those C0 at its edges reach one span beyond them, and their traces on the
// part must split like the neighbour's).
template <int D>
Box<D> planes_extent(const LRSpline<D>& s, const BlockInterface<D>& f, int to, int rows) {
  const auto t = static_cast<std::size_t>(to);
  Box<D> part = s.domain(), out = s.domain();
  for (int a : along_directions<D>(f.side[t])) {
    part.lo[a] = std::min(f.lo[t][a], f.hi[t][a]), part.hi[a] = std::max(f.lo[t][a], f.hi[t][a]);
    out.lo[a] = part.lo[a], out.hi[a] = part.hi[a];
  }
  std::vector<int> first;
  for (int r = 0; r < std::max(rows, 1); ++r) {
    const std::vector<int> row = side_row(s, f.side[t], r);
    first.insert(first.end(), row.begin(), row.end());
  }
  for (int id : first) {
    const auto& knots = s.basis_function(id).knots;
    bool meets = true;
    for (int a : along_directions<D>(f.side[t]))
      meets = meets && knots[static_cast<std::size_t>(a)].back() > part.lo[a] && knots[static_cast<std::size_t>(a)].front() < part.hi[a];
    if (!meets) continue;
    for (int a : along_directions<D>(f.side[t])) {
      out.lo[a] = std::min(out.lo[a], knots[static_cast<std::size_t>(a)].front());
      out.hi[a] = std::max(out.hi[a], knots[static_cast<std::size_t>(a)].back());
    }
  }
  return out;
}

struct UnionFind {
  std::vector<int> parent;
  int find(int a) {
    while (parent[static_cast<std::size_t>(a)] != a)
      a = parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
    return a;
  }
  void join(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

// The trace of a row-0 B-spline on the common part: per direction of side 0 along the side, its knots clamped to
// the part, in side 0's parameters.
template <int D>
using Trace = std::array<std::vector<double>, D - 1>;

// Row-0 B-splines of side `k` of interface f whose support meets the open common part, with their traces.
template <int D>
std::vector<std::pair<Trace<D>, int>> traces(const std::vector<LRSpline<D>>& B, const BlockInterface<D>& f, int k) {
  const auto kk = static_cast<std::size_t>(k);
  const LRSpline<D>& S = B[static_cast<std::size_t>(f.block[kk])];
  const auto dirs = along_directions<D>(f.side[kk]);
  const auto dirs0 = along_directions<D>(f.side[0]);
  std::vector<std::pair<Trace<D>, int>> out;
  for (int id : side_row(S, f.side[kk], 0)) {
    const LRBSpline<D>& b = S.basis_function(id);
    // Meeting the open part takes every direction (a support beside the part, touching it at an edge, may cross
    // the part's other edges without a C0 knot: those are only where the part is).
    bool meets = true;
    for (int a : dirs)
      meets = meets && b.knots[static_cast<std::size_t>(a)].back() > std::min(f.lo[kk][a], f.hi[kk][a]) &&
              b.knots[static_cast<std::size_t>(a)].front() < std::max(f.lo[kk][a], f.hi[kk][a]);
    if (!meets) continue;
    Trace<D> tr;
    for (int a : dirs) {
      const double lo = std::min(f.lo[kk][a], f.hi[kk][a]), hi = std::max(f.lo[kk][a], f.hi[kk][a]);
      std::vector<double> t = b.knots[static_cast<std::size_t>(a)];
      // Clamping the knots to the part gives the restriction only where the support ends there or is C0 there.
      for (double e : {lo, hi})
        require(!(t.front() < e && e < t.back()) || std::count(t.begin(), t.end(), e) >= S.degree(a), [&] {
          return "multiblock: " + where(f.block[kk], f.side[kk]) + " has a B-spline crossing the edge of its interface "
                 "with block " + std::to_string(f.block[1 - kk]) + " without a C0 knot there";
        });
      for (double& x : t) {
        x = std::clamp(x, lo, hi);
        if (k == 1) x = map_value(f, 1, a, x);
      }
      if (t.front() > t.back()) std::reverse(t.begin(), t.end());
      const int a0 = k == 0 ? a : to_dir(f, 1, a);
      const auto slot = static_cast<std::size_t>(std::find(dirs0.begin(), dirs0.end(), a0) - dirs0.begin());
      tr[slot] = std::move(t);
    }
    out.emplace_back(std::move(tr), id);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// True when the element side's box (directions along the side) lies within the common part of f on side k.
template <int D>
bool inside_part(const BlockInterface<D>& f, int k, DomainSide side, const Box<D>& box, double eps) {
  const auto kk = static_cast<std::size_t>(k);
  for (int a : along_directions<D>(side)) {
    const double lo = std::min(f.lo[kk][a], f.hi[kk][a]), hi = std::max(f.lo[kk][a], f.hi[kk][a]);
    if (box.lo[a] < lo - eps || box.hi[a] > hi + eps) return false;
  }
  return true;
}

}  // namespace

template <int D>
Param<D> interface_param(const BlockInterface<D>& f, int from, const Param<D>& u) {
  return map_param(f, from, u);
}

template <int D>
std::vector<BlockInterface<D>> match_blocks(std::vector<LRSpline<D>>& blocks, const MultiblockOptions& options, int rows) {
  const int nb = static_cast<int>(blocks.size());
  constexpr int S = 2 * D;  // sides per block
  require(nb >= 1, "multiblock: no blocks");
  double diag = 0;
  const auto degrees = [](const LRSpline<D>& s) {
    std::string t;
    for (int k = 0; k < D; ++k) t += (k ? ", " : "") + std::to_string(s.degree(k));
    return "(" + t + ")";
  };
  for (int b = 0; b < nb; ++b) {
    const LRSpline<D>& s = blocks[static_cast<std::size_t>(b)];
    require(s.degrees() == blocks[0].degrees(), [&] {
      return "multiblock: block " + std::to_string(b) + " has degrees " + degrees(s) + ", block 0 " + degrees(blocks[0]);
    });
    require(s.dim() == blocks[0].dim() && s.is_rational() == blocks[0].is_rational(), [&] {
      return "multiblock: block " + std::to_string(b) + " has " + std::to_string(s.dim()) + " coordinates" +
             (s.is_rational() ? " (rational)" : "") + ", block 0 " + std::to_string(blocks[0].dim()) +
             (blocks[0].is_rational() ? " (rational)" : "");
    });
    diag = std::max(diag, control_net_diagonal(s));
  }
  const double tol = options.tolerance > 0 ? options.tolerance : 1e-8 * diag;

  std::vector<BlockInterface<D>> interfaces;
  std::vector<std::array<SideKnots<D>, S>> trace_knots(static_cast<std::size_t>(nb));  // per block and side
  for (int b = 0; b < nb; ++b)
    for (int sd = 0; sd < S; ++sd)
      trace_knots[static_cast<std::size_t>(b)][static_cast<std::size_t>(sd)] = side_trace_knots(blocks[static_cast<std::size_t>(b)], DomainSide{sd / 2, sd % 2});
  for (int i = 0; i < nb; ++i)
    for (int j = i + 1; j < nb; ++j)
      for (int si = 0; si < S; ++si)
        for (int sj = 0; sj < S; ++sj) {
          BlockInterface<D> f;
          if (common_part(blocks, i, {si / 2, si % 2}, j, {sj / 2, sj % 2}, trace_knots[static_cast<std::size_t>(i)][static_cast<std::size_t>(si)],
                          trace_knots[static_cast<std::size_t>(j)][static_cast<std::size_t>(sj)], tol, f))
            interfaces.push_back(f);
        }

  // One point of a block found by several interfaces (a T-joint's corner projected from two neighbours) is one
  // parameter: bounds within rounding of a value seen before (or of the domain's ends) become that value, or the
  // block would get two knot planes an ulp apart.
  std::vector<std::array<std::vector<double>, D>> seen(static_cast<std::size_t>(nb));
  for (int b = 0; b < nb; ++b)
    for (int a = 0; a < D; ++a)
      seen[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)] = {blocks[static_cast<std::size_t>(b)].domain().lo[a],
                                                                        blocks[static_cast<std::size_t>(b)].domain().hi[a]};
  for (BlockInterface<D>& f : interfaces)
    for (std::size_t k = 0; k < 2; ++k) {
      const auto b = static_cast<std::size_t>(f.block[k]);
      for (int a : along_directions<D>(f.side[k])) {
        std::vector<double>& values = seen[b][static_cast<std::size_t>(a)];
        for (double* x : {&f.lo[k][a], &f.hi[k][a]}) {
          const auto near = std::find_if(values.begin(), values.end(), [&](double v) {
            return std::abs(v - *x) <= 1e-10 * blocks[b].domain().extent(a);
          });
          if (near != values.end()) *x = *near;
          else values.push_back(*x);
        }
      }
    }

  // Adjust the side knot lines until every interface's two traces agree (a line given to one block can be
  // passed on to a third one through another interface, hence the rounds).
  if (options.whole_lines) rows = 0;
  for (int round = 0;; ++round) {
    int changed = 0;
    for (const BlockInterface<D>& f : interfaces)
      for (int to = 0; to < 2; ++to) {
        // On volumes the neighbour's knots and the edges of the common part (C0 there) enter over the common part
        // only, widened to the first-row supports meeting it, so a block's face is refined where its neighbour
        // needs it (on surfaces the lines are points along the side: nothing to restrict).
        const auto t = static_cast<std::size_t>(to);
        LRSpline<D>& s = blocks[static_cast<std::size_t>(f.block[t])];
        SideKnots<D> edges;
        SideKnots<D> inner = knots_for(blocks, f, to, edges);
        if (D == 2 || options.whole_lines) {  // one LR refinement batch
          for (int a = 0; a < D; ++a)
            inner[static_cast<std::size_t>(a)].insert(inner[static_cast<std::size_t>(a)].end(), edges[static_cast<std::size_t>(a)].begin(),
                                                      edges[static_cast<std::size_t>(a)].end());
          changed += insert_side_knot_lines(s, f.side[t], inner, rows);
          continue;
        }
        const Box<D> part = planes_extent(s, f, to, rows);
        changed += insert_side_knot_lines(s, f.side[t], edges, rows, options.whole_face_edges ? nullptr : &part);
        changed += insert_side_knot_lines(s, f.side[t], inner, rows, &part);
      }
    if (changed == 0) break;
    require(round < 16, "multiblock: the interface knot lines did not settle");
  }
  return interfaces;
}

template <int D>
MultiblockSpace<D> multiblock_space(std::vector<LRSpline<D>> blocks, const MultiblockOptions& options) {
  const int nb = static_cast<int>(blocks.size());
  constexpr int S = 2 * D;  // sides per block
  for (int b = 0; b < nb; ++b) {
    const LRSpline<D>& s = blocks[static_cast<std::size_t>(b)];
    require(!s.is_rational() && s.dim() == D, [&] {
      return "multiblock: block " + std::to_string(b) + " is not a polynomial " +
             (D == 2 ? "planar surface (2 coordinates)" : "volume (3 coordinates)");
    });
  }
  MultiblockSpace<D> out;
  out.interfaces = match_blocks(blocks, options, 1);
  double diag = 0;
  for (const LRSpline<D>& s : blocks) diag = std::max(diag, control_net_diagonal(s));
  const double tol = options.tolerance > 0 ? options.tolerance : 1e-8 * diag;

  // Identify the traces across every interface.
  std::vector<int> offset(static_cast<std::size_t>(nb) + 1, 0);
  for (int b = 0; b < nb; ++b)
    offset[static_cast<std::size_t>(b) + 1] = offset[static_cast<std::size_t>(b)] + blocks[static_cast<std::size_t>(b)].num_basis();
  UnionFind uf;
  uf.parent.resize(static_cast<std::size_t>(offset.back()));
  std::iota(uf.parent.begin(), uf.parent.end(), 0);
  for (const BlockInterface<D>& f : out.interfaces) {
    const auto a = traces(blocks, f, 0), c = traces(blocks, f, 1);
    const double scale = blocks[static_cast<std::size_t>(f.block[0])].domain().extent(along_directions<D>(f.side[0])[0]);
    bool same = a.size() == c.size();
    for (std::size_t k = 0; same && k < a.size(); ++k)
      for (std::size_t d = 0; same && d < a[k].first.size(); ++d) {
        same = a[k].first[d].size() == c[k].first[d].size();
        for (std::size_t l = 0; same && l < a[k].first[d].size(); ++l)
          same = std::abs(a[k].first[d][l] - c[k].first[d][l]) <= 1e-9 * scale;
      }
    require(same, [&] {
      return "multiblock: " + where(f.block[0], f.side[0]) + " and " + where(f.block[1], f.side[1]) +
             " are not conforming after matching their knot lines (" + std::to_string(a.size()) + " and " +
             std::to_string(c.size()) + " B-splines on the interface)";
    });
    for (std::size_t k = 0; k < a.size(); ++k)
      uf.join(offset[static_cast<std::size_t>(f.block[0])] + a[k].second, offset[static_cast<std::size_t>(f.block[1])] + c[k].second);
  }

  // Global numbering in first appearance; control points of the unscaled B-splines.
  std::vector<int> number(uf.parent.size(), -1);
  out.global.resize(static_cast<std::size_t>(nb));
  std::vector<double>& control = out.space.control;
  for (int b = 0; b < nb; ++b) {
    const LRSpline<D>& s = blocks[static_cast<std::size_t>(b)];
    auto& g = out.global[static_cast<std::size_t>(b)];
    for (int i = 0; i < s.num_basis(); ++i) {
      int& n = number[static_cast<std::size_t>(uf.find(offset[static_cast<std::size_t>(b)] + i))];
      const LRBSpline<D>& f = s.basis_function(i);
      double d[D];
      for (int k = 0; k < D; ++k) d[k] = f.gamma * f.coef[static_cast<std::size_t>(k)];
      if (n < 0) {
        n = static_cast<int>(control.size() / D);
        control.insert(control.end(), d, d + D);
      } else {
        const double gap = point_distance(d, control.data() + static_cast<std::size_t>(D) * static_cast<std::size_t>(n), D);
        require(gap <= tol, [&] {
          return "multiblock: block " + std::to_string(b) + " does not meet its neighbour continuously (control points of "
                 "one interface function differ by " + format_number(gap) + ")";
        });
      }
      g.push_back(n);
    }
  }

  // Elements with global ids; their sides on interfaces; per block side the functions on its boundary part.
  RefinedSpace<D>& sp = out.space;
  sp.num_basis = static_cast<int>(control.size() / D);
  sp.degrees = blocks[0].degrees();
  sp.domain = blocks[0].domain();
  sp.blocks.resize(static_cast<std::size_t>(nb));
  std::vector<char> on_boundary(static_cast<std::size_t>(sp.num_basis), 0);
  for (int b = 0; b < nb; ++b) {
    const LRSpline<D>& s = blocks[static_cast<std::size_t>(b)];
    RefinedBlock<D>& rb = sp.blocks[static_cast<std::size_t>(b)];
    rb.domain = s.domain();
    for (int k = 0; k < D; ++k) {
      sp.domain.lo[k] = std::min(sp.domain.lo[k], s.domain().lo[k]);
      sp.domain.hi[k] = std::max(sp.domain.hi[k], s.domain().hi[k]);
    }
    std::array<std::vector<char>, S> row0;  // per side: LR id -> non-zero on the side
    std::array<int, S> exposed{}, covered{};
    for (int sd = 0; sd < S; ++sd) {
      row0[static_cast<std::size_t>(sd)].assign(static_cast<std::size_t>(s.num_basis()), 0);
      for (int id : side_row(s, DomainSide{sd / 2, sd % 2}, 0)) row0[static_cast<std::size_t>(sd)][static_cast<std::size_t>(id)] = 1;
    }
    RefinedSpace<D> local = refined_space(s, 1);
    for (RefinedElement<D>& el : local.elements) {
      RefinedElement<D> g;
      g.box = el.box;
      g.block = b;
      // Sides of the element on the block's sides: on an interface when within one common part (matching splits
      // the sides at the edges of every common part, so an element side is wholly on one or wholly off).
      for (int sd = 0; sd < S; ++sd) {
        const DomainSide side{sd / 2, sd % 2};
        if (!on_domain_face(s.domain(), g.box, Face{side.dir, side.end, b})) continue;
        const double eps = 1e-12 * s.domain().extent(side.dir == 0 ? 1 : 0);
        bool on_interface = false;
        for (const BlockInterface<D>& f : out.interfaces)
          for (int k = 0; k < 2; ++k)
            on_interface = on_interface || (f.block[static_cast<std::size_t>(k)] == b && f.side[static_cast<std::size_t>(k)].dir == side.dir &&
                                             f.side[static_cast<std::size_t>(k)].end == side.end && inside_part(f, k, side, g.box, eps));
        if (on_interface) {
          g.interface_sides |= 1u << sd;
          ++covered[static_cast<std::size_t>(sd)];
          continue;
        }
        ++exposed[static_cast<std::size_t>(sd)];
        for (int id : el.ids)
          if (row0[static_cast<std::size_t>(sd)][static_cast<std::size_t>(id)]) {
            const int gid = out.global[static_cast<std::size_t>(b)][static_cast<std::size_t>(id)];
            rb.face_basis[static_cast<std::size_t>(sd)].push_back(gid);
            on_boundary[static_cast<std::size_t>(gid)] = 1;
          }
      }
      // Unscaled rows, renumbered, ascending (rows of one global function summed: a block meeting itself).
      std::vector<std::pair<int, int>> order;
      for (std::size_t r = 0; r < el.ids.size(); ++r) {
        el.C.row(static_cast<Eigen::Index>(r)) /= s.basis_function(el.ids[r]).gamma;
        order.emplace_back(out.global[static_cast<std::size_t>(b)][static_cast<std::size_t>(el.ids[r])], static_cast<int>(r));
      }
      std::sort(order.begin(), order.end());
      g.C = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(order.size()), el.C.cols());
      for (const auto& [id, r] : order) {
        if (g.ids.empty() || g.ids.back() != id) g.ids.push_back(id);
        g.C.row(static_cast<Eigen::Index>(g.ids.size()) - 1) += el.C.row(r);
      }
      g.C.conservativeResize(static_cast<Eigen::Index>(g.ids.size()), Eigen::NoChange);
      sp.elements.push_back(std::move(g));
      out.element_block.push_back(b);
    }
    for (int sd = 0; sd < S; ++sd) {
      std::vector<int>& face = rb.face_basis[static_cast<std::size_t>(sd)];
      std::sort(face.begin(), face.end());
      face.erase(std::unique(face.begin(), face.end()), face.end());
      const DomainSide side{sd / 2, sd % 2};
      if (covered[static_cast<std::size_t>(sd)] == 0) out.boundary_sides.push_back({b, side});
      else if (exposed[static_cast<std::size_t>(sd)] > 0) out.partial_sides.push_back({b, side});
    }
  }
  for (int i = 0; i < sp.num_basis; ++i)
    if (on_boundary[static_cast<std::size_t>(i)]) out.boundary.push_back(i);
  out.blocks = std::move(blocks);
  return out;
}

template <int D>
std::vector<Face> boundary_faces(const MultiblockSpace<D>& m) {
  std::vector<Face> out;
  for (std::size_t b = 0; b < m.space.blocks.size(); ++b)
    for (int sd = 0; sd < 2 * D; ++sd)
      if (!m.space.blocks[b].face_basis[static_cast<std::size_t>(sd)].empty()) out.push_back(Face{sd / 2, sd % 2, static_cast<int>(b)});
  return out;
}

template <int D>
std::vector<LRSpline<D>> multiblock_fields(const MultiblockSpace<D>& m, const Eigen::VectorXd& coefs, int components) {
  const int N = m.space.num_basis;
  require(components >= 1 && coefs.size() == static_cast<Eigen::Index>(N) * components, [&] {
    return "multiblock: " + std::to_string(coefs.size()) + " coefficients for " + std::to_string(components) +
           " components of " + std::to_string(N) + " functions";
  });
  std::vector<LRSpline<D>> out;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const LRSpline<D>& s = m.blocks[b];
    std::vector<LRBSpline<D>> basis(s.basis_functions().begin(), s.basis_functions().end());
    for (std::size_t i = 0; i < basis.size(); ++i) {
      const int g = m.global[b][i];
      basis[i].coef.resize(static_cast<std::size_t>(components));
      for (int c = 0; c < components; ++c)
        basis[i].coef[static_cast<std::size_t>(c)] = coefs[static_cast<Eigen::Index>(c) * N + g] / basis[i].gamma;
    }
    // The B-splines stay in id order (it depends on the knots only), so coefficient i stays with id i.
    out.emplace_back(s.degrees(), components, false, std::move(basis), s.mesh());
  }
  return out;
}

namespace {

// The tensor spline of an LR spline whose mesh rectangles all cross the whole domain (written by hand: the LR
// layer converts tensor to LR only). lr_id[tensor index] is the LR B-spline of each tensor one.
template <int D>
TensorSpline<D> as_tensor(const LRSpline<D>& s, int block, std::vector<int>& lr_id) {
  auto fail = [&] { return "multiblock: block " + std::to_string(block) + " is locally refined, not a tensor spline"; };
  std::array<KnotVector, D> kv;
  std::array<std::map<std::vector<double>, int>, D> index;  // local knot vector -> B-spline index
  for (int k = 0; k < D; ++k) {
    std::map<double, int> mult;
    for (const MeshRectangle<D>& r : s.mesh())
      if (r.dir == k) {
        require(r.contains_across(s.domain()), fail);
        mult[r.value] = std::max(mult[r.value], r.multiplicity);
      }
    std::vector<double> t;
    for (const auto& [value, m] : mult) t.insert(t.end(), static_cast<std::size_t>(m), value);
    kv[static_cast<std::size_t>(k)] = KnotVector(s.degree(k), t);
    const auto p2 = static_cast<std::ptrdiff_t>(s.degree(k) + 2);
    for (int i = 0; i < kv[static_cast<std::size_t>(k)].size(); ++i)
      index[static_cast<std::size_t>(k)][std::vector<double>(t.begin() + i, t.begin() + i + p2)] = i;
  }
  int total = 1;
  for (const KnotVector& k : kv) total *= k.size();
  require(s.num_basis() == total, fail);
  std::vector<double> coefs(static_cast<std::size_t>(s.num_basis() * s.dim()));
  lr_id.assign(static_cast<std::size_t>(s.num_basis()), -1);
  for (int id = 0; id < s.num_basis(); ++id) {
    const LRBSpline<D>& f = s.basis_function(id);
    // gamma is 1 up to the rounding of the splits that made the B-spline; gamma * c is its tensor coefficient.
    require(std::abs(f.gamma - 1.0) <= 1e-12, fail);
    int t = 0;
    for (int k = D - 1; k >= 0; --k) {
      const auto it = index[static_cast<std::size_t>(k)].find(f.knots[static_cast<std::size_t>(k)]);
      require(it != index[static_cast<std::size_t>(k)].end(), fail);
      t = t * kv[static_cast<std::size_t>(k)].size() + it->second;
    }
    lr_id[static_cast<std::size_t>(t)] = id;
    for (int c = 0; c < s.dim(); ++c)
      coefs[static_cast<std::size_t>(t * s.dim() + c)] = f.gamma * f.coef[static_cast<std::size_t>(c)];
  }
  require(std::find(lr_id.begin(), lr_id.end(), -1) == lr_id.end(), fail);
  return TensorSpline<D>(kv, s.dim(), false, std::move(coefs));
}

}  // namespace

template <int D>
MultipatchSpace<D> tensor_multipatch(const MultiblockSpace<D>& m) {
  require(m.partial_sides.empty(), [&] {
    return "multiblock: block " + std::to_string(m.partial_sides[0].first) +
           " has a side partly on interfaces and partly on the boundary, which a tensor multipatch space cannot "
           "describe";
  });
  MultipatchSpace<D> out;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    std::vector<int> lr_id;
    out.patches.push_back(TensorSpace<D>{as_tensor(m.blocks[b], static_cast<int>(b), lr_id)});
    std::vector<int>& g = out.global.emplace_back();
    for (int id : lr_id) g.push_back(m.global[b][static_cast<std::size_t>(id)]);
  }
  out.num_basis = m.space.num_basis;
  for (const auto& [b, side] : m.boundary_sides) out.boundary.push_back(Face{side.dir, side.end, b});
  return out;
}

#define TRIVAR_INSTANTIATE(D)                                                                                   \
  template MultiblockSpace<D> multiblock_space(std::vector<LRSpline<D>>, const MultiblockOptions&);            \
  template std::vector<Face> boundary_faces(const MultiblockSpace<D>&);                                         \
  template std::vector<LRSpline<D>> multiblock_fields(const MultiblockSpace<D>&, const Eigen::VectorXd&, int); \
  template MultipatchSpace<D> tensor_multipatch(const MultiblockSpace<D>&);                                    \
  template std::vector<BlockInterface<D>> match_blocks(std::vector<LRSpline<D>>&, const MultiblockOptions&, int); \
  template Param<D> interface_param(const BlockInterface<D>&, int, const Param<D>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
