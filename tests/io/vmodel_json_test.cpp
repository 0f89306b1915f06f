#include "trivar/io/vmodel_json.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "trivar/core/error.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/block.hpp"

using namespace trivar;
using json = nlohmann::json;

namespace {

// The 7-cell ball with a constant density on every cell, a 2-component material field on the core cell and
// an expression attribute on the first shell cell.
VModel graded_ball() {
  VModel m;
  for (const auto& c : make_ball({.radius = 2.0})) m.add_cell(VCell(c));
  for (int i = 0; i < m.num_cells(); ++i) m.cell(i).set_attribute("density", Attribute::constant({1.5 + i}));
  const TensorSpline<3> field = make_block<3>({1, 1, 2}, {1, 1, 1}, {1.0, 1.0, 1.0});
  std::vector<double> coefs;  // two components, the first rising with w, the second its complement
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        coefs.push_back(0.5 * k);
        coefs.push_back(1 - 0.5 * k);
      }
  m.cell(0).set_attribute("material", Attribute::field(TensorSpline<3>(field.knot_vectors(), 2, false, coefs)));
  m.cell(1).set_attribute("temperature", Attribute::expression({"x^2 + y", "sin(z)"}, Attribute::Space::model));
  m.set_materials(MaterialTable({{"VeroCyan", {0, 174, 239, 255}}, {"Agilus <soft>", {10, 20, 30, 128}}}));
  m.glue();
  return m;
}

std::filesystem::path temp(const char* name) { return std::filesystem::temp_directory_path() / name; }

VModel from_text(const std::string& text) { return io::vmodel_from_json(json::parse(text), "m.json"); }

void expect_vmodel_error(const std::string& text, const std::string& fragment) {
  try {
    from_text(text);
    ADD_FAILURE() << "no error for " << text;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("m.json", 0), 0u) << e.what();
  }
}

}  // namespace

TEST(VModelJson, RoundTripKeepsCellsAttributesAndTopology) {
  const VModel m = graded_ball();
  const auto path = temp("trivar_vmodel_test.json");
  io::write_vmodel(path.string(), m);
  const VModel back = io::read_vmodel(path.string());
  std::filesystem::remove(path);

  ASSERT_EQ(back.num_cells(), m.num_cells());
  EXPECT_EQ(back.topology().num_shared_surfaces(), m.topology().num_shared_surfaces());
  EXPECT_EQ(back.topology().num_boundary_surfaces(), m.topology().num_boundary_surfaces());
  EXPECT_EQ(back.topology().curves.size(), m.topology().curves.size());
  EXPECT_EQ(back.topology().points.size(), m.topology().points.size());
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> U(0, 1);
  for (int c = 0; c < m.num_cells(); ++c) {
    const auto& a = m.cell(c);
    const auto& b = back.cell(c);
    ASSERT_EQ(a.attributes().size(), b.attributes().size());
    const Box<3> d = a.geometry().domain();
    for (int n = 0; n < 20; ++n) {
      Param<3> u;
      for (int k = 0; k < 3; ++k) u[k] = d.lo[k] + U(rng) * (d.hi[k] - d.lo[k]);
      double x[3], y[3];
      a.geometry().eval(u, x);
      b.geometry().eval(u, y);
      // Rational control points are stored Cartesian: one rounding of w * x may differ.
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], y[k], 1e-14);
      for (const auto& [name, attr] : a.attributes()) {
        std::vector<double> p(static_cast<std::size_t>(attr.components())), q(p.size());
        a.eval_attribute(name, u, p.data());
        b.eval_attribute(name, u, q.data());
        for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(p[i], q[i], 1e-14) << name;
      }
    }
  }
  // The material field at w = 1 (a cell parameter mapped onto the field's [0, 1]) is (1, 0).
  double mat[2];
  const Box<3> d0 = back.cell(0).geometry().domain();
  back.eval_attribute(0, "material", {d0.lo[0], d0.lo[1], d0.hi[2]}, mat);
  EXPECT_NEAR(mat[0], 1.0, 1e-15);
  EXPECT_NEAR(mat[1], 0.0, 1e-15);
  EXPECT_NEAR(back.mass("density"), m.mass("density"), 1e-12 * m.mass("density"));
  ASSERT_EQ(back.materials().size(), 2);
  EXPECT_EQ(back.materials()[1].name, "Agilus <soft>");
  EXPECT_EQ(back.materials()[1].colour, (Rgba{10, 20, 30, 128}));
}

TEST(VModelJson, SummaryDescribesTheTopology) {
  const json j = io::to_json(graded_ball());
  EXPECT_EQ(j.at("kind"), "vmodel");
  EXPECT_EQ(j.at("summary").at("cells"), 7);
  // Ball: the core shares its 6 faces with the shells, neighbouring shells share 12 faces; 6 sphere patches.
  EXPECT_EQ(j.at("summary").at("shared_surfaces"), 18);
  EXPECT_EQ(j.at("summary").at("boundary_surfaces"), 6);
  // V-curves: 12 cube edges, 12 sphere-patch edges and 8 radial edges from cube corners to the sphere;
  // V-points: 8 cube corners and 8 sphere-patch corners.
  EXPECT_EQ(j.at("summary").at("curves"), 32);
  EXPECT_EQ(j.at("summary").at("points"), 16);
  EXPECT_EQ(j.at("summary").at("non_conforming_faces"), 0);
  EXPECT_TRUE(io::is_vmodel_json(j));
}

TEST(VModelJson, MalformedModelsFailWithTheirPath) {
  json good = io::to_json(graded_ball());
  good.erase("summary");
  const auto with = [&](auto edit) {
    json j = good;
    edit(j);
    return j.dump();
  };
  expect_vmodel_error(R"({"trivar": 1, "kind": "volume"})", "vmodel");
  expect_vmodel_error(with([](json& j) { j.erase("cells"); }), "missing key \"cells\"");
  expect_vmodel_error(with([](json& j) { j["cells"] = json::array(); }), "cells");
  expect_vmodel_error(with([](json& j) { j["colour"] = 1; }), "unexpected key \"colour\"");
  expect_vmodel_error(with([](json& j) { j["glue"]["samples"] = 1; }), "glue: samples");
  expect_vmodel_error(with([](json& j) { j["materials"][0]["color"] = "#12345"; }), "materials[0]: color");
  expect_vmodel_error(with([](json& j) { j["materials"][1]["name"] = "VeroCyan"; }), "materials[1]");
  expect_vmodel_error(with([](json& j) { j["cells"][2]["attributes"]["density"]["kind"] = "table"; }),
               "cells[2]: attributes: density: kind");
  expect_vmodel_error(with([](json& j) { j["cells"][1]["attributes"]["temperature"]["components"][0] = "x +"; }),
               "cells[1]: attributes: temperature");
  expect_vmodel_error(with([](json& j) { j["cells"][0]["attributes"]["density"]["values"] = json::array(); }),
               "cells[0]: attributes: density: values");
  expect_vmodel_error(with([](json& j) { j["cells"][3]["geometry"]["kind"] = "surface"; }), "cells[3]: geometry");
  expect_vmodel_error(with([](json& j) { j["cells"][3]["geometry"]["control_points"][0][0] = "a"; }),
               "cells[3]: geometry");
}
