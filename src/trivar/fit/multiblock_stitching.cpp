#include "trivar/fit/multiblock_stitching.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/fit/seam_weights.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

namespace {

double ratio_or_zero(double a, double b) { return b == 0.0 ? 0.0 : a / b; }

// Value and derivative at x of the one B-spline on the p + 2 local knots t, with the limit from the left when
// `from_left` (a block's side at the end of its domain). Written by hand: spline/basis evaluates the p + 1
// functions of a span of a knot vector, not one function on its own knots with a chosen one-sided limit.
void local_bspline(const std::vector<double>& t, double x, bool from_left, double& value, double& slope) {
  const int p = static_cast<int>(t.size()) - 2;
  double N[kMaxDegree + 2] = {};
  for (int j = 0; j <= p; ++j) {
    const double a = t[static_cast<std::size_t>(j)], b = t[static_cast<std::size_t>(j) + 1];
    N[j] = (from_left ? a < x && x <= b : a <= x && x < b) ? 1.0 : 0.0;
  }
  slope = 0.0;
  for (int q = 1; q <= p; ++q) {
    if (q == p)
      slope = p * (ratio_or_zero(N[0], t[static_cast<std::size_t>(p)] - t[0]) -
                   ratio_or_zero(N[1], t[static_cast<std::size_t>(p) + 1] - t[1]));
    for (int j = 0; j + q <= p; ++j) {
      const auto s = static_cast<std::size_t>(j), sq = static_cast<std::size_t>(j + q);
      N[j] = ratio_or_zero((x - t[s]) * N[j], t[sq] - t[s]) + ratio_or_zero((t[sq + 1] - x) * N[j + 1], t[sq + 1] - t[s + 1]);
    }
  }
  value = N[0];
}

// One B-spline's value and derivative across the side (times `sign`: outward for block 0 of an interface,
// inward for block 1), scaling factor included.
struct SideValue {
  int id;
  double value, cross;
};

template <int D>
void side_values(const LRSpline<D>& s, DomainSide side, const std::vector<int>& ids, const Param<D>& u, double sign,
                 std::vector<SideValue>& out) {
  out.clear();
  for (int id : ids) {
    const LRBSpline<D>& f = s.basis_function(id);
    double v = f.gamma, d = f.gamma * sign;
    for (int k = 0; k < D; ++k) {
      double val, slope;
      local_bspline(f.knots[static_cast<std::size_t>(k)], u[k], k == side.dir && side.end == 1, val, slope);
      v *= val;
      d *= k == side.dir ? slope : val;
    }
    if (v != 0.0 || d != 0.0) out.push_back({id, v, d});
  }
}

// The B-splines of rows 0 .. rows - 1 of a side (the only ones with a value or a cross derivative on it).
template <int D>
std::vector<int> first_rows(const LRSpline<D>& s, DomainSide side, int rows) {
  std::vector<int> ids;
  for (int r = 0; r < rows; ++r) {
    const std::vector<int> row = side_row(s, side, r);
    ids.insert(ids.end(), row.begin(), row.end());
  }
  return ids;
}

// Points of the common part of f in side 0's parameters: per direction along the side the breakpoints of both
// sides' first-row B-splines inside the part, and in each span the given fractions of it.
template <int D>
std::vector<Param<D>> part_points(const std::vector<LRSpline<D>>& B, const BlockInterface<D>& f,
                                  const std::array<std::vector<int>, 2>& ids, const std::vector<double>& fractions) {
  const auto dirs = along_directions<D>(f.side[0]);
  std::array<std::vector<double>, D - 1> values;
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    const int a = dirs[k], b = f.along[a];
    const double lo = std::min(f.lo[0][a], f.hi[0][a]), hi = std::max(f.lo[0][a], f.hi[0][a]);
    std::vector<double> breaks{lo, hi};
    for (int id : ids[0])
      for (double t : B[static_cast<std::size_t>(f.block[0])].basis_function(id).knots[static_cast<std::size_t>(a)])
        if (t > lo && t < hi) breaks.push_back(t);
    for (int id : ids[1])
      for (double t : B[static_cast<std::size_t>(f.block[1])].basis_function(id).knots[static_cast<std::size_t>(b)]) {
        Param<D> q = f.lo[1];
        q[b] = t;
        const double m = interface_param(f, 1, q)[a];
        if (m > lo && m < hi) breaks.push_back(m);
      }
    std::sort(breaks.begin(), breaks.end());
    // Breakpoints a rounding apart (a knot mapped from the other side) are one.
    const double eps = 1e-10 * (hi - lo);
    breaks.erase(std::unique(breaks.begin(), breaks.end(), [&](double x, double y) { return y - x <= eps; }), breaks.end());
    for (std::size_t s = 0; s + 1 < breaks.size(); ++s)
      for (double c : fractions) values[k].push_back(breaks[s] + c * (breaks[s + 1] - breaks[s]));
  }
  std::vector<Param<D>> out;
  std::size_t total = 1;
  for (const auto& v : values) total *= v.size();
  for (std::size_t g = 0; g < total; ++g) {
    Param<D> u = f.lo[0];
    for (std::size_t k = 0, r = g; k < dirs.size(); r /= values[k].size(), ++k) u[dirs[k]] = values[k][r % values[k].size()];
    out.push_back(u);
  }
  return out;
}

double outward(DomainSide s) { return s.end == 1 ? 1.0 : -1.0; }

}  // namespace

template <int D>
StitchedBlocks<D> stitch_blocks(std::vector<LRSpline<D>> blocks, const StitchOptions& options, CrossSpeed speed) {
  StitchedBlocks<D> out;
  out.continuity = options.continuity;
  const bool c1 = options.continuity == Continuity::C1;
  const int rows = c1 ? 2 : 1;
  MultiblockOptions match;
  match.tolerance = options.tolerance;
  out.interfaces = match_blocks(blocks, match, rows);
  const int nb = static_cast<int>(blocks.size());
  const int dim = blocks[0].dim(), stride = blocks[0].stride();
  const bool rational = blocks[0].is_rational();
  double diag = 0;
  for (const LRSpline<D>& s : blocks) diag = std::max(diag, control_net_diagonal(s));
  const int p = *std::max_element(blocks[0].degrees().begin(), blocks[0].degrees().end());
  // p + 1 distinct inner points per span pin a polynomial of degree p along it; the checks lie between them.
  std::vector<double> pinned, checks{0.0, 1.0};
  for (int k = 0; k <= p; ++k) pinned.push_back((k + 1.0) / (p + 2.0));
  for (int k = 0; k <= p + 1; ++k) checks.push_back((k + 0.5) / (p + 2.0));

  // Columns: the first-row B-splines of every interface side; rows: the conditions at the pinned points.
  std::map<std::pair<int, int>, int> column;  // (block, id) -> column
  std::vector<std::pair<int, int>> owner;
  const auto col = [&](int b, int id) {
    const auto [it, added] = column.emplace(std::make_pair(b, id), static_cast<int>(owner.size()));
    if (added) owner.emplace_back(b, id);
    return it->second;
  };
  std::vector<std::vector<std::pair<int, double>>> conditions;
  std::vector<SideValue> va, vb;
  const auto combination = [&](int b, const std::vector<SideValue>& v, bool cross, int c) {
    double x = 0;
    for (const SideValue& e : v)
      x += (cross ? e.cross : e.value) * blocks[static_cast<std::size_t>(b)].basis_function(e.id).coef[static_cast<std::size_t>(c)];
    return x;
  };
  for (const BlockInterface<D>& f : out.interfaces) {
    const int i = f.block[0], j = f.block[1];
    const LRSpline<D>& A = blocks[static_cast<std::size_t>(i)];
    const LRSpline<D>& C = blocks[static_cast<std::size_t>(j)];
    const std::array<std::vector<int>, 2> ids{first_rows(A, f.side[0], rows), first_rows(C, f.side[1], rows)};
    const std::vector<Param<D>> points = part_points(blocks, f, ids, pinned);
    const auto name = [&] { return "stitch: blocks " + std::to_string(i) + " and " + std::to_string(j); };
    // lambda: from the parametrisation (block 1's parameters run 1 / lambda times as fast as block 0's across the
    // seam as along it; the geometric mean of the directions along a face), or fitted to the input's cross
    // derivatives (least squares), which must not point against each other in either case.
    double lambda = 1.0;
    for (int a : along_directions<D>(f.side[0]))
      lambda *= std::abs((f.hi[0][a] - f.lo[0][a]) / (f.hi[1][f.along[a]] - f.lo[1][f.along[a]]));
    lambda = std::pow(lambda, 1.0 / (D - 1));
    if (c1) {
      double ab = 0, aa = 0;
      for (const Param<D>& u : points) {
        side_values(A, f.side[0], ids[0], u, outward(f.side[0]), va);
        side_values(C, f.side[1], ids[1], interface_param(f, 0, u), -outward(f.side[1]), vb);
        for (int c = 0; c < dim; ++c) {
          const double x = combination(i, va, true, c), y = combination(j, vb, true, c);
          ab += x * y;
          aa += x * x;
        }
      }
      require(aa > 0 && ab > 0, [&] {
        return name() + ": the derivatives across their interface point against each other (the blocks fold back); "
               "C1 is impossible there";
      });
      if (speed == CrossSpeed::fitted) lambda = ab / aa;
    }
    out.speed.push_back(lambda);
    for (const Param<D>& u : points) {
      side_values(A, f.side[0], ids[0], u, outward(f.side[0]), va);
      side_values(C, f.side[1], ids[1], interface_param(f, 0, u), -outward(f.side[1]), vb);
      if (rational) {
        // The weights are kept: they must already be continuous (C1) across the seam.
        const double wa = combination(i, va, false, dim), wb = combination(j, vb, false, dim);
        require(std::abs(wa - wb) <= 1e-10 * std::max(std::abs(wa), std::abs(wb)), [&] {
          return name() + ": the weights differ across their interface (" + format_number(wa) + " against " +
                 format_number(wb) + "); rational stitching keeps the weights and needs them equal there";
        });
        if (c1) {
          require_weights_c1(lambda * combination(i, va, true, dim), combination(j, vb, true, dim), wa,
                             A.domain().extent(f.side[0].dir), name, "their interface");
        }
      }
      for (int kind = 0; kind < (c1 ? 2 : 1); ++kind) {
        std::vector<std::pair<int, double>> row;
        for (const SideValue& e : va) row.emplace_back(col(i, e.id), kind == 0 ? e.value : lambda * e.cross);
        for (const SideValue& e : vb) row.emplace_back(col(j, e.id), kind == 0 ? -e.value : -e.cross);
        conditions.push_back(std::move(row));
      }
    }
  }

  // The smallest move meeting every condition: per coordinate, x -= pinv(M) (M x) (complete orthogonal
  // decomposition, so conditions that repeat each other, as at corners and T-joints, do no harm). Rows are
  // scaled to unit size first (values and derivatives differ by the span lengths).
  const auto n = static_cast<Eigen::Index>(owner.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(conditions.size()), n);
  for (std::size_t r = 0; r < conditions.size(); ++r) {
    for (const auto& [c, v] : conditions[r]) M(static_cast<Eigen::Index>(r), c) += v;
    const double size = M.row(static_cast<Eigen::Index>(r)).cwiseAbs().maxCoeff();
    if (size > 0) M.row(static_cast<Eigen::Index>(r)) /= size;
  }
  out.conditions = static_cast<int>(M.rows());
  out.unknowns = static_cast<int>(n);
  std::vector<std::vector<LRBSpline<D>>> basis(static_cast<std::size_t>(nb));
  for (int b = 0; b < nb; ++b)
    basis[static_cast<std::size_t>(b)].assign(blocks[static_cast<std::size_t>(b)].basis_functions().begin(),
                                              blocks[static_cast<std::size_t>(b)].basis_functions().end());
  if (n > 0 && M.rows() > 0) {
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(M);
    Eigen::VectorXd x(n);
    for (int c = 0; c < dim; ++c) {
      for (Eigen::Index k = 0; k < n; ++k) {
        const auto [b, id] = owner[static_cast<std::size_t>(k)];
        x[k] = basis[static_cast<std::size_t>(b)][static_cast<std::size_t>(id)].coef[static_cast<std::size_t>(c)];
      }
      const Eigen::VectorXd move = cod.solve(M * x);
      for (Eigen::Index k = 0; k < n; ++k) {
        const auto [b, id] = owner[static_cast<std::size_t>(k)];
        basis[static_cast<std::size_t>(b)][static_cast<std::size_t>(id)].coef[static_cast<std::size_t>(c)] -= move[k];
        out.moved = std::max(out.moved, std::abs(move[k]));
      }
    }
  }
  std::vector<char> touched(static_cast<std::size_t>(nb), 0);
  for (const auto& [b, id] : owner) touched[static_cast<std::size_t>(b)] = 1;
  for (int b = 0; b < nb; ++b)
    if (touched[static_cast<std::size_t>(b)]) {
      const LRSpline<D>& s = blocks[static_cast<std::size_t>(b)];
      // The B-splines keep their ids (the order depends on the knots only), so the coefficients stay with them.
      blocks[static_cast<std::size_t>(b)] =
          LRSpline<D>(s.degrees(), dim, rational, std::move(basis[static_cast<std::size_t>(b)]), s.mesh());
    }

  // The jumps left, through the blocks' own evaluation, at points between the pinned ones and at the spans' ends.
  std::vector<double> xa(static_cast<std::size_t>((D + 1) * dim)), xb(xa.size());
  double size = diag;
  for (std::size_t k = 0; k < out.interfaces.size(); ++k) {
    const BlockInterface<D>& f = out.interfaces[k];
    const LRSpline<D>& A = blocks[static_cast<std::size_t>(f.block[0])];
    const LRSpline<D>& C = blocks[static_cast<std::size_t>(f.block[1])];
    const std::array<std::vector<int>, 2> ids{first_rows(A, f.side[0], rows), first_rows(C, f.side[1], rows)};
    for (const Param<D>& u : part_points(blocks, f, ids, checks)) {
      A.eval_first_derivatives(u, xa.data());
      C.eval_first_derivatives(interface_param(f, 0, u), xb.data());
      const int ca = f.side[0].dir, cb = f.side[1].dir;
      for (int c = 0; c < dim; ++c) {
        const auto cc = static_cast<std::size_t>(c);
        out.jump = std::max(out.jump, std::abs(xa[cc] - xb[cc]));
        if (!c1) continue;
        const double da = outward(f.side[0]) * out.speed[k] * xa[static_cast<std::size_t>(dim * (1 + ca)) + cc];
        const double db = -outward(f.side[1]) * xb[static_cast<std::size_t>(dim * (1 + cb)) + cc];
        out.jump = std::max(out.jump, std::abs(da - db));
        size = std::max(size, std::abs(db));
      }
    }
  }
  require(out.jump <= 1e-9 * size, [&] {
    return "stitch: the blocks could not be made " + std::string(c1 ? "C1" : "C0") + " across their interfaces (jump " +
           format_number(out.jump) + " left)";
  });
  out.blocks = std::move(blocks);
  return out;
}

template StitchedBlocks<2> stitch_blocks(std::vector<LRSpline<2>>, const StitchOptions&, CrossSpeed);
template StitchedBlocks<3> stitch_blocks(std::vector<LRSpline<3>>, const StitchOptions&, CrossSpeed);

}  // namespace trivar
