#include "trivar/iga/assembler.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "iga/iga_test_support.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/iga/point_basis.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/knot_insertion.hpp"

using namespace trivar;

namespace {

// The stiffness (grad R_I . grad R_J) and mass (R_I R_J) matrices by plain per-point quadrature with the same
// Gauss rule (degree + 1 points per direction), dense: the reference for the sum-factorised assembly.
template <int D>
Eigen::MatrixXd brute_force(const TensorSpace<D>& space, bool mass) {
  const int N = space.num_basis();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N, N);
  std::array<std::vector<double>, D> bp;
  std::array<QuadratureRule, D> rule;
  int cells = 1, pts = 1;
  for (int k = 0; k < D; ++k) {
    bp[k] = space.geometry.knots(k).breakpoints();
    rule[k] = gauss_legendre(space.degree(k) + 1);
    cells *= static_cast<int>(bp[k].size()) - 1;
    pts *= space.degree(k) + 1;
  }
  PointBasis<D> b;
  for (int c = 0; c < cells; ++c)
    for (int q = 0; q < pts; ++q) {
      Param<D> u;
      double w = 1;
      for (int k = 0, rc = c, rq = q; k < D; ++k) {
        const int ne = static_cast<int>(bp[k].size()) - 1, nq = space.degree(k) + 1;
        const int e = rc % ne, i = rq % nq;
        rc /= ne;
        rq /= nq;
        const double lo = bp[k][static_cast<std::size_t>(e)], hi = bp[k][static_cast<std::size_t>(e) + 1];
        u[k] = lo + (hi - lo) * rule[k].nodes[static_cast<std::size_t>(i)];
        w *= (hi - lo) * rule[k].weights[static_cast<std::size_t>(i)];
      }
      point_basis(space, u, b);
      Eigen::Matrix<double, D, D> J;
      for (int r = 0; r < D; ++r)
        for (int s = 0; s < D; ++s) J(r, s) = b.J[r][s];
      const Eigen::Matrix<double, D, D> JinvT = J.inverse().transpose();
      const double dV = std::abs(J.determinant()) * w;
      const int n = static_cast<int>(b.ids.size());
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          double v;
          if (mass) {
            v = b.R[static_cast<std::size_t>(i)] * b.R[static_cast<std::size_t>(j)];
          } else {
            const Eigen::Matrix<double, D, 1> gi = JinvT * Eigen::Map<const Eigen::Matrix<double, D, 1>>(&b.dR[static_cast<std::size_t>(i * D)]);
            const Eigen::Matrix<double, D, 1> gj = JinvT * Eigen::Map<const Eigen::Matrix<double, D, 1>>(&b.dR[static_cast<std::size_t>(j * D)]);
            v = gi.dot(gj);
          }
          A(b.ids[static_cast<std::size_t>(i)], b.ids[static_cast<std::size_t>(j)]) += v * dV;
        }
    }
  return A;
}

template <int D>
BilinearForm<D> laplace_or_mass(bool mass) {
  BilinearForm<D> f;
  f.value_terms = mass;
  f.gradient_terms = !mass;
  f.coefficients = [mass](const double*, double* P) {
    for (int a = 0; a < (D + 1) * (D + 1); ++a) P[a] = 0.0;
    if (mass)
      P[0] = 1.0;
    else
      for (int a = 1; a <= D; ++a) P[a * (D + 1) + a] = 1.0;
  };
  return f;
}

template <int D>
void expect_matches_brute_force(const TensorSpace<D>& space) {
  for (bool mass : {false, true}) {
    const Eigen::MatrixXd ref = brute_force(space, mass);
    const Eigen::MatrixXd A = Eigen::MatrixXd(assemble_matrix(space, laplace_or_mass<D>(mass)));
    EXPECT_LE((A - ref).cwiseAbs().maxCoeff(), 1e-12 * ref.cwiseAbs().maxCoeff()) << "mass " << mass;
  }
}

}  // namespace

TEST(Assembler, SumFactorisationMatchesPointwiseQuadratureOnCurvedNurbs) {
  for (bool rational : {false, true}) {
    expect_matches_brute_force<2>({iga_test::distorted_box<2>(2, 3, rational, 11)});
    expect_matches_brute_force<3>({iga_test::distorted_box<3>(2, 2, rational, 12)});
  }
}

TEST(Assembler, MixedDegreesAndRepeatedKnots) {
  // Degree 3 in u, 2 in v, with a double interior knot in v (C0 line): non-uniform 1-D patterns and offsets.
  TensorSpline<2> g = elevate_degree(iga_test::distorted_box<2>(2, 3, true, 13), 0, 1);
  g = insert_knot(g, 1, 1.0 / 3.0, 1);
  expect_matches_brute_force<2>(TensorSpace<2>{g});
}

TEST(Assembler, ResultDoesNotDependOnThreadCount) {
  const TensorSpace<3> space{iga_test::distorted_box<3>(2, 4, true, 14)};
  const SparseMatrix a = assemble_matrix(space, laplace_or_mass<3>(false), 1);
  const SparseMatrix b = assemble_matrix(space, laplace_or_mass<3>(false), 2);
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  for (Eigen::Index i = 0; i < a.nonZeros(); ++i) EXPECT_EQ(a.valuePtr()[i], b.valuePtr()[i]);
}
