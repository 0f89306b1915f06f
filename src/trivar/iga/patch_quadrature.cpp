#include "trivar/iga/patch_quadrature.hpp"

#include <cmath>

#include "trivar/iga/sum_factorization.hpp"

namespace trivar {

template <int D>
Ints<D> PatchQuadrature<D>::elements() const {
  Ints<D> n;
  for (int k = 0; k < D; ++k) n[k] = dir[k].elements();
  return n;
}

template <int D>
int PatchQuadrature<D>::num_elements() const {
  int n = 1;
  for (int k = 0; k < D; ++k) n *= dir[k].elements();
  return n;
}

template <int D>
int PatchQuadrature<D>::points() const {
  int n = 1;
  for (int k = 0; k < D; ++k) n *= dir[k].points;
  return n;
}

template <int D>
Ints<D> PatchQuadrature<D>::element_index(int e) const {
  Ints<D> m;
  for (int k = 0; k < D; ++k) {
    m[k] = e % dir[k].elements();
    e /= dir[k].elements();
  }
  return m;
}

template <int D>
PatchQuadrature<D> patch_quadrature(const TensorSpace<D>& space, const Ints<D>& points_per_dir) {
  PatchQuadrature<D> q;
  for (int k = 0; k < D; ++k) q.dir[k] = direction_table(space.geometry.knots(k), points_per_dir[k]);
  return q;
}

template <int D>
PatchQuadrature<D> patch_quadrature(const TensorSpace<D>& space, int extra) {
  Ints<D> n;
  for (int k = 0; k < D; ++k) n[k] = space.degree(k) + extra;
  return patch_quadrature(space, n);
}

template <int D>
int global_basis(const TensorSpace<D>& space, const PatchQuadrature<D>& quad, const Ints<D>& e, int local) {
  int index = 0, stride = 1;
  for (int k = 0; k < D; ++k) {
    const int nk = quad.dir[k].functions();
    index += (quad.dir[k].first[static_cast<std::size_t>(e[k])] + local % nk) * stride;
    local /= nk;
    stride *= space.geometry.count(k);
  }
  return index;
}

namespace {

// Depth-first over the directions: at direction k contract with the values, recurse, then (if no derivative
// was taken yet) with the derivatives and recurse, so each partial result is computed once and shared by
// all derivatives below it: 2 + 3 + 4 contractions in 3-D instead of 4 x 3. Components ride along as the
// innermost index.
template <int D>
void grid_tree(const PatchQuadrature<D>& quad, const Ints<D>& e, const double* in, int k, int deriv, int inner,
               int outer, GridScratch& s, double* out, int points, int components) {
  const DirectionTable& t = quad.dir[k];
  outer /= t.functions();
  for (int branch = 0; branch < (deriv < 0 ? 2 : 1); ++branch) {
    const int d = branch == 0 ? deriv : k;
    const double* F = branch == 0 ? t.values(e[k]) : t.derivatives(e[k]);
    double* dst;
    if (k == D - 1) {
      dst = out + static_cast<std::ptrdiff_t>(d + 1) * points * components;
    } else {
      std::vector<double>& buf = s.level[static_cast<std::size_t>(k)];
      buf.resize(static_cast<std::size_t>(inner) * t.points * outer);
      dst = buf.data();
    }
    contract(in, inner, t.functions(), outer, F, t.points, 1, t.points, dst);
    if (k < D - 1) grid_tree(quad, e, dst, k + 1, d, inner * t.points, outer, s, out, points, components);
  }
}

}  // namespace

template <int D>
void grid_fields(const TensorSpace<D>& space, const PatchQuadrature<D>& quad, const Ints<D>& e, const double* coefs,
                 int stride, int components, GridScratch& s, std::vector<double>& out) {
  int nloc = 1, points = 1;
  for (int k = 0; k < D; ++k) {
    nloc *= quad.dir[k].functions();
    points *= quad.dir[k].points;
  }
  s.block.resize(static_cast<std::size_t>(nloc) * components);
  for (int l = 0; l < nloc; ++l) {
    const double* c = coefs + static_cast<std::size_t>(global_basis(space, quad, e, l)) * stride;
    for (int m = 0; m < components; ++m) s.block[static_cast<std::size_t>(l * components + m)] = c[m];
  }
  out.resize(static_cast<std::size_t>(components) * (D + 1) * points);
  grid_tree(quad, e, s.block.data(), 0, -1, components, nloc, s, out.data(), points, components);
}

template <int D>
void grid_geometry(const TensorSpace<D>& space, const PatchQuadrature<D>& quad, const Ints<D>& e, GridScratch& s,
                   GridGeometry<D>& g) {
  const TensorSpline<D>& geo = space.geometry;
  const bool rational = geo.is_rational();
  const int comps = geo.stride();
  std::vector<double>& f = s.fields;
  grid_fields(space, quad, e, geo.coefs().data(), comps, comps, s, f);
  const int Q = quad.points();
  g.x.resize(static_cast<std::size_t>(Q) * D);
  g.jinv.resize(static_cast<std::size_t>(Q) * D * D);
  g.measure.resize(static_cast<std::size_t>(Q));
  g.W.resize(static_cast<std::size_t>(Q));
  g.dW.resize(static_cast<std::size_t>(Q) * D);
  // Quadrature weight of point q: product of the 1-D weights.
  for (int q = 0; q < Q; ++q) {
    auto at = [&](int comp, int a) { return f[static_cast<std::size_t>((a * Q + q) * comps + comp)]; };
    const double W = rational ? at(D, 0) : 1.0;
    double dW[D], J[D][D];
    for (int a = 0; a < D; ++a) dW[a] = rational ? at(D, a + 1) : 0.0;
    for (int c = 0; c < D; ++c) {
      const double x = at(c, 0) / W;
      g.x[static_cast<std::size_t>(q * D + c)] = x;
      for (int a = 0; a < D; ++a) J[c][a] = (at(c, a + 1) - x * dW[a]) / W;
    }
    double inv[D][D], det;
    if constexpr (D == 2) {
      det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      inv[0][0] = J[1][1] / det;
      inv[0][1] = -J[0][1] / det;
      inv[1][0] = -J[1][0] / det;
      inv[1][1] = J[0][0] / det;
    } else {
      const double c00 = J[1][1] * J[2][2] - J[1][2] * J[2][1];
      const double c01 = J[1][2] * J[2][0] - J[1][0] * J[2][2];
      const double c02 = J[1][0] * J[2][1] - J[1][1] * J[2][0];
      det = J[0][0] * c00 + J[0][1] * c01 + J[0][2] * c02;
      inv[0][0] = c00 / det;
      inv[1][0] = c01 / det;
      inv[2][0] = c02 / det;
      inv[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
      inv[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
      inv[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
      inv[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
      inv[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
      inv[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
    }
    // inv is J^{-1}: inv[a][c] = d u_a / d x_c.
    for (int a = 0; a < D; ++a) {
      g.dW[static_cast<std::size_t>(q * D + a)] = dW[a];
      for (int c = 0; c < D; ++c) g.jinv[static_cast<std::size_t>((q * D + a) * D + c)] = inv[a][c];
    }
    g.W[static_cast<std::size_t>(q)] = W;
    double w = 1.0;
    for (int k = 0, r = q; k < D; r /= quad.dir[k].points, ++k)
      w *= quad.dir[k].weight[static_cast<std::size_t>(e[k] * quad.dir[k].points + r % quad.dir[k].points)];
    g.measure[static_cast<std::size_t>(q)] = std::abs(det) * w;
  }
}

template <int D>
void grid_integrate(const PatchQuadrature<D>& quad, const Ints<D>& e, const double* g, GridScratch& s,
                    std::vector<double>& out) {
  const double* in = g;
  int inner = 1, outer = quad.points();
  for (int k = 0; k < D; ++k) {
    const DirectionTable& t = quad.dir[k];
    outer /= t.points;
    std::vector<double>& dst = k == D - 1 ? out : (k % 2 == 0 ? s.a : s.b);
    dst.resize(static_cast<std::size_t>(inner) * t.functions() * outer);
    contract(in, inner, t.points, outer, t.values(e[k]), t.functions(), t.points, 1, dst.data());
    in = dst.data();
    inner *= t.functions();
  }
}

#define TRIVAR_INSTANTIATE(D)                                                                                        \
  template struct PatchQuadrature<D>;                                                                                \
  template PatchQuadrature<D> patch_quadrature(const TensorSpace<D>&, const Ints<D>&);                               \
  template PatchQuadrature<D> patch_quadrature(const TensorSpace<D>&, int);                                          \
  template int global_basis(const TensorSpace<D>&, const PatchQuadrature<D>&, const Ints<D>&, int);                  \
  template void grid_fields(const TensorSpace<D>&, const PatchQuadrature<D>&, const Ints<D>&, const double*, int, int, \
                            GridScratch&, std::vector<double>&);                                                     \
  template void grid_geometry(const TensorSpace<D>&, const PatchQuadrature<D>&, const Ints<D>&, GridScratch&,        \
                              GridGeometry<D>&);                                                                     \
  template void grid_integrate(const PatchQuadrature<D>&, const Ints<D>&, const double*, GridScratch&,               \
                               std::vector<double>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
