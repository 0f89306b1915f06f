// trivar make ball|cylinder|cone|torus, info, convert and export on V-models; reference values are the
// primitives' closed-form volumes.
#include <cmath>
#include <cstring>
#include <numbers>

#include "cli/cli_fixture.hpp"

using namespace cli_test;

namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

class ModelCli : public Cli {
protected:
  double volume_of(const std::string& file) const {
    return nlohmann::json::parse(ok("info --json " + file).out).at("volume").get<double>();
  }
};

TEST_F(ModelCli, PrimitivesHaveExactVolumesAndClosedBoundaries) {
  ok("make ball --radius 2 --center 1 0 0 -o ball.json");
  const Result info = ok("info ball.json");
  EXPECT_NE(info.out.find("V-model, 7 cells"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("topology: 18 shared surfaces, 6 boundary surfaces"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("boundary: closed"), std::string::npos) << info.out;
  EXPECT_NEAR(volume_of("ball.json"), 4.0 / 3.0 * kPi * 8, 1e-9 * 4.0 / 3.0 * kPi * 8);
  const auto cells = nlohmann::json::parse(ok("info --json ball.json").out).at("cell_info");
  ASSERT_EQ(cells.size(), 7u);
  for (const auto& c : cells) {
    EXPECT_EQ(c.at("jacobian"), "valid");
    EXPECT_GT(c.at("min_det_j_lower_bound").get<double>(), 0.0);
  }

  ok("make cylinder --radius 0.5 --height 3 -o cyl.json");
  EXPECT_NEAR(volume_of("cyl.json"), kPi * 0.25 * 3, 1e-12);
  ok("make cone --radii 2 --top-radius 1 --height 1.5 -o cone.json");
  EXPECT_NEAR(volume_of("cone.json"), kPi * 1.5 * (4 + 2 + 1) / 3, 1e-12);
  ok("make torus --major 3 --minor 1 -o torus.json");
  EXPECT_NEAR(volume_of("torus.json"), 2 * kPi * kPi * 3 * 1, 1e-11);
}

TEST_F(ModelCli, MaterialsBlendAsAPartitionOfUnity) {
  ok("make cylinder --radius 1 --height 2 --materials 3 --blend axial -o graded.json");
  const auto j = nlohmann::json::parse(ok("info --json graded.json").out);
  EXPECT_EQ(j.at("attributes").at("material").at("components"), 3);
  EXPECT_EQ(j.at("attributes").at("material").at("cells").size(), 5u);
  // The VTK file carries the fractions; at z = 0 material 0 is pure, at z = 1 (rho = 0.5) material 1.
  ok("convert graded.json graded.vtu");
  const std::string vtu = slurp(work_ / "graded.vtu");
  EXPECT_NE(vtu.find("Name=\"material\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"vcell\""), std::string::npos);
  ok("convert graded.json copy.json");
  EXPECT_EQ(nlohmann::json::parse(ok("info --json copy.json").out).at("attributes"), j.at("attributes"));
}

TEST_F(ModelCli, BoxModelWithFormulaMaterials) {
  ok("make box --model --size 2 1 1 --material-field x/2 1-x/2 -o box.json");
  const auto j = nlohmann::json::parse(ok("info --json box.json").out);
  EXPECT_EQ(j.at("cells"), 1);
  EXPECT_NEAR(j.at("volume").get<double>(), 2.0, 1e-14);
  EXPECT_EQ(j.at("attributes").at("material").at("components"), 2);
  ok("export box.json box.vtu");
  EXPECT_NE(slurp(work_ / "box.vtu").find("Name=\"material\""), std::string::npos);
  fails("make box --materials 2 -o b.json");
  fails("make box --model --materials 2 --material-field x -o b.json", 2);
}

TEST_F(ModelCli, SweepMorphAndRevolveFromFiles) {
  ok("make box --elements 1 1 --size 1 1 -o square.json");
  write("line.json", R"({"trivar": 1, "kind": "curve", "dim": 3, "rational": false, "degrees": [1],
                         "knots": [[0, 0, 1, 1]], "control_points": [[0, 0, 0], [0, 0, 2]]})");
  // Along a straight path the sweep is the extrusion: the unit square times [0, 2] in z.
  const Result s = ok("make sweep square.json line.json -o swept.json");
  EXPECT_LT(numbers_after(s.out, "max error").at(0), 1e-12);
  const auto x = numbers_after(ok("eval swept.json 0.5 0.25 0.5").out, "S");
  ASSERT_EQ(x.size(), 3u);
  EXPECT_NEAR(x[0], 0.5, 1e-12);
  EXPECT_NEAR(x[1], 0.25, 1e-12);
  EXPECT_NEAR(x[2], 1.0, 1e-12);

  ok("make box --elements 1 1 --size 2 2 -o big.json");
  ok("make morph square.json big.json --smoothness 1 -o morph.json");
  // w = 0.5: the smoothstep blend is 1/2, so the corner (1, 1) of u = v = 1 sits at (1.5, 1.5).
  const auto y = numbers_after(ok("eval morph.json 1 1 0.5").out, "S");
  EXPECT_NEAR(y.at(0), 1.5, 1e-14);

  // A quarter turn of the segment x in [1, 2] about the z-axis: a quarter annulus of radii 1 and 2.
  write("seg.json", R"({"trivar": 1, "kind": "curve", "dim": 3, "rational": false, "degrees": [1],
                        "knots": [[0, 0, 1, 1]], "control_points": [[1, 0, 0], [2, 0, 0]]})");
  ok("make revolve --profile seg.json --angle 90 -o quarter.json");
  const auto p = numbers_after(ok("eval quarter.json 0.5 0.5").out, "S");
  ASSERT_EQ(p.size(), 3u);
  EXPECT_NEAR(std::hypot(p[0], p[1]), 1.5, 1e-14);
  fails("make sweep line.json square.json -o x.json");
  fails("make revolve --profile seg.json --axis-dir 0 0 0 -o x.json");
}

TEST_F(ModelCli, ExportWritesAWatertightStl) {
  ok("make ball --radius 1 -o ball.json");
  const Result r = ok("export ball.json ball.stl --tolerance 0.001");
  EXPECT_NE(r.out.find("watertight yes"), std::string::npos) << r.out;
  const double v = numbers_after(r.out.substr(r.out.find("enclosed volume")), "enclosed volume").at(0);
  EXPECT_NEAR(v, 4.0 / 3.0 * kPi, 0.005);
  const std::string stl = slurp(work_ / "ball.stl");
  std::uint32_t count = 0;
  std::memcpy(&count, stl.data() + 80, 4);
  EXPECT_EQ(stl.size(), 84 + 50 * std::size_t{count});
  // A volume file exports too: the unit cube, 12 triangles at least.
  ok("make box --elements 2 -o cube.json");
  EXPECT_NE(ok("export cube.json cube.stl").out.find("enclosed volume 1"), std::string::npos);
}

TEST_F(ModelCli, GradedExportTo3mfAndAmf) {
  ok("make ball --radius 10 --materials 3 -o ball.json");
  const auto j = nlohmann::json::parse(slurp(work_ / "ball.json"));
  ASSERT_EQ(j.at("materials").size(), 3u);
  EXPECT_EQ(j.at("materials")[0].at("name"), "M1");
  EXPECT_NE(ok("export ball.json ball.3mf --tolerance 0.05").out.find("watertight yes"), std::string::npos);
  EXPECT_EQ(slurp(work_ / "ball.3mf").substr(0, 2), "PK");  // an OPC (zip) package
  ok("export ball.json ball.amf --tolerance 0.05");
  const std::string amf = slurp(work_ / "ball.amf");
  // Every cell shares the blend formulas, so the volume is a composite material defined by them.
  EXPECT_NE(amf.find("<composite materialid=\"1\">max(0, 1 - abs("), std::string::npos);
  EXPECT_NE(amf.find("<metadata type=\"name\">M3</metadata>"), std::string::npos);
}

TEST_F(ModelCli, BadModelInputFailsCleanly) {
  ok("make ball -o ball.json");
  ok("make box --elements 2 2 -o plate.json");
  fails("make torus --major 1 --minor 2 -o t.json");
  fails("make ball --core 1.5 -o b.json");
  fails("make ball --radius -1 -o b.json", 2);
  fails("make cone --top-radius 0 -o c.json", 2);
  fails("make ball --materials 2 --blend spiral -o b.json", 2);
  fails("export ball.json ball.obj");
  fails("export plate.json plate.stl");
  // A cell flattened into the plane z = 0 encloses no volume: gluing refuses it, whatever the output.
  nlohmann::json flat{{"trivar", 1}, {"kind", "volume"}, {"dim", 3}, {"rational", false}, {"degrees", {1, 1, 1}}};
  flat["knots"] = {{0, 0, 1, 1}, {0, 0, 1, 1}, {0, 0, 1, 1}};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) flat["control_points"].push_back({i, j, 0});
  write("flat.json", flat.dump());
  fails("export flat.json flat.stl");
  fails("export flat.json flat.stl --allow-open");
  EXPECT_EQ(lines(run("export flat.json flat.3mf").err).at(0),
            "trivar: error: glue: cell 0 is collapsed: volume 0 is no more than the tolerance 1.4142135623730952e-07 "
            "times its extent 1 x 1");
  EXPECT_FALSE(std::filesystem::exists(work_ / "flat.3mf"));
  fails("convert ball.json ball.g2");
  write("broken.json", R"({"trivar": 1, "kind": "vmodel", "cells": []})");
  fails("info broken.json");
}
