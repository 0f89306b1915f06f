#include "trivar/iga/point_basis.hpp"

#include "trivar/spline/basis.hpp"

namespace trivar {

template <int D>
void point_basis(const TensorSpace<D>& space, const Param<D>& u, PointBasis<D>& out) {
  const TensorSpline<D>& g = space.geometry;
  double N[D][kMaxDegree + 1], dN[D][kMaxDegree + 1];
  Ints<D> first, n;
  int nloc = 1;
  for (int k = 0; k < D; ++k) {
    const KnotVector& kv = g.knots(k);
    const int s = kv.find_span(u[k]);
    basis_values_first_derivatives(kv, s, u[k], N[k], dN[k]);
    first[k] = s - kv.degree();
    n[k] = kv.degree() + 1;
    nloc *= n[k];
  }
  out.ids.resize(static_cast<std::size_t>(nloc));
  out.R.resize(static_cast<std::size_t>(nloc));
  out.dR.resize(static_cast<std::size_t>(nloc) * D);
  double W = 0, dW[D] = {};
  for (int l = 0; l < nloc; ++l) {
    int id = 0, stride = 1;
    double B = 1, dB[D];
    for (int a = 0; a < D; ++a) dB[a] = 1;
    for (int k = 0, r = l; k < D; r /= n[k], ++k) {
      const int i = r % n[k];
      id += (first[k] + i) * stride;
      stride *= g.count(k);
      B *= N[k][i];
      for (int a = 0; a < D; ++a) dB[a] *= (a == k ? dN[k][i] : N[k][i]);
    }
    const double w = g.weight(id);
    out.ids[static_cast<std::size_t>(l)] = id;
    out.R[static_cast<std::size_t>(l)] = w * B;
    W += w * B;
    for (int a = 0; a < D; ++a) {
      out.dR[static_cast<std::size_t>(l * D + a)] = w * dB[a];
      dW[a] += w * dB[a];
    }
  }
  for (auto& row : out.J) row.fill(0.0);
  out.x.fill(0.0);
  for (int l = 0; l < nloc; ++l) {
    const double wB = out.R[static_cast<std::size_t>(l)];
    out.R[static_cast<std::size_t>(l)] = wB / W;
    for (int a = 0; a < D; ++a) {
      double& d = out.dR[static_cast<std::size_t>(l * D + a)];
      d = d / W - wB * dW[a] / (W * W);
    }
    double x[D];
    g.control_point(out.ids[static_cast<std::size_t>(l)], x);
    for (int c = 0; c < D; ++c) {
      out.x[c] += x[c] * out.R[static_cast<std::size_t>(l)];
      for (int a = 0; a < D; ++a) out.J[c][a] += x[c] * out.dR[static_cast<std::size_t>(l * D + a)];
    }
  }
}

template void point_basis(const TensorSpace<2>&, const Param<2>&, PointBasis<2>&);
template void point_basis(const TensorSpace<3>&, const Param<3>&, PointBasis<3>&);

}  // namespace trivar
