// trivar slice on graded primitives: file layout, manifest, statistics against the analytic volume, thread
// independence and clean failures.
#include <numbers>

#include "cli/cli_fixture.hpp"

using namespace cli_test;

namespace {

std::vector<std::string> layer_files(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

class SliceCli : public Cli {};

TEST_F(SliceCli, GradedBallSlicesToPalettePngsWithAManifest) {
  ok("make ball --radius 2 --materials 2 -o ball.json");
  const Result r = ok("slice ball.json --out slices --layer 0.25 --dpi 127");
  const auto m = nlohmann::json::parse(slurp(work_ / "slices" / "manifest.json"));
  // The summary line reports the manifest's counts: "layers L, pixels P, inside pixels I, ...".
  const auto summary = [&](const std::string& label) {
    const std::size_t at = r.out.find(", " + label + " ");
    EXPECT_NE(at, std::string::npos) << label << "\n" << r.out;
    return at == std::string::npos ? -1.0 : std::stod(r.out.substr(at + label.size() + 3));
  };
  EXPECT_EQ(numbers_after(r.out, "layers").at(0), m.at("layers").get<double>());
  EXPECT_EQ(summary("pixels"), m.at("statistics").at("pixels").get<double>());
  EXPECT_EQ(summary("inside pixels"), m.at("statistics").at("inside_pixels").get<double>());
  EXPECT_EQ(numbers_after(r.out, "output: slices (").at(0), m.at("layers").get<double>());
  const int layers = m.at("layers").get<int>();
  const auto names = layer_files(work_ / "slices");
  ASSERT_EQ(names.size(), static_cast<std::size_t>(layers) + 2);  // the layers, the manifest and the file list
  EXPECT_EQ(names.front(), ".trivar-files");
  EXPECT_EQ(names[1], "layer_00000.png");
  EXPECT_EQ(m.at("materials").size(), 2u);
  EXPECT_EQ(m.at("materials")[1].at("palette_index"), 2);
  // 127 dpi: 0.2 mm pixels; inside pixels times the voxel volume approximate the ball.
  const double voxel = 0.2 * 0.2 * 0.25;
  const double inside = m.at("statistics").at("inside_pixels").get<double>();
  const double ball = 4.0 / 3.0 * std::numbers::pi * 8;
  EXPECT_NEAR(inside * voxel, ball, 0.03 * ball);
  // Dithering keeps the pixel count: every inside pixel gets exactly one material.
  EXPECT_EQ(m.at("materials")[0].at("pixels").get<long long>() + m.at("materials")[1].at("pixels").get<long long>(),
            m.at("statistics").at("inside_pixels").get<long long>());
  EXPECT_LT(m.at("statistics").at("max_residual").get<double>(), 1e-6 * 25.4 / 600);  // a millionth of a pixel
}

TEST_F(SliceCli, ThreadCountDoesNotChangeTheFiles) {
  ok("make cylinder --radius 1 --height 0.5 --materials 3 --blend axial -o cyl.json");
  ok("--threads 1 slice cyl.json --out one --layer 0.1 --dpi 100x50 --mode per-material");
  ok("--threads 2 slice cyl.json --out two --layer 0.1 --dpi 100x50 --mode per-material");
  const auto a = layer_files(work_ / "one"), b = layer_files(work_ / "two");
  ASSERT_EQ(a, b);
  EXPECT_NE(std::find(a.begin(), a.end(), "layer_00000_M3.png"), a.end());
  for (const std::string& f : a) {
    if (f == "manifest.json") continue;
    EXPECT_EQ(slurp(work_ / "one" / f), slurp(work_ / "two" / f)) << f;
  }
  ok("slice cyl.json --out ordered --layer 0.25 --dpi 100 --dither ordered");
}

TEST_F(SliceCli, BadParametersFailCleanly) {
  ok("make ball --materials 2 -o ball.json");
  ok("make ball -o plain.json");
  fails("slice ball.json --out s --dpi 0");
  fails("slice ball.json --out s --dpi 600x");
  fails("slice ball.json --out s --z-range 1 1");
  fails("slice ball.json --out s --z-range 5 6");
  fails("slice plain.json --out s");
  fails("slice ball.json --out s --layer 0", 2);
  fails("slice ball.json --out s --mode stripes", 2);
}
