// trivar make ball|cylinder|cone|torus, info, convert and export on V-models; reference values are the
// primitives' closed-form volumes.
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
    return nlohmann::json::parse(ok("info --json " + file).out).at("model").at("volume").get<double>();
  }
};

TEST_F(ModelCli, PrimitivesHaveExactVolumesAndClosedBoundaries) {
  ok("make ball --radius 2 --center 1 0 0 -o ball.json");
  const Result info = ok("info ball.json");
  EXPECT_NE(info.out.find("V-model, 7 cells"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("topology: 18 shared surfaces, 6 boundary surfaces"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("boundary: closed"), std::string::npos) << info.out;
  EXPECT_NEAR(volume_of("ball.json"), 4.0 / 3.0 * kPi * 8, 1e-9 * 4.0 / 3.0 * kPi * 8);

  ok("make cylinder --radius 0.5 --height 3 -o cyl.json");
  EXPECT_NEAR(volume_of("cyl.json"), kPi * 0.25 * 3, 1e-12);
  ok("make cone --radii 2 --top-radius 1 --height 1.5 -o cone.json");
  EXPECT_NEAR(volume_of("cone.json"), kPi * 1.5 * (4 + 2 + 1) / 3, 1e-12);
  ok("make torus --major 3 --minor 1 -o torus.json");
  EXPECT_NEAR(volume_of("torus.json"), 2 * kPi * kPi * 3 * 1, 1e-11);
}

TEST_F(ModelCli, MaterialsBlendAsAPartitionOfUnity) {
  ok("make cylinder --radius 1 --height 2 --materials 3 --blend axial -o graded.json");
  const auto j = nlohmann::json::parse(ok("info --json graded.json").out).at("model");
  EXPECT_EQ(j.at("attributes").at("material").at("components"), 3);
  EXPECT_EQ(j.at("attributes").at("material").at("cells").size(), 5u);
  // The VTK file carries the fractions; at z = 0 material 0 is pure, at z = 1 (rho = 0.5) material 1.
  ok("convert graded.json graded.vtu");
  const std::string vtu = slurp(work_ / "graded.vtu");
  EXPECT_NE(vtu.find("Name=\"material\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"vcell\""), std::string::npos);
  ok("convert graded.json copy.json");
  EXPECT_EQ(nlohmann::json::parse(ok("info --json copy.json").out).at("model").at("attributes"), j.at("attributes"));
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
  fails("convert ball.json ball.g2");
  write("broken.json", R"({"trivar": 1, "kind": "vmodel", "cells": []})");
  fails("info broken.json");
}
