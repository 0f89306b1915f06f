// AMF writer: the XML is parsed back by the minimal scanner of tests/io/am_test_support.hpp and checked for
// materials, composite formulas, the volume's material, exact coordinates and the per-vertex colour mix; the
// zipped form unzips (independent reader) to the same document.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "io/am_test_support.hpp"
#include "io/io_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/amf_writer.hpp"

using namespace trivar;

namespace {

MaterialTable amf_materials() {
  return MaterialTable({{"A<1>", {255, 0, 51, 255}}, {"B", {0, 102, 255, 0}}});
}

double number(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

std::vector<double> colour(const std::string& text) {
  std::vector<double> c;
  for (const char* tag : {"r", "g", "b", "a"}) c.push_back(number(test::elements(text, tag).at(0).text));
  return c;
}

}  // namespace

TEST(AmfWriter, GradedVolumeWithFormulasAndVertexColours) {
  test::TempDir dir;
  const double s = 0.1;
  const auto mesh = test::octahedron(s);
  const auto materials = amf_materials();
  std::vector<double> f;
  for (const auto& p : mesh.vertices) f.insert(f.end(), {(p[2] + s) / (2 * s), 1 - (p[2] + s) / (2 * s)});
  const io::AmfGrading grading{0, {"(z+0.1)/0.2", "1-(z+0.1)/0.2"}};
  io::write_amf(dir.file("part.amf"), mesh, materials, grading, f);
  const std::string xml = test::read_binary(dir.file("part.amf"));
  ASSERT_TRUE(test::well_formed(xml));

  const auto amf = test::elements(xml, "amf").at(0);
  EXPECT_EQ(amf.attributes.at("unit"), "millimeter");
  const auto mats = test::elements(xml, "material");
  ASSERT_EQ(mats.size(), 3u);
  EXPECT_EQ(mats[0].attributes.at("id"), "1");
  EXPECT_EQ(test::elements(mats[0].text, "metadata").at(0).text, "A&lt;1&gt;");
  EXPECT_EQ(colour(mats[0].text), (std::vector<double>{1, 0, 0.2, 1}));
  EXPECT_EQ(colour(mats[1].text), (std::vector<double>{0, 0.4, 1, 0}));
  const auto composites = test::elements(mats[2].text, "composite");
  ASSERT_EQ(composites.size(), 2u);
  EXPECT_EQ(composites[0].attributes.at("materialid"), mats[0].attributes.at("id"));
  EXPECT_EQ(composites[1].attributes.at("materialid"), mats[1].attributes.at("id"));
  EXPECT_EQ(composites[0].text, grading.formulas[0]);
  EXPECT_EQ(composites[1].text, grading.formulas[1]);

  const auto volumes = test::elements(xml, "volume");
  ASSERT_EQ(volumes.size(), 1u);
  EXPECT_EQ(volumes[0].attributes.at("materialid"), mats[2].attributes.at("id"));

  TriangleMesh back;
  const auto vertices = test::elements(xml, "vertex");
  ASSERT_EQ(vertices.size(), mesh.vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const auto& t = vertices[v].text;
    back.vertices.push_back({number(test::elements(t, "x").at(0).text), number(test::elements(t, "y").at(0).text),
                             number(test::elements(t, "z").at(0).text)});
    // Colour = fraction-weighted mix of (1, 0, 0.2, 1) and (0, 0.4, 1, 0).
    const double a = f[2 * v], b = f[2 * v + 1];
    const auto c = colour(t);
    const double expected[] = {a, 0.4 * b, 0.2 * a + b, a};
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(c[static_cast<std::size_t>(k)], expected[k], 1e-15);
  }
  EXPECT_EQ(back.vertices, mesh.vertices);
  for (const auto& t : test::elements(xml, "triangle"))
    back.triangles.push_back({std::stoi(test::elements(t.text, "v1").at(0).text), std::stoi(test::elements(t.text, "v2").at(0).text),
                              std::stoi(test::elements(t.text, "v3").at(0).text)});
  EXPECT_EQ(back.triangles, mesh.triangles);
  EXPECT_TRUE(is_watertight(back));
  EXPECT_NEAR(enclosed_volume(back), 4.0 / 3.0 * s * s * s, 1e-17);
}

TEST(AmfWriter, SingleMaterialVolumeWithoutColours) {
  test::TempDir dir;
  io::write_amf(dir.file("p.amf"), test::octahedron(), amf_materials(), io::AmfGrading{1, {}});
  const std::string xml = test::read_binary(dir.file("p.amf"));
  ASSERT_TRUE(test::well_formed(xml));
  EXPECT_EQ(test::elements(xml, "material").size(), 2u);
  EXPECT_TRUE(test::elements(xml, "composite").empty());
  EXPECT_EQ(test::elements(xml, "volume").at(0).attributes.at("materialid"), "2");
  EXPECT_EQ(test::elements(xml, "color").size(), 2u);  // the two materials' colours only
}

TEST(AmfWriter, ZippedFileHoldsTheSameDocument) {
  test::TempDir dir;
  const auto mesh = test::octahedron(2);
  const io::AmfGrading grading{0, {"x*x", "1"}};
  io::write_amf(dir.file("plain.amf"), mesh, amf_materials(), grading);
  io::write_amf(dir.file("zipped.amf"), mesh, amf_materials(), grading, {}, {.zip = true});
  const auto zip = test::read_zip(dir.file("zipped.amf"));
  ASSERT_EQ(zip.size(), 1u);
  EXPECT_EQ(zip.at("zipped.amf"), test::read_binary(dir.file("plain.amf")));
}

TEST(AmfWriter, BadInputThrowsAndWritesNothing) {
  test::TempDir dir;
  const auto path = dir.file("bad.amf");
  const auto mesh = test::octahedron();
  const auto mats = amf_materials();
  EXPECT_THROW(io::write_amf(path, mesh, MaterialTable{}, {}), Error);
  EXPECT_THROW(io::write_amf(path, TriangleMesh{}, mats, {}), Error);
  EXPECT_THROW(io::write_amf(path, mesh, mats, io::AmfGrading{2, {}}), Error);
  EXPECT_THROW(io::write_amf(path, mesh, mats, io::AmfGrading{0, {"z"}}), Error);
  EXPECT_THROW(io::write_amf(path, mesh, mats, io::AmfGrading{0, {"z", "  "}}), Error);
  EXPECT_THROW(io::write_amf(path, mesh, mats, {}, std::vector<double>(11, 0.5)), Error);
  auto zero = std::vector<double>(12, 0.5);
  zero[6] = zero[7] = 0;
  EXPECT_THROW(io::write_amf(path, mesh, mats, {}, zero), Error);
  auto negative = std::vector<double>(12, 0.5);
  negative[7] = -0.25;  // clamping it would have hidden the error
  EXPECT_THROW(io::write_amf(path, mesh, mats, {}, negative), Error);
  auto bad_mesh = mesh;
  bad_mesh.triangles[0][0] = -1;
  EXPECT_THROW(io::write_amf(path, bad_mesh, mats, {}), Error);
  bad_mesh = mesh;
  bad_mesh.vertices[3][2] = std::nan("");
  EXPECT_THROW(io::write_amf(path, bad_mesh, mats, {}), Error);
  EXPECT_EQ(dir.entries(), 0);
}
