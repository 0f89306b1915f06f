// LR splines on the command line: make box --lr, refine --strategy with --levels / --report, info with
// --check-independence, eval, and conversions between .lr, .json, .g2 and .vtu. Reference values: the counts of a
// uniform tensor refinement, and the tensor spline's own values (LR refinement leaves the geometry unchanged).
#include <regex>

#include "cli/cli_fixture.hpp"
#include "support/vtu_arrays.hpp"

using namespace cli_test;

namespace {

struct ReportLine {
  int level = 0, refined = 0, basis = 0, elements = 0, meshrects = 0;
};

// Parses --report output; every line must have exactly the documented form.
std::vector<ReportLine> report_lines(const std::string& out) {
  static const std::regex re(R"(level (\d+): refined (\d+), basis (\d+), elements (\d+), meshrects (\d+), seconds (\d+\.\d+))");
  std::vector<ReportLine> r;
  for (const std::string& l : lines(out)) {
    std::smatch m;
    EXPECT_TRUE(std::regex_match(l, m, re)) << "'" << l << "'";
    if (m.empty()) continue;
    r.push_back({std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]), std::stoi(m[4]), std::stoi(m[5])});
  }
  return r;
}

// The element lines of a .lr file ("k [D] : (lo..) x (hi..)    {ids}"), as (lo, hi) number lists, in file order.
std::vector<std::pair<std::vector<double>, std::vector<double>>> lr_elements(const std::string& text) {
  static const std::regex re(R"(^\d+ \[\d\] : \(([^)]*)\) x \(([^)]*)\).*)");
  const auto numbers = [](std::string t) {
    std::replace(t.begin(), t.end(), ',', ' ');
    std::istringstream in(t);
    std::vector<double> v;
    for (double x; in >> x;) v.push_back(x);
    return v;
  };
  std::vector<std::pair<std::vector<double>, std::vector<double>>> out;
  const std::string elements = text.substr(text.find("# Elements:"));
  for (const std::string& l : lines(elements)) {
    std::smatch m;
    if (std::regex_match(l, m, re)) out.emplace_back(numbers(m[1]), numbers(m[2]));
  }
  return out;
}

// The distinct values of the full-length mesh lines u = const of a 2D .lr file ("x x [0, 1] (m)"), as written.
std::vector<std::string> u_lines(const std::string& text) {
  static const std::regex re(R"(^([-0-9.e]+) x \[0, 1\] \(\d\)$)");
  std::vector<std::string> out;
  for (const std::string& l : lines(text)) {
    std::smatch m;
    if (std::regex_match(l, m, re)) out.push_back(m[1]);
  }
  return out;
}

}  // namespace

class LRCli : public Cli {
protected:
  nlohmann::json info(const std::string& args) const {
    return nlohmann::json::parse(ok("info --json " + args).out).at("objects").at(0);
  }
  // The value and first derivatives at one parameter, as `eval` prints them (one CLI run for every label).
  std::string evaluation(const std::string& file, const std::string& params) const {
    return ok("eval " + file + " " + params + " --derivs 1").out;
  }
  std::vector<double> eval(const std::string& file, const std::string& params, const std::string& label = "S") const {
    return numbers_after(evaluation(file, params), label);
  }
};

TEST_F(LRCli, StrategiesOnTheDiagonalGrowLevelByLevel) {
  ok("make box --lr --degree 2 --elements 4 4 -o box.lr");
  const nlohmann::json b = info("box.lr");
  EXPECT_EQ(b.at("kind"), "lr_surface");
  EXPECT_EQ(b.at("num_basis"), 36);     // (4 + 2)^2
  EXPECT_EQ(b.at("num_elements"), 16);
  EXPECT_EQ(b.at("num_meshrects"), 10);  // 5 lines per direction
  for (const char* strategy : {"fullspan", "minspan", "structured"}) {
    SCOPED_TRACE(strategy);
    const std::string out = std::string(strategy) + ".lr";
    const Result r = ok("refine box.lr -o " + out + " --strategy " + strategy + " --segment 0 0 1 1 --levels 2 --report");
    const std::vector<ReportLine> rep = report_lines(r.out);
    ASSERT_EQ(rep.size(), 2u) << r.out;
    int basis = 36, elements = 16, meshrects = 10;
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(rep[i].level, i + 1);
      // The diagonal of a uniform 4 x 4 mesh crosses the interiors of 4 elements; FULLSPAN halves each of
      // them in both directions, so the next level sees 8.
      if (std::string(strategy) == "fullspan") {
        EXPECT_EQ(rep[i].refined, 4 << i);
      }
      EXPECT_GT(rep[i].refined, 0);
      EXPECT_GT(rep[i].basis, basis);
      EXPECT_GT(rep[i].elements, elements);
      EXPECT_GT(rep[i].meshrects, meshrects);
      basis = rep[i].basis, elements = rep[i].elements, meshrects = rep[i].meshrects;
    }
    const nlohmann::json d = info(out);
    EXPECT_EQ(d.at("num_basis"), basis);
    EXPECT_EQ(d.at("num_elements"), elements);
    EXPECT_EQ(d.at("num_meshrects"), meshrects);
  }
  // A volume, selected by a box.
  ok("make box --lr --degree 2 --elements 2 2 2 -o vol.json");
  const std::vector<ReportLine> rep =
      report_lines(ok("refine vol.json -o vol.g2 --strategy structured --box 0 0 0 0.5 0.5 0.5 --levels 2 --report").out);
  ASSERT_EQ(rep.size(), 2u);
  EXPECT_GT(rep[0].basis, 64);
  EXPECT_GT(rep[1].basis, rep[0].basis);
  EXPECT_EQ(info("vol.g2").at("kind"), "lr_volume");
}

TEST_F(LRCli, FullspanOnEveryElementIsUniformRefinement) {
  ok("make box --lr --degree 2 --elements 4 4 -o box.json");
  const std::vector<ReportLine> rep =
      report_lines(ok("refine box.json -o fine.json --strategy fullspan --levels 2 --report").out);
  ASSERT_EQ(rep.size(), 2u);
  // Every element halved in both directions per level: 8 x 8 then 16 x 16 elements, (n + 2)^2 B-splines.
  EXPECT_EQ(rep[0].elements, 64);
  EXPECT_EQ(rep[0].basis, 100);
  EXPECT_EQ(rep[0].meshrects, 18);
  EXPECT_EQ(rep[1].elements, 256);
  EXPECT_EQ(rep[1].basis, 324);
  EXPECT_EQ(info("fine.json").at("gamma").at("min"), 1.0);
}

TEST_F(LRCli, RefinedTensorSplineEvaluatesAsTheTensor) {
  // A rational volume (exact quarter annulus) and a polynomial surface with non-uniform knots.
  ok("make revolve --radii 1 2 --height 1 --angle 90 --degree 2 --elements 2 -o rev.json");
  ok("refine rev.json -o rev.lr --strategy minspan --box 0 0 0 0.6 0.6 0.6 --levels 2 --multiplicity 2");
  ok("make box --degree 3 --elements 3 2 --size 2 1 -o plate.json");
  ok("refine plate.json --insert u:0.1 -o plate2.json");
  ok("refine plate2.json -o plate.g2 --strategy structured --segment 0 0 1 1 --levels 2");
  for (const char* p : {"0 0 0", "0.3 0.45 0.9", "0.55 0.125 0.25", "1 1 1", "0.7 0.3 0.05"}) {
    SCOPED_TRACE(p);
    const std::string want_out = evaluation("rev.json", p), got_out = evaluation("rev.lr", p);
    for (const char* label : {"S ", "S_u", "S_v", "S_w"}) {
      const std::vector<double> want = numbers_after(want_out, label), got = numbers_after(got_out, label);
      ASSERT_EQ(want.size(), 3u);
      ASSERT_EQ(got.size(), 3u);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(got[d], want[d], 1e-12 * (1 + std::abs(want[d]))) << label;
    }
  }
  for (const char* p : {"0 0", "0.2 0.7", "0.05 0.95", "1 1", "0.5 0.5"}) {
    SCOPED_TRACE(p);
    const std::string want_out = evaluation("plate2.json", p), got_out = evaluation("plate.g2", p);
    for (const char* label : {"S ", "S_u", "S_v"}) {
      const std::vector<double> want = numbers_after(want_out, label), got = numbers_after(got_out, label);
      ASSERT_EQ(want.size(), 3u);
      ASSERT_EQ(got.size(), 3u);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(got[d], want[d], 1e-12 * (1 + std::abs(want[d]))) << label;
    }
  }
  // The identity map of the plate: x = 2u, y = v exactly.
  const std::vector<double> x = eval("plate.g2", "0.25 0.75");
  EXPECT_NEAR(x.at(0), 0.5, 1e-14);
  EXPECT_NEAR(x.at(1), 0.75, 1e-14);
  fails("eval rev.lr 0.5 0.5 0.5 --derivs 2");
}

TEST_F(LRCli, RefinedSplinesAreIndependent) {
  ok("make box --lr --degree 3 --elements 4 4 -o box.lr");
  for (const char* strategy : {"fullspan", "structured"}) {
    SCOPED_TRACE(strategy);
    ok("refine box.lr -o r.lr --strategy " + std::string(strategy) + " --segment 0 0 1 1 --levels 3");
    const nlohmann::json d = info("r.lr --check-independence peeling");
    EXPECT_EQ(d.at("independence").at("status"), "independent");
    EXPECT_EQ(d.at("independence").at("unresolved"), 0);
    // These refinements go hand in hand: the B-splines are a basis of the spline space of the mesh.
    EXPECT_EQ(d.at("dimension_formula").at("dimension"), d.at("num_basis"));
    EXPECT_EQ(d.at("dimension_formula").at("status"), "independent");
    EXPECT_EQ(info("r.lr --check-independence exact").at("independence").at("status"), "independent");
    const std::string text = ok("info r.lr --check-independence peeling").out;
    EXPECT_NE(text.find("independence (peeling): independent"), std::string::npos) << text;
  }
  // MINSPAN along the diagonal is a known source of dependence: after four levels the exact rank test finds
  // relations among the cubic B-splines although there are fewer of them than the dimension of the spline
  // space (so the count cannot show it), and the rank cannot exceed that dimension.
  ok("refine box.lr -o m.lr --strategy minspan --segment 0 0 1 1 --levels 4");
  const nlohmann::json m = info("m.lr --check-independence exact");
  const long long basis = m.at("num_basis").get<long long>();
  const long long dim = m.at("dimension_formula").at("dimension").get<long long>();
  EXPECT_LT(basis, dim);
  EXPECT_EQ(m.at("dimension_formula").at("status"), "not_tested");
  EXPECT_EQ(m.at("independence").at("status"), "not_independent");
  EXPECT_GT(m.at("independence").at("nullity").get<long long>(), 0);
  EXPECT_LE(basis - m.at("independence").at("nullity").get<long long>(), dim);
  EXPECT_EQ(info("m.lr --check-independence peeling").at("independence").at("status"), "not_tested");
  EXPECT_FALSE(info("box.lr").contains("independence"));
}

TEST_F(LRCli, ConversionsRoundTrip) {
  ok("make revolve --radii 1 2 --angle 90 --degree 2 -o rev.json");
  ok("refine rev.json -o r.lr --strategy fullspan --segment 0 0 0 1 1 1 --levels 2");
  ok("convert r.lr r.json");
  ok("convert r.json r.g2");
  ok("convert r.g2 back.lr");
  ok("convert r.lr r.vtu --samples 2");
  ok("convert r.lr mesh.vtu --parametric-mesh");
  nlohmann::json a = nlohmann::json::parse(ok("info --json r.lr").out), b = nlohmann::json::parse(ok("info --json back.lr").out);
  a.erase("file");
  b.erase("file");
  EXPECT_EQ(a, b);
  // JSON is lossless; g2 stores gamma-scaled Cartesian coefficients, so values agree to rounding.
  ok("convert r.json again.lr");
  EXPECT_EQ(slurp(work_ / "r.lr"), slurp(work_ / "again.lr"));
  const std::string want_out = evaluation("r.lr", "0.3 0.6 0.9"), got_out = evaluation("back.lr", "0.3 0.6 0.9");
  for (const char* label : {"S ", "S_u", "S_w"}) {
    const std::vector<double> want = numbers_after(want_out, label), got = numbers_after(got_out, label);
    ASSERT_EQ(got.size(), 3u);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(got[d], want[d], 1e-14 * (1 + std::abs(want[d]))) << label;
  }
  EXPECT_NE(slurp(work_ / "r.vtu").find("<Piece"), std::string::npos);
  // Tensor to LR: implied by .lr, asked for by --lr otherwise; the values are the tensor's.
  ok("convert rev.json t.lr");
  ok("convert rev.json t.json --lr");
  EXPECT_EQ(info("t.json").at("kind"), "lr_volume");
  EXPECT_EQ(info("t.lr").at("num_basis"), 27);  // degree 2, one element per direction (one 90-degree arc)
  const std::vector<double> want = eval("rev.json", "0.3 0.6 0.9"), got = eval("t.lr", "0.3 0.6 0.9");
  ASSERT_EQ(got.size(), 3u);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(got[d], want[d], 1e-14 * (1 + std::abs(want[d])));
  EXPECT_EQ(info("rev.json").at("kind"), "volume");
}

TEST_F(LRCli, BadInputFailsWithOneLine) {
  ok("make box --lr --degree 2 --elements 4 4 -o box.lr");
  write("line.json", R"({"trivar": 1, "kind": "curve", "dim": 3, "rational": false, "degrees": [1],
                         "knots": [[0, 0, 1, 1]], "control_points": [[0, 0, 0], [0, 0, 2]]})");
  fails("refine box.lr -o o.lr --strategy widespan");
  fails("refine box.lr -o o.lr --strategy fullspan --elements 3 16");
  fails("refine box.lr -o o.lr --strategy structured --functions 36");
  fails("refine box.lr -o o.lr --strategy fullspan --segment 0 0 1");
  fails("refine box.lr -o o.lr --strategy fullspan --box 0 0 1 1 1 1");
  fails("refine box.lr -o o.lr --strategy fullspan --box 2 2 3 3");
  fails("refine box.lr -o o.lr --strategy structured --segment 0 0 1 0");  // along the boundary: no interior met
  fails("refine line.json -o o.lr --strategy fullspan");
  fails("refine box.lr -o o.lr --strategy fullspan --elements 1 --levels 2");
  fails("refine box.lr -o o.lr --strategy fullspan --elements 1 --segment 0 0 1 1");
  fails("refine box.lr -o o.lr --strategy fullspan --multiplicity 4");
  fails("refine box.lr -o o.stl --strategy fullspan");
  fails("refine box.lr -o o.lr --uniform 2");
  fails("refine box.lr -o o.lr --strategy fullspan --uniform 2");
  ok("make box --degree 2 --elements 2 2 -o t.json");
  fails("refine t.json -o o.json --uniform 2 --levels 2");
  fails("info t.json --check-independence peeling");
  fails("info box.lr --check-independence maybe", 2);
  fails("convert box.lr o.vtu --control-net");
  fails("convert box.lr o.vtu --bezier --samples 2", 2);
  fails("convert line.json o.lr");
  fails("make box --lr --model -o m.json");
  // A g2 file mixing LR and tensor objects is rejected (the first object decides the reader).
  ok("convert box.lr b.g2");
  ok("convert t.json t.g2");
  write("mixed.g2", slurp(work_ / "b.g2") + slurp(work_ / "t.g2"));
  fails("info mixed.g2");
  // The tensor options are unchanged.
  ok("refine t.json --uniform 2 -o t2.json");
  EXPECT_EQ(info("t2.json").at("num_elements"), 16);
}

// One element numbering: refine --elements k refines the element listed k-th in the .lr file trivar wrote,
// which is also the k-th cell of the VTK parametric mesh.
TEST_F(LRCli, ElementIdsAreTheOrderOfTheWrittenFile) {
  ok("make box --lr --degree 2 --elements 3 3 -o box.lr");
  ok("refine box.lr -o r.lr --strategy fullspan --elements 4");  // the centre: ids of split parts are appended
  const auto listed = lr_elements(slurp(work_ / "r.lr"));
  ASSERT_EQ(listed.size(), static_cast<std::size_t>(info("r.lr").at("num_elements").get<int>()));
  ok("convert r.lr mesh.vtu --parametric-mesh");
  const std::string vtu = (work_ / "mesh.vtu").string();
  const std::vector<double> points = trivar::test::vtu_array(vtu, ""),
                            conn = trivar::test::vtu_array(vtu, "connectivity"),
                            offsets = trivar::test::vtu_array(vtu, "offsets");
  ASSERT_EQ(offsets.size(), listed.size());
  for (int k : {0, static_cast<int>(listed.size()) / 2, static_cast<int>(listed.size()) - 1}) {
    SCOPED_TRACE(k);
    const auto& [lo, hi] = listed[static_cast<std::size_t>(k)];
    ASSERT_EQ(lo.size(), 2u);
    // Cell k of the parametric mesh spans the k-th listed element.
    double ulo = 1e9, uhi = -1e9, vlo = 1e9, vhi = -1e9;
    for (std::size_t c = k ? static_cast<std::size_t>(offsets[static_cast<std::size_t>(k) - 1]) : 0;
         c < static_cast<std::size_t>(offsets[static_cast<std::size_t>(k)]); ++c) {
      const auto p = static_cast<std::size_t>(conn[c]) * 3;
      ulo = std::min(ulo, points[p]), uhi = std::max(uhi, points[p]);
      vlo = std::min(vlo, points[p + 1]), vhi = std::max(vhi, points[p + 1]);
    }
    EXPECT_EQ(ulo, lo[0]);
    EXPECT_EQ(uhi, hi[0]);
    EXPECT_EQ(vlo, lo[1]);
    EXPECT_EQ(vhi, hi[1]);
    // FULLSPAN on element k halves it in both directions: its lower-left quarter becomes an element.
    ok("refine r.lr -o k.lr --strategy fullspan --elements " + std::to_string(k));
    const auto after = lr_elements(slurp(work_ / "k.lr"));
    const std::vector<double> qlo = lo, qhi = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2};
    EXPECT_TRUE(std::find(after.begin(), after.end(), std::make_pair(qlo, qhi)) != after.end());
  }
}

// The literature's cross (LRsplines' regression cases cross_1_5_m1 / _m2): a cubic mesh of 7 x 7 elements
// (10 x 10 B-splines), the lines v = 3.5 and u = 3.5 (in element units) over [1, 5], multiplicity 1 or 2.
// LRsplines gives 103 (m = 1) and 108 (m = 2) B-splines, 18 mesh lines and 58 elements (49 + 4 cut by the first
// line + 5 by the second, which crosses the first's halves), and the dimension formula must agree.
TEST_F(LRCli, RectanglesOfTheLiteraturesCross) {
  ok("make box --lr --degree 3 --elements 7 7 -o box.lr");
  const std::vector<std::string> t = u_lines(slurp(work_ / "box.lr"));
  ASSERT_EQ(t.size(), 8u);
  for (int m : {1, 2}) {
    SCOPED_TRACE(m);
    const std::string ms = std::to_string(m);
    ok("refine box.lr -o cross.lr --rectangle v 0.5 " + t[1] + " " + t[5] + " " + ms + " --rectangle u 0.5 " + t[1] +
       " " + t[5] + " " + ms);
    const nlohmann::json d = info("cross.lr --check-independence peeling");
    EXPECT_EQ(d.at("num_basis"), m == 1 ? 103 : 108);
    EXPECT_EQ(d.at("num_elements"), 58);
    EXPECT_EQ(d.at("num_meshrects"), 18);
    EXPECT_EQ(d.at("dimension_formula").at("dimension"), d.at("num_basis"));
    // The same rectangles from a file, with comments.
    write("cross.txt", "# dir value start stop mult\nv 0.5 " + t[1] + " " + t[5] + " " + ms + "\n\n0 0.5 " + t[1] +
                           " " + t[5] + " " + ms + "  # the vertical line\n");
    ok("refine box.lr -o file.lr --rectangles cross.txt");
    EXPECT_TRUE(slurp(work_ / "file.lr") == slurp(work_ / "cross.lr"));
  }
  // A volume: the plane piece w = 0.25 over u in [0, 1], v in [0, 0.5] cuts the 2 elements below it.
  ok("make box --lr --degree 2 --elements 2 2 2 -o vol.lr");
  ok("refine vol.lr -o v2.lr --rectangle w 0.25 0 1 0 0.5 1");
  EXPECT_EQ(info("v2.lr").at("num_elements"), 10);
  const std::vector<double> want = eval("vol.lr", "0.3 0.2 0.1"), got = eval("v2.lr", "0.3 0.2 0.1");
  ASSERT_EQ(got.size(), 3u);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(got[d], want[d], 1e-14);
  fails("refine vol.lr -o o.lr --rectangle w 0.25 0 1 0.5 1");         // 5 values for a volume
  fails("refine box.lr -o o.lr --rectangle x 0.5 0 1 1");              // no such direction
  fails("refine box.lr -o o.lr --rectangle u 0.5 0.3 0.6 1");          // ends inside elements
  fails("refine box.lr -o o.lr --rectangle u " + t[1] + " 0 1 1");     // already in the mesh
  fails("refine box.lr -o o.lr --rectangle u 0.5 0 1 1 --strategy fullspan");
  fails("refine box.lr -o o.lr --rectangles missing.txt");
}

// A request that would exhaust the memory is refused before it runs, naming the request.
TEST_F(LRCli, LevelsBeyondTheMemoryAreRefused) {
  ok("make box --lr --degree 2 --elements 2 2 -o box.lr");
  const Result r = run("refine box.lr -o o.lr --strategy fullspan --levels 1000");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("refine --levels 1000: level 1000 (more elements than a double can count, 4 times as many "
                       "per level)"), std::string::npos) << r.err;
  EXPECT_NE(run("refine box.lr -o o.lr --strategy fullspan --levels 30").err.find(
                "level 30 (about 4.61e+18 elements and "), std::string::npos);
  EXPECT_NE(r.err.find("would need"), std::string::npos) << r.err;
  EXPECT_FALSE(exists("o.lr"));
}
