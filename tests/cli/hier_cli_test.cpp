// Hierarchical splines on the command line through the outputs LR splines have: `solve --adaptive --space thb`
// writes the final mesh and solution as .vtu, `convert` takes a G+Smo THB file to .vtu and STEP.
#include "cli/cli_fixture.hpp"
#include "support/vtu_arrays.hpp"

using namespace cli_test;

TEST_F(Cli, AdaptiveThbWritesMeshAndSolution) {
  const Result r = ok("solve poisson --problem l-shape --adaptive --space thb --steps 2 --out run");
  for (const char* f : {"run/convergence.csv", "run/convergence.svg", "run/mesh.vtu", "run/solution.vtu"})
    EXPECT_TRUE(exists(f)) << f << "\n" << r.out;
  const trivar::test::VtuPiece v = trivar::test::read_vtu((work_ / "run/solution.vtu").string());
  // One Bezier cell per leaf of the final mesh, the solution and the per-element errors attached.
  const std::size_t at = r.out.find("step 1: dofs");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::size_t e = r.out.find("elements ", at);
  EXPECT_EQ(v.cells, std::stoll(r.out.substr(e + 9)));
  for (const char* a : {"u", "estimate", "error_l2", "error_h1", "support"}) EXPECT_TRUE(v.arrays.count(a)) << a;
}

TEST_F(Cli, ConvertsAGsmoThbFileToVtuAndStep) {
  const std::string in = std::string(TRIVAR_TEST_DATA) + "/gismo/thb_simple_leaf_boxes.xml";
  ok("convert " + in + " simple.vtu");
  EXPECT_EQ(trivar::test::read_vtu((work_ / "simple.vtu").string()).cells, 55);  // G+Smo's element count for this hierarchy
  const Result s = ok("convert " + in + " simple.stp");
  EXPECT_NE(s.out.find("1 hierarchical object"), std::string::npos) << s.out;
  EXPECT_NE(slurp(work_ / "simple.stp").find(".HIERARCHICAL_B_SPLINE."), std::string::npos);
}
