#include "trivar/iga/refined_space.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/hier/hierarchical_evaluator.hpp"
#include "trivar/lr/lr_bezier_extraction.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

namespace {

template <int D>
void check_geometry(bool rational, int dim, const char* kind) {
  require(!rational && dim == D, [&] {
    return std::string("iga: ") + kind + " analysis needs a polynomial geometry with " + std::to_string(D) + " coordinates";
  });
}

// Functions non-zero on a side: a Bernstein coefficient of the side's layer is non-zero on an element there.
// Truncation writes exact zeros, and the blossoms of B-splines vanishing on a side are zero up to rounding, so
// coefficients below 1e-14 (the rows are O(1): THB rows and those of T-splines that are a partition of unity
// sum to one) count as zero.
template <int D>
void side_functions_from_elements(RefinedSpace<D>& s) {
  for (int dir = 0; dir < D; ++dir)
    for (int side = 0; side < 2; ++side) {
      std::vector<char> on(static_cast<std::size_t>(s.num_basis), 0);
      const double end = side == 0 ? s.domain.lo[dir] : s.domain.hi[dir];
      for (const RefinedElement<D>& el : s.elements) {
        if ((side == 0 ? el.box.lo[dir] : el.box.hi[dir]) != end) continue;
        for (Eigen::Index j = 0; j < el.C.cols(); ++j) {
          int a = static_cast<int>(j);
          for (int k = 0; k < dir; ++k) a /= s.degrees[k] + 1;
          if (a % (s.degrees[dir] + 1) != (side == 0 ? 0 : s.degrees[dir])) continue;
          for (Eigen::Index r = 0; r < el.C.rows(); ++r)
            if (std::abs(el.C(r, j)) > 1e-14) on[static_cast<std::size_t>(el.ids[static_cast<std::size_t>(r)])] = 1;
        }
      }
      auto& ids = s.face_basis[static_cast<std::size_t>(2 * dir + side)];
      for (int i = 0; i < s.num_basis; ++i)
        if (on[static_cast<std::size_t>(i)]) ids.push_back(i);
    }
}

}  // namespace

template <int D>
RefinedSpace<D> refined_space(const LRSpline<D>& g, int threads) {
  check_geometry<D>(g.is_rational(), g.dim(), "LR");
  RefinedSpace<D> s;
  s.degrees = g.degrees();
  s.domain = g.domain();
  s.num_basis = g.num_basis();
  s.control.resize(static_cast<std::size_t>(s.num_basis) * D);
  for (int i = 0; i < s.num_basis; ++i)
    std::copy_n(g.basis_function(i).coef.data(), D, s.control.data() + static_cast<std::ptrdiff_t>(i) * D);
  s.elements.resize(static_cast<std::size_t>(g.num_elements()));
  parallel_for(g.num_elements(), threads, [&](std::ptrdiff_t e) {
    RefinedElement<D>& b = s.elements[static_cast<std::size_t>(e)];
    const auto support = g.element_support(static_cast<int>(e));
    b.ids.assign(support.begin(), support.end());
    b.box = g.element(static_cast<int>(e));
    b.C = extraction_operator<D>(g.degrees(), g.basis_functions(), b.ids, b.box);
  });
  // Functions non-zero on a side: local knots clamped (p + 1 equal) there.
  for (int dir = 0; dir < D; ++dir)
    for (int side = 0; side < 2; ++side) {
      const int p = g.degree(dir);
      const double end = side == 0 ? g.domain().lo[dir] : g.domain().hi[dir];
      auto& ids = s.face_basis[static_cast<std::size_t>(2 * dir + side)];
      for (int i = 0; i < g.num_basis(); ++i) {
        const auto& t = g.basis_function(i).knots[dir];
        bool clamped = true;
        for (int j = 0; j <= p; ++j) clamped = clamped && t[static_cast<std::size_t>(side == 0 ? j : j + 1)] == end;
        if (clamped) ids.push_back(i);
      }
    }
  const ElementEvaluator<D>* locator = &g.evaluator();
  s.locate = [locator](const Param<D>& u) { return locator->find_element(u); };
  return s;
}

template <int D>
RefinedSpace<D> refined_space(const HierarchicalSpline<D>& g, int threads) {
  check_geometry<D>(g.is_rational(), g.dim(), "hierarchical");
  const HierarchicalSpace<D>& h = g.space();
  RefinedSpace<D> s;
  s.degrees = h.degrees();
  s.domain = h.domain();
  s.num_basis = h.num_basis();
  s.control.assign(g.coefs().begin(), g.coefs().end());
  s.elements.resize(static_cast<std::size_t>(h.num_elements()));
  parallel_for(h.num_elements(), threads, [&](std::ptrdiff_t e) {
    HierarchicalElement<D> el = h.element_operator(static_cast<int>(e));
    RefinedElement<D>& r = s.elements[static_cast<std::size_t>(e)];
    r.ids = std::move(el.ids);
    r.C = std::move(el.C);
    r.box = el.box;
  });
  side_functions_from_elements(s);
  const HierarchicalEvaluator<D>* locator = &g.evaluator();
  const HierarchicalSpace<D>* space = &h;
  s.locate = [locator, space](const Param<D>& u) { return locator->find_element(*space, u); };
  return s;
}

RefinedSpace<2> refined_space(const TSplineSurface& g, int threads) {
  const PartitionOfUnity& pu = g.partition_of_unity();
  require(pu.max_defect <= 1e-12, [&] {
    return "iga: the T-spline's blending functions do not sum to one (between " + std::to_string(pu.min_sum) + " and " +
           std::to_string(pu.max_sum) + "): analysis needs a standard T-spline (e.g. analysis-suitable)";
  });
  RefinedSpace<2> s;
  s.degrees = g.degrees();
  s.domain = g.domain();
  s.num_basis = static_cast<int>(g.basis().size());
  s.control.resize(static_cast<std::size_t>(s.num_basis) * 2);
  double size = 0;
  for (const LRBSpline<2>& b : g.basis()) size = std::max({size, std::abs(b.coef[0]), std::abs(b.coef[1])});
  for (int i = 0; i < s.num_basis; ++i) {
    const LRBSpline<2>& b = g.basis()[static_cast<std::size_t>(i)];
    require(b.coef[3] == 1.0, [&] {
      return "iga: T-spline point " + std::to_string(i) + " has weight " + std::to_string(b.coef[3]) +
             " (analysis needs the polynomial T-spline, all weights 1)";
    });
    require(std::abs(b.coef[2]) <= 1e-12 * std::max(size, 1.0), [&] {
      return "iga: T-spline point " + std::to_string(i) + " has z = " + std::to_string(b.coef[2]) +
             " (analysis needs a planar T-spline in the plane z = 0)";
    });
    std::copy_n(b.coef.data(), 2, s.control.data() + static_cast<std::ptrdiff_t>(i) * 2);
  }
  double area = 0;
  for (const Box<2>& e : g.elements()) area += e.extent(0) * e.extent(1);
  const double box = s.domain.extent(0) * s.domain.extent(1);
  require(std::abs(area - box) <= 1e-12 * box,
          "iga: the T-faces do not fill the domain rectangle (analysis on T-splines needs a rectangular domain)");
  s.elements.resize(g.elements().size());
  parallel_for(static_cast<std::ptrdiff_t>(s.elements.size()), threads, [&](std::ptrdiff_t e) {
    RefinedElement<2>& el = s.elements[static_cast<std::size_t>(e)];
    const auto ids = g.element_supports()[static_cast<int>(e)];
    el.ids.assign(ids.begin(), ids.end());
    el.box = g.elements()[static_cast<std::size_t>(e)];
    el.C = extraction_operator<2>(g.degrees(), g.basis(), el.ids, el.box);
  });
  side_functions_from_elements(s);
  s.locate = [&g](const Param<2>& u) { return g.locate(u); };
  return s;
}

template <int D>
void refined_point(const RefinedSpace<D>& g, const RefinedElement<D>& el, const Param<D>& u, RefinedPoint<D>& out) {
  // Bernstein polynomials of each direction on the element's interval: the B-splines of the knot vector
  // with p + 1 copies of each end, and their derivatives up to order 2.
  double B[D][3][kMaxDegree + 1];
  Ints<D> n;
  int nb = 1;
  for (int k = 0; k < D; ++k) {
    const int p = g.degrees[k];
    n[k] = p + 1;
    nb *= n[k];
    double t[2 * (kMaxDegree + 1)];
    for (int i = 0; i <= p; ++i) {
      t[i] = el.box.lo[k];
      t[p + 1 + i] = el.box.hi[k];
    }
    double ders[3 * (kMaxDegree + 1)];
    basis_derivatives(t, p, p, u[k], 2, ders);
    for (int o = 0; o < 3; ++o)
      for (int i = 0; i <= p; ++i) B[k][o][i] = ders[o * (p + 1) + i];
  }
  // Tensor Bernstein values and derivatives: orders per direction.
  thread_local std::vector<double> tb;
  const int nd = 1 + D + D * D;
  tb.resize(static_cast<std::size_t>(nb * nd));
  for (int j = 0; j < nb; ++j) {
    int idx[D];
    for (int k = 0, r = j; k < D; r /= n[k], ++k) idx[k] = r % n[k];
    auto prod = [&](int a, int b) {  // derivative once along a and once along b (-1: none)
      double v = 1;
      for (int k = 0; k < D; ++k) v *= B[k][(a == k) + (b == k)][idx[k]];
      return v;
    };
    tb[static_cast<std::size_t>(j * nd)] = prod(-1, -1);
    for (int a = 0; a < D; ++a) {
      tb[static_cast<std::size_t>(j * nd + 1 + a)] = prod(a, -1);
      for (int b = 0; b < D; ++b) tb[static_cast<std::size_t>(j * nd + 1 + D + a * D + b)] = prod(a, b);
    }
  }
  const int m = static_cast<int>(el.ids.size());
  out.R.assign(static_cast<std::size_t>(m), 0.0);
  out.dR.assign(static_cast<std::size_t>(m) * D, 0.0);
  out.d2R.assign(static_cast<std::size_t>(m) * D * D, 0.0);
  for (int l = 0; l < m; ++l)
    for (int j = 0; j < nb; ++j) {
      const double c = el.C(l, j);
      if (c == 0.0) continue;
      const double* t = &tb[static_cast<std::size_t>(j * nd)];
      out.R[static_cast<std::size_t>(l)] += c * t[0];
      for (int a = 0; a < D; ++a) {
        out.dR[static_cast<std::size_t>(l * D + a)] += c * t[1 + a];
        for (int b = 0; b < D; ++b) out.d2R[static_cast<std::size_t>((l * D + a) * D + b)] += c * t[1 + D + a * D + b];
      }
    }
  out.x.fill(0.0);
  for (auto& r : out.J) r.fill(0.0);
  for (auto& h : out.H)
    for (auto& r : h) r.fill(0.0);
  for (int l = 0; l < m; ++l) {
    const double* x = g.control.data() + static_cast<std::ptrdiff_t>(el.ids[static_cast<std::size_t>(l)]) * D;
    for (int c = 0; c < D; ++c) {
      out.x[c] += x[c] * out.R[static_cast<std::size_t>(l)];
      for (int a = 0; a < D; ++a) {
        out.J[c][a] += x[c] * out.dR[static_cast<std::size_t>(l * D + a)];
        for (int b = 0; b < D; ++b) out.H[c][a][b] += x[c] * out.d2R[static_cast<std::size_t>((l * D + a) * D + b)];
      }
    }
  }
}

template <int D>
double physical_gradients(const RefinedPoint<D>& p, std::vector<double>& grad) {
  Eigen::Matrix<double, D, D> J;
  for (int r = 0; r < D; ++r)
    for (int s = 0; s < D; ++s) J(r, s) = p.J[r][s];
  const Eigen::Matrix<double, D, D> JinvT = J.inverse().transpose();
  const int m = static_cast<int>(p.R.size());
  grad.resize(static_cast<std::size_t>(m) * D);
  for (int l = 0; l < m; ++l) {
    const Eigen::Matrix<double, D, 1> g =
        JinvT * Eigen::Map<const Eigen::Matrix<double, D, 1>>(&p.dR[static_cast<std::size_t>(l * D)]);
    for (int c = 0; c < D; ++c) grad[static_cast<std::size_t>(l * D + c)] = g[c];
  }
  return std::abs(J.determinant());
}

#define TRIVAR_INSTANTIATE(D)                                                                               \
  template RefinedSpace<D> refined_space(const LRSpline<D>&, int);                                         \
  template RefinedSpace<D> refined_space(const HierarchicalSpline<D>&, int);                               \
  template void refined_point(const RefinedSpace<D>&, const RefinedElement<D>&, const Param<D>&, RefinedPoint<D>&);      \
  template double physical_gradients(const RefinedPoint<D>&, std::vector<double>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
