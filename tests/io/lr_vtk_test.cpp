#include "trivar/io/lr_vtk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "io_test_support.hpp"
#include "support/vtu_arrays.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

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

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace

TEST(LrVtk, SampledElementsOfTheIdentityMapLieAtTheirParameters) {
  test::TempDir dir;
  const LRSpline<2> s = identity_surface();
  ASSERT_EQ(s.num_elements(), 3);
  io::write_lr_vtu(dir.file("s.vtu"), AnyLRSpline(s), {.samples_per_element = 3});
  const std::string xml = slurp(dir.file("s.vtu"));
  EXPECT_NE(xml.find("NumberOfPoints=\"48\" NumberOfCells=\"27\""), std::string::npos);
  const auto points = test::vtu_array(xml, ""), params = test::vtu_array(xml, "param");
  ASSERT_EQ(points.size(), 48u * 3);
  ASSERT_EQ(params.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(points[i], params[i], 1e-14) << i;
  const auto element = test::vtu_array(xml, "element"), support = test::vtu_array(xml, "support");
  ASSERT_EQ(element.size(), 27u);
  for (std::size_t c = 0; c < element.size(); ++c) {
    EXPECT_EQ(element[c], static_cast<double>(c / 9));
    EXPECT_EQ(support[c], static_cast<double>(s.element_support(static_cast<int>(c / 9)).size()));
  }
  // Every cell is a VTK_QUAD with 4 distinct corners of its own element.
  const auto types = test::vtu_array(xml, "types"), conn = test::vtu_array(xml, "connectivity");
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
  io::write_lr_vtu(dir.file("m.vtu"), {AnyLRSpline(v), AnyLRSpline(identity_surface())}, {.parametric_mesh = true});
  const std::string xml = slurp(dir.file("m.vtu"));
  EXPECT_NE(xml.find("NumberOfPoints=\"16\" NumberOfCells=\"2\""), std::string::npos);
  EXPECT_NE(xml.find("NumberOfPoints=\"12\" NumberOfCells=\"3\""), std::string::npos);
  const auto points = test::vtu_array(xml, ""), params = test::vtu_array(xml, "param");
  ASSERT_EQ(points.size(), 16u * 3);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(points[i], params[i]);
  // Hexahedra: the second element's bottom corners lie on w = 0.5 (VTK order: bottom face first).
  double volume = 0;
  for (int e = 0; e < 2; ++e) {
    const Box<3>& b = v.element(e);
    volume += b.extent(0) * b.extent(1) * b.extent(2);
  }
  EXPECT_DOUBLE_EQ(volume, 1.0);
  EXPECT_NE(xml.find("<DataArray type=\"UInt8\" Name=\"types\" NumberOfComponents=\"1\" format=\"ascii\">\n          12 12\n"),
            std::string::npos);
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
  io::write_lr_vtu(dir.file("f.vtu"), AnyLRSpline(s), {.samples_per_element = 2}, {uv}, {twice});
  const std::string xml = slurp(dir.file("f.vtu"));
  const auto params = test::vtu_array(xml, "param"), values = test::vtu_array(xml, "uv");
  ASSERT_EQ(values.size(), 27u * 2);
  for (std::size_t q = 0; q < 27; ++q)
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(values[2 * q + k], params[3 * q + k], 1e-15) << q;
  const auto element = test::vtu_array(xml, "element"), doubled = test::vtu_array(xml, "twice");
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

TEST(LrVtk, InvalidOptionsWriteNothing) {
  test::TempDir dir;
  EXPECT_THROW(io::write_lr_vtu(dir.file("a.vtu"), AnyLRSpline(identity_surface()), {.samples_per_element = 0}), Error);
  EXPECT_THROW(io::write_lr_vtu(dir.file("b.vtu"), std::vector<AnyLRSpline>{}), Error);
  EXPECT_EQ(dir.entries(), 0);
}
