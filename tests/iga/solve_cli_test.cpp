#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "cli/cli_fixture.hpp"
#include "support/vtu_arrays.hpp"

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
  EXPECT_TRUE(exists("result/convergence.svg"));
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
  EXPECT_TRUE(exists("ad/convergence.svg"));
  EXPECT_TRUE(exists("ad/mesh.vtu"));
  // The solution on the final LR mesh against the exact r^(2/3) sin(2 theta / 3): one Bezier quadrilateral
  // per element, evaluated here from VTK's point order (corners, edges, interior); the L2 error by 4 x 4 Gauss
  // points per cell agrees with the reported one to the rule's accuracy, and the cells tile the L-shape (area
  // 3, exact for the biquadratic map). Then the per-element errors and indicators (one value per cell): their
  // squares add up to the reported final values.
  const std::string line = cli_test::lines(r.out).back();
  ASSERT_EQ(line.rfind("step 2:", 0), 0u) << line;
  auto reported = [&line](const std::string& label) { return std::stod(line.substr(line.find(label) + label.size())); };
  const trivar::test::VtuPiece vtu = trivar::test::read_vtu((work_ / "ad/solution.vtu").string());
  const auto& x = vtu.arrays.at("Points");
  const auto& u = vtu.arrays.at("u");
  const auto& conn = vtu.arrays.at("connectivity");
  ASSERT_EQ(x.size(), 3 * u.size());
  ASSERT_EQ(conn.size(), 9u * static_cast<std::size_t>(vtu.cells));
  EXPECT_EQ(vtu.arrays.count("RationalWeights"), 0u);
  // VTK's biquadratic order: node (i, j) of the 3 x 3 Bernstein net at position order[j][i].
  const int order[3][3] = {{0, 4, 1}, {7, 8, 5}, {3, 6, 2}};
  auto b2 = [](int i, double t) { return i == 0 ? (1 - t) * (1 - t) : i == 1 ? 2 * t * (1 - t) : t * t; };
  auto db2 = [](int i, double t) { return i == 0 ? -2 * (1 - t) : i == 1 ? 2 - 4 * t : 2 * t; };
  const double gauss[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
  const double weight[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
  double area = 0, l2 = 0;
  for (long long c = 0; c < vtu.cells; ++c) {
    EXPECT_EQ(vtu.arrays.at("types")[static_cast<std::size_t>(c)], 77);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        double px = 0, py = 0, pu = 0, xs = 0, xt = 0, ys = 0, yt = 0;
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) {
            const auto q = static_cast<std::size_t>(conn[static_cast<std::size_t>(9 * c + order[j][i])]);
            const double B = b2(i, gauss[a]) * b2(j, gauss[b]);
            const double Bs = db2(i, gauss[a]) * b2(j, gauss[b]), Bt = b2(i, gauss[a]) * db2(j, gauss[b]);
            px += B * x[3 * q];
            py += B * x[3 * q + 1];
            pu += B * u[q];
            xs += Bs * x[3 * q];
            xt += Bt * x[3 * q];
            ys += Bs * x[3 * q + 1];
            yt += Bt * x[3 * q + 1];
          }
        double theta = std::atan2(py, px);
        if (theta < 0) theta += 2 * M_PI;
        const double e = pu - std::pow(std::hypot(px, py), 2.0 / 3) * std::sin(2 * theta / 3);
        const double dA = std::abs(xs * yt - xt * ys) * weight[a] * weight[b];  // the map reverses orientation
        area += dA;
        l2 += dA * e * e;
      }
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
  EXPECT_NEAR(std::sqrt(l2), reported("L2 error"), 0.1 * reported("L2 error"));
  for (const auto& [name, label] : {std::pair{"error_l2", "L2 error"}, std::pair{"error_h1", "H1 error"},
                                    std::pair{"estimate", "estimate"}}) {
    const auto& cells = vtu.arrays.at(name);
    EXPECT_EQ(cells.size(), static_cast<std::size_t>(vtu.cells)) << name;
    double sum = 0;
    for (double e : cells) sum += e * e;
    EXPECT_NEAR(std::sqrt(sum), reported(label), 1e-3 * reported(label)) << name;
  }
  fails("solve poisson --problem l-shape --adaptive --beta 0 --out x");
  fails("solve elasticity --problem lame-ring --adaptive --out x");
}

namespace {

// The cylinder's torsional mode of a shaft clamped at one end: omega^2 = (pi / (2 L))^2 G / rho, exact in 3-D
// elasticity for a circular section (plane sections rotate rigidly).
double torsion_omega2(double E, double nu, double rho, double L) {
  const double G = E / (2 * (1 + nu));
  return std::pow(M_PI / (2 * L), 2) * G / rho;
}

// The number after `label` on every line that has it (mode tables: one value per mode).
std::vector<double> values_after(const std::string& text, const std::string& label) {
  std::vector<double> v;
  for (const std::string& l : cli_test::lines(text)) {
    const std::size_t at = l.find(label);
    if (at != std::string::npos) v.push_back(std::stod(l.substr(at + label.size())));
  }
  return v;
}

// The printed omega^2 closest to `value`.
double closest(const std::vector<double>& values, double value) {
  double best = values.front();
  for (double v : values)
    if (std::abs(v - value) < std::abs(best - value)) best = v;
  return best;
}

}  // namespace

TEST_F(Cli, SolveOnAMultiCellModelWithCellMaterials) {
  ok("make cylinder --radius 0.5 --height 4 -o cyl.json");
  // Poisson on all five cells: one VTU piece per cell.
  ok("solve poisson cyl.json --degree 2 --refine 2 --out p");
  EXPECT_EQ(trivar::test::read_vtu_pieces((work_ / "p/solution.vtu").string()).size(), 5u);
  // Free vibration clamped at z = 0 (E and rho from the options); values are printed to 4 digits.
  const double exact = torsion_omega2(1000, 0.3, 1, 4);
  auto torsion = [&](const std::string& file, double expected) {
    const auto r = ok("solve modes " + file + " --degree 3 --refine 2 --modes 6 --clamp z- --youngs 1000");
    return closest(values_after(r.out, "omega^2 "), expected);
  };
  const auto r = ok("solve modes cyl.json --degree 3 --refine 2 --modes 6 --clamp z- --youngs 1000 --out m");
  EXPECT_NEAR(closest(values_after(r.out, "omega^2 "), exact), exact, 5e-4 * exact) << r.out;
  EXPECT_TRUE(exists("m/modes.vtu"));
  // Cell attributes override the options: E = 4000 (a constant) and rho = 2 (an expression) double omega^2;
  // ignoring either or both would give 4, 1/2 or 1 times.
  nlohmann::json model = nlohmann::json::parse(cli_test::slurp(work_ / "cyl.json"));
  for (auto& cell : model["cells"]) {
    cell["attributes"]["youngs_modulus"] = {{"kind", "constant"}, {"values", {4000}}};
    cell["attributes"]["density"] = {{"kind", "expression"}, {"space", "model"}, {"components", {"2 + 0 * z"}}};
  }
  write("graded.json", model.dump());
  EXPECT_NEAR(torsion("graded.json", 2 * exact), 2 * exact, 5e-4 * 2 * exact);
  model["cells"][2]["attributes"]["poisson_ratio"] = {{"kind", "constant"}, {"values", {0.5}}};
  write("bad.json", model.dump());
  fails("solve elasticity bad.json --clamp z- --out x");
  EXPECT_FALSE(exists("x"));
  fails("solve elasticity cyl.json --clamp q- --out x", 2);  // a usage error
  fails("solve elasticity cyl.json --clamp none --out x");
}

TEST_F(Cli, SolveElasticModesOfTheRollerCube) {
  const auto r =
      ok("solve modes --problem elastic-cube-modes --degree 3 --refine 4 --modes 8 --youngs 200 --density 7.8");
  const auto errors = values_after(r.out, "relative error ");
  ASSERT_EQ(errors.size(), 8u) << r.out;
  for (double e : errors) EXPECT_LT(e, 1e-4);
}

TEST_F(Cli, SolveAdaptiveOnHierarchicalSpaces) {
  // THB and HB span the same spaces: the same dofs, elements and errors at every step (printed to four
  // digits); one line per step, and the table with --out.
  const auto thb = ok("solve poisson --problem l-shape --degree 2 --refine 4 --adaptive --steps 4 --space thb "
                      "--solver cholmod --out thb");
  const auto hb = ok("solve poisson --problem l-shape --degree 2 --refine 4 --adaptive --steps 4 --space hb --solver cholmod");
  const auto t = cli_test::lines(thb.out), h = cli_test::lines(hb.out);
  ASSERT_EQ(t.size(), 4u) << thb.out;
  ASSERT_EQ(h.size(), 4u) << hb.out;
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(t[i].substr(0, t[i].find(", estimate")), h[i].substr(0, h[i].find(", estimate")));
  EXPECT_GT(cli_test::numbers_after(thb.out, "step 3: dofs").at(0), cli_test::numbers_after(thb.out, "step 0: dofs").at(0));
  EXPECT_TRUE(exists("thb/convergence.csv"));
  EXPECT_EQ(cli_test::lines(cli_test::slurp(work_ / "thb/convergence.csv")).size(), 5u);
  EXPECT_EQ(cli_test::lines(run("solve poisson --problem l-shape --space thb").err).at(0),
            "trivar: error: solve: --space is an option of --adaptive");
}
