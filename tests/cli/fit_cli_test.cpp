// trivar fit: terrain and volume fits end to end (every output format, the report, the pictures), and bad point
// files refused with one line and no output.
#include "cli/cli_fixture.hpp"

namespace cli_test {
namespace {

class FitCli : public Cli {
protected:
  // n x n grid of a hill with a ridge, "x y z" rows.
  std::string terrain(int n) const {
    std::ostringstream s;
    s << "x y z\n";
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = 10.0 * i / (n - 1), y = 5.0 * j / (n - 1);
        s << x << ' ' << y << ' ' << std::exp(-((x - 4) * (x - 4) + (y - 2) * (y - 2)) / 4) + 0.3 * std::exp(-std::abs(x - 7) * 3)
          << '\n';
      }
    return s.str();
  }
};

TEST_F(FitCli, TerrainToEveryFormatWithReportAndPictures) {
  write("hill.xyz", terrain(60));
  const Result r = ok("fit hill.xyz --relative-tolerance 0.005 -o hill.lr -o hill.g2 -o hill.json -o hill.vtu -o hill.stp "
                      "--report --report-json report.json --image hill.png --error-image error.png --image-width 200");
  EXPECT_NE(r.out.find("level   coefs elements"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tolerance reached"), std::string::npos) << r.out;
  for (const char* f : {"hill.lr", "hill.g2", "hill.json", "hill.vtu", "hill.stp", "hill.png", "error.png", "report.json"})
    EXPECT_TRUE(exists(f)) << f;
  const nlohmann::json rep = nlohmann::json::parse(slurp(work_ / "report.json"));
  EXPECT_TRUE(rep.at("converged").get<bool>());
  EXPECT_EQ(rep.at("points"), 3600);
  const nlohmann::json& last = rep.at("iterations").back();
  EXPECT_LE(last.at("max_error").get<double>(), rep.at("tolerance").get<double>());
  EXPECT_EQ(last.at("outside"), 0);
  // The surface is the graph (x, y, z): three control values, the points' box as domain.
  const nlohmann::json info = nlohmann::json::parse(ok("info hill.lr --json").out).at("objects").at(0);
  EXPECT_EQ(info.at("kind"), "lr_surface");
  EXPECT_EQ(info.at("dim"), 3);
  EXPECT_EQ(info.at("num_basis"), last.at("coefficients"));
  // The graph evaluates to x and y at (x, y).
  const Result e = ok("eval hill.lr 7.5 1.25");
  const std::vector<double> p = numbers_after(e.out, "S");
  ASSERT_GE(p.size(), 3u) << e.out;
  EXPECT_NEAR(p[0], 7.5, 1e-12);
  EXPECT_NEAR(p[1], 1.25, 1e-12);
  // The STEP file holds one locally refined surface.
  EXPECT_NE(slurp(work_ / "hill.stp").find("LOCALLY_REFINED_SPLINE_SURFACE"), std::string::npos);
}

TEST_F(FitCli, VolumeFieldFromFourColumns) {
  std::ostringstream s;
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) {
        const double x = i / 11.0, y = j / 11.0, z = k / 11.0;
        s << x << ',' << y << ',' << z << ',' << std::sin(3 * x) * y + z * z << '\n';
      }
  write("field.csv", s.str());
  const Result r = ok("fit field.csv --volume --tolerance 1e-3 -o field.lr");
  EXPECT_NE(r.out.find("LR volume"), std::string::npos) << r.out;
  const nlohmann::json info = nlohmann::json::parse(ok("info field.lr --json").out).at("objects").at(0);
  EXPECT_EQ(info.at("kind"), "lr_volume");
  EXPECT_EQ(info.at("dim"), 1);
}

TEST_F(FitCli, BadPointFilesAreOneLineErrors) {
  write("empty.xyz", "");
  fails("fit empty.xyz --tolerance 0.1 -o out.lr");
  write("nan.xyz", "0 0 1\n1 0 2\n0 1 nan\n1 1 3\n");
  fails("fit nan.xyz --tolerance 0.1 -o out.lr");
  write("two.xyz", "0 0 1\n1 0 2\n");
  fails("fit two.xyz --tolerance 0.1 -o out.lr");
  write("line.xyz", "0 0 1\n1 1 2\n2 2 3\n3 3 4\n4 4 5\n");
  fails("fit line.xyz --tolerance 0.1 -o out.lr");
  write("ragged.xyz", "0 0 1\n1 0\n");
  fails("fit ragged.xyz --tolerance 0.1 -o out.lr");
  write("ok.xyz", terrain(10));
  fails("fit ok.xyz -o out.lr");                                     // no tolerance
  fails("fit ok.xyz --tolerance 0.1 -o out.stl");                    // not an LR format
  fails("fit ok.xyz --tolerance 0.1 -o out.lr --image out.jpg");     // not a PNG
  fails("fit missing.xyz --tolerance 0.1 -o out.lr");
  const Result r = run("fit nan.xyz --tolerance 0.1 -o out.lr");
  EXPECT_NE(r.err.find("nan.xyz: line 3: 'nan' is not a finite number"), std::string::npos) << r.err;
  const Result l = run("fit line.xyz --tolerance 0.1 -o out.lr");
  EXPECT_NE(l.err.find("all points lie on a line"), std::string::npos) << l.err;
}

}  // namespace
}  // namespace cli_test

namespace cli_test {
namespace {

// The unit cube as a one-cell V-model of materials A and B, evenly mixed.
std::string even_cube() {
  nlohmann::json cell{{"geometry", nlohmann::json::parse(unit_cube_json(false))}};
  cell["geometry"].erase("trivar");
  cell["attributes"]["material"] = {{"kind", "constant"}, {"values", {0.5, 0.5}}};
  const nlohmann::json materials = {{{"name", "A"}, {"color", "#FF0000"}}, {{"name", "B"}, {"color", "#0000FF"}}};
  return nlohmann::json{{"trivar", 1}, {"kind", "vmodel"}, {"materials", materials}, {"cells", {cell}}}.dump();
}

TEST_F(FitCli, SampledFractionsBecomeTheCellsMaterialFieldAndSlice) {
  write("cube.json", even_cube());
  // Fraction of A = x^2 at 8^3 sample points (a quadratic: the fit reproduces it), B the rest.
  std::ostringstream s;
  s.precision(17);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const double x = i / 7.0, y = j / 7.0, z = k / 7.0;
        s << x << ' ' << y << ' ' << z << ' ' << x * x << ' ' << 1 - x * x << '\n';
      }
  s << "3 3 3 0.5 0.5\n";  // outside the cube: skipped
  write("samples.txt", s.str());
  const Result r = ok("fit samples.txt --volume --into cube.json --tolerance 1e-9 --smoothing 0 --initial-elements 2 -o graded.json");
  EXPECT_NE(r.out.find("512 samples in the cell, 1 outside"), std::string::npos) << r.out;
  const nlohmann::json cell = nlohmann::json::parse(slurp(work_ / "graded.json")).at("cells").at(0);
  EXPECT_EQ(cell.at("attributes").at("material").at("kind"), "field") << cell.dump();
  // Sliced: the share of A's pixels is the mean of x^2 over the cube, 1/3 (error diffusion keeps the mean).
  ok("slice graded.json --out slices --layer 0.25 --dpi 1270");
  const auto m = nlohmann::json::parse(slurp(work_ / "slices" / "manifest.json"));
  const double a = m.at("materials").at(0).at("pixels").get<double>(), b = m.at("materials").at(1).at("pixels").get<double>();
  EXPECT_NEAR(a / (a + b), 1.0 / 3.0, 0.02) << a << " " << b;

  // Three fractions per sample for a model of two materials, --into without --volume: one line, nothing written.
  write("three.txt", "0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n0 0 1 1 0 0\n1 1 1 0 1 0\n");
  const Result bad = run("fit three.txt --volume --into cube.json --tolerance 0.1 -o bad.json");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("3 fractions per sample but cube.json lists 2 materials"), std::string::npos) << bad.err;
  const Result flat = run("fit samples.txt --into cube.json --tolerance 0.1 -o bad.json");
  EXPECT_NE(flat.err.find("give --volume"), std::string::npos) << flat.err;
  EXPECT_FALSE(exists("bad.json"));
}

}  // namespace
}  // namespace cli_test
