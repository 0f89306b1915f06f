// `trivar info|eval|convert` on T-splines: the hand-written Bezier patch in TSM, converted to both STEP forms,
// JSON, .lr, meshes; malformed input fails with one line and writes nothing.
#include "cli_fixture.hpp"

namespace {

using namespace cli_test;

class TSplineCli : public Cli {
protected:
  void SetUp() override {
    Cli::SetUp();
    fs::copy_file(std::string(TRIVAR_TEST_DATA) + "/tsm/bezier_patch.tsm", work_ / "patch.tsm");
  }
};

// The patch's value at (0.3, 0.6), from the tensor NURBS the file was written from (tests/tspline).
TEST_F(TSplineCli, InfoEvalAndConversionsAgree) {
  const Result info = ok("info patch.tsm");
  EXPECT_NE(info.out.find("T-spline surface (TSM #TS0200), degrees 3 x 3"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("Part 42 type ANALYSIS_SUITABLE_T_SPLINE"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("100001uv x1"), std::string::npos) << info.out;  // reported, not silently dropped
  const auto p = numbers_after(ok("eval patch.tsm 0.3 0.6").out, "S");
  ASSERT_EQ(p.size(), 3u);
  for (const std::string out : {"patch.stp", "patch42.stp", "patch.json", "patch.lr"}) {
    const std::string form = out == std::string("patch42.stp") ? " --step-form part42" : "";
    ok("convert patch.tsm " + out + form);
    if (out == std::string("patch.lr")) continue;
    const auto q = numbers_after(ok("eval " + out + " 0.3 0.6").out, "S");
    ASSERT_EQ(q.size(), 3u);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(p[static_cast<std::size_t>(d)], q[static_cast<std::size_t>(d)], 1e-13) << out;
  }
  const auto lr = numbers_after(ok("eval patch.lr 0.3 0.6").out, "S");
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(p[static_cast<std::size_t>(d)], lr[static_cast<std::size_t>(d)], 1e-13);
  ok("convert patch.tsm patch.stl --tolerance 1e-3");
  ok("convert patch.tsm patch.obj");
  ok("convert patch.tsm patch.vtu");
  for (const char* f : {"patch.stl", "patch.obj", "patch.vtu"}) EXPECT_TRUE(fs::exists(work_ / f)) << f;
}

TEST_F(TSplineCli, MalformedTsmFailsWithOneLine) {
  std::string text = slurp(work_ / "patch.tsm");
  text.replace(text.find("l 3 1 4 0 0 0 0"), 15, "l 3 1 40 0 0 0 0");
  std::ofstream(work_ / "bad.tsm") << text;
  fails("info bad.tsm");
  fails("convert bad.tsm bad.stp");
  EXPECT_FALSE(fs::exists(work_ / "bad.stp"));
  fails("eval patch.tsm 2 0.5");  // outside the domain
  fails("convert patch.tsm patch.png");
}

}  // namespace
