#include "trivar/io/lr_json.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <random>

#include "io_test_support.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;
using nlohmann::json;

namespace {

using test::mid_knot;

// A distinct interior knot of direction k (partial rectangles must end on mesh lines).
template <int D>
LRSpline<D> refined_json_case(bool rational, unsigned seed) {
  Ints<D> degrees, elements;
  for (int k = 0; k < D; ++k) {
    degrees[k] = 2 + (k % 2);
    elements[k] = 3;
  }
  const TensorSpline<D> t = test::random_spline<D>(degrees, elements, 2 + D % 2, rational, seed);
  LRSpline<D> lr(t);
  const Box<D> d = lr.domain();
  Param<D> hi = d.hi;
  hi[1] = mid_knot(t, 1);
  lr.insert(MeshRectangle<D>::make(0, d.lo[0] + 0.4 * (d.hi[0] - d.lo[0]), d.lo, hi));
  lr.insert(MeshRectangle<D>::make(D - 1, d.lo[D - 1] + 0.8 * (d.hi[D - 1] - d.lo[D - 1]), d.lo, d.hi, 2));
  return lr;
}

template <int D>
void expect_bit_identical(const LRSpline<D>& a, const LRSpline<D>& b) {
  ASSERT_EQ(a.num_basis(), b.num_basis());
  ASSERT_EQ(a.mesh().size(), b.mesh().size());
  EXPECT_EQ(a.num_elements(), b.num_elements());
  EXPECT_EQ(a.dim(), b.dim());
  EXPECT_EQ(a.is_rational(), b.is_rational());
  EXPECT_EQ(a.degrees(), b.degrees());
  for (int i = 0; i < a.num_basis(); ++i) {
    const auto &x = a.basis_function(i), &y = b.basis_function(i);
    for (int k = 0; k < D; ++k) EXPECT_EQ(x.knots[k], y.knots[k]);
    EXPECT_EQ(x.gamma, y.gamma);
    EXPECT_EQ(x.coef, y.coef);
  }
  for (std::size_t i = 0; i < a.mesh().size(); ++i) {
    const auto &r = a.mesh()[i], &q = b.mesh()[i];
    EXPECT_EQ(r.dir, q.dir);
    EXPECT_EQ(r.value, q.value);
    EXPECT_EQ(r.multiplicity, q.multiplicity);
    for (int k = 0; k < D; ++k)
      if (k != r.dir) {
        EXPECT_EQ(r.extent.lo[k], q.extent.lo[k]);
        EXPECT_EQ(r.extent.hi[k], q.extent.hi[k]);
      }
  }
  std::mt19937 rng(3);
  std::vector<double> p(static_cast<std::size_t>(a.dim())), s(p.size());
  for (int n = 0; n < 100; ++n) {
    Param<D> u;
    for (int k = 0; k < D; ++k) u[k] = std::uniform_real_distribution<double>(a.domain().lo[k], a.domain().hi[k])(rng);
    a.eval(u, p.data());
    b.eval(u, s.data());
    EXPECT_EQ(p, s);
  }
}

void expect_json_error(const json& j, const std::string& fragment) {
  try {
    io::lr_spline_from_json(j, "f.json");
    ADD_FAILURE() << "no error for " << j.dump();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("f.json: ", 0), 0u) << m;
    EXPECT_NE(m.find(fragment), std::string::npos) << m;
  }
}

}  // namespace

TEST(LrJson, SchemaOfAHandWrittenBilinearSquare) {
  // The unit square, bilinear, as the identity map, written by hand in the documented schema.
  const json j = json::parse(R"({"trivar": 1, "kind": "lr_surface", "dim": 2, "rational": false, "degrees": [1, 1],
    "basis": [{"knots": [[0, 0, 1], [0, 0, 1]], "gamma": 1, "coef": [0, 0]},
              {"knots": [[0, 1, 1], [0, 0, 1]], "gamma": 1, "coef": [1, 0]},
              {"knots": [[0, 0, 1], [0, 1, 1]], "gamma": 1, "coef": [0, 1]},
              {"knots": [[0, 1, 1], [0, 1, 1]], "gamma": 1, "coef": [1, 1]}],
    "mesh": [{"dir": 0, "value": 0, "lo": [0, 0], "hi": [0, 1], "multiplicity": 2},
             {"dir": 0, "value": 1, "lo": [1, 0], "hi": [1, 1], "multiplicity": 2},
             {"dir": 1, "value": 0, "lo": [0, 0], "hi": [1, 0], "multiplicity": 2},
             {"dir": 1, "value": 1, "lo": [0, 1], "hi": [1, 1], "multiplicity": 2}]})");
  const LRSpline<2> s = std::get<LRSpline<2>>(io::lr_spline_from_json(j, "sq.json"));
  double x[2];
  for (double u : {0.0, 0.3, 1.0})
    for (double v : {0.0, 0.7, 1.0}) {
      s.eval({u, v}, x);
      EXPECT_NEAR(x[0], u, 1e-15);
      EXPECT_NEAR(x[1], v, 1e-15);
    }
  // Written back, the object is the same JSON (same order of B-splines and rectangles, numbers as written).
  const json back = io::to_json(AnyLRSpline(s));
  EXPECT_EQ(back["basis"], j["basis"]);
  EXPECT_EQ(back["kind"], "lr_surface");
}

TEST(LrJson, FilesRoundTripBitExactly) {
  test::TempDir dir;
  const LRSpline<2> s = refined_json_case<2>(true, 1);
  const LRSpline<3> v = refined_json_case<3>(false, 2), w = refined_json_case<3>(true, 3);
  io::write_lr_json(dir.file("one.json"), {AnyLRSpline(w)});
  io::write_lr_json(dir.file("three.json"), {AnyLRSpline(s), AnyLRSpline(v), AnyLRSpline(w)});
  const auto one = io::read_lr_json(dir.file("one.json"));
  ASSERT_EQ(one.size(), 1u);
  expect_bit_identical(w, std::get<LRSpline<3>>(one[0]));
  const auto three = io::read_lr_json(dir.file("three.json"));
  ASSERT_EQ(three.size(), 3u);
  expect_bit_identical(s, std::get<LRSpline<2>>(three[0]));
  expect_bit_identical(v, std::get<LRSpline<3>>(three[1]));
  expect_bit_identical(w, std::get<LRSpline<3>>(three[2]));
  EXPECT_THROW(io::write_lr_json(dir.file("none.json"), {}), Error);
  EXPECT_EQ(dir.entries(), 2);
}

TEST(LrJson, ErrorsNameTheJsonPath) {
  const json good = io::to_json(AnyLRSpline(refined_json_case<2>(false, 4)));
  json j = good;
  j["basis"][1]["knots"][0][2] = "x";
  expect_json_error(j, "basis[1].knots[0][2]: expected a number, got string");
  j = good;
  j["basis"][2]["knots"][1].push_back(1.0);
  expect_json_error(j, "basis[2].knots[1]: expected 5 entries, got 6");
  j = good;
  j["basis"][0]["coef"].push_back(1.0);
  expect_json_error(j, "basis[0].coef: expected 2 entries, got 3");
  j = good;
  j["basis"][0]["color"] = 1;
  expect_json_error(j, "basis[0]: unexpected key \"color\"");
  j = good;
  j["mesh"][3]["multiplicity"] = 0;
  expect_json_error(j, "mesh[3].multiplicity: expected an integer in [1, 65], got 0");
  j = good;
  j["mesh"][0]["lo"][static_cast<std::size_t>(j["mesh"][0]["dir"].get<int>())] = 0.123;
  expect_json_error(j, "mesh[0]: lo and hi must equal");
  j = good;
  j["kind"] = "surface";
  expect_json_error(j, "kind: expected \"lr_surface\" or \"lr_volume\"");
  j = good;
  j.erase("mesh");
  expect_json_error(j, "missing key \"mesh\"");
  j = good;
  j["basis"][0]["gamma"] = 0.0;  // rejected by the LRSpline constructor, after the file name
  expect_json_error(j, "f.json: ");
  // One B-spline deleted: the rest no longer sums to one on the elements of its support.
  j = good;
  j["basis"].erase(7);
  expect_json_error(j, "do not sum to one on element [");
}

TEST(LrJson, DocumentLevelErrors) {
  test::TempDir dir;
  std::ofstream(dir.file("bad.json")) << R"({"trivar": 1, "objects": []})";
  try {
    io::read_lr_json(dir.file("bad.json"));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("objects: expected a non-empty array"), std::string::npos) << e.what();
  }
  std::ofstream(dir.file("syntax.json")) << "{\"trivar\": 1,";
  EXPECT_THROW(io::read_lr_json(dir.file("syntax.json")), Error);
}
