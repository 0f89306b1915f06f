// 3MF writer: the package is unzipped by an independent reader (tests/io/am_test_support.hpp) and the model
// XML checked for structure, references, exact coordinates, composites summing to 1 and the per-vertex
// mixtures of the input field; the re-built mesh is watertight with the analytic volume.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "io/am_test_support.hpp"
#include "io/io_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/threemf_writer.hpp"

using namespace trivar;

namespace {

MaterialTable threemf_materials() {
  return MaterialTable({{"hard & stiff", {200, 30, 40, 255}}, {"soft", {10, 220, 30, 100}}});
}

// Material 0 grows linearly with z over the octahedron (z in [-s, s]); material 1 is the rest.
std::vector<double> z_gradient(const TriangleMesh& mesh, double s) {
  std::vector<double> f;
  for (const auto& p : mesh.vertices) {
    const double a = (p[2] + s) / (2 * s);
    f.push_back(a);
    f.push_back(1 - a);
  }
  return f;
}

std::vector<double> numbers(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> v;
  for (std::string word; in >> word;) v.push_back(std::strtod(word.c_str(), nullptr));
  return v;
}

int integer(const test::XmlElement& e, const std::string& key) { return std::stoi(e.attributes.at(key)); }

}  // namespace

TEST(ThreeMfWriter, PackageHasTheOpcParts) {
  test::TempDir dir;
  const auto mesh = test::octahedron();
  io::write_3mf(dir.file("part.3mf"), mesh, threemf_materials(), z_gradient(mesh, 1));
  const auto zip = test::read_zip(dir.file("part.3mf"));
  ASSERT_EQ(zip.size(), 3u);
  const auto& types = zip.at("[Content_Types].xml");
  EXPECT_TRUE(test::well_formed(types));
  const auto defaults = test::elements(types, "Default");
  ASSERT_EQ(defaults.size(), 2u);
  EXPECT_EQ(defaults[1].attributes.at("Extension"), "model");
  EXPECT_EQ(defaults[1].attributes.at("ContentType"), "application/vnd.ms-package.3dmanufacturing-3dmodel+xml");
  const auto rels = test::elements(zip.at("_rels/.rels"), "Relationship");
  ASSERT_EQ(rels.size(), 1u);
  EXPECT_EQ(rels[0].attributes.at("Target"), "/3D/3dmodel.model");
  EXPECT_EQ(rels[0].attributes.at("Type"), "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel");
  EXPECT_EQ(zip.count("3D/3dmodel.model"), 1u);
}

TEST(ThreeMfWriter, ModelCarriesMaterialsCompositesAndExactGeometry) {
  test::TempDir dir;
  const double s = 1.0 / 3.0;  // coordinates with no short decimal form test the shortest round trip
  const auto mesh = test::octahedron(s);
  const auto fractions = z_gradient(mesh, s);
  const auto materials = threemf_materials();
  io::write_3mf(dir.file("part.3mf"), mesh, materials, fractions);
  const std::string xml = test::read_zip(dir.file("part.3mf")).at("3D/3dmodel.model");
  ASSERT_TRUE(test::well_formed(xml));

  const auto model = test::elements(xml, "model").at(0);
  EXPECT_EQ(model.attributes.at("unit"), "millimeter");
  EXPECT_EQ(model.attributes.at("xmlns"), "http://schemas.microsoft.com/3dmanufacturing/core/2015/02");
  EXPECT_EQ(model.attributes.at("xmlns:m"), "http://schemas.microsoft.com/3dmanufacturing/material/2015/02");
  EXPECT_EQ(model.attributes.at("requiredextensions"), "m");

  const auto groups = test::elements(xml, "basematerials");
  ASSERT_EQ(groups.size(), 1u);
  const auto bases = test::elements(xml, "base");
  ASSERT_EQ(bases.size(), 2u);
  EXPECT_EQ(bases[0].attributes.at("name"), "hard &amp; stiff");
  EXPECT_EQ(bases[0].attributes.at("displaycolor"), "#C81E28");
  EXPECT_EQ(bases[1].attributes.at("name"), "soft");
  EXPECT_EQ(bases[1].attributes.at("displaycolor"), "#0ADC1E64");

  const auto cgroups = test::elements(xml, "m:compositematerials");
  ASSERT_EQ(cgroups.size(), 1u);
  EXPECT_EQ(cgroups[0].attributes.at("matid"), groups[0].attributes.at("id"));
  EXPECT_EQ(cgroups[0].attributes.at("matindices"), "0 1");
  const auto composites = test::elements(xml, "m:composite");
  // Mixtures (1, 0) at the top, (1/2, 1/2) on the equator and (0, 1) at the bottom: one composite each.
  ASSERT_EQ(composites.size(), 3u);
  std::vector<std::vector<double>> values;
  for (const auto& c : composites) {
    values.push_back(numbers(c.attributes.at("values")));
    ASSERT_EQ(values.back().size(), 2u);
    EXPECT_NEAR(values.back()[0] + values.back()[1], 1.0, 1e-6);
  }

  const auto objects = test::elements(xml, "object");
  ASSERT_EQ(objects.size(), 1u);
  const std::string cid = cgroups[0].attributes.at("id");
  EXPECT_EQ(objects[0].attributes.at("pid"), cid);
  EXPECT_LT(integer(objects[0], "pindex"), 3);
  const auto items = test::elements(xml, "item");
  ASSERT_EQ(items.size(), 1u);
  EXPECT_EQ(items[0].attributes.at("objectid"), objects[0].attributes.at("id"));

  TriangleMesh back;
  for (const auto& v : test::elements(xml, "vertex"))
    back.vertices.push_back({std::strtod(v.attributes.at("x").c_str(), nullptr), std::strtod(v.attributes.at("y").c_str(), nullptr),
                             std::strtod(v.attributes.at("z").c_str(), nullptr)});
  EXPECT_EQ(back.vertices, mesh.vertices);  // bit-exact
  const auto triangles = test::elements(xml, "triangle");
  ASSERT_EQ(triangles.size(), mesh.triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& e = triangles[t];
    back.triangles.push_back({integer(e, "v1"), integer(e, "v2"), integer(e, "v3")});
    EXPECT_EQ(back.triangles.back(), mesh.triangles[t]);
    EXPECT_EQ(e.attributes.at("pid"), cid);
    for (int i = 0; i < 3; ++i) {
      const int p = integer(e, "p" + std::to_string(i + 1));
      ASSERT_GE(p, 0);
      ASSERT_LT(p, 3);
      const int v = mesh.triangles[t][static_cast<std::size_t>(i)];
      const double expected = (mesh.vertices[static_cast<std::size_t>(v)][2] + s) / (2 * s);
      EXPECT_NEAR(values[static_cast<std::size_t>(p)][0], expected, 1e-15);
      EXPECT_NEAR(values[static_cast<std::size_t>(p)][1], 1 - expected, 1e-15);
    }
  }
  EXPECT_TRUE(is_watertight(back));
  EXPECT_NEAR(enclosed_volume(back), 4.0 / 3.0 * s * s * s, 1e-15);
}

// Fractions are proportions: divided by their sum, never clamped; a negative one is an error naming the vertex.
TEST(ThreeMfWriter, FractionsAreNormalisedAndNegativesRejected) {
  test::TempDir dir;
  const auto mesh = test::octahedron();
  const MaterialTable three({{"a", {}}, {"b", {}}, {"c", {}}});
  std::vector<double> f;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) f.insert(f.end(), {3.0, 1.0, 0.0});  // -> (3, 1, 0) / 4
  io::write_3mf(dir.file("p.3mf"), mesh, three, f);
  const std::string xml = test::read_zip(dir.file("p.3mf")).at("3D/3dmodel.model");
  const auto composites = test::elements(xml, "m:composite");
  ASSERT_EQ(composites.size(), 1u);
  EXPECT_EQ(numbers(composites[0].attributes.at("values")), (std::vector<double>{0.75, 0.25, 0}));
  f[3 * 4 + 2] = -2;
  try {
    io::write_3mf(dir.file("n.3mf"), mesh, three, f);
    FAIL() << "expected trivar::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "write_3mf: vertex 4: material fractions (3, 1, -2): fraction 2 is negative; "
                                     "fractions must be finite and >= 0 with a positive sum");
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("n.3mf")));
}

TEST(ThreeMfWriter, OutputIsDeterministic) {
  test::TempDir dir;
  const auto mesh = test::octahedron(2.5);
  io::write_3mf(dir.file("a.3mf"), mesh, threemf_materials(), z_gradient(mesh, 2.5));
  io::write_3mf(dir.file("b.3mf"), mesh, threemf_materials(), z_gradient(mesh, 2.5));
  EXPECT_EQ(test::read_binary(dir.file("a.3mf")), test::read_binary(dir.file("b.3mf")));
}

TEST(ThreeMfWriter, BadInputThrowsAndWritesNothing) {
  test::TempDir dir;
  const auto path = dir.file("bad.3mf");
  const auto mesh = test::octahedron();
  const auto f = z_gradient(mesh, 1);
  EXPECT_THROW(io::write_3mf(path, mesh, MaterialTable{}, {}), Error);
  EXPECT_THROW(io::write_3mf(path, TriangleMesh{}, threemf_materials(), {}), Error);
  EXPECT_THROW(io::write_3mf(path, mesh, threemf_materials(), std::span(f).first(f.size() - 1)), Error);
  auto zero = f;
  zero[4] = zero[5] = 0;
  EXPECT_THROW(io::write_3mf(path, mesh, threemf_materials(), zero), Error);
  auto nan = f;
  nan[3] = std::nan("");
  EXPECT_THROW(io::write_3mf(path, mesh, threemf_materials(), nan), Error);
  auto bad_mesh = mesh;
  bad_mesh.triangles[2][1] = 6;
  EXPECT_THROW(io::write_3mf(path, bad_mesh, threemf_materials(), f), Error);
  bad_mesh = mesh;
  bad_mesh.vertices[1][0] = INFINITY;
  EXPECT_THROW(io::write_3mf(path, bad_mesh, threemf_materials(), f), Error);
  EXPECT_EQ(dir.entries(), 0);
}
