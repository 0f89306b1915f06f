#include "trivar/iga/surface_poisson.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/iga/point_basis.hpp"

namespace trivar {

namespace {

using V3 = std::array<double, 3>;

// One quadrature point of the surface: the patch's functions there (global ids, values, surface gradients),
// the point, the tangent-plane projector's factors (J, G^-1) and the area weight.
struct SurfacePoint {
  std::vector<int> ids;
  std::vector<double> R;
  std::vector<V3> grad;
  V3 x{};
  std::array<V3, 2> J{};  // dx/du, dx/dv
  std::array<std::array<double, 2>, 2> Ginv{};
  double dA = 0;

  // The tangential part of an ambient vector: J G^-1 J^T g.
  V3 tangential(const double* g) const {
    const double a = J[0][0] * g[0] + J[0][1] * g[1] + J[0][2] * g[2], b = J[1][0] * g[0] + J[1][1] * g[1] + J[1][2] * g[2];
    const double s = Ginv[0][0] * a + Ginv[0][1] * b, t = Ginv[1][0] * a + Ginv[1][1] * b;
    return {J[0][0] * s + J[1][0] * t, J[0][1] * s + J[1][1] * t, J[0][2] * s + J[1][2] * t};
  }
};

// Calls f(point) at the (p + 1)^2 Gauss points of every element of every patch.
template <class F>
void for_each_surface_point(const TMeshSurfaceSpace& s, F&& f) {
  PointBasis<2> pb;
  SurfacePoint sp;
  for (int p = 0; p < s.space.num_patches(); ++p) {
    const TensorSpace<2>& space = s.space.patches[static_cast<std::size_t>(p)];
    const TensorSpline<2>& surface = s.surfaces[static_cast<std::size_t>(p)];
    const QuadratureRule rule = gauss_legendre(std::max(space.degree(0), space.degree(1)) + 1);
    const std::vector<double> ku = space.geometry.knots(0).unique(), kv = space.geometry.knots(1).unique();
    for (std::size_t j = 0; j + 1 < kv.size(); ++j)
      for (std::size_t i = 0; i + 1 < ku.size(); ++i)
        for (std::size_t b = 0; b < rule.nodes.size(); ++b)
          for (std::size_t a = 0; a < rule.nodes.size(); ++a) {
            const double lu = ku[i + 1] - ku[i], lv = kv[j + 1] - kv[j];
            point_basis(space, {ku[i] + lu * rule.nodes[a], kv[j] + lv * rule.nodes[b]}, pb);
            const std::size_t n = pb.ids.size();
            sp.x = {};
            sp.J = {};
            for (std::size_t l = 0; l < n; ++l) {
              double X[3];
              surface.control_point(pb.ids[l], X);
              for (std::size_t c = 0; c < 3; ++c) {
                sp.x[c] += pb.R[l] * X[c];
                sp.J[0][c] += pb.dR[2 * l] * X[c];
                sp.J[1][c] += pb.dR[2 * l + 1] * X[c];
              }
            }
            const auto dot = [](const V3& x, const V3& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
            const double g00 = dot(sp.J[0], sp.J[0]), g01 = dot(sp.J[0], sp.J[1]), g11 = dot(sp.J[1], sp.J[1]);
            const double det = g00 * g11 - g01 * g01;
            require(det > 1e-24 * g00 * g11 && det > 0, [&] {
              return "surface Poisson: the surface's metric is singular in patch " + std::to_string(p) + " at (" +
                     std::to_string(ku[i] + lu * rule.nodes[a]) + ", " + std::to_string(kv[j] + lv * rule.nodes[b]) + ")";
            });
            sp.Ginv = {{{g11 / det, -g01 / det}, {-g01 / det, g00 / det}}};
            sp.dA = std::sqrt(det) * rule.weights[a] * rule.weights[b] * lu * lv;
            sp.ids.resize(n);
            sp.R.assign(pb.R.begin(), pb.R.end());
            sp.grad.resize(n);
            for (std::size_t l = 0; l < n; ++l) {
              sp.ids[l] = s.space.global[static_cast<std::size_t>(p)][static_cast<std::size_t>(pb.ids[l])];
              const double du = pb.dR[2 * l], dv = pb.dR[2 * l + 1];
              const double s0 = sp.Ginv[0][0] * du + sp.Ginv[0][1] * dv, s1 = sp.Ginv[1][0] * du + sp.Ginv[1][1] * dv;
              for (std::size_t c = 0; c < 3; ++c) sp.grad[l][c] = sp.J[0][c] * s0 + sp.J[1][c] * s1;
            }
            f(static_cast<const SurfacePoint&>(sp));
          }
  }
}

}  // namespace

SurfacePoissonResult solve_surface_poisson(const TMeshSurfaceSpace& s, const SurfacePoissonProblem& pb, LinearSolver& solver) {
  require(pb.reaction >= 0, "surface Poisson: the reaction coefficient must not be negative");
  require(!s.space.boundary.empty() || pb.reaction > 0,
          "surface Poisson: a closed surface without a reaction term determines u only up to a constant (give c > 0)");
  const int n = s.space.num_basis;
  // Boundary functions are fixed to 0; the others numbered.
  std::vector<int> free(static_cast<std::size_t>(n), 0);
  for (const Face& f : s.space.boundary)
    for (int i : face_basis(s.space.patches[static_cast<std::size_t>(f.patch)], f))
      free[static_cast<std::size_t>(s.space.global[static_cast<std::size_t>(f.patch)][static_cast<std::size_t>(i)])] = -1;
  int dofs = 0;
  for (int& k : free) k = k < 0 ? -1 : dofs++;
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(dofs);
  SurfacePoissonResult r;
  for_each_surface_point(s, [&](const SurfacePoint& q) {
    r.area += q.dA;
    const double f = pb.source ? pb.source(q.x.data()) : 0.0;
    V3 g{};
    if (pb.flux_source) {
      double a[3];
      pb.flux_source(q.x.data(), a);
      g = q.tangential(a);
    }
    for (std::size_t i = 0; i < q.ids.size(); ++i) {
      const int gi = free[static_cast<std::size_t>(q.ids[i])];
      if (gi < 0) continue;
      const V3& di = q.grad[i];
      b[gi] += (f * q.R[i] + g[0] * di[0] + g[1] * di[1] + g[2] * di[2]) * q.dA;
      for (std::size_t j = 0; j < q.ids.size(); ++j) {
        const int gj = free[static_cast<std::size_t>(q.ids[j])];
        if (gj < 0) continue;
        const V3& dj = q.grad[j];
        t.emplace_back(gi, gj, (di[0] * dj[0] + di[1] * dj[1] + di[2] * dj[2] + pb.reaction * q.R[i] * q.R[j]) * q.dA);
      }
    }
  });
  SparseMatrix A(dofs, dofs);
  A.setFromTriplets(t.begin(), t.end());
  solver.compute(A);
  const Eigen::VectorXd x = solver.solve(b);
  r.coefs = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i)
    if (free[static_cast<std::size_t>(i)] >= 0) r.coefs[i] = x[free[static_cast<std::size_t>(i)]];
  r.dofs = dofs;
  return r;
}

ErrorNorms surface_error_norms(const TMeshSurfaceSpace& s, const Eigen::VectorXd& coefs, const ExactSolution<3>& exact) {
  double l2 = 0, h1 = 0;
  for_each_surface_point(s, [&](const SurfacePoint& q) {
    double uh = 0;
    V3 gh{};
    for (std::size_t i = 0; i < q.ids.size(); ++i) {
      const double c = coefs[q.ids[i]];
      uh += c * q.R[i];
      for (std::size_t k = 0; k < 3; ++k) gh[k] += c * q.grad[i][k];
    }
    double u = 0, g[3];
    exact(q.x.data(), &u, g);
    const V3 gt = q.tangential(g);
    l2 += (u - uh) * (u - uh) * q.dA;
    h1 += ((gt[0] - gh[0]) * (gt[0] - gh[0]) + (gt[1] - gh[1]) * (gt[1] - gh[1]) + (gt[2] - gh[2]) * (gt[2] - gh[2])) * q.dA;
  });
  return {std::sqrt(l2), std::sqrt(h1)};
}

}  // namespace trivar
