#include "trivar/io/lr_vtk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "io_test_support.hpp"
#include "support/vtu_arrays.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

using test::bernstein;

// The identity map on [0, 2] x [0, 1] (bilinear, coefficients = Greville abscissae) refined by u = 1 over the
// whole domain and v = 0.5 for u in [0, 1]: three elements, with supports of 4 B-splines each.
LRSpline<2> identity_surface() {
  const KnotVector ku(1, {0, 0, 2, 2}), kv(1, {0, 0, 1, 1});
  const std::vector<double> points = {0, 0, 2, 0, 0, 1, 2, 1};
  LRSpline<2> s(TensorSpline<2>::from_cartesian({ku, kv}, 2, points, {}));
  s.insert(MeshRectangle<2>::make(0, 1.0, {0, 0}, {0, 1}));
  s.insert(MeshRectangle<2>::make(1, 0.5, {0, 0}, {1, 0}));
  return s;
}

}  // namespace

TEST(LrVtk, SampledElementsOfTheIdentityMapLieAtTheirParameters) {
  test::TempDir dir;
  const LRSpline<2> s = identity_surface();
  ASSERT_EQ(s.num_elements(), 3);
  io::write_lr_vtu(dir.file("s.vtu"), AnyLRSpline(s), {.cells = io::LRVtkCells::sampled, .samples_per_element = 3});
  const test::VtuPiece xml = test::read_vtu(dir.file("s.vtu"));
  EXPECT_EQ(xml.points, 48);
  EXPECT_EQ(xml.cells, 27);
  const auto points = xml.arrays.at("Points"), params = xml.arrays.at("param");
  ASSERT_EQ(points.size(), 48u * 3);
  ASSERT_EQ(params.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(points[i], params[i], 1e-14) << i;
  const auto element = xml.arrays.at("element"), support = xml.arrays.at("support");
  ASSERT_EQ(element.size(), 27u);
  for (std::size_t c = 0; c < element.size(); ++c) {
    EXPECT_EQ(element[c], static_cast<double>(c / 9));
    EXPECT_EQ(support[c], static_cast<double>(s.element_support(static_cast<int>(c / 9)).size()));
  }
  // Every cell is a VTK_QUAD with 4 distinct corners of its own element.
  const auto types = xml.arrays.at("types"), conn = xml.arrays.at("connectivity");
  for (double t : types) EXPECT_EQ(t, 9.0);
  ASSERT_EQ(conn.size(), 27u * 4);
  for (std::size_t c = 0; c < 27; ++c)
    for (int v = 0; v < 4; ++v) EXPECT_EQ(static_cast<int>(conn[4 * c + v]) / 16, static_cast<int>(c / 9));
}

TEST(LrVtk, ParametricMeshOfAVolume) {
  test::TempDir dir;
  const KnotVector k(1, {0, 0, 1, 1});
  std::vector<double> pts(8 * 4, 0.0);
  LRSpline<3> v(TensorSpline<3>::from_cartesian({k, k, k}, 4, pts, std::vector<double>{}));
  v.insert(MeshRectangle<3>::make(2, 0.5, {0, 0, 0}, {1, 1, 0}));
  io::write_lr_vtu(dir.file("m.vtu"), {AnyLRSpline(v), AnyLRSpline(identity_surface())}, {.cells = io::LRVtkCells::parametric_mesh});
  const std::vector<test::VtuPiece> pieces = test::read_vtu_pieces(dir.file("m.vtu"));
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].points, 16);
  EXPECT_EQ(pieces[0].cells, 2);
  EXPECT_EQ(pieces[1].points, 12);
  EXPECT_EQ(pieces[1].cells, 3);
  const auto points = pieces[0].arrays.at("Points"), params = pieces[0].arrays.at("param");
  ASSERT_EQ(points.size(), 16u * 3);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(points[i], params[i]);
  // Hexahedra: the second element's bottom corners lie on w = 0.5 (VTK order: bottom face first).
  double volume = 0;
  for (int e = 0; e < 2; ++e) {
    const Box<3>& b = v.element(e);
    volume += b.extent(0) * b.extent(1) * b.extent(2);
  }
  EXPECT_DOUBLE_EQ(volume, 1.0);
  EXPECT_EQ(pieces[0].arrays.at("types"), (std::vector<double>{12, 12}));
  EXPECT_EQ(pieces[1].arrays.at("types"), (std::vector<double>{9, 9, 9}));
}

TEST(LrVtk, PointAndCellFieldsOfTheCaller) {
  // A point field is evaluated at the point's own parameter (one ulp inside the element on interior upper
  // faces), a cell field once per element and repeated on the element's cells.
  test::TempDir dir;
  const LRSpline<2> s = identity_surface();
  const io::VtkPointField uv{"uv", 2, [](int piece, std::span<const double> u, std::span<double> out) {
                               out[0] = u[0] + piece;
                               out[1] = u[1];
                             }};
  const io::LRVtkCellField twice{"twice", 1, [](int, int e, std::span<double> out) { out[0] = 2.0 * e; }};
  io::write_lr_vtu(dir.file("f.vtu"), AnyLRSpline(s), {.cells = io::LRVtkCells::sampled, .samples_per_element = 2}, {uv}, {twice});
  const test::VtuPiece xml = test::read_vtu(dir.file("f.vtu"));
  const auto params = xml.arrays.at("param"), values = xml.arrays.at("uv");
  ASSERT_EQ(values.size(), 27u * 2);
  for (std::size_t q = 0; q < 27; ++q)
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(values[2 * q + k], params[3 * q + k], 1e-15) << q;
  const auto element = xml.arrays.at("element"), doubled = xml.arrays.at("twice");
  ASSERT_EQ(doubled.size(), 12u);
  for (std::size_t c = 0; c < doubled.size(); ++c) EXPECT_EQ(doubled[c], 2 * element[c]);
  // Reserved, duplicate, nameless and valueless fields write nothing.
  const std::string bad = dir.file("bad.vtu");
  const AnyLRSpline any(s);
  EXPECT_THROW(io::write_lr_vtu(bad, any, {}, {{"param", 1, uv.value}}), Error);
  EXPECT_THROW(io::write_lr_vtu(bad, any, {}, {uv, uv}), Error);
  EXPECT_THROW(io::write_lr_vtu(bad, any, {}, {{"", 1, uv.value}}), Error);
  EXPECT_THROW(io::write_lr_vtu(bad, any, {}, {{"v", 1, nullptr}}), Error);
  EXPECT_THROW(io::write_lr_vtu(bad, any, {}, {}, {{"support", 1, twice.value}}), Error);
  EXPECT_THROW(io::write_lr_vtu(bad, any, {}, {}, {{"e", 0, twice.value}}), Error);
  EXPECT_EQ(dir.entries(), 1);
}

TEST(LrVtk, AnElementRunWritesThoseElementsAsTheWholeFileDoes) {
  // The runs [0, 1) and [1, 3) together are the whole file: the same cells, points and fields in element order
  // (elements share no points, so a run's points are a contiguous slice of the whole file's).
  test::TempDir dir;
  const LRSpline<2> s = identity_surface();
  const io::VtkPointField uv{"uv", 1, [](int, std::span<const double> u, std::span<double> out) { out[0] = u[0] * u[1]; }};
  io::write_lr_vtu(dir.file("all.vtu"), AnyLRSpline(s), {}, {uv});
  io::write_lr_vtu(dir.file("a.vtu"), AnyLRSpline(s), {.first_element = 0, .last_element = 1}, {uv});
  io::write_lr_vtu(dir.file("b.vtu"), AnyLRSpline(s), {.first_element = 1, .last_element = 3}, {uv});
  const test::VtuPiece all = test::read_vtu(dir.file("all.vtu")), a = test::read_vtu(dir.file("a.vtu")),
                       b = test::read_vtu(dir.file("b.vtu"));
  ASSERT_EQ(all.cells, 3);
  EXPECT_EQ(a.cells, 1);
  EXPECT_EQ(b.cells, 2);
  EXPECT_EQ(a.points + b.points, all.points);
  for (const char* name : {"Points", "param", "uv", "element", "support"}) {
    std::vector<double> joined = a.arrays.at(name);
    joined.insert(joined.end(), b.arrays.at(name).begin(), b.arrays.at(name).end());
    EXPECT_EQ(joined, all.arrays.at(name)) << name;
  }
  const std::string bad = dir.file("bad.vtu");
  EXPECT_THROW(io::write_lr_vtu(bad, AnyLRSpline(s), {.first_element = 2, .last_element = 1}), Error);
  EXPECT_THROW(io::write_lr_vtu(bad, AnyLRSpline(s), {.first_element = 0, .last_element = 4}), Error);
  EXPECT_THROW(io::write_lr_vtu(bad, AnyLRSpline(s), {.first_element = -1}), Error);
  EXPECT_EQ(dir.entries(), 3);
}

TEST(LrVtk, PerObjectRunsWriteEachObjectsShare) {
  // Two objects, each with its own run (a multi-block model's share of one process): piece k holds object k's run,
  // as the same run of that object written alone; runs not one per object write nothing.
  test::TempDir dir;
  const LRSpline<2> s = identity_surface();
  const io::VtkPointField uv{"uv", 1, [](int piece, std::span<const double> u, std::span<double> out) { out[0] = piece + u[0] * u[1]; }};
  io::LRVtkOptions both;
  both.runs = {{2, 3}, {0, 2}};
  io::write_lr_vtu(dir.file("both.vtu"), {AnyLRSpline(s), AnyLRSpline(s)}, both, {uv});
  io::write_lr_vtu(dir.file("first.vtu"), AnyLRSpline(s), {.first_element = 2, .last_element = 3}, {uv});
  const std::vector<test::VtuPiece> pieces = test::read_vtu_pieces(dir.file("both.vtu"));
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].cells, 1);
  EXPECT_EQ(pieces[1].cells, 2);
  const test::VtuPiece first = test::read_vtu(dir.file("first.vtu"));
  for (const char* name : {"Points", "param", "uv", "element"}) EXPECT_EQ(pieces[0].arrays.at(name), first.arrays.at(name)) << name;
  EXPECT_EQ(pieces[1].arrays.at("element"), (std::vector<double>{0, 1}));
  for (double v : pieces[1].arrays.at("uv")) EXPECT_GE(v, 1.0);  // the field called with piece 1
  io::LRVtkOptions one;
  one.runs = {{0, 1}};
  EXPECT_THROW(io::write_lr_vtu(dir.file("bad.vtu"), {AnyLRSpline(s), AnyLRSpline(s)}, one), Error);
  one.runs = {{0, 1}, {2, 4}};
  EXPECT_THROW(io::write_lr_vtu(dir.file("bad.vtu"), {AnyLRSpline(s), AnyLRSpline(s)}, one), Error);
  EXPECT_EQ(dir.entries(), 2);
}

TEST(LrVtk, InvalidOptionsWriteNothing) {
  test::TempDir dir;
  EXPECT_THROW(io::write_lr_vtu(dir.file("a.vtu"), AnyLRSpline(identity_surface()), {.cells = io::LRVtkCells::sampled, .samples_per_element = 0}), Error);
  EXPECT_THROW(io::write_lr_vtu(dir.file("b.vtu"), std::vector<AnyLRSpline>{}), Error);
  EXPECT_EQ(dir.entries(), 0);
}

// Bezier cells (the default): one VTK_BEZIER_HEXAHEDRON per LR element whose rational Bezier form, evaluated
// here from VTK's point order, is the LR volume; a point field that is itself a spline on the volume's
// B-splines (here its own x coordinate) is reproduced inside the cells, not only at the nodes.
TEST(LrVtk, BezierCellsReproduceTheVolumeAndSplineFields) {
  test::TempDir dir;
  const KnotVector ku(2, {0, 0, 0, 0.5, 1, 1, 1}), kv(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}), kw(1, {0, 0, 0.5, 1, 1});
  std::mt19937 rng(62);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> points(4 * 5 * 3 * 3);
  for (double& c : points) c = unit(rng);
  LRSpline<3> s(TensorSpline<3>::from_cartesian({ku, kv, kw}, 3, points, std::vector<double>{}));
  s.insert(MeshRectangle<3>::make(0, 0.25, {0, 0, 0}, {0, 0.5, 1}));
  s.insert(MeshRectangle<3>::make(2, 0.75, {0, 0, 0}, {0.5, 1, 0}));
  const io::VtkPointField x{"x", 1, [&](int, std::span<const double> u, std::span<double> out) {
                              double p[3];
                              s.eval({u[0], u[1], u[2]}, p);
                              out[0] = p[0];
                            }};
  io::write_lr_vtu(dir.file("b.vtu"), AnyLRSpline(s), {}, {x});
  const test::VtuPiece v = test::read_vtu(dir.file("b.vtu"));
  ASSERT_EQ(v.cells, s.num_elements());
  EXPECT_EQ(v.points, s.num_elements() * 3 * 4 * 2);
  EXPECT_NE(v.cell_data_tag.find("HigherOrderDegrees=HigherOrderDegrees"), std::string::npos);
  const auto& conn = v.arrays.at("connectivity");
  const auto& P = v.arrays.at("Points");
  const auto& U = v.arrays.at("param");
  const auto& X = v.arrays.at("x");
  const int p[3] = {2, 3, 1};
  for (long long c = 0; c < v.cells; ++c) {
    EXPECT_EQ(v.arrays.at("types")[c], 79);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(v.arrays.at("HigherOrderDegrees")[3 * c + k], p[k]);
    const Box<3>& b = s.element(static_cast<int>(v.arrays.at("element")[c]));
    const long long begin = c ? static_cast<long long>(v.arrays.at("offsets")[c - 1]) : 0;
    ASSERT_EQ(v.arrays.at("offsets")[c], static_cast<double>(begin + 24));
    // The local node of each point from its parameter.
    std::vector<std::array<int, 3>> node(24);
    for (int q = 0; q < 24; ++q) {
      const auto pt = static_cast<std::size_t>(conn[begin + q]);
      for (int k = 0; k < 3; ++k)
        node[static_cast<std::size_t>(q)][k] = static_cast<int>(std::lround((U[3 * pt + k] - b.lo[k]) / b.extent(k) * p[k]));
    }
    EXPECT_EQ(node[1], (std::array<int, 3>{2, 0, 0}));  // VTK corner order
    EXPECT_EQ(node[2], (std::array<int, 3>{2, 3, 0}));
    EXPECT_EQ(node[6], (std::array<int, 3>{2, 3, 1}));
    for (int r = 0; r < 4; ++r) {
      const double tt[3] = {unit(rng), unit(rng), unit(rng)};
      double sum[4] = {0, 0, 0, 0};
      for (int q = 0; q < 24; ++q) {
        double B = 1;
        for (int k = 0; k < 3; ++k) B *= bernstein(p[k], node[static_cast<std::size_t>(q)][k], tt[k]);
        const auto pt = static_cast<std::size_t>(conn[begin + q]);
        for (int d = 0; d < 3; ++d) sum[d] += B * P[3 * pt + d];
        sum[3] += B * X[pt];
      }
      double want[3];
      s.eval({b.lo[0] + tt[0] * b.extent(0), b.lo[1] + tt[1] * b.extent(1), b.lo[2] + tt[2] * b.extent(2)}, want);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(sum[d], want[d], 1e-12);
      EXPECT_NEAR(sum[3], want[0], 1e-12);
    }
  }
}

TEST(LrVtk, BezierCellsOfAThbVolume) {
  // The leaves of a refined THB volume as Bezier hexahedra: the cells' Bezier points reproduce the spline, and
  // "support" counts the functions non-zero on each leaf.
  test::TempDir dir;
  std::array<KnotVector, 3> kv{KnotVector::open_uniform(2, 2), KnotVector::open_uniform(2, 2), KnotVector::open_uniform(1, 2)};
  std::mt19937 rng(63);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> points(4 * 4 * 3 * 3);
  for (double& c : points) c = unit(rng);
  HierarchicalSpline<3> h(TensorSpline<3>::from_cartesian(kv, 3, points, std::vector<double>{}), HierarchicalBasis::thb);
  h.refine_elements(std::vector<int>{0});
  h.refine_elements(std::vector<int>{0, 3});
  io::write_hierarchical_vtu(dir.file("h.vtu"), {AnyHierarchicalSpline(h)});
  const test::VtuPiece v = test::read_vtu(dir.file("h.vtu"));
  ASSERT_EQ(v.cells, h.space().num_elements());
  const auto& conn = v.arrays.at("connectivity");
  const auto& P = v.arrays.at("Points");
  const auto& U = v.arrays.at("param");
  const int p[3] = {2, 2, 1};
  for (long long c = 0; c < v.cells; ++c) {
    EXPECT_EQ(v.arrays.at("types")[c], 79);
    const int e = static_cast<int>(v.arrays.at("element")[c]);
    EXPECT_EQ(v.arrays.at("support")[c], static_cast<double>(h.space().element_operator(e).ids.size()));
    const Box<3> b = h.space().element_box(e);
    const long long begin = c ? static_cast<long long>(v.arrays.at("offsets")[c - 1]) : 0;
    std::vector<std::array<int, 3>> node(18);
    for (int q = 0; q < 18; ++q) {
      const auto pt = static_cast<std::size_t>(conn[begin + q]);
      for (int k = 0; k < 3; ++k)
        node[static_cast<std::size_t>(q)][k] = static_cast<int>(std::lround((U[3 * pt + k] - b.lo[k]) / b.extent(k) * p[k]));
    }
    const double tt[3] = {unit(rng), unit(rng), unit(rng)};
    double sum[3] = {0, 0, 0}, want[3];
    for (int q = 0; q < 18; ++q) {
      double B = 1;
      for (int k = 0; k < 3; ++k) B *= bernstein(p[k], node[static_cast<std::size_t>(q)][k], tt[k]);
      const auto pt = static_cast<std::size_t>(conn[begin + q]);
      for (int d = 0; d < 3; ++d) sum[d] += B * P[3 * pt + d];
    }
    h.eval({b.lo[0] + tt[0] * b.extent(0), b.lo[1] + tt[1] * b.extent(1), b.lo[2] + tt[2] * b.extent(2)}, want);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(sum[d], want[d], 1e-12);
  }
}
