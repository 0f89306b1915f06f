#include <gtest/gtest.h>

#include "cli/cli_fixture.hpp"

using cli_test::Cli;

TEST_F(Cli, SolvePoissonPrintsSummaryAndWritesFields) {
  const auto r = ok("solve poisson --problem sine-cube --degree 2 --refine 4 --study --out result");
  const auto v = cli_test::numbers_after(r.out, "dofs");
  ASSERT_FALSE(v.empty());
  EXPECT_NE(r.out.find("L2 error"), std::string::npos);
  EXPECT_NE(r.out.find("H1 error"), std::string::npos);
  EXPECT_NE(r.out.find("assembly"), std::string::npos);
  EXPECT_TRUE(exists("result/solution.vtu"));
  EXPECT_TRUE(exists("result/convergence.csv"));
  EXPECT_TRUE(exists("result/convergence.png"));
  const auto csv = cli_test::lines(cli_test::slurp(work_ / "result/convergence.csv"));
  EXPECT_EQ(csv.size(), 3u);  // header, 2 and 4 elements per direction
}

TEST_F(Cli, SolveModesOfTheCube) {
  const auto r = ok("solve modes --problem cube-modes --degree 2 --refine 4 --modes 4");
  const auto m1 = cli_test::numbers_after(r.out, "mode 1: lambda");
  ASSERT_FALSE(m1.empty());
  EXPECT_NEAR(m1[0], 3 * M_PI * M_PI, 0.01 * 3 * M_PI * M_PI);
}

TEST_F(Cli, SolveOnASplineFile) {
  write("cube.json", cli_test::unit_cube_json(false));
  const auto r = ok("solve poisson cube.json --degree 2 --refine 3 --out res");
  EXPECT_NE(r.out.find("dofs 27,"), std::string::npos) << r.out;
  EXPECT_TRUE(exists("res/solution.vtu"));
}

TEST_F(Cli, SolveRejectsBadInput) {
  fails("solve poisson --problem nope --out x");
  fails("solve poisson --problem sine-cube --degree 0 --out x");
  fails("solve poisson --problem sine-cube --refine 0 --out x");
  fails("solve modes --problem sine-cube --out x");
  fails("solve poisson missing.json --out x");
  fails("solve poisson");
  fails("solve poisson --problem sine-cube --solver lu --out x");
}

TEST_F(Cli, SolveElasticityWritesDisplacementAndVonMises) {
  const auto r = ok("solve elasticity --problem lame-ring --degree 2 --refine 4 --solver cholmod --out lame");
  EXPECT_NE(r.out.find("L2 error"), std::string::npos);
  const std::string vtu = cli_test::slurp(work_ / "lame/solution.vtu");
  EXPECT_NE(vtu.find("Name=\"displacement\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"von_mises\""), std::string::npos);
  fails("solve elasticity --problem sine-cube --out x");
  // Kirsch's plate: errors against the exact solution and the solution file.
  const auto k = ok("solve elasticity --problem plate-hole --degree 2 --refine 8 --solver cholmod --out plate");
  EXPECT_NE(k.out.find("H1 error"), std::string::npos) << k.out;
  EXPECT_TRUE(exists("plate/solution.vtu"));
}

TEST_F(Cli, SolveAdaptiveLShapeWritesTheTable) {
  const auto r = ok("solve poisson --problem l-shape --degree 2 --refine 4 --adaptive --steps 3 --beta 0.3 --out ad");
  EXPECT_NE(r.out.find("step 2: dofs"), std::string::npos) << r.out;
  EXPECT_EQ(cli_test::lines(cli_test::slurp(work_ / "ad/convergence.csv")).size(), 4u);
  EXPECT_TRUE(exists("ad/convergence.png"));
  EXPECT_TRUE(exists("ad/mesh.vtu"));
  fails("solve poisson --problem l-shape --adaptive --beta 0 --out x");
  fails("solve elasticity --problem lame-ring --adaptive --out x");
}
