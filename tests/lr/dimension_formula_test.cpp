#include "trivar/lr/dimension_formula.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>

#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

MeshRectangle<2> line(int dir, double value, double a, double b, int m = 1) {
  Param<2> lo{}, hi{};
  lo[1 - dir] = a;
  hi[1 - dir] = b;
  return MeshRectangle<2>::make(dir, value, lo, hi, m);
}

// Tensor mesh on [0, n0] x [0, n1] with unit lines, boundary multiplicity p + 1.
std::vector<MeshRectangle<2>> tensor_mesh(int n0, int n1, const Ints<2>& p) {
  std::vector<MeshRectangle<2>> m;
  for (int i = 0; i <= n0; ++i) m.push_back(line(0, i, 0, n1, (i == 0 || i == n0) ? p[0] + 1 : 1));
  for (int j = 0; j <= n1; ++j) m.push_back(line(1, j, 0, n0, (j == 0 || j == n1) ? p[1] + 1 : 1));
  return m;
}

// A mesh with the counts of seed 004's bicubic example (16 elements, 13 horizontal and 14 vertical interior
// edges, 12 interior vertices; the seed's own figure is not reproduced): the 3 x 3 mesh on [0, 3]^2, a full line u = 1.5, the segments v = 1.5 on [1, 2] and
// u = 1.25 on [1, 2].
std::vector<MeshRectangle<2>> seed_mesh() {
  auto m = tensor_mesh(3, 3, {3, 3});
  m.push_back(line(0, 1.5, 0, 3));
  m.push_back(line(1, 1.5, 1, 2));
  m.push_back(line(0, 1.25, 1, 2));
  return m;
}

// Independent reference: dim of the piecewise polynomials of bidegree p on the elements with C^(p - mu)
// continuity across every edge = #coefficients - rank of the continuity conditions. Elements are the cells of
// the grid where the line values are given explicitly; conditions are jumps of normal derivatives 0..p-mu at
// p+1 points of every grid segment that lies on a mesh line (segments not on the mesh are C^infinity: all
// derivatives up to p). Monomials in coordinates shifted to the domain centre.
long long numerical_dimension(const std::vector<MeshRectangle<2>>& mesh, const Ints<2>& p) {
  std::array<std::vector<double>, 2> g;
  for (const auto& r : mesh) {
    g[r.dir].push_back(r.value);
    g[1 - r.dir].push_back(r.extent.lo[1 - r.dir]);
    g[1 - r.dir].push_back(r.extent.hi[1 - r.dir]);
  }
  for (auto& v : g) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  const int nx = static_cast<int>(g[0].size()) - 1, ny = static_cast<int>(g[1].size()) - 1;
  const int P = (p[0] + 1) * (p[1] + 1);
  const double cx = 0.5 * (g[0].front() + g[0].back()), cy = 0.5 * (g[1].front() + g[1].back());
  auto mult = [&](int dir, double value, double a, double b) {
    int m = 0;
    for (const auto& r : mesh)
      if (r.dir == dir && r.value == value && r.extent.lo[1 - dir] <= a && b <= r.extent.hi[1 - dir]) m = std::max(m, r.multiplicity);
    return m;
  };
  // d^k/dn^k of monomial x^i y^j at (x, y), n = direction dir.
  auto dmono = [&](int i, int j, int dir, int k, double x, double y) {
    double c = 1.0;
    int e = dir == 0 ? i : j;
    for (int s = 0; s < k; ++s) c *= (e - s);
    if (k > e) return 0.0;
    return dir == 0 ? c * std::pow(x, i - k) * std::pow(y, j) : c * std::pow(x, i) * std::pow(y, j - k);
  };
  std::vector<Eigen::RowVectorXd> rows;
  const int ncols = nx * ny * P;
  auto cell = [&](int i, int j) { return (j * nx + i) * P; };
  for (int dir = 0; dir < 2; ++dir) {
    const int o = 1 - dir, nlines = static_cast<int>(g[dir].size()), nseg = static_cast<int>(g[o].size()) - 1;
    for (int l = 1; l + 1 < nlines; ++l)
      for (int s = 0; s < nseg; ++s) {
        const int mu = mult(dir, g[dir][l], g[o][s], g[o][s + 1]);
        const int r = mu > 0 ? p[dir] - mu : p[dir];
        const int left = dir == 0 ? cell(l - 1, s) : cell(s, l - 1), right = dir == 0 ? cell(l, s) : cell(s, l);
        for (int k = 0; k <= r; ++k)
          for (int q = 0; q <= p[o]; ++q) {
            const double t = g[o][s] + (q + 0.5) / (p[o] + 1) * (g[o][s + 1] - g[o][s]);
            const double x = (dir == 0 ? g[0][l] : t) - cx, y = (dir == 0 ? t : g[1][l]) - cy;
            Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(ncols);
            for (int j = 0; j <= p[1]; ++j)
              for (int i = 0; i <= p[0]; ++i) {
                const double v = dmono(i, j, dir, k, x, y);
                row(left + j * (p[0] + 1) + i) += v;
                row(right + j * (p[0] + 1) + i) -= v;
              }
            rows.push_back(row);
          }
      }
  }
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), ncols);
  for (std::size_t i = 0; i < rows.size(); ++i) A.row(static_cast<Eigen::Index>(i)) = rows[i];
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  qr.setThreshold(1e-10);
  return ncols - qr.rank();
}

}  // namespace

TEST(DimensionFormula, SeedBicubicExampleHasDimension40) {
  // The seed's closed form with its counts.
  const TMeshCounts seed{16, 14, 13, 12};
  EXPECT_EQ(dimension_from_counts({3, 3}, {2, 2}, seed), 4 * 4 * 16 - 4 * 3 * 13 - 4 * 3 * 14 + 3 * 3 * 12);
  EXPECT_EQ(dimension_from_counts({3, 3}, {2, 2}, seed), 40);
  // A mesh with those counts.
  const auto m = seed_mesh();
  const TMeshCounts c = tmesh_counts(m);
  EXPECT_EQ(c.elements, 16);
  EXPECT_EQ(c.edges_const_v, 13);
  EXPECT_EQ(c.edges_const_u, 14);
  EXPECT_EQ(c.interior_vertices, 12);
  EXPECT_EQ(dimension(m, {3, 3}), 40);
  // The two short segments (2 edges each, fewer than p + 1) are not LR refinements and carry a homology term:
  // the true dimension is larger, the formula (h = 0) a lower bound, as documented.
  EXPECT_EQ(numerical_dimension(m, {3, 3}), 42);
}

TEST(DimensionFormula, TensorMeshesGiveTheTensorCount) {
  for (const Ints<2> p : {Ints<2>{3, 3}, Ints<2>{2, 1}, Ints<2>{1, 4}, Ints<2>{0, 2}})
    for (const auto& [n0, n1] : {std::pair{1, 1}, std::pair{4, 3}, std::pair{2, 6}})
      EXPECT_EQ(dimension(tensor_mesh(n0, n1, p), p), static_cast<long long>(n0 + p[0]) * (n1 + p[1]));
  // Interior multiplicity 2 on u = 1 (knot vector 0000 1 1 2 3 3333: 7 functions) x 5.
  auto m = tensor_mesh(3, 2, {3, 3});
  m.push_back(line(0, 1, 0, 2, 2));
  EXPECT_EQ(dimension(m, {3, 3}), 7 * 5);
  EXPECT_EQ(numerical_dimension(m, {3, 3}), 7 * 5);
}

TEST(DimensionFormula, TMeshesAgreeWithTheNumericalDimension) {
  // T-joints, crossings, a line through to the boundary and one of multiplicity 2 ending at T-vertices.
  std::vector<std::vector<MeshRectangle<2>>> meshes;
  {
    auto m = tensor_mesh(4, 4, {3, 3});
    m.push_back(line(0, 2.5, 0, 4));
    m.push_back(line(1, 2.5, 1, 4));
    meshes.push_back(m);
  }
  {
    auto m = tensor_mesh(5, 5, {2, 2});
    m.push_back(line(0, 2.5, 1, 4));
    m.push_back(line(1, 1.5, 1, 4));
    meshes.push_back(m);
  }
  {
    auto m = tensor_mesh(6, 6, {3, 3});
    m.push_back(line(0, 2.5, 1, 5, 2));
    meshes.push_back(m);
  }
  for (const Ints<2> p : {Ints<2>{3, 3}, Ints<2>{2, 2}})
    for (const auto& m : meshes) EXPECT_EQ(dimension(m, p), numerical_dimension(m, p));
}

TEST(DimensionFormula, HandInHandReportsTheThreeCases) {
  const auto m = tensor_mesh(3, 3, {2, 2});
  EXPECT_EQ(hand_in_hand(25, m, {2, 2}).status, Independence::independent);
  EXPECT_TRUE(hand_in_hand(25, m, {2, 2}).matches());
  EXPECT_EQ(hand_in_hand(26, m, {2, 2}).status, Independence::not_independent);
  EXPECT_EQ(hand_in_hand(24, m, {2, 2}).status, Independence::not_tested);
}

TEST(DimensionFormula, RejectsMultiplicityChangeThroughAVertex) {
  auto m = tensor_mesh(4, 4, {3, 3});
  m.push_back(line(0, 2, 0, 2, 2));  // u = 2 has multiplicity 2 below v = 2 and 1 above
  EXPECT_THROW(dimension(m, {3, 3}), Error);
}
