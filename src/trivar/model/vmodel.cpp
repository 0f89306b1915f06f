#include "trivar/model/vmodel.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/core/tolerance.hpp"
#include "trivar/model/trimmed_integral.hpp"
#include "trivar/spline/measure.hpp"

namespace trivar {

namespace {

int default_gauss_points(const TensorSpline<3>& g) {
  const int p = std::max({g.degree(0), g.degree(1), g.degree(2)});
  return g.is_rational() ? 2 * p + 8 : (3 * p + 1) / 2 + 1;
}

// Element boundaries of direction k: the geometry's breakpoints and, for a field density, the field's mapped
// affinely onto the cell's domain (as Attribute::eval maps it).
std::vector<double> element_breaks(const TensorSpline<3>& g, const Attribute& a, int k) {
  std::vector<double> b = g.knots(k).breakpoints();
  const double lo = g.knots(k).start(), len = g.knots(k).end() - lo;
  if (const TensorSpline<3>* f = a.spline()) {
    const double flo = f->knots(k).start(), flen = f->knots(k).end() - flo;
    for (double x : f->knots(k).breakpoints()) b.push_back(lo + (x - flo) / flen * len);
    std::sort(b.begin(), b.end());
    b.erase(std::unique(b.begin(), b.end(), [&](double x, double y) { return y - x <= tol::knot * len; }), b.end());
  }
  return b;
}

// The density integrated over a trimmed cell on its exact boundary (trimmed_integral.hpp): the antiderivative
// in x is a Gauss sum over the density's elements along x from the box's left side (x = u on a trimmed cell).
double trimmed_mass(const VCell& c, const Attribute& a, int n) {
  // Expressions are integrated to the accuracy of the rule; 16 points leave the loop quadrature in charge.
  constexpr int kTrimmedPoints = 16;
  const QuadratureRule rule = gauss_legendre(std::max(n, kTrimmedPoints));
  const TensorSpline<3>& g = c.geometry();
  if (a.kind() == Attribute::Kind::constant) {
    double rho;
    a.eval(g, g.domain().center(), &rho);
    return rho * c.trim()->volume();
  }
  const std::vector<double> br = element_breaks(g, a, 0);
  const auto antiderivative = [&](const std::array<double, 3>& x) {
    double sum = 0, rho;
    for (std::size_t s = 0; s + 1 < br.size() && br[s] < x[0]; ++s) {
      const double lo = br[s], hi = std::min(br[s + 1], x[0]);
      for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
        a.eval(g, {lo + rule.nodes[q] * (hi - lo), x[1], x[2]}, &rho);
        sum += rule.weights[q] * (hi - lo) * rho;
      }
    }
    return sum;
  };
  return trimmed_integral(c.trim()->boundary(), antiderivative);
}

}  // namespace

int VModel::add_cell(VCell cell) {
  cells_.push_back(std::move(cell));
  glued_ = false;
  return num_cells() - 1;
}

const VCell& VModel::cell(int i) const {
  require(i >= 0 && i < num_cells(), [&] { return "V-model: cell index " + std::to_string(i) + " out of range"; });
  return cells_[i];
}

VCell& VModel::cell(int i) {
  require(i >= 0 && i < num_cells(), [&] { return "V-model: cell index " + std::to_string(i) + " out of range"; });
  return cells_[i];
}

const VTopology& VModel::glue(const GlueOptions& options) {
  topology_ = trivar::glue(cells_, options);
  glued_ = true;
  return topology_;
}

const VTopology& VModel::topology() const {
  require(glued_, "V-model: not glued (call glue() after adding cells)");
  return topology_;
}

std::vector<int> VModel::neighbours(int c, CellRelation at_least) const {
  cell(c);
  std::vector<int> out;
  for (int other = 0; other < num_cells(); ++other)
    if (other != c && relation(c, other) >= at_least) out.push_back(other);
  return out;
}

CellRelation VModel::relation(int a, int b) const {
  const VTopology& t = topology();
  cell(a), cell(b);
  for (int f = 0; f < 6; ++f) {
    const int twin = t.halves[6 * a + f].twin;
    if (twin >= 0 && twin / 6 == b) return CellRelation::face;
  }
  for (int ea : t.cell_edges[a])
    for (int eb : t.cell_edges[b])
      if (ea == eb) return CellRelation::curve;
  for (int pa : t.cell_corners[a])
    for (int pb : t.cell_corners[b])
      if (pa == pb) return CellRelation::point;
  return CellRelation::none;
}

Box<3> VModel::bounding_box() const {
  Box<3> box = Box<3>::empty();
  for (const auto& c : cells_) {
    double lo[3], hi[3];
    c.geometry().control_bounds(lo, hi);
    box.extend(lo);
    box.extend(hi);
  }
  return box;
}

double VModel::volume(int n) const {
  require(n >= 0, "V-model volume: negative number of Gauss points");
  double v = 0;
  for (const auto& c : cells_)
    v += c.is_trimmed() ? c.trim()->volume() : measure(c.geometry(), n > 0 ? n : default_gauss_points(c.geometry()));
  return v;
}

double VModel::mass(const std::string& density, int n) const {
  require(n >= 0, "V-model mass: negative number of Gauss points");
  double total = 0;
  for (int ci = 0; ci < num_cells(); ++ci) {
    const VCell& c = cells_[ci];
    require(c.has_attribute(density),
            [&] { return "V-model mass: cell " + std::to_string(ci) + " has no attribute '" + density + "'"; });
    const Attribute& a = c.attribute(density);
    require(a.components() == 1, [&] {
      return "V-model mass: attribute '" + density + "' of cell " + std::to_string(ci) + " has " +
             std::to_string(a.components()) + " components, a density needs 1";
    });
    if (c.is_trimmed()) {
      total += trimmed_mass(c, a, n);
      continue;
    }
    const TensorSpline<3>& g = c.geometry();
    const QuadratureRule rule = gauss_legendre(n > 0 ? n : default_gauss_points(g));
    const std::array<std::vector<double>, 3> br{element_breaks(g, a, 0), element_breaks(g, a, 1),
                                               element_breaks(g, a, 2)};
    double d[12], rho;
    for (std::size_t k = 0; k + 1 < br[2].size(); ++k)
      for (std::size_t j = 0; j + 1 < br[1].size(); ++j)
        for (std::size_t i = 0; i + 1 < br[0].size(); ++i) {
          const double hu = br[0][i + 1] - br[0][i], hv = br[1][j + 1] - br[1][j], hw = br[2][k + 1] - br[2][k];
          double sum = 0;
          for (std::size_t qk = 0; qk < rule.nodes.size(); ++qk)
            for (std::size_t qj = 0; qj < rule.nodes.size(); ++qj)
              for (std::size_t qi = 0; qi < rule.nodes.size(); ++qi) {
                const Param<3> u{br[0][i] + rule.nodes[qi] * hu, br[1][j] + rule.nodes[qj] * hv,
                                 br[2][k] + rule.nodes[qk] * hw};
                g.eval_derivs(u, 1, d);
                const double* du = d + 3;
                const double* dv = d + 6;
                const double* dw = d + 9;
                const double det = du[0] * (dv[1] * dw[2] - dv[2] * dw[1]) - du[1] * (dv[0] * dw[2] - dv[2] * dw[0]) +
                                   du[2] * (dv[0] * dw[1] - dv[1] * dw[0]);
                a.eval(g, u, &rho);
                sum += rule.weights[qi] * rule.weights[qj] * rule.weights[qk] * rho * std::abs(det);
              }
          total += sum * hu * hv * hw;
        }
  }
  return total;
}

}  // namespace trivar
