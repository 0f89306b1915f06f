// trivar make extrude|ruled|loft|coons on hand-written inputs whose results have closed forms: bilinear
// faces of a cuboid, parallel plates, straight segments.
#include <array>
#include <string>

#include "cli/cli_fixture.hpp"

using namespace cli_test;

namespace {

using Point = std::array<double, 3>;

// Degree-1 curve from a to b.
std::string segment_json(const Point& a, const Point& b) {
  nlohmann::json j{{"trivar", 1}, {"kind", "curve"}, {"dim", 3}, {"rational", false}, {"degrees", {1}}};
  j["knots"] = {{0, 0, 1, 1}};
  j["control_points"] = {a, b};
  return j.dump();
}

// Bilinear patch with corners c00, c10, c01, c11 (first index: first parameter).
std::string patch_json(const Point& c00, const Point& c10, const Point& c01, const Point& c11) {
  nlohmann::json j{{"trivar", 1}, {"kind", "surface"}, {"dim", 3}, {"rational", false}, {"degrees", {1, 1}}};
  j["knots"] = {{0, 0, 1, 1}, {0, 0, 1, 1}};
  j["control_points"] = {c00, c10, c01, c11};
  return j.dump();
}

class MakeCli : public Cli {
protected:
  // The point printed by `trivar eval`.
  std::vector<double> eval_at(const std::string& file, const std::string& params) const {
    return numbers_after(ok("eval " + file + " " + params).out, "S");
  }
};

void expect_point(const std::vector<double>& x, const Point& expected) {
  ASSERT_EQ(x.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(x[i], expected[i], 1e-14) << "coordinate " << i;
}

TEST_F(MakeCli, MakeExtrudeAlongVectorAndPath) {
  ok("make box --degree 2 --elements 2 3 --size 2 1 -o plate.json");
  ok("make extrude plate.json --direction 0.5 0 3 -o slab.json");
  // The plate is (2u, v, 0); extruded: (2u + 0.5w, v, 3w).
  expect_point(eval_at("slab.json", "0.25 0.5 0.5"), {0.75, 0.5, 1.5});
  write("path.json", segment_json({1, 1, 1}, {1, 3, 2}));
  ok("make extrude plate.json --path path.json -o swept.json");
  // The plate slides by path(w) - path(0) = (0, 2w, w).
  expect_point(eval_at("swept.json", "0.5 0.5 0.25"), {1.0, 1.0, 0.25});
  write("line.json", segment_json({0, 0, 0}, {1, 0, 0}));
  ok("make extrude line.json --direction 0 2 0 -o strip.json");
  expect_point(eval_at("strip.json", "0.5 0.5"), {0.5, 1.0, 0.0});

  fails("make extrude plate.json -o x.json");
  fails("make extrude plate.json --direction 1 0 -o x.json");
  fails("make extrude slab.json --direction 0 0 1 -o x.json");
  fails("make extrude plate.json --path plate.json -o x.json");
  fails("make extrude plate.json --direction 0 0 1 --path path.json -o x.json", 2);
}

TEST_F(MakeCli, MakeRuledBetweenSegmentsAndPlates) {
  write("a.json", segment_json({0, 0, 0}, {1, 0, 0}));
  write("b.json", segment_json({0, 1, 1}, {2, 1, 1}));
  ok("make ruled a.json b.json -o ruled.json");
  // (1 - v) a(u) + v b(u) at u = 0.5, v = 0.5: ((0.5 + 1) / 2, 0.5, 0.5).
  expect_point(eval_at("ruled.json", "0.5 0.5"), {0.75, 0.5, 0.5});

  write("bottom.json", patch_json({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}));
  write("top.json", patch_json({0, 0, 2}, {1, 0, 2}, {0, 1, 2}, {1, 1, 2}));
  ok("make ruled bottom.json top.json -o box.json");
  expect_point(eval_at("box.json", "0.25 0.75 0.5"), {0.25, 0.75, 1.0});
  EXPECT_EQ(lines(ok("check box.json").out).at(0), "valid");

  fails("make ruled a.json -o x.json");
  fails("make ruled a.json bottom.json -o x.json");
}

TEST_F(MakeCli, MakeLoftThroughParallelPlates) {
  const std::array<std::string, 3> names{"p0.json", "p1.json", "p2.json"};
  for (int k = 0; k < 3; ++k)
    write(names[k], patch_json({0, 0, 1.0 * k}, {1, 0, 1.0 * k}, {0, 1, 1.0 * k}, {1, 1, 1.0 * k}));
  ok("make loft p0.json p1.json p2.json --degree 2 --params 0 0.5 1 -o loft.json");
  // Sections at z = 2t interpolated at t = 0, 0.5, 1 by a quadratic: z = 2t exactly.
  expect_point(eval_at("loft.json", "0.5 0.5 0.25"), {0.5, 0.5, 0.5});
  // Chord-length parameters of equally spaced sections are 0, 0.5, 1 too.
  expect_point(eval_at("loft.json", "0.2 0.9 0.75"), {0.2, 0.9, 1.5});
  ok("make loft p0.json p2.json -o two.json");
  expect_point(eval_at("two.json", "0.5 0.5 0.5"), {0.5, 0.5, 1.0});

  fails("make loft p0.json -o x.json");
  fails("make loft p0.json p1.json p2.json --params 0 1 -o x.json");
  fails("make loft p0.json p0.json -o x.json");
}

TEST_F(MakeCli, MakeCoonsFromCuboidFaces) {
  // The cuboid [0,1] x [0,2] x [0,3]: faces u = 0, u = 1 parametrised by (v, w), v-faces by (u, w), w-faces by (u, v).
  const double X = 1, Y = 2, Z = 3;
  write("u0.json", patch_json({0, 0, 0}, {0, Y, 0}, {0, 0, Z}, {0, Y, Z}));
  write("u1.json", patch_json({X, 0, 0}, {X, Y, 0}, {X, 0, Z}, {X, Y, Z}));
  write("v0.json", patch_json({0, 0, 0}, {X, 0, 0}, {0, 0, Z}, {X, 0, Z}));
  write("v1.json", patch_json({0, Y, 0}, {X, Y, 0}, {0, Y, Z}, {X, Y, Z}));
  write("w0.json", patch_json({0, 0, 0}, {X, 0, 0}, {0, Y, 0}, {X, Y, 0}));
  write("w1.json", patch_json({0, 0, Z}, {X, 0, Z}, {0, Y, Z}, {X, Y, Z}));
  ok("make coons u0.json u1.json v0.json v1.json w0.json w1.json -o cuboid.json");
  expect_point(eval_at("cuboid.json", "0.3 0.6 0.2"), {0.3, 1.2, 0.6});
  EXPECT_EQ(lines(ok("check cuboid.json").out).at(0), "valid");

  // A face moved off the others: its edges no longer meet those of its neighbours.
  write("w1.json", patch_json({0, 0, Z + 1}, {X, 0, Z + 1}, {0, Y, Z + 1}, {X, Y, Z + 1}));
  fails("make coons u0.json u1.json v0.json v1.json w0.json w1.json -o x.json");
  fails("make coons u0.json u1.json -o x.json");
}

}  // namespace
