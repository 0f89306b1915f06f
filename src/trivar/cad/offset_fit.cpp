#include "trivar/cad/offset_fit.hpp"

#include <Eigen/Dense>
#include <GeomAdaptor_Surface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar::cad {

namespace {

constexpr std::size_t kMaxOffsetControlPoints = std::size_t{1} << 18;
constexpr int kMaxOffsetHalvings = 40;
// Below this fraction of the largest |Su| |Sv| on the face, |Su x Sv| leaves the normal undefined.
constexpr double kDegenerateSine = 1e-9;

// The fit's degree: quintic interpolation's error falls as h^6, so a tolerance of 1e-9 of the part takes tens
// of cells per direction, where cubics took hundreds.
constexpr int kFitDegree = 5;
constexpr std::size_t kNodes = kFitDegree + 1;  // interpolation nodes per cell and direction

// The grid's parameters at the (2 p)-ths of every cell: even positions are the interpolation nodes (the cells'
// p-ths), odd ones the check points midway between them.
std::vector<double> check_grid(const std::vector<double>& breaks) {
  constexpr int parts = 2 * kFitDegree;
  std::vector<double> out;
  out.reserve(parts * breaks.size());
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i)
    for (int k = 0; k < parts; ++k) out.push_back(breaks[i] + (breaks[i + 1] - breaks[i]) * k / parts);
  out.push_back(breaks.back());
  return out;
}

// The basis's breakpoints of continuity C3 inside [a, b] (the offset is C2 across none of them in general),
// and at least four cells.
std::vector<double> initial_breaks(const TColStd_Array1OfReal& knots, double a, double b) {
  std::vector<double> out{a};
  for (int i = knots.Lower(); i <= knots.Upper(); ++i)
    if (knots(i) > a + 1e-12 * (b - a) && knots(i) < b - 1e-12 * (b - a)) out.push_back(knots(i));
  out.push_back(b);
  while (out.size() < 5) {
    std::vector<double> finer{out.front()};
    for (std::size_t i = 1; i < out.size(); ++i) finer.insert(finer.end(), {0.5 * (out[i - 1] + out[i]), out[i]});
    out = std::move(finer);
  }
  return out;
}

std::array<std::vector<double>, 2> basis_breaks(const Handle(Geom_Surface)& basis, const Box<2>& uv) {
  GeomAdaptor_Surface a(basis, uv.lo[0], uv.hi[0], uv.lo[1], uv.hi[1]);
  TColStd_Array1OfReal ku(1, a.NbUIntervals(GeomAbs_C3) + 1), kv(1, a.NbVIntervals(GeomAbs_C3) + 1);
  a.UIntervals(ku, GeomAbs_C3);
  a.VIntervals(kv, GeomAbs_C3);
  return {initial_breaks(ku, uv.lo[0], uv.hi[0]), initial_breaks(kv, uv.lo[1], uv.hi[1])};
}

// The inverse of the Bernstein matrix B_i(k / p) (row k): Bezier coefficients from values at the nodes.
using NodeMatrix = std::array<std::array<double, kNodes>, kNodes>;
NodeMatrix inverse_bernstein() {
  Eigen::Matrix<double, kNodes, kNodes> m;
  for (std::size_t k = 0; k < kNodes; ++k) {
    const double t = static_cast<double>(k) / kFitDegree;
    double binom = 1;
    for (std::size_t i = 0; i < kNodes; ++i) {
      if (i > 0) binom = binom * static_cast<double>(kFitDegree + 1 - i) / static_cast<double>(i);
      m(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)) =
          binom * std::pow(t, static_cast<double>(i)) * std::pow(1 - t, static_cast<double>(kFitDegree - static_cast<int>(i)));
    }
  }
  const Eigen::Matrix<double, kNodes, kNodes> inv = m.partialPivLu().inverse();
  NodeMatrix out{};
  for (std::size_t r = 0; r < kNodes; ++r)
    for (std::size_t c = 0; c < kNodes; ++c) out[r][c] = inv(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
  return out;
}

// Bezier coefficients of each cell's interpolant applied along one direction of a grid of 3-vectors: `n`
// nodes (p per cell + 1) with stride `step` between nodes, `lines` lines `jump` apart.
void interpolate_cells(std::vector<double>& g, std::size_t n, std::size_t step, std::size_t lines, std::size_t jump) {
  static const NodeMatrix inv = inverse_bernstein();
  for (std::size_t l = 0; l < lines; ++l)
    for (std::size_t c = 0; c + 1 < n; c += kFitDegree)
      for (std::size_t x = 0; x < 3; ++x) {
        const auto at = [&](std::size_t k) -> double& { return g[3 * (l * jump + (c + k) * step) + x]; };
        std::array<double, kNodes> f{}, b{};
        for (std::size_t k = 0; k < kNodes; ++k) f[k] = at(k);
        for (std::size_t i = 0; i < kNodes; ++i)
          for (std::size_t k = 0; k < kNodes; ++k) b[i] += inv[i][k] * f[k];
        for (std::size_t k = 1; k + 1 < kNodes; ++k) at(k) = b[k];  // the ends interpolate: b = f there
      }
}

// Knots of multiplicity p at the breaks (C0 joins of the Bezier cells).
KnotVector cell_knots(const std::vector<double>& breaks) {
  std::vector<double> k(kNodes, breaks.front());
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i) k.insert(k.end(), kFitDegree, breaks[i]);
  k.insert(k.end(), kNodes, breaks.back());
  return KnotVector(kFitDegree, std::move(k));
}

}  // namespace

OffsetFit fit_offset_surface(const Handle(Geom_Surface)& basis, double distance, const Box<2>& uv, double tolerance) {
  require(tolerance > 0, "offset surface: the fitting tolerance must be > 0");
  const std::string kind = basis->DynamicType()->Name();
  std::array<std::vector<double>, 2> breaks = basis_breaks(basis, uv);
  // The exact offset on a grid. The normal is undefined where Su x Sv vanishes against the largest |Su| |Sv| of
  // the grid (a collapsed edge, where rounding leaves Su tiny and the normal's direction arbitrary, or a cusp).
  const auto offset_points = [&](const std::array<std::vector<double>, 2>& grid) {
    const std::size_t fu = grid[0].size(), fv = grid[1].size();
    std::vector<gp_XYZ> points(fu * fv), normals(fu * fv);
    double su = 0, sv = 0;
    for (std::size_t j = 0; j < fv; ++j)
      for (std::size_t i = 0; i < fu; ++i) {
        gp_Pnt p;
        gp_Vec du, dv;
        basis->D1(grid[0][i], grid[1][j], p, du, dv);
        points[j * fu + i] = p.XYZ();
        normals[j * fu + i] = du.Crossed(dv).XYZ();
        su = std::max(su, du.Magnitude());
        sv = std::max(sv, dv.Magnitude());
      }
    std::vector<double> out(3 * fu * fv);
    for (std::size_t k = 0; k < fu * fv; ++k) {
      const double m = normals[k].Modulus();
      if (!(m > kDegenerateSine * su * sv))
        throw Error("offset surface: the basis surface (" + kind + ") is degenerate at (u, v) = (" + std::to_string(grid[0][k % fu]) +
                    ", " + std::to_string(grid[1][k / fu]) + "): its normal, which the offset needs, is undefined there");
      const gp_XYZ q = points[k] + (distance / m) * normals[k];
      out[3 * k] = q.X();
      out[3 * k + 1] = q.Y();
      out[3 * k + 2] = q.Z();
    }
    return out;
  };
  for (int round = 0;; ++round) {
    const std::size_t cu = breaks[0].size() - 1, cv = breaks[1].size() - 1;
    const std::size_t nu = kFitDegree * cu + 1, nv = kFitDegree * cv + 1;
    if (nu * nv > kMaxOffsetControlPoints || round > kMaxOffsetHalvings)
      throw Error("offset surface: fitting the offset of the " + kind + " to " + std::to_string(tolerance) + " needs more than " +
                  std::to_string(kMaxOffsetControlPoints) + " control points");
    const std::array<std::vector<double>, 2> fine{check_grid(breaks[0]), check_grid(breaks[1])};
    const std::size_t fu = fine[0].size(), fv = fine[1].size();
    const std::vector<double> exact = offset_points(fine);
    std::vector<double> ctrl(3 * nu * nv);
    for (std::size_t j = 0; j < nv; ++j)
      for (std::size_t i = 0; i < nu; ++i)
        std::copy_n(&exact[3 * (2 * j * fu + 2 * i)], 3, &ctrl[3 * (j * nu + i)]);
    interpolate_cells(ctrl, nu, 1, nv, nu);
    interpolate_cells(ctrl, nv, nu, nu, 1);
    OffsetFit fit{TensorSpline<2>({cell_knots(breaks[0]), cell_knots(breaks[1])}, 3, false, std::move(ctrl)), 0};
    std::vector<double> fitted(3 * fu * fv);
    fit.surface.eval_grid(fine, fitted, 1);
    // Per cell: the deviation along the v-node lines (u-interpolation error), along the u-node lines, and
    // overall.
    std::vector<bool> split_u(cu, false), split_v(cv, false);
    bool any = false;
    for (std::size_t cj = 0; cj < cv; ++cj)
      for (std::size_t ci = 0; ci < cu; ++ci) {
        double eu = 0, ev = 0, e = 0;
        constexpr std::size_t parts = 2 * kFitDegree;
        for (std::size_t j = parts * cj; j <= parts * cj + parts; ++j)
          for (std::size_t i = parts * ci; i <= parts * ci + parts; ++i) {
            const std::size_t at = 3 * (j * fu + i);
            const double d = std::hypot(fitted[at] - exact[at], fitted[at + 1] - exact[at + 1], fitted[at + 2] - exact[at + 2]);
            e = std::max(e, d);
            if (j % 2 == 0) eu = std::max(eu, d);
            if (i % 2 == 0) ev = std::max(ev, d);
          }
        fit.deviation = std::max(fit.deviation, e);
        if (e <= 0.5 * tolerance) continue;
        any = true;
        // Halve along u when the u-interpolation carries a fair share of the error (its error falls 64-fold
        // per halving), along v likewise; a cell whose iso-lines both fit is halved both ways.
        if (eu >= ev / 8) split_u[ci] = true;
        if (ev >= eu / 8) split_v[cj] = true;
      }
    if (!any) return fit;
    for (int k = 0; k < 2; ++k) {
      const std::vector<bool>& split = k == 0 ? split_u : split_v;
      std::vector<double> finer{breaks[static_cast<std::size_t>(k)].front()};
      for (std::size_t i = 0; i < split.size(); ++i) {
        const double a = breaks[static_cast<std::size_t>(k)][i], b = breaks[static_cast<std::size_t>(k)][i + 1];
        if (split[i]) finer.push_back(0.5 * (a + b));
        finer.push_back(b);
      }
      breaks[static_cast<std::size_t>(k)] = std::move(finer);
    }
  }
}

}  // namespace trivar::cad
