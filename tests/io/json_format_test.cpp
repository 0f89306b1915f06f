#include "trivar/io/json_format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "io/io_test_support.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;
using nlohmann::json;

namespace {

// Values whose decimal form needs all 17 digits, extremes of the range, subnormals and a negative zero.
SplineCurve awkward_curve() {
  const std::vector<double> pts = {1.0 / 3,
                                   0.1,
                                   -0.0,
                                   1e-300,
                                   std::numeric_limits<double>::denorm_min(),
                                   std::numeric_limits<double>::max(),
                                   -2.5e-17,
                                   123456789.12345679,
                                   std::nextafter(1.0, 2.0),
                                   9007199254740993.0,
                                   -1e22,
                                   4.9406564584124654e-320};
  const KnotVector kv(
      2, {-1.0 / 7, -1.0 / 7, -1.0 / 7, 0.1 + 0.2, 0.7, 0.7, std::sqrt(2.0), std::sqrt(2.0), std::sqrt(2.0)});
  return SplineCurve::from_cartesian({kv}, 2, pts);
}

}  // namespace

TEST(JsonFormat, PolynomialRoundTripIsBitExact) {
  test::TempDir dir;
  auto objects = test::random_objects(false, 11);
  objects.emplace_back(awkward_curve());
  io::write_json(dir.file("p.json"), objects);
  const auto back = io::read_json(dir.file("p.json"));
  ASSERT_EQ(back.size(), objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) test::expect_identical(objects[i], back[i]);
}

// The schema stores Cartesian points and weights; the homogeneous coefficients are rebuilt as x * w, one
// rounding away from the original w * x: knots and weights are exact, coefficients within 2 ulp.
TEST(JsonFormat, RationalRoundTripKeepsKnotsAndWeightsExactly) {
  test::TempDir dir;
  const auto objects = test::random_objects(true, 12);
  io::write_json(dir.file("r.json"), objects);
  const auto back = io::read_json(dir.file("r.json"));
  ASSERT_EQ(back.size(), objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i)
    std::visit(
        [&](const auto& a) {
          const auto& b = std::get<std::decay_t<decltype(a)>>(back[i]);
          ASSERT_TRUE(b.is_rational());
          EXPECT_TRUE(a.knot_vectors() == b.knot_vectors());
          ASSERT_EQ(a.num_coefs(), b.num_coefs());
          for (int l = 0; l < a.num_coefs(); ++l) {
            EXPECT_EQ(a.weight(l), b.weight(l));
            for (int d = 0; d < a.dim(); ++d)
              EXPECT_LE(std::abs(a.coef(l)[d] - b.coef(l)[d]),
                        2 * std::numeric_limits<double>::epsilon() * std::abs(a.coef(l)[d]));
          }
          EXPECT_LT(test::max_deviation(a, b, test::random_params(a, 50, 13)), 1e-14);
        },
        objects[i]);
}

TEST(JsonFormat, OneObjectIsWrittenBareSeveralUnderObjects) {
  test::TempDir dir;
  const auto objects = test::random_objects(false, 14);
  io::write_json(dir.file("one.json"), {objects[0]});
  io::write_json(dir.file("two.json"), {objects[0], objects[1]});
  std::ifstream one(dir.file("one.json")), two(dir.file("two.json"));
  const json a = json::parse(one), b = json::parse(two);
  EXPECT_EQ(a["trivar"], 1);
  EXPECT_EQ(a["kind"], "curve");
  EXPECT_FALSE(a.contains("objects"));
  EXPECT_EQ(b["trivar"], 1);
  ASSERT_EQ(b["objects"].size(), 2u);
  EXPECT_EQ(b["objects"][1]["kind"], "surface");
}

TEST(JsonFormat, SchemaOfAQuarterCircle) {
  const double w = std::sqrt(0.5);
  const SplineCurve arc = SplineCurve::from_cartesian(
      {KnotVector(2, {0, 0, 0, 1, 1, 1})}, 2, std::vector<double>{1, 0, 1, 1, 0, 1}, std::vector<double>{1, w, 1});
  const json j = io::to_json(arc);
  EXPECT_EQ(j["kind"], "curve");
  EXPECT_EQ(j["dim"], 2);
  EXPECT_EQ(j["rational"], true);
  EXPECT_EQ(j["degrees"], json::parse("[2]"));
  EXPECT_EQ(j["knots"], json::parse("[[0, 0, 0, 1, 1, 1]]"));
  EXPECT_EQ(j["control_points"], json::parse("[[1, 0], [1, 1], [0, 1]]"));
  ASSERT_EQ(j["weights"].size(), 3u);
  EXPECT_EQ(j["weights"][1].get<double>(), w);

  const auto back = std::get<SplineCurve>(io::spline_from_json(j, "arc"));
  double x[2];
  for (double u : {0.0, 0.2, 0.5, 0.9, 1.0}) {
    back.eval({u}, x);
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0, 1e-15);
  }
  back.eval({0.5}, x);
  EXPECT_NEAR(x[0], w, 1e-15);
  EXPECT_NEAR(x[1], w, 1e-15);
}

TEST(JsonFormat, ReadsHandWrittenVolume) {
  const auto objects = io::read_json(TRIVAR_TEST_DATA "/io/trilinear_volume.json");
  ASSERT_EQ(objects.size(), 1u);
  const auto& v = std::get<SplineVolume>(objects[0]);
  double x[3];
  for (const Param<3>& u : {Param<3>{0.5, 0.25, 0.75}, Param<3>{0.1, 0.9, 0.3}, Param<3>{1, 1, 1}}) {
    v.eval(u, x);  // the file maps (u, v, w) to (2u, v, 3w)
    EXPECT_NEAR(x[0], 2 * u[0], 1e-15);
    EXPECT_NEAR(x[1], u[1], 1e-15);
    EXPECT_NEAR(x[2], 3 * u[2], 1e-15);
  }
}

TEST(JsonFormat, ErrorsArePrefixedWithTheCallersLocation) {
  json j = io::to_json(test::random_spline<2>({2, 2}, {2, 2}, 3, false, 15));
  j["knots"][1][2] = "x";
  try {
    io::spline_from_json(j, "model.json: objects[4]");
    FAIL() << "expected trivar::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "model.json: objects[4]: knots[1][2]: expected a number, got string");
  }
  EXPECT_THROW(io::spline_from_json(json::parse(R"({"kind": "curve"})"), "x"), Error);
}

TEST(JsonFormat, EmptySplineCannotBeWritten) {
  test::TempDir dir;
  EXPECT_THROW(io::to_json(AnySpline{}), Error);
  EXPECT_THROW(io::write_json(dir.file("e.json"), {test::random_spline<1>({2}, {3}, 2, false, 16), AnySpline{}}),
               Error);
  EXPECT_THROW(io::write_json(dir.file("e.json"), {}), Error);
  EXPECT_EQ(dir.entries(), 0);
}

namespace {

std::string read_error(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  try {
    io::read_json(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

// Copying, comparing and destroying a parsed JSON value recurse once per level: the reader bounds the depth.
TEST(JsonFormat, DeepNestingIsAnErrorNotAStackOverflow) {
  test::TempDir dir;
  const std::string path = dir.file("deep.json");
  const std::size_t levels = 200000;
  EXPECT_EQ(read_error(path, "{\"trivar\": 1, \"x\": " + std::string(levels, '[') + std::string(levels, ']') + "}"),
            path + ": objects and arrays nested deeper than 64 levels");
  // 64 levels (the top-level object and 63 arrays) parse; the document then fails on its content.
  EXPECT_EQ(read_error(path, "{\"trivar\": 1, \"x\": " + std::string(63, '[') + std::string(63, ']') + "}"),
            path + ": unexpected key \"x\"");
}

TEST(JsonFormat, DuplicateKeysAreRejectedWithTheirPath) {
  test::TempDir dir;
  const std::string path = dir.file("dup.json");
  EXPECT_EQ(read_error(path, R"({"trivar": 1, "kind": "curve", "kind": "surface"})"),
            path + ": duplicate key \"kind\" in the top-level object");
  EXPECT_EQ(read_error(path, R"({"trivar": 1, "objects": [{"dim": 1}, {"a": [1, {"b": 0}], "dim": 1, "dim": 2}]})"),
            path + ": duplicate key \"dim\" in objects[1]");
  EXPECT_EQ(read_error(path, R"({"trivar": 1, "objects": [[1, 2, {"b": {"c": 0, "c": 1}}]]})"),
            path + ": duplicate key \"c\" in objects[0][2].b");
}

// Every reader constructs its knot vectors and splines through the validating constructors; the JSON reader
// adds the object, the key path and the direction.
TEST(JsonFormat, DegenerateKnotsAndWeightsAreRejectedOnRead) {
  json j = io::to_json(test::random_spline<3>({2, 2, 2}, {2, 2, 2}, 3, true, 16));
  j["knots"][1] = {0, 0, 0, 1e-320, 1, 1, 1};  // still 4 B-splines, with a subnormal first span
  EXPECT_EQ(std::string([&] {
              try {
                io::spline_from_json(j, "x.json");
              } catch (const Error& e) {
                return std::string(e.what());
              }
              return std::string("no error");
            }()),
            "x.json: knots[1]: invalid knot vector in direction v: knot vector: span [t_2, t_3] = [0, 1e-320] is "
            "non-zero but shorter than 1e-12 (1e-12 of the domain length)");
  json w = io::to_json(test::random_spline<3>({1, 1, 1}, {1, 1, 1}, 3, true, 17));
  w["weights"] = std::vector<double>(8, 1e-320);
  try {
    io::spline_from_json(w, "w.json");
    FAIL() << "expected trivar::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("w.json: spline: the largest weight 1e-320 (control point 0)", 0), 0u)
        << e.what();
  }
}
