#include "trivar/iga/error_norms.hpp"

#include <cmath>
#include <vector>

#include "trivar/core/parallel.hpp"
#include "trivar/iga/patch_quadrature.hpp"

namespace trivar {

template <int D>
ErrorNorms error_norms(const TensorSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                       const ExactSolution<D>& exact, int threads, const ElementPartition& part) {
  const int m = components, N = space.num_basis();
  const PatchQuadrature<D> quad = patch_quadrature(space, 2);
  const int Q = quad.points();
  // sum_I c_I R_I = (sum_I c_I w_I B_I) / W: the numerator is a B-spline sum.
  std::vector<double> num(static_cast<std::size_t>(N) * m);
  for (int I = 0; I < N; ++I)
    for (int c = 0; c < m; ++c)
      num[static_cast<std::size_t>(I * m + c)] = coefs[static_cast<Eigen::Index>(c) * N + I] * space.geometry.weight(I);
  // Elements are numbered with the last direction slowest: a part's layers are one run of elements.
  const int per_layer = quad.num_elements() / quad.dir[D - 1].elements();
  const std::pair<int, int> layers = part.layers(quad.dir[D - 1].elements());
  const int first = layers.first * per_layer;
  std::vector<double> l2(static_cast<std::size_t>((layers.second - layers.first) * per_layer)), h1(l2.size());
  parallel_for(static_cast<std::ptrdiff_t>(l2.size()), threads, [&](std::ptrdiff_t i) {
    const std::ptrdiff_t el = first + i;
    thread_local GridScratch scratch;
    thread_local GridGeometry<D> g;
    thread_local std::vector<double> f, u, grad;
    const Ints<D> e = quad.element_index(static_cast<int>(el));
    grid_geometry(space, quad, e, scratch, g);
    grid_fields(space, quad, e, num.data(), m, m, scratch, f);
    u.resize(static_cast<std::size_t>(m));
    grad.resize(static_cast<std::size_t>(m) * D);
    double sl2 = 0, sh1 = 0;
    for (int q = 0; q < Q; ++q) {
      const double W = g.W[static_cast<std::size_t>(q)];
      exact(&g.x[static_cast<std::size_t>(q * D)], u.data(), grad.data());
      for (int c = 0; c < m; ++c) {
        auto at = [&](int a) { return f[static_cast<std::size_t>((a * Q + q) * m + c)]; };
        const double uh = at(0) / W;
        double du[D];
        for (int a = 0; a < D; ++a) du[a] = (at(a + 1) - uh * g.dW[static_cast<std::size_t>(q * D + a)]) / W;
        const double d0 = uh - u[static_cast<std::size_t>(c)];
        sl2 += d0 * d0 * g.measure[static_cast<std::size_t>(q)];
        for (int k = 0; k < D; ++k) {
          double gk = 0;
          for (int a = 0; a < D; ++a) gk += g.jinv[static_cast<std::size_t>((q * D + a) * D + k)] * du[a];
          const double d = gk - grad[static_cast<std::size_t>(c * D + k)];
          sh1 += d * d * g.measure[static_cast<std::size_t>(q)];
        }
      }
    }
    l2[static_cast<std::size_t>(i)] = sl2;
    h1[static_cast<std::size_t>(i)] = sh1;
  });
  ErrorNorms r;
  for (std::size_t i = 0; i < l2.size(); ++i) {
    r.l2 += l2[i];
    r.h1 += h1[i];
  }
  r.l2 = std::sqrt(r.l2);
  r.h1 = std::sqrt(r.h1);
  return r;
}

template <int D>
ErrorNorms error_norms(const MultipatchSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                       const ExactSolution<D>& exact, int threads, const ElementPartition& part) {
  double l2 = 0, h1 = 0;
  for (int p = 0; p < space.num_patches(); ++p) {
    const ErrorNorms e = error_norms(space.patches[static_cast<std::size_t>(p)],
                                     patch_coefs(space, p, coefs, components), components, exact, threads, part);
    l2 += e.l2 * e.l2;
    h1 += e.h1 * e.h1;
  }
  return {std::sqrt(l2), std::sqrt(h1)};
}

#define TRIVAR_INSTANTIATE(D)                                                                                   \
  template ErrorNorms error_norms(const TensorSpace<D>&, const Eigen::VectorXd&, int, const ExactSolution<D>&, int, \
                                  const ElementPartition&);                                                      \
  template ErrorNorms error_norms(const MultipatchSpace<D>&, const Eigen::VectorXd&, int, const ExactSolution<D>&, int, \
                                  const ElementPartition&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
