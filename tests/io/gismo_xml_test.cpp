#include "trivar/io/gismo_xml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "trivar/core/error.hpp"

using namespace trivar;
using namespace trivar::io;

namespace {

const std::string kData = std::string(TRIVAR_TEST_DATA) + "/gismo/";

template <int D>
TensorSpline<D> generic(int p, int n, int dim, unsigned seed) {
  std::array<KnotVector, D> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(p, n);
  int count = 1;
  for (const auto& k : kv) count *= k.size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(-1, 1);
  std::vector<double> c(static_cast<std::size_t>(count) * dim);
  for (auto& v : c) v = x(rng);
  return TensorSpline<D>(kv, dim, false, c);
}

template <int D>
HierarchicalSpline<D> refined(HierarchicalBasis basis, unsigned seed) {
  HierarchicalSpline<D> h(generic<D>(2, 3, 3, seed), basis);
  std::mt19937 rng(seed);
  for (int step = 0; step < 3; ++step) {
    std::uniform_int_distribution<int> pick(0, h.space().num_elements() - 1);
    std::vector<int> marked{0, pick(rng), pick(rng)};
    h.refine_elements(marked);
  }
  return h;
}

// The one-line message of parsing `text`, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_gismo_xml(text, "bad.xml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string thb_text(const std::string& boxes, const std::string& coefs, int dim = 1) {
  return R"(<xml><Geometry type="THBSpline2"><Basis type="THBSplineBasis2"><Basis type="TensorBSplineBasis2">
<Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 0.25 0.5 0.75 1 1</KnotVector></Basis>
<Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 0.25 0.5 0.75 1 1</KnotVector></Basis>
</Basis>)" + boxes + "</Basis><coefs geoDim=\"" + std::to_string(dim) + "\">" + coefs + "</coefs></Geometry></xml>";
}

}  // namespace

TEST(GismoXml, ReadsATensorBSplineSurface) {
  const auto g = read_gismo_xml(kData + "bilinear_patch.xml");
  ASSERT_EQ(g.size(), 1u);
  const auto& s = std::get<TensorSpline<2>>(g[0]);
  double x[3];
  for (double u : {0.0, 0.3, 0.77, 1.0})
    for (double v : {0.0, 0.6, 1.0}) {
      s.eval({u, v}, x);
      EXPECT_NEAR(x[0], u, 1e-15);
      EXPECT_NEAR(x[1], v, 1e-15);
      EXPECT_NEAR(x[2], u * v + 0.1 * u, 1e-15);
    }
}

TEST(GismoXml, ReadsAnExactNurbsAnnulus) {
  const auto g = read_gismo_xml(kData + "quarter_annulus_nurbs.xml");
  const auto& s = std::get<TensorSpline<2>>(g[0]);
  ASSERT_TRUE(s.is_rational());
  double x[2];
  for (double u = 0; u <= 1; u += 0.125)
    for (double v : {0.0, 0.25, 1.0}) {
      s.eval({u, v}, x);
      EXPECT_NEAR(std::hypot(x[0], x[1]), 1 + v, 1e-14);
    }
  // Written and read back: the same homogeneous coefficients.
  const auto back = parse_gismo_xml(gismo_xml_text(g), "back.xml");
  const auto& t = std::get<TensorSpline<2>>(back[0]);
  for (std::size_t i = 0; i < s.coefs().size(); ++i) EXPECT_NEAR(t.coefs()[i], s.coefs()[i], 1e-15);
}

TEST(GismoXml, HierarchicalSplinesRoundTrip) {
  std::vector<GismoGeometry> all{refined<2>(HierarchicalBasis::thb, 1), refined<2>(HierarchicalBasis::hb, 2),
                                 refined<3>(HierarchicalBasis::thb, 3), generic<3>(3, 2, 3, 4)};
  const std::string text = gismo_xml_text(all);
  EXPECT_EQ(text.find("<MultiPatch"), std::string::npos);  // mixed dimensions: no multipatch node
  const auto back = parse_gismo_xml(text, "round.xml");
  ASSERT_EQ(back.size(), all.size());
  auto same = [](const auto& a, const auto& b) {
    EXPECT_EQ(a.space().num_basis(), b.space().num_basis());
    EXPECT_EQ(a.space().num_elements(), b.space().num_elements());
    EXPECT_EQ(a.space().basis(), b.space().basis());
    ASSERT_EQ(a.coefs().size(), b.coefs().size());
    for (std::size_t i = 0; i < a.coefs().size(); ++i) EXPECT_EQ(a.coefs()[i], b.coefs()[i]);
  };
  same(std::get<HierarchicalSpline<2>>(all[0]), std::get<HierarchicalSpline<2>>(back[0]));
  same(std::get<HierarchicalSpline<2>>(all[1]), std::get<HierarchicalSpline<2>>(back[1]));
  same(std::get<HierarchicalSpline<3>>(all[2]), std::get<HierarchicalSpline<3>>(back[2]));
  EXPECT_EQ(std::get<TensorSpline<3>>(all[3]).coefs()[5], std::get<TensorSpline<3>>(back[3]).coefs()[5]);
  // A two-patch surface file gets a MultiPatch node listing both.
  const std::string two = gismo_xml_text({all[0], all[1]});
  EXPECT_NE(two.find("<patches type=\"id_range\">0 1</patches>"), std::string::npos);
}

TEST(GismoXml, ReadsAHandWrittenTHBIdentity) {
  // Coefficients at the Greville points of each function's level: THB splines preserve the coefficients of
  // the level representation, so the file is the identity map (an independent check of reading and truncation).
  const auto g = read_gismo_xml(kData + "thb_identity_corner.xml");
  const auto& h = std::get<HierarchicalSpline<2>>(g[0]);
  EXPECT_EQ(h.space().num_basis(), 37);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0, 1);
  double x[2];
  for (int i = 0; i < 200; ++i) {
    const Param<2> u{U(rng), U(rng)};
    h.eval(u, x);
    EXPECT_NEAR(x[0], u[0], 1e-15);
    EXPECT_NEAR(x[1], u[1], 1e-15);
  }
}

TEST(GismoXml, ReadsAlignedBoxes) {
  // Bilinear, 4 x 4 level-0 cells; the level-1 box is level-1 cells [0, 4)^2 = level-0 cells [0, 2)^2: the
  // level-0 functions with support in [0, 1/2]^2 (t_{i+2} <= 1/2: 2 x 2) leave, the level-1 ones there
  // (t_{i+2} <= 1/2: 4 x 4) join: 25 - 4 + 16 functions, 16 - 4 + 16 elements.
  std::string coefs;
  for (int i = 0; i < 37; ++i) coefs += std::to_string(i) + " ";
  const auto g = parse_gismo_xml(thb_text(R"(<box level="1">0 0 4 4</box>)", coefs), "aligned.xml");
  const auto& h = std::get<HierarchicalSpline<2>>(g[0]);
  EXPECT_EQ(h.space().num_basis(), 37);
  EXPECT_EQ(h.space().num_elements(), 28);
  EXPECT_EQ(h.space().num_levels(), 2);
  EXPECT_EQ(h.coefs()[36], 36.0);
}

// The coefficients of the THB identity map of a bilinear space on 4 x 4 cells: each function's Greville point
// in its level (level-l knots i / (4 2^l)).
std::string bilinear_identity(const HierarchicalSpace<2>& s) {
  std::string out;
  for (int id = 0; id < s.num_basis(); ++id) {
    const HierarchicalFunction<2> f = s.function(id);
    for (int k = 0; k < 2; ++k) out += std::to_string(f.index[k] / double(4 << f.level)) + " ";
  }
  return out;
}

void expect_identity(const HierarchicalSpline<2>& h, int points) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  double x[2];
  for (int i = 0; i < points; ++i) {
    const Param<2> u{U(rng), U(rng)};
    h.eval(u, x);
    ASSERT_NEAR(x[0], u[0], 1e-14);
    ASSERT_NEAR(x[1], u[1], 1e-14);
  }
}

TEST(GismoXml, ReadsTheLeafBoxesGsmoWrites) {
  // G+Smo's own test of this hierarchy (its MATLAB interface test): 55 functions, 55 elements, and at (1/2, 1/2)
  // the non-zero functions are 50, 51, 54, 55 (1-based), each 1/4.
  const auto g = read_gismo_xml(kData + "thb_simple_leaf_boxes.xml");
  const auto& h = std::get<HierarchicalSpline<2>>(g[0]);
  EXPECT_EQ(h.space().num_basis(), 55);
  EXPECT_EQ(h.space().num_elements(), 55);
  std::vector<int> ids;
  std::vector<double> values;
  h.space().eval_basis({0.5, 0.5}, 0, ids, values);
  std::vector<int> nonzero;
  for (std::size_t r = 0; r < ids.size(); ++r)
    if (std::abs(values[r]) > 1e-15) {
      nonzero.push_back(ids[r]);
      EXPECT_NEAR(values[r], 0.25, 1e-15);
    }
  EXPECT_EQ(nonzero, (std::vector<int>{49, 50, 53, 54}));
  expect_identity(h, 300);
  // The same hierarchy given as G+Smo's input file gives it (overlapping boxes of levels 1 and 2).
  std::string boxes = R"(<box level="1">2 2 6 6</box><box level="2">4 4 10 10</box>)";
  std::string text = read_text(kData + "thb_simple_leaf_boxes.xml");
  const std::size_t a = text.find("<box"), b = text.rfind("</box>") + 6;
  text.replace(a, b - a, boxes);
  const auto other = parse_gismo_xml(text, "simple.xml");
  const auto& same = std::get<HierarchicalSpline<2>>(other[0]);
  EXPECT_EQ(same.space().num_basis(), 55);
  EXPECT_EQ(same.space().num_elements(), 55);
  EXPECT_TRUE(std::ranges::equal(same.coefs(), h.coefs()));
}

TEST(GismoXml, ReadsDomainsCuttingCoarserCells) {
  // Bilinear, 4 x 4 cells. Level-1 box [3, 8)^2 cuts level-0 cell 1; the level-2 box [7, 12)^2 cuts level-1
  // cell 3. Counted by hand from the definitions (bilinear function i has support cells [i - 1, i + 1), clipped
  // to the domain): level 0 loses the functions with support in the covered cells [2, 4)^2 (indices 3, 4):
  // 25 - 4; level 1 has the functions inside [3, 8)^2 (indices 4..8) less the one inside the covered level-1
  // cells [4, 6)^2 (index 5): 25 - 1; level 2 has those inside [7, 12)^2 (indices 8..11): 16; 61 functions.
  // Elements: 16 - 9 split level-0 cells, 36 - 9 split level-1 cells, 36 of level 2: 70.
  const std::string boxes = R"(<box level="1">3 3 8 8</box><box level="2">7 7 12 12</box>)";
  auto space_of = [&](const std::string& coefs, int dim) { return parse_gismo_xml(thb_text(boxes, coefs, dim), "cut.xml"); };
  std::string ones;
  for (int i = 0; i < 61; ++i) ones += "1 ";
  const auto read = space_of(ones, 1);
  const auto& unit = std::get<HierarchicalSpline<2>>(read[0]);
  const HierarchicalSpace<2>& s = unit.space();
  EXPECT_EQ(s.num_basis(0), 21);
  EXPECT_EQ(s.num_basis(1), 24);
  EXPECT_EQ(s.num_basis(2), 16);
  EXPECT_EQ(s.num_elements(), 70);
  // Partition of unity and non-negativity, every function non-zero somewhere.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<int> ids;
  std::vector<double> values;
  std::vector<bool> seen(61, false);
  for (int i = 0; i < 2000; ++i) {
    s.eval_basis({U(rng), U(rng)}, 0, ids, values);
    double sum = 0;
    for (std::size_t r = 0; r < ids.size(); ++r) {
      EXPECT_GE(values[r], -1e-15);
      sum += values[r];
      if (values[r] > 1e-12) seen[static_cast<std::size_t>(ids[r])] = true;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 61);
  // The identity map from Greville coefficients (coefficient preservation of THB splines).
  const auto g = space_of(bilinear_identity(s), 2);
  const auto& h = std::get<HierarchicalSpline<2>>(g[0]);
  expect_identity(h, 300);
  // Written back (boxes of the uncovered domain cells) and read again: the same space and coefficients.
  const auto back = parse_gismo_xml(gismo_xml_text(g), "back.xml");
  const auto& r = std::get<HierarchicalSpline<2>>(back[0]);
  EXPECT_EQ(r.space().num_basis(), 61);
  EXPECT_EQ(r.space().num_elements(), 70);
  EXPECT_TRUE(std::ranges::equal(r.coefs(), h.coefs()));
  // Refining the read spline keeps the map.
  HierarchicalSpline<2> refined = h;
  refined.refine_elements(std::vector<int>{0, 20, 69});
  expect_identity(refined, 300);
}

TEST(GismoXml, BadFilesGiveOneLineErrors) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"<xml><Geometry type=\"TensorBSpline2\"></xml>", "malformed XML"},
      {"<xml></xml>", "no <Geometry>"},
      {"<other/>", "root node must be <xml>"},
      {"<xml><Geometry type=\"TensorBSpline1\"><Basis/></Geometry></xml>", "unsupported geometry type 'TensorBSpline1'"},
      {R"(<xml><Geometry type="TensorBSpline2"><Basis type="TensorBSplineBasis2">
<Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
<Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
</Basis><coefs geoDim="2">0 0 1 0 0 1</coefs></Geometry></xml>)", "6 coefficient values, expected 4 functions x geoDim 2"},
      {R"(<xml><Geometry type="TensorBSpline2"><Basis type="TensorBSplineBasis2">
<Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 x 1</KnotVector></Basis>
<Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
</Basis><coefs geoDim="1">0 0 1 0</coefs></Geometry></xml>)", "'x' is not a number"},
      {R"(<xml><Geometry type="TensorBSpline2"><Basis type="TensorBSplineBasis2">
<Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 0.5</KnotVector></Basis>
<Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
</Basis><coefs geoDim="1">0 0 1 0</coefs></Geometry></xml>)", "non-decreasing"},
      {thb_text(R"(<box level="1">6 2 5 6</box>)", "0"), "lower <= upper"},
      {thb_text(R"(<box level="1">0 0 9 2</box>)", "0"), "box exceeds the 8 cells of level 1 in direction 0"},
      {thb_text(R"(<box level="1">0 0 2</box>)", "0"), "a box needs 4 indices"},
      {thb_text(R"(<box level="14">0 0 65536 65536</box>)", "0"), "the boxes cover more than 20000000 cells"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string msg = error_of(text);
    EXPECT_NE(msg.find(expected), std::string::npos) << "got: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind("gismo xml: bad.xml", 0), 0u) << msg;
  }
}
