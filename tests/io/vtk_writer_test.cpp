#include "trivar/io/vtk_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include "io/io_test_support.hpp"
#include "support/vtu_arrays.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

using test::bernstein;

using Vtu = test::VtuPiece;

Vtu parse_vtu(const std::string& path) { return test::read_vtu(path); }

template <int D>
std::array<int, D> element_index(const TensorSpline<D>& s, int e) {
  std::array<int, D> idx;
  for (int k = 0; k < D; ++k) {
    const int ne = s.knots(k).num_elements();
    idx[k] = e % ne;
    e /= ne;
  }
  return idx;
}

// Checks every Bezier cell against the spline: the local node (i, j, k) of each cell point is recovered from
// its "param" value, the cell is evaluated as a rational Bezier with those nodes, "RationalWeights" and the
// Cartesian points, and compared with the spline. Returns the local nodes of every cell in file order.
template <int D>
std::vector<std::vector<std::array<int, D>>> check_bezier_cells(const TensorSpline<D>& s, const Vtu& v) {
  const auto& conn = v.arrays.at("connectivity");
  const auto& offsets = v.arrays.at("offsets");
  const auto& param = v.arrays.at("param");
  const auto& pts = v.arrays.at("Points");
  // Without RationalWeights the cells are polynomial (weights 1).
  const std::vector<double> w = v.arrays.count("RationalWeights") ? v.arrays.at("RationalWeights")
                                                                   : std::vector<double>(pts.size() / 3, 1.0);
  std::array<std::vector<double>, D> bp;
  int npts = 1;
  for (int k = 0; k < D; ++k) {
    bp[k] = s.knots(k).breakpoints();
    npts *= s.degree(k) + 1;
  }
  std::vector<std::vector<std::array<int, D>>> nodes;
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> U(0, 1);
  for (long long c = 0; c < v.cells; ++c) {
    const auto e = element_index(s, static_cast<int>(v.arrays.at("element")[c]));
    const long long begin = c ? static_cast<long long>(offsets[c - 1]) : 0;
    EXPECT_EQ(static_cast<long long>(offsets[c]) - begin, npts);
    auto& local = nodes.emplace_back();
    for (long long q = begin; q < static_cast<long long>(offsets[c]); ++q) {
      const auto pt = static_cast<std::size_t>(conn[q]);
      std::array<int, D> ijk;
      for (int k = 0; k < D; ++k) {
        const double t = (param[3 * pt + k] - bp[k][e[k]]) / (bp[k][e[k] + 1] - bp[k][e[k]]);
        ijk[k] = static_cast<int>(std::lround(t * s.degree(k)));
        EXPECT_NEAR(t * s.degree(k), ijk[k], 1e-9);
      }
      local.push_back(ijk);
    }
    const std::set<std::array<int, D>> distinct(local.begin(), local.end());
    EXPECT_EQ(distinct.size(), local.size());
    for (int r = 0; r < 5; ++r) {
      Param<D> u, t;
      for (int k = 0; k < D; ++k) {
        t[k] = U(rng);
        u[k] = bp[k][e[k]] + t[k] * (bp[k][e[k] + 1] - bp[k][e[k]]);
      }
      double num[3] = {0, 0, 0}, den = 0;
      for (long long q = begin; q < static_cast<long long>(offsets[c]); ++q) {
        const auto pt = static_cast<std::size_t>(conn[q]);
        double b = w[pt];
        for (int k = 0; k < D; ++k) b *= bernstein(s.degree(k), local[q - begin][k], t[k]);
        for (int d = 0; d < 3; ++d) num[d] += b * pts[3 * pt + d];
        den += b;
      }
      std::vector<double> x(s.dim());
      s.eval(u, x.data());
      for (int d = 0; d < std::min(3, s.dim()); ++d) EXPECT_NEAR(num[d] / den, x[d], 1e-12);
    }
  }
  return nodes;
}

}  // namespace

TEST(VtkWriter, SampledVolumePointsAreSplineValues) {
  test::TempDir dir;
  const auto s = test::random_spline<3>({2, 3, 1}, {2, 3, 2}, 3, true, 51);
  const int n = 3;
  io::write_vtu(dir.file("v.vtu"), s, {.cells = io::VtkCells::sampled, .samples_per_element = n});
  const Vtu v = parse_vtu(dir.file("v.vtu"));
  EXPECT_EQ(v.points, (2 * n + 1) * (3 * n + 1) * (2 * n + 1));
  EXPECT_EQ(v.cells, 2 * n * 3 * n * 2 * n);
  ASSERT_EQ(v.arrays.at("Points").size(), 3u * v.points);
  ASSERT_EQ(v.arrays.at("param").size(), 3u * v.points);
  ASSERT_EQ(v.arrays.at("connectivity").size(), 8u * v.cells);
  for (long long c = 0; c < v.cells; ++c) {
    EXPECT_EQ(v.arrays.at("types")[c], 12);
    EXPECT_EQ(v.arrays.at("offsets")[c], 8 * static_cast<double>(c + 1));
  }
  const auto& P = v.arrays.at("Points");
  const auto& U = v.arrays.at("param");
  double x[3];
  for (long long q = 0; q < v.points; ++q) {
    s.eval({U[3 * q], U[3 * q + 1], U[3 * q + 2]}, x);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(P[3 * q + d], x[d], 1e-13);
  }
  // VTK hexahedron corner order: 0-1 along u, 0-3 along v, 0-4 along w, 2 = (u of 1, v of 3); each cell lies
  // in the element named by its "element" value.
  const auto& conn = v.arrays.at("connectivity");
  for (long long c = 0; c < v.cells; ++c) {
    auto u = [&](int corner, int k) { return U[3 * static_cast<std::size_t>(conn[8 * c + corner]) + k]; };
    EXPECT_GT(u(1, 0), u(0, 0));
    EXPECT_EQ(u(1, 1), u(0, 1));
    EXPECT_GT(u(3, 1), u(0, 1));
    EXPECT_EQ(u(3, 0), u(0, 0));
    EXPECT_GT(u(4, 2), u(0, 2));
    EXPECT_EQ(u(2, 0), u(1, 0));
    EXPECT_EQ(u(2, 1), u(3, 1));
    for (int corner = 4; corner < 8; ++corner) EXPECT_EQ(u(corner, 2), u(4, 2));
    const auto e = element_index(s, static_cast<int>(v.arrays.at("element")[c]));
    for (int k = 0; k < 3; ++k) {
      const auto bp = s.knots(k).breakpoints();
      EXPECT_GE(u(0, k), bp[e[k]]);
      EXPECT_LE(u(6, k), bp[e[k] + 1]);
    }
  }
}

TEST(VtkWriter, ControlDimensionsOtherThanThree) {
  test::TempDir dir;
  const auto planar = test::random_spline<2>({2, 2}, {2, 3}, 2, false, 52);
  io::write_vtu(dir.file("p.vtu"), planar, {.cells = io::VtkCells::sampled, .samples_per_element = 2});
  const Vtu p = parse_vtu(dir.file("p.vtu"));
  EXPECT_EQ(p.points, 5 * 7);
  EXPECT_EQ(p.cells, 4 * 6);
  for (long long q = 0; q < p.points; ++q) {
    EXPECT_EQ(p.arrays.at("Points")[3 * q + 2], 0.0);
    EXPECT_EQ(p.arrays.at("param")[3 * q + 2], 0.0);
  }
  for (double t : p.arrays.at("types")) EXPECT_EQ(t, 9);

  const auto curve5 = test::random_spline<1>({3}, {4}, 5, true, 53);
  io::write_vtu(dir.file("c.vtu"), curve5, {.cells = io::VtkCells::sampled, .samples_per_element = 5});
  const Vtu c = parse_vtu(dir.file("c.vtu"));
  EXPECT_EQ(c.points, 21);
  EXPECT_EQ(c.components.at("higher_components"), 2);
  double x[5];
  for (long long q = 0; q < c.points; ++q) {
    curve5.eval({c.arrays.at("param")[3 * q]}, x);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(c.arrays.at("Points")[3 * q + d], x[d], 1e-13);
    for (int d = 0; d < 2; ++d) EXPECT_NEAR(c.arrays.at("higher_components")[2 * q + d], x[3 + d], 1e-13);
  }
}

// Interior knot of multiplicity p + 1: the curve jumps from P1 to P2 at u = 1, so both sides get points.
TEST(VtkWriter, DiscontinuityGetsPointsOnBothSides) {
  test::TempDir dir;
  const SplineCurve c =
      SplineCurve::from_cartesian({KnotVector(1, {0, 0, 1, 1, 2, 2})}, 2, std::vector<double>{0, 0, 1, 0, 5, 5, 6, 5});
  io::write_vtu(dir.file("d.vtu"), c, {.cells = io::VtkCells::sampled, .samples_per_element = 2});
  const Vtu v = parse_vtu(dir.file("d.vtu"));
  ASSERT_EQ(v.points, 6);
  EXPECT_EQ(v.cells, 4);
  const auto& P = v.arrays.at("Points");
  EXPECT_NEAR(P[3 * 2], 1.0, 1e-15);
  EXPECT_NEAR(P[3 * 2 + 1], 0.0, 1e-15);
  EXPECT_EQ(P[3 * 3], 5.0);
  EXPECT_EQ(P[3 * 3 + 1], 5.0);
  EXPECT_EQ(v.arrays.at("connectivity"), (std::vector<double>{0, 1, 1, 2, 3, 4, 4, 5}));
}

TEST(VtkWriter, BezierVolumeReproducesTheSpline) {
  test::TempDir dir;
  const auto s = test::random_spline<3>({1, 2, 3}, {2, 3, 2}, 3, true, 54);
  io::write_vtu(dir.file("b.vtu"), s, {.cells = io::VtkCells::bezier});
  const Vtu v = parse_vtu(dir.file("b.vtu"));
  EXPECT_EQ(v.cells, 2 * 3 * 2);
  EXPECT_EQ(v.points, (2 * 1 + 1) * (3 * 2 + 1) * (2 * 3 + 1));  // continuous: shared Bezier points
  EXPECT_NE(v.point_data_tag.find("RationalWeights=RationalWeights"), std::string::npos);
  EXPECT_NE(v.cell_data_tag.find("HigherOrderDegrees=HigherOrderDegrees"), std::string::npos);
  for (long long c = 0; c < v.cells; ++c) {
    EXPECT_EQ(v.arrays.at("types")[c], 79);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(v.arrays.at("HigherOrderDegrees")[3 * c + k], k + 1);
  }
  const auto nodes = check_bezier_cells(s, v);
  // Corners first, in VTK hexahedron order.
  const int p[3] = {1, 2, 3};
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& cell : nodes)
    for (int q = 0; q < 8; ++q)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(cell[q][k], corner[q][k] * p[k]);
}

// Point order of VTK's Lagrange/Bezier cells, written out by hand for small degrees: corners, edges (each
// from its lower to its higher parameter), faces (-u, +u, -v, +v, -w, +w), interior.
TEST(VtkWriter, BezierPointOrderFollowsVtk) {
  test::TempDir dir;
  const auto hex = test::random_spline<3>({2, 2, 2}, {1, 1, 1}, 3, true, 55);
  io::write_vtu(dir.file("h.vtu"), hex, {.cells = io::VtkCells::bezier});
  const auto h = check_bezier_cells(hex, parse_vtu(dir.file("h.vtu")));
  const std::vector<std::array<int, 3>> hex_order = {
      {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2},  // corners
      {1, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 1, 0}, {1, 0, 2}, {2, 1, 2}, {1, 2, 2}, {0, 1, 2},  // u, v edges
      {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1},                                              // w edges
      {0, 1, 1}, {2, 1, 1}, {1, 0, 1}, {1, 2, 1}, {1, 1, 0}, {1, 1, 2},                        // faces
      {1, 1, 1}};
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h[0], hex_order);

  const auto quad = test::random_spline<2>({3, 2}, {1, 1}, 3, false, 56);
  io::write_vtu(dir.file("q.vtu"), quad, {.cells = io::VtkCells::bezier});
  const auto q = check_bezier_cells(quad, parse_vtu(dir.file("q.vtu")));
  const std::vector<std::array<int, 2>> quad_order = {{0, 0}, {3, 0}, {3, 2}, {0, 2}, {1, 0}, {2, 0},
                                                      {3, 1}, {1, 2}, {2, 2}, {0, 1}, {1, 1}, {2, 1}};
  ASSERT_EQ(q.size(), 1u);
  EXPECT_EQ(q[0], quad_order);

  const auto curve = SplineCurve::from_cartesian({KnotVector(3, {0, 0, 0, 0, 1, 1, 1, 1})}, 2,
                                                 std::vector<double>{0, 0, 1, 2, 2, 2, 3, 0});
  io::write_vtu(dir.file("c.vtu"), curve, {.cells = io::VtkCells::bezier});
  const Vtu cv = parse_vtu(dir.file("c.vtu"));
  const auto c = check_bezier_cells(curve, cv);
  EXPECT_EQ(c[0], (std::vector<std::array<int, 1>>{{0}, {3}, {1}, {2}}));
  EXPECT_EQ(cv.arrays.at("types")[0], 75);
}

// A field that is a spline on the object's knots and weights (as a solution is) is written as the Bezier
// coefficients of that field, so the cells show it exactly between the nodes; a polynomial object has no
// RationalWeights array.
TEST(VtkWriter, BezierCellsCarrySplineFieldsExactly) {
  test::TempDir dir;
  for (bool rational : {true, false}) {
    const auto s = test::random_spline<3>({2, 3, 2}, {3, 2, 2}, 3, rational, 63);
    // The field's homogeneous coefficients share the geometry's weights: f = sum c_I w_I N_I / sum w_I N_I.
    std::vector<double> coefs;
    std::mt19937 rng(64);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int I = 0; I < s.num_coefs(); ++I) {
      const double w = s.weight(I);
      coefs.push_back(w * unit(rng));
      if (rational) coefs.push_back(w);
    }
    const TensorSpline<3> f(s.knot_vectors(), 1, rational, coefs);
    const io::VtkPointField field{"f", 1, [&](int, std::span<const double> u, std::span<double> out) {
                                    f.eval({u[0], u[1], u[2]}, out.data());
                                  }};
    io::write_vtu(dir.file("f.vtu"), s, {}, {field});
    const Vtu v = parse_vtu(dir.file("f.vtu"));
    EXPECT_EQ(v.arrays.count("RationalWeights"), rational ? 1u : 0u);
    const auto nodes = check_bezier_cells(s, v);
    const auto& conn = v.arrays.at("connectivity");
    const auto& F = v.arrays.at("f");
    const std::vector<double> w = rational ? v.arrays.at("RationalWeights") : std::vector<double>(F.size(), 1.0);
    for (long long c = 0; c < v.cells; ++c) {
      const auto e = element_index(s, static_cast<int>(v.arrays.at("element")[c]));
      const long long begin = c ? static_cast<long long>(v.arrays.at("offsets")[c - 1]) : 0;
      for (int r = 0; r < 3; ++r) {
        const double t[3] = {unit(rng) * 0.5 + 0.5, unit(rng) * 0.5 + 0.5, unit(rng) * 0.5 + 0.5};
        Param<3> u;
        double num = 0, den = 0;
        for (int k = 0; k < 3; ++k) {
          const auto bp = s.knots(k).breakpoints();
          u[k] = bp[e[k]] + t[k] * (bp[e[k] + 1] - bp[e[k]]);
        }
        for (std::size_t q = 0; q < nodes[c].size(); ++q) {
          const auto pt = static_cast<std::size_t>(conn[begin + static_cast<long long>(q)]);
          double b = w[pt];
          for (int k = 0; k < 3; ++k) b *= bernstein(s.degree(k), nodes[c][q][k], t[k]);
          num += b * F[pt];
          den += b;
        }
        double exact;
        f.eval(u, &exact);
        EXPECT_NEAR(num / den, exact, 1e-12);
      }
    }
  }
}

TEST(VtkWriter, ControlNet) {
  test::TempDir dir;
  const auto s = test::random_spline<3>({2, 1, 2}, {2, 3, 1}, 3, true, 57);
  io::write_vtu(dir.file("n.vtu"), s, {.cells = io::VtkCells::control_net});
  const Vtu v = parse_vtu(dir.file("n.vtu"));
  const auto n = s.counts();
  EXPECT_EQ(v.points, s.num_coefs());
  EXPECT_EQ(v.cells, (n[0] - 1) * n[1] * n[2] + n[0] * (n[1] - 1) * n[2] + n[0] * n[1] * (n[2] - 1));
  double x[3];
  for (int l = 0; l < s.num_coefs(); ++l) {
    s.control_point(l, x);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(v.arrays.at("Points")[3 * l + d], x[d]);
  }
  for (double t : v.arrays.at("types")) EXPECT_EQ(t, 3);
  EXPECT_EQ(v.arrays.count("direction"), 1u);
}

TEST(VtkWriter, ExtraPointFields) {
  test::TempDir dir;
  const auto s = test::random_spline<2>({2, 2}, {2, 2}, 3, false, 58);
  const std::vector<io::VtkPointField> fields = {
      {"u_plus_v", 1, [](int, std::span<const double> u, std::span<double> out) { out[0] = u[0] + u[1]; }},
      {"normal", 3, [&](int piece, std::span<const double>, std::span<double> out) {
         out[0] = piece;
         out[1] = 1;
         out[2] = 2;
       }}};
  io::write_vtu(dir.file("f.vtu"), s, {.cells = io::VtkCells::sampled, .samples_per_element = 2}, fields);
  const Vtu v = parse_vtu(dir.file("f.vtu"));
  EXPECT_EQ(v.components.at("normal"), 3);
  for (long long q = 0; q < v.points; ++q) {
    EXPECT_EQ(v.arrays.at("u_plus_v")[q], v.arrays.at("param")[3 * q] + v.arrays.at("param")[3 * q + 1]);
    EXPECT_EQ(v.arrays.at("normal")[3 * q + 2], 2.0);
  }
}

TEST(VtkWriter, InvalidRequestsWriteNothing) {
  test::TempDir dir;
  const auto s = test::random_spline<2>({2, 0}, {2, 2}, 3, false, 59);
  EXPECT_THROW(io::write_vtu(dir.file("a.vtu"), s, {.cells = io::VtkCells::sampled, .samples_per_element = 0}), Error);
  EXPECT_THROW(io::write_vtu(dir.file("a.vtu"), s, {.cells = io::VtkCells::bezier}), Error);  // degree 0 in v
  const auto f = [](int, std::span<const double>, std::span<double> out) { out[0] = 0; };
  EXPECT_THROW(io::write_vtu(dir.file("a.vtu"), s, {}, {{"param", 1, f}}), Error);
  EXPECT_THROW(io::write_vtu(dir.file("a.vtu"), s, {}, {{"a", 1, f}, {"a", 1, f}}), Error);
  EXPECT_THROW(io::write_vtu(dir.file("a.vtu"), AnySpline{}), Error);
  // 1201^3 samples fit VTK's 32-bit point ids but not this machine's memory (about 125 GB): refused by name
  // before anything is allocated.
  const auto cube = test::random_spline<3>({1, 1, 1}, {1, 1, 1}, 3, false, 60);
  try {
    io::write_vtu(dir.file("a.vtu"), cube, {.cells = io::VtkCells::sampled, .samples_per_element = 1200});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("VTU output of 1732323601 points would need"), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.entries(), 0);
  // Degree 0 is fine when sampled: every element boundary is a discontinuity.
  io::write_vtu(dir.file("ok.vtu"), s, {.cells = io::VtkCells::sampled, .samples_per_element = 1});
  const Vtu v = parse_vtu(dir.file("ok.vtu"));
  EXPECT_EQ(v.points, 3 * 4);
  EXPECT_EQ(v.cells, 2 * 2);
}
