#include "trivar/io/lr_vtk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "io_test_support.hpp"
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

// The values of the DataArray named `name` ("" for the points), parsed as doubles.
std::vector<double> array_of(const std::string& xml, const std::string& name) {
  const std::string tag = name.empty() ? "<Points>" : "Name=\"" + name + "\"";
  std::size_t at = xml.find(tag);
  EXPECT_NE(at, std::string::npos) << name;
  at = xml.find('>', name.empty() ? xml.find("<DataArray", at) : at) + 1;
  std::istringstream in(xml.substr(at, xml.find("</DataArray>", at) - at));
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

}  // namespace

TEST(LrVtk, SampledElementsOfTheIdentityMapLieAtTheirParameters) {
  test::TempDir dir;
  const LRSpline<2> s = identity_surface();
  ASSERT_EQ(s.num_elements(), 3);
  io::write_lr_vtu(dir.file("s.vtu"), AnyLRSpline(s), {.samples_per_element = 3});
  const std::string xml = slurp(dir.file("s.vtu"));
  EXPECT_NE(xml.find("NumberOfPoints=\"48\" NumberOfCells=\"27\""), std::string::npos);
  const auto points = array_of(xml, ""), params = array_of(xml, "param");
  ASSERT_EQ(points.size(), 48u * 3);
  ASSERT_EQ(params.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(points[i], params[i], 1e-14) << i;
  const auto element = array_of(xml, "element"), support = array_of(xml, "support");
  ASSERT_EQ(element.size(), 27u);
  for (std::size_t c = 0; c < element.size(); ++c) {
    EXPECT_EQ(element[c], static_cast<double>(c / 9));
    EXPECT_EQ(support[c], static_cast<double>(s.element_support(static_cast<int>(c / 9)).size()));
  }
  // Every cell is a VTK_QUAD with 4 distinct corners of its own element.
  const auto types = array_of(xml, "types"), conn = array_of(xml, "connectivity");
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
  const auto points = array_of(xml, ""), params = array_of(xml, "param");
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

TEST(LrVtk, InvalidOptionsWriteNothing) {
  test::TempDir dir;
  EXPECT_THROW(io::write_lr_vtu(dir.file("a.vtu"), AnyLRSpline(identity_surface()), {.samples_per_element = 0}), Error);
  EXPECT_THROW(io::write_lr_vtu(dir.file("b.vtu"), std::vector<AnyLRSpline>{}), Error);
  EXPECT_EQ(dir.entries(), 0);
}
