// Runs the built `trivar` binary in a temporary directory and checks its outputs, exit codes and error
// messages. Reference values come from the models' closed forms (box: x = size * u; revolution: exact radii).
#include <numbers>

#include "cli/cli_fixture.hpp"

using namespace cli_test;

TEST_F(Cli, VersionAndHelp) {
  EXPECT_NE(ok("--version").out.find(TRIVAR_VERSION), std::string::npos);
  for (const char* sub : {"info", "eval", "convert", "refine", "elevate", "check", "make", "make box", "make revolve",
                          "invert", "demo"})
    EXPECT_NE(ok(std::string(sub) + " --help").out.find("Usage"), std::string::npos) << sub;
}

TEST_F(Cli, MakeBoxInfoShowsCounts) {
  ok("make box --degree 2 3 1 --elements 2 2 4 --size 2 1 3 -o box.json");
  const Result text = ok("info box.json");
  EXPECT_NE(text.out.find("control points: 4 x 5 x 5 = 100"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("elements: 2 x 2 x 4 = 16"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("degrees: 2 3 1"), std::string::npos) << text.out;
  const auto j = nlohmann::json::parse(ok("info box.json --json").out);
  const auto& o = j.at("objects").at(0);
  EXPECT_EQ(o.at("kind"), "volume");
  EXPECT_EQ(o.at("counts"), nlohmann::json({4, 5, 5}));
  EXPECT_EQ(o.at("num_elements"), 16);
  EXPECT_EQ(o.at("control_bounds").at("hi"), nlohmann::json({2.0, 1.0, 3.0}));

  ok("make box --degree 2 --elements 3 2 --size 4 1 -o plate.json");
  const auto p = nlohmann::json::parse(ok("info --json plate.json").out).at("objects").at(0);
  EXPECT_EQ(p.at("kind"), "surface");
  EXPECT_EQ(p.at("counts"), nlohmann::json({5, 4}));
}

TEST_F(Cli, EvalOfBoxIsScaledIdentity) {
  ok("make box --degree 3 --elements 3 --size 2 1 3 -o box.json");
  const Result r = ok("eval box.json 0.5 0.5 0.5 --derivs 1");
  const auto x = numbers_after(r.out, "S ");
  ASSERT_EQ(x.size(), 3u);
  EXPECT_NEAR(x[0], 1.0, 1e-14);
  EXPECT_NEAR(x[1], 0.5, 1e-14);
  EXPECT_NEAR(x[2], 1.5, 1e-14);
  const auto su = numbers_after(r.out, "S_u"), sw = numbers_after(r.out, "S_w");
  ASSERT_EQ(su.size(), 3u);
  EXPECT_NEAR(su[0], 2.0, 1e-13);
  EXPECT_NEAR(sw[2], 3.0, 1e-13);
  const auto y = numbers_after(ok("eval box.json 0.25 1 0").out, "S");
  ASSERT_EQ(y.size(), 3u);
  EXPECT_NEAR(y[0], 0.5, 1e-14);
  EXPECT_NEAR(y[1], 1.0, 1e-14);
  EXPECT_NEAR(y[2], 0.0, 1e-14);
}

TEST_F(Cli, RevolvedModelIsValidAndExact) {
  ok("make revolve --radii 1 2 --height 1.5 --angle 270 --degree 2 --elements 2 1 2 -o ring.json");
  const Result c = run("check ring.json");
  EXPECT_EQ(c.code, 0) << c.out << c.err;
  EXPECT_EQ(lines(c.out).at(0), "valid");
  EXPECT_EQ(lines(c.out).at(1).rfind("min det J >= ", 0), 0u);
  EXPECT_GT(numbers_after(c.out, "min det J >=").at(0), 0.0);
  // u along the axis, v radial, w angular: u = 0.5 is height 0.75, v = 0.25 radius 1.25, w = 1 angle 270 degrees.
  const auto x = numbers_after(ok("eval ring.json 0.5 0.25 1").out, "S");
  ASSERT_EQ(x.size(), 3u);
  EXPECT_NEAR(x[0], 0.0, 1e-12);
  EXPECT_NEAR(x[1], -1.25, 1e-12);
  EXPECT_NEAR(x[2], 0.75, 1e-12);
  for (const char* w : {"0.1", "0.37", "0.9"}) {
    const auto y = numbers_after(ok(std::string("eval ring.json 0.5 0.25 ") + w).out, "S");
    EXPECT_NEAR(std::hypot(y[0], y[1]), 1.25, 1e-12);
  }
}

TEST_F(Cli, CheckReportsInvalidModel) {
  write("mirrored.json", unit_cube_json(true));
  const Result r = run("check mirrored.json");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(lines(r.out).at(0), "invalid");
  EXPECT_NEAR(numbers_after(r.out, "min det J found").at(0), -1.0, 1e-12);
  write("cube.json", unit_cube_json(false));
  EXPECT_EQ(lines(ok("check cube.json").out).at(0), "valid");
}

TEST_F(Cli, RefineAndElevateKeepGeometry) {
  ok("make revolve --angle 200 --elements 2 -o ring.json");
  ok("refine ring.json --uniform 3 -o fine.json");
  ok("refine ring.json --insert u:0.3,0.7 --insert w:0.55 -o inserted.json");
  ok("elevate ring.json --by 1 -o elevated.json");
  const auto fine = nlohmann::json::parse(ok("info --json fine.json").out).at("objects").at(0);
  EXPECT_EQ(fine.at("elements"), nlohmann::json({6, 6, 9}));
  const auto ins = nlohmann::json::parse(ok("info --json inserted.json").out).at("objects").at(0);
  EXPECT_EQ(ins.at("elements"), nlohmann::json({4, 2, 4}));
  const auto ele = nlohmann::json::parse(ok("info --json elevated.json").out).at("objects").at(0);
  EXPECT_EQ(ele.at("degrees"), nlohmann::json({3, 3, 3}));
  for (const char* u : {"0.1 0.2 0.3", "0.77 0.5 0.91", "1 0 0.5"}) {
    const auto ref = numbers_after(ok(std::string("eval ring.json ") + u + " --derivs 1").out, "S_v");
    for (const char* f : {"fine.json", "inserted.json", "elevated.json"}) {
      const auto x = numbers_after(ok(std::string("eval ") + f + " " + u + " --derivs 1").out, "S_v");
      ASSERT_EQ(x.size(), 3u);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], ref[k], 1e-12) << f << " at " << u;
    }
  }
}

TEST_F(Cli, ConvertRoundTripIsIdentical) {
  ok("make revolve --angle 120 --degree 3 2 --elements 2 3 -o a.json");
  ok("convert a.json b.g2");
  ok("convert b.g2 c.json");
  EXPECT_EQ(slurp(work_ / "a.json"), slurp(work_ / "c.json"));
  ok("convert a.json a.vtu --samples 3");
  ok("convert a.json bezier.vtu --bezier");
  EXPECT_NE(slurp(work_ / "a.vtu").find("UnstructuredGrid"), std::string::npos);
  EXPECT_NE(slurp(work_ / "bezier.vtu").find("UnstructuredGrid"), std::string::npos);
}

TEST_F(Cli, InvertFindsParameterOrReportsOutside) {
  ok("make box --degree 2 --elements 2 --size 2 1 3 -o box.json");
  const Result r = ok("invert box.json 0.5 0.25 2.25");
  const auto u = numbers_after(r.out, "param");
  ASSERT_EQ(u.size(), 3u);
  EXPECT_NEAR(u[0], 0.25, 1e-10);
  EXPECT_NEAR(u[1], 0.25, 1e-10);
  EXPECT_NEAR(u[2], 0.75, 1e-10);
  EXPECT_NE(r.out.find("converged"), std::string::npos);
  const Result out = run("invert box.json 5 -1 0.5");
  EXPECT_EQ(out.code, 4) << out.err;
  EXPECT_NE(out.out.find("outside"), std::string::npos);
}

TEST_F(Cli, BadInputGivesOneErrorLineAndNoOutput) {
  ok("make box --elements 2 -o box.json");
  write("broken.json", "{ \"trivar\": 1, \"kind\": ");
  write("badknots.json", [] {
    auto j = nlohmann::json::parse(unit_cube_json(false));
    j["knots"][1] = {0, 0, 1, 0.5};
    return j.dump();
  }());
  fails("info missing.json");
  fails("refine missing.json --uniform 2 -o out.json");
  fails("info broken.json");
  fails("convert broken.json out.g2");
  fails("check badknots.json");
  fails("convert badknots.json out.json");
  fails("eval box.json 1.5 0.5 0.5");
  fails("eval box.json 0.5 0.5");
  fails("convert box.json out.xyz");
  fails("make box --elements 2 -o box.xyz");
  fails("make revolve --radii 2 1 -o ring.json");
  fails("make revolve --angle 400 -o ring.json");
  fails("refine box.json --insert q:0.5 -o out.json");
  fails("refine box.json --insert u:1.5 -o out.json");
  fails("refine box.json -o out.json");
  // Usage errors: exit code 2.
  fails("", 2);
  fails("frobnicate", 2);
  fails("eval", 2);
  fails("make box --elements two -o b.json", 2);
  fails("refine box.json --uniform 0 -o out.json", 2);
}

TEST_F(Cli, DemoWritesItsOutputs) {
  const Result r = ok("demo --out demo_out");
  // Ring r in [1, 2], height 1, swept 270 degrees: volume 3 pi / 4 * (2^2 - 1^2) = 9 pi / 4.
  const std::vector<double> volume = numbers_after(r.out, "  volume");
  ASSERT_GE(volume.size(), 1u);
  EXPECT_NEAR(volume[0], 9 * std::numbers::pi / 4, 1e-12);
  // Graded ball of radius 5 (the second "volume" line): 4/3 pi 5^3, exact up to quadrature rounding.
  const auto out_lines = lines(r.out);
  const auto ball = std::find_if(out_lines.rbegin(), out_lines.rend(),
                                 [](const std::string& l) { return l.rfind("  volume", 0) == 0; });
  ASSERT_NE(ball, out_lines.rend());
  // Gauss quadrature of a rational integrand is not exact, but a wrong model would be off by far more.
  EXPECT_NEAR(numbers_after(*ball, "  volume").at(0), 500 * std::numbers::pi / 3, 1e-10 * 500 * std::numbers::pi / 3);
  // The demo's files list exactly what it wrote, sorted.
  EXPECT_EQ(lines(slurp(work_ / "demo_out" / ".trivar-files")),
            (std::vector<std::string>{"ball.3mf", "ball.json", "ball.stl", "ring.json", "ring.vtu", "ring_bezier.vtu",
                                      "ring_net.vtu", "slices"}));
  for (const char* f : {"demo_out/ring.json", "demo_out/ring.vtu", "demo_out/ring_bezier.vtu", "demo_out/ring_net.vtu",
                        "demo_out/ball.json", "demo_out/ball.3mf", "demo_out/ball.stl", "demo_out/slices/manifest.json",
                        "demo_out/slices/layer_00000.png"})
    EXPECT_TRUE(exists(f)) << f;
  EXPECT_EQ(lines(ok("check demo_out/ring.json").out).at(0), "valid");
  EXPECT_NE(r.out.find("Jacobian     valid for every cell"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("watertight yes"), std::string::npos) << r.out;
  // A rerun into its own folder replaces its files and keeps the user's, in the slices folder too.
  write("demo_out/notes.txt", "mine\n");
  write("demo_out/slices/mine.txt", "also mine\n");
  const std::string one = ok("--threads 1 demo --out demo_out").out;
  EXPECT_EQ(slurp(work_ / "demo_out" / "notes.txt"), "mine\n");
  EXPECT_EQ(slurp(work_ / "demo_out" / "slices" / "mine.txt"), "also mine\n");
  // Same results whatever the thread count (timings aside): the ring report and every slice file.
  const std::string two = ok("--threads 2 demo --out two").out;
  EXPECT_EQ(one.substr(0, one.find("outputs:")), two.substr(0, two.find("outputs:")));
  for (const auto& e : fs::directory_iterator(work_ / "two" / "slices")) {
    if (e.path().filename() != "manifest.json") {
      EXPECT_EQ(slurp(e.path()), slurp(work_ / "demo_out" / "slices" / e.path().filename())) << e.path();
    }
  }
}

TEST_F(Cli, ExamplesBehaveAsDocumented) {
  const std::string examples = "'" TRIVAR_TEST_DATA "/../../examples/";
  EXPECT_NE(ok("info " + examples + "cube.g2'").out.find("control points: 4 x 4 x 4 = 64"), std::string::npos);
  EXPECT_EQ(lines(ok("check " + examples + "quarter_annulus.json'").out).at(0), "valid");
  const Result bad = run("check " + examples + "mirrored_cube.json'");
  EXPECT_EQ(bad.code, 3);
  EXPECT_EQ(lines(bad.out).at(0), "invalid");
  // Radius 1.5 at v = 0.5, height 0.25 at u = 0.5, 45 degrees at w = 0.5.
  const auto x = numbers_after(ok("eval " + examples + "quarter_annulus.json' 0.5 0.5 0.5").out, "S");
  ASSERT_EQ(x.size(), 3u);
  EXPECT_NEAR(x[0], 1.5 * std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(x[1], 1.5 * std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(x[2], 0.25, 1e-15);
}

TEST_F(Cli, EvalPicksAnObjectOfAMultiObjectFile) {
  // Object 1 is the unit cube moved by (10, 0, 0): S(u, v, w) = (10 + u, v, w).
  nlohmann::json a = nlohmann::json::parse(unit_cube_json(false)), b = a;
  a.erase("trivar");
  b.erase("trivar");
  for (auto& p : b["control_points"]) p[0] = p[0].get<double>() + 10;
  write("two.json", nlohmann::json{{"trivar", 1}, {"objects", {a, b}}}.dump());
  EXPECT_EQ(numbers_after(ok("eval two.json 0.25 0.5 0.75 --object 0").out, "S"),
            (std::vector<double>{0.25, 0.5, 0.75}));
  EXPECT_EQ(numbers_after(ok("eval two.json 0.25 0.5 0.75 --object 1").out, "S"),
            (std::vector<double>{10.25, 0.5, 0.75}));
  EXPECT_EQ(lines(run("eval two.json 0.25 0.5 0.75 --object 2").err).at(0),
            "trivar: error: eval: --object 2 is out of range: two.json holds 2 objects, numbered 0 to 1");
  EXPECT_EQ(lines(run("eval two.json 0.25 0.5 0.75").err).at(0),
            "trivar: error: eval: two.json holds 2 objects; choose one with --object N (0 to 1)");
  fails("eval two.json 0.25 0.5 0.75 --object -1");
}

TEST_F(Cli, EveryExtensionTheErrorNamesIsAccepted) {
  write("cube.json", unit_cube_json(false));
  const std::string err = lines(run("eval cube.xyz 0.5 0.5 0.5").err).at(0);
  const std::string head = "trivar: error: cube.xyz: unknown spline file extension '.xyz' (expected ";
  ASSERT_EQ(err.rfind(head, 0), 0u) << err;
  // ".json, .g2, .lr, .stp, .step, .p21 or .xml)": every name starting with a dot.
  std::vector<std::string> extensions;
  std::string rest = err.substr(head.size());
  for (std::size_t p = rest.find('.'); p != std::string::npos; p = rest.find('.', p + 1)) {
    const std::size_t end = rest.find_first_of(",) ", p);
    extensions.push_back(rest.substr(p, end - p));
    p = end;
  }
  EXPECT_EQ(extensions, (std::vector<std::string>{".json", ".g2", ".lr", ".stp", ".step", ".p21", ".xml"}));
  for (const std::string& ext : extensions) {
    if (ext != ".json") ok("convert cube.json cube" + ext);
    // The identity cube: S(u, v, w) = (u, v, w) whatever the format.
    EXPECT_EQ(numbers_after(ok("eval cube" + ext + " 0.25 0.5 0.75").out, "S"), (std::vector<double>{0.25, 0.5, 0.75}))
        << ext;
  }
}
