#include "trivar/fit/multiblock_space.hpp"

#include <algorithm>
#include <map>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/iga/refined_quadrature.hpp"

namespace trivar {

namespace {

std::string where(int i, DomainSide s) {
  static const char* names[2][2] = {{"u = lo", "u = hi"}, {"v = lo", "v = hi"}};
  return "block " + std::to_string(i) + " side " + names[s.dir][s.end];
}

double lo_along(const LRSpline<2>& s, DomainSide side) { return s.domain().lo[side.along()]; }
double hi_along(const LRSpline<2>& s, DomainSide side) { return s.domain().hi[side.along()]; }

// The parameter of the side's point closest to x (samples, then Gauss-Newton); false when farther than tol.
bool on_side(const LRSpline<2>& s, DomainSide side, const double* x, double tol, double& t) {
  constexpr int n = 65;
  const double lo = lo_along(s, side), hi = hi_along(s, side);
  double c[6], best = HUGE_VAL;
  for (int i = 0; i < n; ++i) {
    const double ti = lo + (hi - lo) * i / (n - 1);
    s.eval(side_param(s, side, ti), c);
    const double d = std::hypot(c[0] - x[0], c[1] - x[1]);
    if (d < best) best = d, t = ti;
  }
  for (int it = 0; it < 30; ++it) {
    s.eval_first_derivatives(side_param(s, side, t), c);
    const double* dc = c + 2 * (1 + side.along());
    const double g = (c[0] - x[0]) * dc[0] + (c[1] - x[1]) * dc[1], h = dc[0] * dc[0] + dc[1] * dc[1];
    if (h <= 0) break;
    const double next = std::clamp(t - g / h, lo, hi);
    if (next == t) break;
    t = next;
  }
  s.eval(side_param(s, side, t), c);
  // Ends exactly when within rounding of them.
  if (std::abs(t - lo) <= 1e-10 * (hi - lo)) t = lo;
  if (std::abs(t - hi) <= 1e-10 * (hi - lo)) t = hi;
  return std::hypot(c[0] - x[0], c[1] - x[1]) <= tol;
}

// A value within rounding of one of `knots` becomes that knot, so knots passed back and forth stay identical.
double snap(double t, const std::vector<std::pair<double, int>>& knots, double scale) {
  for (const auto& k : knots)
    if (std::abs(k.first - t) <= 1e-10 * scale) return k.first;
  return t;
}

double map_param(const BlockInterface& f, int from, double x) {
  const int to = 1 - from;
  if (x == f.lo[from]) return f.lo[to];
  if (x == f.hi[from]) return f.hi[to];
  return f.lo[to] + (x - f.lo[from]) / (f.hi[from] - f.lo[from]) * (f.hi[to] - f.lo[to]);
}

// The common segment of two sides, if they share one of positive length.
bool common_segment(const std::vector<LRSpline<2>>& B, int i, DomainSide si, int j, DomainSide sj, double tol,
                    BlockInterface& out) {
  const LRSpline<2>& A = B[static_cast<std::size_t>(i)];
  const LRSpline<2>& C = B[static_cast<std::size_t>(j)];
  std::vector<std::pair<double, double>> hits;  // (t on si, s on sj)
  double x[6], t = 0;
  for (double s : {lo_along(C, sj), hi_along(C, sj)}) {
    C.eval(side_param(C, sj, s), x);
    if (on_side(A, si, x, tol, t)) hits.emplace_back(t, s);
  }
  for (double a : {lo_along(A, si), hi_along(A, si)}) {
    A.eval(side_param(A, si, a), x);
    if (on_side(C, sj, x, tol, t)) hits.emplace_back(a, t);
  }
  if (hits.size() < 2) return false;
  std::sort(hits.begin(), hits.end());
  const double range = hi_along(A, si) - lo_along(A, si);
  if (hits.back().first - hits.front().first <= 1e-9 * range) return false;
  out.block = {i, j};
  out.side = {si, sj};
  out.lo = {hits.front().first, hits.front().second};
  out.hi = {hits.back().first, hits.back().second};
  // The segment must be one curve in linearly corresponding parameters.
  double y[6];
  for (int k = 1; k < 16; ++k) {
    const double ta = out.lo[0] + (out.hi[0] - out.lo[0]) * k / 16;
    A.eval(side_param(A, si, ta), x);
    C.eval(side_param(C, sj, map_param(out, 0, ta)), y);
    require(std::hypot(x[0] - y[0], x[1] - y[1]) <= tol, [&] {
      return "multiblock: " + where(i, si) + " and " + where(j, sj) +
             " meet at both ends of a common segment but differ in between (different curves, or parametrisations "
             "that do not correspond linearly)";
    });
  }
  require(A.degree(si.along()) == C.degree(sj.along()), [&] {
    return "multiblock: " + where(i, si) + " and " + where(j, sj) + " have different degrees along their interface";
  });
  return true;
}

// Knot lines of the other side of interface f (side `from` receives them) on the segment, and the segment's
// ends where they lie inside the receiving side (a T-joint) with multiplicity p.
std::vector<std::pair<double, int>> knots_for(const std::vector<LRSpline<2>>& B, const BlockInterface& f, int to) {
  const int from = 1 - to;
  const LRSpline<2>& R = B[static_cast<std::size_t>(f.block[to])];
  const LRSpline<2>& S = B[static_cast<std::size_t>(f.block[from])];
  const auto own = side_trace_knots(R, f.side[to])[static_cast<std::size_t>(f.side[to].along())];
  const double scale = hi_along(R, f.side[to]) - lo_along(R, f.side[to]);
  const double slo = std::min(f.lo[from], f.hi[from]), shi = std::max(f.lo[from], f.hi[from]);
  std::vector<std::pair<double, int>> out;
  const auto theirs = side_trace_knots(S, f.side[from])[static_cast<std::size_t>(f.side[from].along())];
  for (const auto& [s, m] : theirs)
    if (s > slo && s < shi) out.emplace_back(snap(map_param(f, from, s), own, scale), m);
  const int p = R.degree(f.side[to].along());
  for (double e : {f.lo[to], f.hi[to]}) out.emplace_back(e, p);
  return out;
}

// The parts of a block side on interfaces, as sorted parameter intervals along it.
std::vector<std::pair<double, double>> covered_parts(const std::vector<BlockInterface>& interfaces, int b, DomainSide side) {
  std::vector<std::pair<double, double>> covered;
  for (const BlockInterface& f : interfaces)
    for (int k = 0; k < 2; ++k)
      if (f.block[k] == b && f.side[k].dir == side.dir && f.side[k].end == side.end)
        covered.emplace_back(std::min(f.lo[k], f.hi[k]), std::max(f.lo[k], f.hi[k]));
  std::sort(covered.begin(), covered.end());
  return covered;
}

// How far from `from` the covered parts reach without a gap (eps: the rounding allowed at joins).
double covered_until(const std::vector<std::pair<double, double>>& covered, double from, double eps) {
  for (const auto& [c0, c1] : covered)
    if (c0 <= from + eps && c1 > from) from = c1;
  return from;
}

struct UnionFind {
  std::vector<int> parent;
  int find(int a) {
    while (parent[static_cast<std::size_t>(a)] != a) a = parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
    return a;
  }
  void join(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

// Row-0 B-splines of side `k` of interface f whose support along the side meets the open segment, each with its
// knots along the side clamped to the segment, in the parameter of side 0.
std::vector<std::pair<std::vector<double>, int>> traces(const std::vector<LRSpline<2>>& B, const BlockInterface& f, int k) {
  const LRSpline<2>& S = B[static_cast<std::size_t>(f.block[k])];
  const int a = f.side[k].along();
  const double lo = std::min(f.lo[k], f.hi[k]), hi = std::max(f.lo[k], f.hi[k]);
  std::vector<std::pair<std::vector<double>, int>> out;
  for (int id : side_row(S, f.side[k], 0)) {
    std::vector<double> t = S.basis_function(id).knots[static_cast<std::size_t>(a)];
    if (t.back() <= lo || t.front() >= hi) continue;
    // Clamping the knots to the segment gives the restriction only where the support ends there or is C0 there.
    for (double e : {lo, hi})
      require(!(t.front() < e && e < t.back()) || std::count(t.begin(), t.end(), e) >= S.degree(a), [&] {
        return "multiblock: " + where(f.block[k], f.side[k]) + " has a B-spline crossing the end of its interface with block " +
               std::to_string(f.block[1 - k]) + " without a C0 knot there";
      });
    for (double& x : t) {
      x = std::clamp(x, lo, hi);
      if (k == 1) x = map_param(f, 1, x);
    }
    if (t.front() > t.back()) std::reverse(t.begin(), t.end());
    out.emplace_back(std::move(t), id);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

MultiblockSpace multiblock_space(std::vector<LRSpline<2>> blocks, const MultiblockOptions& options) {
  const int nb = static_cast<int>(blocks.size());
  require(nb >= 1, "multiblock: no blocks");
  double diag = 0;
  for (int b = 0; b < nb; ++b) {
    const LRSpline<2>& s = blocks[static_cast<std::size_t>(b)];
    require(!s.is_rational() && s.dim() == 2, [&] {
      return "multiblock: block " + std::to_string(b) + " is not a planar polynomial surface (2 coordinates)";
    });
    require(s.degrees() == blocks[0].degrees(), [&] {
      return "multiblock: block " + std::to_string(b) + " has degrees (" + std::to_string(s.degree(0)) + ", " +
             std::to_string(s.degree(1)) + "), block 0 (" + std::to_string(blocks[0].degree(0)) + ", " +
             std::to_string(blocks[0].degree(1)) + ")";
    });
    diag = std::max(diag, control_net_diagonal(s));
  }
  const double tol = options.tolerance > 0 ? options.tolerance : 1e-8 * diag;

  MultiblockSpace out;
  for (int i = 0; i < nb; ++i)
    for (int j = i + 1; j < nb; ++j)
      for (int si = 0; si < 4; ++si)
        for (int sj = 0; sj < 4; ++sj) {
          BlockInterface f;
          if (common_segment(blocks, i, {si / 2, si % 2}, j, {sj / 2, sj % 2}, tol, f)) out.interfaces.push_back(f);
        }

  // Adjust the side knot lines until every interface's two traces agree (a line given to one block can be
  // passed on to a third one through another interface, hence the rounds).
  for (int round = 0;; ++round) {
    int changed = 0;
    for (const BlockInterface& f : out.interfaces)
      for (int to = 0; to < 2; ++to) {
        SideKnots<2> k;
        k[static_cast<std::size_t>(f.side[to].along())] = knots_for(blocks, f, to);
        changed += insert_side_knot_lines(blocks[static_cast<std::size_t>(f.block[to])], f.side[to], k, options.whole_lines ? 0 : 1);
      }
    if (changed == 0) break;
    require(round < 16, "multiblock: the interface knot lines did not settle");
  }

  // Identify the traces across every interface.
  std::vector<int> offset(static_cast<std::size_t>(nb) + 1, 0);
  for (int b = 0; b < nb; ++b) offset[static_cast<std::size_t>(b) + 1] = offset[static_cast<std::size_t>(b)] + blocks[static_cast<std::size_t>(b)].num_basis();
  UnionFind uf;
  uf.parent.resize(static_cast<std::size_t>(offset.back()));
  std::iota(uf.parent.begin(), uf.parent.end(), 0);
  for (const BlockInterface& f : out.interfaces) {
    const auto a = traces(blocks, f, 0), c = traces(blocks, f, 1);
    const double scale = std::abs(f.hi[0] - f.lo[0]);
    bool same = a.size() == c.size();
    for (std::size_t k = 0; same && k < a.size(); ++k)
      for (std::size_t l = 0; same && l < a[k].first.size(); ++l)
        same = std::abs(a[k].first[l] - c[k].first[l]) <= 1e-9 * scale;
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
    const LRSpline<2>& s = blocks[static_cast<std::size_t>(b)];
    auto& g = out.global[static_cast<std::size_t>(b)];
    for (int i = 0; i < s.num_basis(); ++i) {
      int& n = number[static_cast<std::size_t>(uf.find(offset[static_cast<std::size_t>(b)] + i))];
      const LRBSpline<2>& f = s.basis_function(i);
      const double d[2] = {f.gamma * f.coef[0], f.gamma * f.coef[1]};
      if (n < 0) {
        n = static_cast<int>(control.size() / 2);
        control.insert(control.end(), d, d + 2);
      } else {
        const double* e = control.data() + 2 * n;
        require(std::hypot(d[0] - e[0], d[1] - e[1]) <= tol, [&] {
          return "multiblock: block " + std::to_string(b) + " does not meet its neighbour continuously (control points of "
                 "one interface function differ by " + format_number(std::hypot(d[0] - e[0], d[1] - e[1])) + ")";
        });
      }
      g.push_back(n);
    }
  }
  RefinedSpace<2>& sp = out.space;
  sp.num_basis = static_cast<int>(control.size() / 2);
  sp.degrees = blocks[0].degrees();
  sp.domain = blocks[0].domain();
  // Per block side: the parts on interfaces; the row-0 B-splines reaching a part on none are boundary functions.
  std::vector<char> on_boundary(static_cast<std::size_t>(sp.num_basis), 0);
  std::vector<std::array<std::vector<std::pair<double, double>>, 4>> covered(static_cast<std::size_t>(nb));
  sp.blocks.resize(static_cast<std::size_t>(nb));
  for (int b = 0; b < nb; ++b) {
    const LRSpline<2>& s = blocks[static_cast<std::size_t>(b)];
    RefinedBlock<2>& rb = sp.blocks[static_cast<std::size_t>(b)];
    rb.domain = s.domain();
    for (int sd = 0; sd < 4; ++sd) {
      const DomainSide side{sd / 2, sd % 2};
      auto& parts = covered[static_cast<std::size_t>(b)][static_cast<std::size_t>(sd)];
      parts = covered_parts(out.interfaces, b, side);
      const double eps = 1e-12 * (hi_along(s, side) - lo_along(s, side));
      if (parts.empty()) out.boundary_sides.push_back({b, side});
      else if (covered_until(parts, lo_along(s, side), eps) < hi_along(s, side) - eps) out.partial_sides.push_back({b, side});
      std::vector<int>& face = rb.face_basis[static_cast<std::size_t>(sd)];
      for (int id : side_row(s, side, 0)) {
        const auto& t = s.basis_function(id).knots[static_cast<std::size_t>(side.along())];
        // Walk the support, skipping covered parts.
        if (covered_until(parts, t.front(), eps) >= t.back() - eps) continue;
        const int g = out.global[static_cast<std::size_t>(b)][static_cast<std::size_t>(id)];
        face.push_back(g);
        on_boundary[static_cast<std::size_t>(g)] = 1;
      }
      std::sort(face.begin(), face.end());
      face.erase(std::unique(face.begin(), face.end()), face.end());
    }
  }
  for (int b = 0; b < nb; ++b) {
    const LRSpline<2>& s = blocks[static_cast<std::size_t>(b)];
    RefinedSpace<2> local = refined_space(s, 1);
    sp.domain.lo = {std::min(sp.domain.lo[0], s.domain().lo[0]), std::min(sp.domain.lo[1], s.domain().lo[1])};
    sp.domain.hi = {std::max(sp.domain.hi[0], s.domain().hi[0]), std::max(sp.domain.hi[1], s.domain().hi[1])};
    for (RefinedElement<2>& el : local.elements) {
      // Unscaled rows, renumbered, ascending (rows of one global function summed: a block meeting itself).
      std::vector<std::pair<int, int>> order;
      for (std::size_t r = 0; r < el.ids.size(); ++r) {
        el.C.row(static_cast<Eigen::Index>(r)) /= s.basis_function(el.ids[r]).gamma;
        order.emplace_back(out.global[static_cast<std::size_t>(b)][static_cast<std::size_t>(el.ids[r])], static_cast<int>(r));
      }
      std::sort(order.begin(), order.end());
      RefinedElement<2> g;
      g.box = el.box;
      g.block = b;
      g.C = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(order.size()), el.C.cols());
      for (const auto& [id, r] : order) {
        if (g.ids.empty() || g.ids.back() != id) g.ids.push_back(id);
        g.C.row(static_cast<Eigen::Index>(g.ids.size()) - 1) += el.C.row(r);
      }
      g.C.conservativeResize(static_cast<Eigen::Index>(g.ids.size()), Eigen::NoChange);
      // Sides of the element on the block's sides that lie wholly on an interface (matching splits sides at the
      // ends of every interface, so an element side is wholly on one or wholly off).
      for (int sd = 0; sd < 4; ++sd) {
        const DomainSide side{sd / 2, sd % 2};
        const Face face{side.dir, side.end, b};
        if (!on_domain_face(s.domain(), g.box, face)) continue;
        const int a = side.along();
        const double eps = 1e-12 * (hi_along(s, side) - lo_along(s, side));
        if (covered_until(covered[static_cast<std::size_t>(b)][static_cast<std::size_t>(sd)], g.box.lo[a], eps) >= g.box.hi[a] - eps)
          g.interface_sides |= 1u << sd;
      }
      sp.elements.push_back(std::move(g));
      out.element_block.push_back(b);
    }
  }

  for (int i = 0; i < sp.num_basis; ++i)
    if (on_boundary[static_cast<std::size_t>(i)]) out.boundary.push_back(i);
  out.blocks = std::move(blocks);
  return out;
}

namespace {

// The tensor spline of an LR spline whose mesh lines all cross the whole domain (written by hand: the LR layer
// converts tensor to LR only). lr_id[tensor index] is the LR B-spline of each tensor one.
TensorSpline<2> as_tensor(const LRSpline<2>& s, int block, std::vector<int>& lr_id) {
  auto fail = [&] { return "multiblock: block " + std::to_string(block) + " is locally refined, not a tensor spline"; };
  std::array<KnotVector, 2> kv;
  std::array<std::map<std::vector<double>, int>, 2> index;  // local knot vector -> B-spline index
  for (int k = 0; k < 2; ++k) {
    std::map<double, int> mult;
    for (const MeshRectangle<2>& r : s.mesh())
      if (r.dir == k) {
        Box<2> whole = s.domain();
        require(r.contains_across(whole), fail);
        mult[r.value] = std::max(mult[r.value], r.multiplicity);
      }
    std::vector<double> t;
    for (const auto& [value, m] : mult) t.insert(t.end(), static_cast<std::size_t>(m), value);
    kv[static_cast<std::size_t>(k)] = KnotVector(s.degree(k), t);
    const auto p2 = static_cast<std::ptrdiff_t>(s.degree(k) + 2);
    for (int i = 0; i < kv[static_cast<std::size_t>(k)].size(); ++i)
      index[static_cast<std::size_t>(k)][std::vector<double>(t.begin() + i, t.begin() + i + p2)] = i;
  }
  const int nu = kv[0].size();
  require(s.num_basis() == nu * kv[1].size(), fail);
  std::vector<double> coefs(static_cast<std::size_t>(s.num_basis() * s.dim()));
  lr_id.assign(static_cast<std::size_t>(s.num_basis()), -1);
  for (int id = 0; id < s.num_basis(); ++id) {
    const LRBSpline<2>& f = s.basis_function(id);
    const auto i = index[0].find(f.knots[0]), j = index[1].find(f.knots[1]);
    // gamma is 1 up to the rounding of the splits that made the B-spline; gamma * c is its tensor coefficient.
    require(i != index[0].end() && j != index[1].end() && std::abs(f.gamma - 1.0) <= 1e-12, fail);
    const int t = i->second + nu * j->second;
    lr_id[static_cast<std::size_t>(t)] = id;
    for (int c = 0; c < s.dim(); ++c)
      coefs[static_cast<std::size_t>(t * s.dim() + c)] = f.gamma * f.coef[static_cast<std::size_t>(c)];
  }
  require(std::find(lr_id.begin(), lr_id.end(), -1) == lr_id.end(), fail);
  return TensorSpline<2>(kv, s.dim(), false, std::move(coefs));
}

}  // namespace

std::vector<Face> boundary_faces(const MultiblockSpace& m) {
  std::vector<Face> out;
  for (std::size_t b = 0; b < m.space.blocks.size(); ++b)
    for (int sd = 0; sd < 4; ++sd)
      if (!m.space.blocks[b].face_basis[static_cast<std::size_t>(sd)].empty()) out.push_back(Face{sd / 2, sd % 2, static_cast<int>(b)});
  return out;
}

std::vector<LRSpline<2>> multiblock_fields(const MultiblockSpace& m, const Eigen::VectorXd& coefs, int components) {
  const int N = m.space.num_basis;
  require(components >= 1 && coefs.size() == static_cast<Eigen::Index>(N) * components, [&] {
    return "multiblock: " + std::to_string(coefs.size()) + " coefficients for " + std::to_string(components) +
           " components of " + std::to_string(N) + " functions";
  });
  std::vector<LRSpline<2>> out;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const LRSpline<2>& s = m.blocks[b];
    std::vector<LRBSpline<2>> basis(s.basis_functions().begin(), s.basis_functions().end());
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

MultipatchSpace<2> tensor_multipatch(const MultiblockSpace& m) {
  require(m.partial_sides.empty(), [&] {
    return "multiblock: block " + std::to_string(m.partial_sides[0].first) +
           " has a side partly on interfaces and partly on the boundary, which a tensor multipatch space cannot "
           "describe";
  });
  MultipatchSpace<2> out;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    std::vector<int> lr_id;
    out.patches.push_back(TensorSpace<2>{as_tensor(m.blocks[b], static_cast<int>(b), lr_id)});
    std::vector<int>& g = out.global.emplace_back();
    for (int id : lr_id) g.push_back(m.global[b][static_cast<std::size_t>(id)]);
  }
  out.num_basis = m.space.num_basis;
  for (const auto& [b, side] : m.boundary_sides) out.boundary.push_back(Face{side.dir, side.end, b});
  return out;
}

}  // namespace trivar
