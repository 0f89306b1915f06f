// Requests too large to run, limits on options, and choices that used to be silent: each refused by one line
// that names the request and its numbers, with no output left behind.
#include "cli/cli_fixture.hpp"

using namespace cli_test;

namespace {

// The single error line of a failed run, without the "trivar: error: " prefix.
std::string error_of(const Result& r) {
  const auto l = lines(r.err);
  EXPECT_EQ(l.size(), 1u) << r.err;
  const std::string prefix = "trivar: error: ";
  return l.empty() || l[0].rfind(prefix, 0) != 0 ? std::string() : l[0].substr(prefix.size());
}

}  // namespace

class GuardsCli : public Cli {};

TEST_F(GuardsCli, ThreadCountsAboveTheCapAreUsageErrors) {
  write("cube.json", unit_cube_json(false));
  fails("--threads 100000 eval cube.json 0.5 0.5 0.5", 2);
  EXPECT_NE(run("--threads 1025 eval cube.json 0.5 0.5 0.5").err.find("must be at most 1024, got 1025"),
            std::string::npos);
  // The cap itself is accepted, and the result does not depend on the count.
  EXPECT_EQ(numbers_after(ok("--threads 1024 eval cube.json 0.25 0.5 0.75").out, "S"),
            (std::vector<double>{0.25, 0.5, 0.75}));
}

TEST_F(GuardsCli, AHugeBoxIsRefusedBeforeAllocating) {
  // 2000 elements of degree 1 per direction: 2001^3 control points of 3 doubles, more than any test machine.
  const Result r = run("make box --elements 2000 2000 2000 -o box.json");
  EXPECT_EQ(r.code, 1);
  const std::string e = error_of(r);
  EXPECT_EQ(e.rfind("make box: --degree 1 1 1 --elements 2000 2000 2000 (8012006001 control points) would need ", 0), 0u)
      << e;
  // A huge degree is as huge a request: (1 + 1e9)^3 control points.
  EXPECT_EQ(error_of(run("make box --degree 1000000000 -o box.json"))
                .rfind("make box: --degree 1000000000 1000000000 1000000000 --elements 1 1 1 (1.000000003e+27 control points) would need ", 0),
            0u);
  EXPECT_FALSE(exists("box.json"));
  fails("make box --elements 2000 2000 2000 -o box.json");
}

TEST_F(GuardsCli, AZRangeOutsideTheModelNamesTheModelsExtent) {
  ok("make box --elements 1 --size 1 2 3 --model --materials 2 -o box.json");
  // The box spans z in [0, 3].
  const Result r = run("slice box.json --out s --z-range 10 20");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(error_of(r), "slice: --z-range 10 20 does not meet the model, whose z extent is [0, 3]");
  fails("slice box.json --out s --z-range -5 -1");
  fails("slice box.json --out s --z-range 3 4");
  // A range that meets the model slices only the layers inside it: z in [2.5, 4] at 0.5 mm: 3 layers.
  ok("slice box.json --out s --z-range 2.5 4 --layer 0.5 --dpi 25.4");
  EXPECT_EQ(nlohmann::json::parse(slurp(work_ / "s" / "manifest.json")).at("layers").get<int>(), 3);
}

TEST_F(GuardsCli, ASliceResolutionBeyondMemoryIsRefused) {
  ok("make box --elements 1 --size 100 --model --materials 2 -o box.json");
  const Result r = run("--threads 2 slice box.json --out s --dpi 20000x20000");
  EXPECT_EQ(r.code, 1);
  // 100 mm at 20000 dpi: 100 / 25.4 * 20000 = 78740.2 pixels, plus a pixel on each side.
  const std::string e = error_of(r);
  EXPECT_EQ(e.rfind("slice: 2 layers of 78743 x 78743 pixels at once (--dpi 20000x20000, --threads 2) would need ", 0),
            0u)
      << e;
  fails("--threads 2 slice box.json --out s --dpi 20000x20000");
}

TEST_F(GuardsCli, RunningOutOfMemoryIsOneLineNamingTheCommand) {
  // 201^3 control points: a few hundred MB as a JSON document, more than the 700 MB address space allowed here
  // leaves after the program, its libraries and thread stacks. The failure used to end in std::terminate
  // (exit 134) because nlohmann::json allocates while destroying a large array during the unwinding.
  const Result r = run_after("ulimit -v 700000; ", "make box --elements 200 200 200 -o big.json");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(error_of(r).rfind("make box: out of memory", 0), 0u) << r.err;
  EXPECT_TRUE(listing().empty()) << listing().front();
}
