// trivar solve --adaptive on a multi-block file: the L-shape as three blocks with T-joints in one .g2 file, refined
// adaptively inside its blocks (one line per step, the model matched again after every step), its outputs, and
// the refusals of what the multi-block loop does not take.
#include "cli/cli_fixture.hpp"

#include "trivar/iga/tensor_space.hpp"
#include "trivar/io/spline_file.hpp"

namespace cli_test {
namespace {

class MultiblockAdaptiveCli : public Cli {
protected:
  void SetUp() override {
    Cli::SetUp();
    // The left column [-1, 0] x [-1, 1] and two blocks on the upper half of its right side.
    trivar::io::write_spline_file((work_ / "l.g2").string(),
                                  {trivar::box_geometry<2>({-1, -1}, {0, 1}, 2, 3), trivar::box_geometry<2>({0, 0}, {1, 0.5}, 2, 2),
                                   trivar::box_geometry<2>({0, 0.5}, {1, 1}, 2, 4)});
  }
};

TEST_F(MultiblockAdaptiveCli, StepsRefineTheBlocksAndWriteTheirOutputs) {
  const Result r = ok("solve poisson l.g2 --adaptive --steps 4 --solver cholmod --out ad");
  EXPECT_NE(r.out.find("3 blocks, 3 interfaces (2 of them on part of a block side: T-joints)"), std::string::npos) << r.out;
  std::vector<int> dofs;
  std::vector<double> estimate;
  for (const std::string& line : lines(r.out))
    if (line.rfind("step ", 0) == 0) {
      dofs.push_back(std::stoi(line.substr(line.find("dofs ") + 5)));
      estimate.push_back(std::stod(line.substr(line.find("estimate ") + 9)));
    }
  ASSERT_EQ(dofs.size(), 4u) << r.out;
  for (std::size_t i = 1; i < dofs.size(); ++i) {
    EXPECT_GT(dofs[i], dofs[i - 1]);
    EXPECT_LT(estimate[i], estimate[i - 1]);
  }
  EXPECT_NE(r.out.find("final model: "), std::string::npos) << r.out;
  for (const char* f : {"ad/convergence.csv", "ad/convergence.svg", "ad/mesh.vtu", "ad/solution.vtu"}) EXPECT_TRUE(exists(f)) << f;
  fails("solve elasticity l.g2 --adaptive --out bad");
  fails("solve poisson l.g2 --adaptive --space thb --out bad");
  fails("solve poisson l.g2 --adaptive --beta 0 --out bad");
}

}  // namespace
}  // namespace cli_test
