#include "trivar/iga/eigen_modes.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"

using namespace trivar;

TEST(EigenModes, UnitCubeDirichletLaplaceEigenvalues) {
  // Exact: 3 pi^2, then 6 pi^2 three times. Galerkin eigenvalues lie above the exact ones and converge at
  // rate 2p in h.
  const std::vector<double> exact = unit_box_laplace_eigenvalues(3, 4);
  EXPECT_NEAR(exact[0], 3 * M_PI * M_PI, 1e-12);
  for (int i = 1; i < 4; ++i) EXPECT_NEAR(exact[static_cast<std::size_t>(i)], 6 * M_PI * M_PI, 1e-12);
  const int p = 2;
  std::vector<double> prev;
  for (int n : {4, 8}) {
    const ModesResult r = laplace_modes<3>({box_geometry<3>({0, 0, 0}, {1, 1, 1}, p, n)}, all_faces<3>(), 4);
    std::vector<double> err;
    for (int i = 0; i < 4; ++i) {
      EXPECT_GT(r.values[i], exact[static_cast<std::size_t>(i)] * (1 - 1e-12)) << i;
      err.push_back((r.values[i] - exact[static_cast<std::size_t>(i)]) / exact[static_cast<std::size_t>(i)]);
    }
    EXPECT_LE(err[0], n == 4 ? 1e-3 : 5e-5);
    if (!prev.empty()) {
      for (int i = 0; i < 4; ++i) {
        // Pre-asymptotically the error may fall faster than h^2p, never slower.
        const double rate = std::log2(prev[static_cast<std::size_t>(i)] / err[static_cast<std::size_t>(i)]);
        EXPECT_GE(rate, 2 * p - 0.2) << i;
        EXPECT_LE(rate, 2 * p + 0.8) << i;
      }
    }
    prev = err;
  }
}

TEST(EigenModes, SquareWithNaturalConditionsOnTwoSides) {
  // u = 0 on x = 0 and y = 0, natural elsewhere: lambda = pi^2 ((i - 1/2)^2 + (j - 1/2)^2): pi^2 / 2, then
  // 5 pi^2 / 2 twice.
  const ModesResult r =
      laplace_modes<2>({box_geometry<2>({0, 0}, {1, 1}, 3, 8)}, {{0, 0}, {1, 0}}, 3);
  const double pi2 = M_PI * M_PI;
  EXPECT_NEAR(r.values[0], 0.5 * pi2, 1e-6 * pi2);
  EXPECT_NEAR(r.values[1], 2.5 * pi2, 1e-5 * pi2);
  EXPECT_NEAR(r.values[2], 2.5 * pi2, 1e-5 * pi2);
}

TEST(EigenModes, RejectsTooManyModes) {
  EXPECT_THROW(laplace_modes<2>({box_geometry<2>({0, 0}, {1, 1}, 1, 2)}, all_faces<2>(), 5), Error);
}
