// make vmodel, info, export and the V-model JSON of trimmed cells, end to end through the command line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "cad/occt_solids.hpp"
#include <functional>

#include <nlohmann/json.hpp>

#include "trivar/io/stl_writer.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/model/trimmed_tessellation.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;

namespace {

struct CliRun {
  int code;
  std::string out, err;
};

CliRun run(const std::string& args, const std::filesystem::path& dir) {
  const std::string o = (dir / "stdout.txt").string(), e = (dir / "stderr.txt").string();
  const int status = std::system((std::string(TRIVAR_CLI_PATH) + " " + args + " > " + o + " 2> " + e).c_str());
  auto slurp = [](const std::string& p) {
    std::stringstream s;
    s << std::ifstream(p).rdbuf();
    return s.str();
  };
  return {WEXITSTATUS(status), slurp(o), slurp(e)};
}

}  // namespace

TEST(VmodelCli, StepSolidBecomesATrimmedModelThatReadsBack) {
  const auto dir = test::temp_dir("cli");
  const TopoDS_Shape shape = test::box_with_holes();
  const std::string step = test::write_step(shape, dir, "part");
  const std::string json = (dir / "part.json").string();
  const CliRun r = run("make vmodel " + step + " -o " + json + " --materials 2", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const VModel m = io::read_vmodel(json);
  ASSERT_EQ(m.num_cells(), 1);
  ASSERT_TRUE(m.cell(0).is_trimmed());
  const double ref = test::occt_volume(shape);
  EXPECT_NEAR(m.volume(), ref, 1e-6 * ref);
  // OpenCASCADE's own volume only on request, beside trivar's.
  EXPECT_EQ(r.out.find("OpenCASCADE"), std::string::npos) << r.out;
  const CliRun k = run("make vmodel " + step + " -o " + (dir / "part_k.json").string() + " --kernel-volume", dir);
  ASSERT_EQ(k.code, 0) << k.err;
  const auto at = k.out.find("(OpenCASCADE ");
  ASSERT_NE(at, std::string::npos) << k.out;
  EXPECT_NEAR(std::stod(k.out.substr(at + 13)), ref, 1e-6 * ref) << k.out;
  const CliRun ik = run("info " + step + " --kernel-volume", dir);
  ASSERT_EQ(ik.code, 0) << ik.err;
  const auto iat = ik.out.find("; OpenCASCADE ");
  ASSERT_NE(iat, std::string::npos) << ik.out;
  EXPECT_NEAR(std::stod(ik.out.substr(iat + 14)), ref, 1e-6 * ref) << ik.out;
  EXPECT_EQ(run("info " + step, dir).out.find("; OpenCASCADE "), std::string::npos);
  // The closure defect of the closed part: at rounding level, no warning; the JSON has its measures.
  EXPECT_NE(ik.out.find("    closure: integral of the normal over the faces "), std::string::npos) << ik.out;
  EXPECT_EQ(ik.out.find("warning:"), std::string::npos) << ik.out;
  const CliRun ij = run("info " + step + " --json", dir);
  ASSERT_EQ(ij.code, 0) << ij.err;
  const nlohmann::json brep = nlohmann::json::parse(ij.out)["brep"];
  EXPECT_TRUE(brep["open_boundaries"].empty());
  const nlohmann::json& closure = brep["solid_info"].at(0)["closure"];
  EXPECT_TRUE(closure["closed"].get<bool>());
  EXPECT_LE(closure["relative"].get<double>(), 1e-12);
  // The mesh's area against the part's: 2 (40 x 30 - 2 pi 16) + 2 (40 + 30) 20 + 2 (2 pi 4) 20, the holes'
  // walls inscribed within the chordal tolerance.
  const double area = 2 * (1200 - 32 * test::kPi) + 2800 + 320 * test::kPi;
  EXPECT_NEAR(closure["area"].get<double>(), area, 1e-2 * area);
  EXPECT_NEAR(closure["volume_uncertainty"].get<double>(), closure["norm"].get<double>() * std::sqrt(40.0 * 40 + 30 * 30 + 20 * 20),
              1e-2 * closure["volume_uncertainty"].get<double>());
  // Mass of a linear density rho = x by exact-boundary quadrature: the first moment M_x of the part, which for
  // the block with two symmetric holes is the volume times the centroid x = 20.
  Attribute rho = Attribute::expression({"x"}, Attribute::Space::model);
  VModel m2 = io::read_vmodel(json);
  m2.cell(0).set_attribute("rho", rho);
  EXPECT_NEAR(m2.mass("rho"), 20 * ref, 1e-9 * 20 * ref);
  // Parameter points: inside the block, not in a hole, not outside the part.
  EXPECT_TRUE(m.cell(0).contains_param({2, 2, 2}));
  EXPECT_FALSE(m.cell(0).contains_param({12, 15, 10}));
  EXPECT_TRUE(m.cell(0).has_attribute("material"));
  // info shows the trimmed cell and its volume.
  const CliRun info = run("info " + json, dir);
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("trimmed by 8 faces (2 cylinder, 6 plane)"), std::string::npos) << info.out;
  // export writes the watertight trimmed boundary.
  const CliRun ex = run("export " + json + " " + (dir / "part.stl").string(), dir);
  ASSERT_EQ(ex.code, 0) << ex.err;
  EXPECT_NE(ex.out.find("watertight yes"), std::string::npos) << ex.out;
  const ModelTessellation t = trimmed_boundary_mesh(m);
  EXPECT_TRUE(is_watertight(t.mesh));
  EXPECT_NEAR(enclosed_volume(t.mesh), ref, 0.01 * ref);
  std::filesystem::remove_all(dir);
}

TEST(VmodelCli, NonSolidStepIsRefusedWithoutOutput) {
  const auto dir = test::temp_dir("cli_bad");
  BRep_Builder bb;
  TopoDS_Shell shell;
  bb.MakeShell(shell);
  int i = 0;
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(1, 1, 1).Shape();
  for (TopExp_Explorer f(box, TopAbs_FACE); f.More(); f.Next(), ++i)
    if (i != 2) bb.Add(shell, f.Current());
  const std::string step = test::write_step(shell, dir, "open");
  const std::string json = (dir / "open.json").string();
  const CliRun r = run("make vmodel " + step + " -o " + json, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no solid (1 shell outside solids (1 open: 4 free edges))"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  EXPECT_FALSE(std::filesystem::exists(json));
  // info still describes it.
  const CliRun info = run("info " + step, dir);
  EXPECT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("not a solid: 1 shell outside solids"), std::string::npos) << info.out;
  std::filesystem::remove_all(dir);
}

namespace {

// int u over the unit cube for -lap u = 1, u = 0 on the boundary: the sine series
// sum over odd i, j, k of 512 / (pi^8 i^2 j^2 k^2 (i^2 + j^2 + k^2)).
double unit_cube_poisson_integral() {
  double s = 0;
  for (int i = 1; i < 400; i += 2)
    for (int j = 1; j < 400; j += 2)
      for (int k = 1; k < 400; k += 2)
        s += 1.0 / (double(i) * i * j * j * k * k * (i * i + j * j + k * k));
  return 512 / std::pow(test::kPi, 8) * s;
}

}  // namespace

// solve on a trimmed model: the STEP unit cube (every face on a side of its box) against the sine series and its
// first Laplace eigenvalue; the block with holes (cut elements, trimming boundary free) writes its solution;
// check certifies both trims.
TEST(VmodelCli, SolveAndCheckTrimmedModels) {
  const auto dir = test::temp_dir("cli_solve");
  const std::string cube = (dir / "cube.json").string(), part = (dir / "part.json").string();
  ASSERT_EQ(run("make vmodel " + test::write_step(BRepPrimAPI_MakeBox(1, 1, 1).Shape(), dir, "cube") + " -o " + cube, dir).code, 0);
  ASSERT_EQ(run("make vmodel " + test::write_step(test::box_with_holes(), dir, "part") + " -o " + part, dir).code, 0);
  const CliRun c = run("solve poisson " + cube + " --degree 3 --refine 6 --solver cholmod", dir);
  ASSERT_EQ(c.code, 0) << c.err;
  const auto mean = c.out.find("mean u ");
  ASSERT_NE(mean, std::string::npos) << c.out;
  EXPECT_NEAR(std::stod(c.out.substr(mean + 7)), unit_cube_poisson_integral(), 2e-5) << c.out;
  const CliRun p = run("solve poisson " + part + " --refine 6 --solver cholmod --out " + (dir / "sol").string(), dir);
  ASSERT_EQ(p.code, 0) << p.err;
  EXPECT_NE(p.out.find("cut"), std::string::npos) << p.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "sol" / "solution.vtu"));
  // Volume of the quadrature against the exact-boundary volume.
  const auto vol = p.out.find("volume "), exact = p.out.find("exact boundary ");
  ASSERT_NE(exact, std::string::npos) << p.out;
  EXPECT_NEAR(std::stod(p.out.substr(vol + 7)), std::stod(p.out.substr(exact + 15)), 1e-6 * 24000);
  const CliRun e = run("solve elasticity " + part + " --refine 4 --clamp x- --solver cholmod", dir);
  EXPECT_EQ(e.code, 0) << e.err;
  // Laplace modes of the STEP unit cube with u = 0 on its sides: 3 pi^2 first.
  const CliRun md = run("solve modes " + cube + " --physics laplace --modes 1 --degree 3 --refine 4", dir);
  ASSERT_EQ(md.code, 0) << md.err;
  const auto lam = md.out.find("mode 1: lambda ");
  ASSERT_NE(lam, std::string::npos) << md.out;
  const double pi2 = 3.14159265358979323846 * 3.14159265358979323846;
  EXPECT_NEAR(std::stod(md.out.substr(lam + 15)), 3 * pi2, 1e-4 * 3 * pi2) << md.out;
  for (const std::string& m : {cube, part}) {
    const CliRun k = run("check " + m, dir);
    EXPECT_EQ(k.code, 0) << k.out << k.err;
    EXPECT_NE(k.out.find("trim valid"), std::string::npos) << k.out;
  }
  // A face whose orientation flag is flipped: the exact faces no longer enclose what the mesh does.
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(part));
  std::function<bool(nlohmann::json&)> flip = [&](nlohmann::json& j) {
    if (j.is_object() && j.contains("reversed") && j.contains("surface")) {
      j["reversed"] = !j["reversed"].get<bool>();
      return true;
    }
    for (auto& v : j)
      if ((v.is_object() || v.is_array()) && flip(v)) return true;
    return false;
  };
  ASSERT_TRUE(flip(doc));
  const std::string bad = (dir / "bad.json").string();
  std::ofstream(bad) << doc.dump();
  const CliRun k = run("check " + bad, dir);
  EXPECT_EQ(k.code, 3) << k.out << k.err;
  EXPECT_NE(k.out.find("defect: "), std::string::npos) << k.out;
  std::filesystem::remove_all(dir);
}

// trivar boolean end to end: a ball minus a cylinder, the report and the result read back by info; bad
// operations and empty results are one-line errors without an output file.
TEST(BooleanCli, BallMinusCylinder) {
  const auto dir = test::temp_dir("boolean_cli");
  std::filesystem::create_directories(dir);
  const std::string d = dir.string() + "/";
  ASSERT_EQ(run("make ball --radius 1 --material-field 1 0 -o " + d + "ball.json", dir).code, 0);
  ASSERT_EQ(run("make cylinder --radius 0.4 --height 3 --material-field 0 1 -o " + d + "cyl.json", dir).code, 0);
  const CliRun r = run("boolean " + d + "ball.json " + d + "cyl.json --op difference -o " + d + "ring.json --json", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  // The cylinder stands on z = 0: the lower half ball stays, the upper half becomes half a napkin ring,
  // (2/3) pi (1 + (1 - 0.16)^(3/2)).
  const double pi = 3.14159265358979323846;
  const double exact = 2.0 / 3 * pi * (1 + (1 - 0.16) * std::sqrt(1 - 0.16));
  EXPECT_NEAR(j["volume"]["result"].get<double>(), exact, 1e-8 * exact);
  EXPECT_TRUE(j["boundary_mesh"]["watertight"].get<bool>());
  EXPECT_EQ(j["boundary_mesh"]["euler_characteristic"].get<int>(), 2);
  const CliRun info = run("info " + d + "ring.json --json", dir);
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NEAR(nlohmann::json::parse(info.out)["volume"].get<double>(), exact, 1e-8 * exact);
  // A one-cell result (a cube with a spherical cavity) is solved with detrimmed quadrature; its volume there is
  // the quadrature's, close to the exact one.
  ASSERT_EQ(run("make box --degree 1 1 1 --elements 1 1 1 --size 2 2 2 -o " + d + "cube.json", dir).code, 0);
  ASSERT_EQ(run("make ball --radius 0.5 --center 1 1 1 -o " + d + "hole.json", dir).code, 0);
  ASSERT_EQ(run("boolean " + d + "cube.json " + d + "hole.json --op difference -o " + d + "cavity.json", dir).code, 0);
  const CliRun solve = run("solve poisson " + d + "cavity.json --refine 2", dir);
  ASSERT_EQ(solve.code, 0) << solve.err;
  EXPECT_NE(solve.out.find("trimmed cell"), std::string::npos) << solve.out;
  // The cube with a corner ball removed, split through the notch at x = 1.5: two cells sharing the cut face,
  // solved as one model (elasticity clamped on x = 0); info and check report the face they share.
  ASSERT_EQ(run("make ball --radius 0.8 --center 2 2 2 -o " + d + "corner.json", dir).code, 0);
  ASSERT_EQ(run("boolean " + d + "cube.json " + d + "corner.json --op difference -o " + d + "notched.json", dir).code, 0);
  ASSERT_EQ(run("boolean " + d + "notched.json --split plane:1.5,1,1,1,0,0 -o " + d + "halves.json", dir).code, 0);
  const CliRun two = run("solve elasticity " + d + "halves.json --refine 2 --clamp x-", dir);
  ASSERT_EQ(two.code, 0) << two.err;
  EXPECT_NE(two.out.find("trimmed cells: 2, sharing 1 faces"), std::string::npos) << two.out;
  const CliRun hi = run("info " + d + "halves.json", dir);
  EXPECT_NE(hi.out.find("trimming faces: 1 shared by two cells"), std::string::npos) << hi.out;
  EXPECT_NE(hi.out.find("watertight, Euler characteristic 2"), std::string::npos) << hi.out;
  const CliRun hc = run("check " + d + "halves.json", dir);
  EXPECT_EQ(hc.code, 0) << hc.out;
  EXPECT_NE(hc.out.find("0 non-conforming"), std::string::npos) << hc.out;
  // Split by a plane: the ball cut at z = 0.5, the cap above pi h^2 (3 - h) / 3 with h = 0.5.
  const CliRun split = run("boolean " + d + "ball.json --split plane:0,0,0.5,0,0,1 -o " + d + "parts.json --json", dir);
  ASSERT_EQ(split.code, 0) << split.err;
  const nlohmann::json js = nlohmann::json::parse(split.out);
  EXPECT_EQ(js["operation"].get<std::string>(), "split");
  EXPECT_NEAR(js["volume"]["result"].get<double>(), 4 * pi / 3, 1e-8 * 4 * pi / 3);
  EXPECT_GT(js["cells"]["result"].get<int>(), 7);
  EXPECT_TRUE(js["boundary_mesh"]["watertight"].get<bool>());
  EXPECT_EQ(run("boolean " + d + "ball.json --split plane:0,0,0.5 -o " + d + "p2.json", dir).code, 1);
  EXPECT_EQ(run("boolean " + d + "ball.json " + d + "cyl.json --split plane:0,0,0.5,0,0,1 -o " + d + "p3.json", dir).code, 1);
  EXPECT_FALSE(std::filesystem::exists(d + "p2.json"));
  const CliRun bad = run("boolean " + d + "ball.json " + d + "cyl.json --op xor -o " + d + "x.json", dir);
  EXPECT_NE(bad.code, 0);
  const CliRun empty = run("boolean " + d + "cyl.json " + d + "cyl.json --op difference -o " + d + "e.json", dir);
  EXPECT_EQ(empty.code, 1);
  EXPECT_NE(empty.err.find("difference is empty"), std::string::npos) << empty.err;
  EXPECT_FALSE(std::filesystem::exists(d + "e.json"));
  std::filesystem::remove_all(dir);
}

// info and check report the V-curves and V-points of a Boolean's result (two unit cubes sharing a face: 20
// V-curves, 12 V-points, boundary 12 - 20 + 10 = 2); a trimming loop that names the wrong edge leaves one edge
// used by an odd number of loops, which check reports as a defect (exit 3).
TEST(BooleanCli, InfoAndCheckReportVCurvesAndVPoints) {
  const auto dir = test::temp_dir("boolean_topology_cli");
  std::filesystem::create_directories(dir);
  const std::string d = dir.string() + "/";
  const auto cube_at = [](double x) {
    VModel m;
    m.add_cell(VCell(test::block_at(x, 0, 0)));
    m.glue();
    return m;
  };
  std::ofstream(d + "a.json") << io::to_json(cube_at(0)).dump();
  std::ofstream(d + "b.json") << io::to_json(cube_at(1)).dump();
  ASSERT_EQ(run("boolean " + d + "a.json " + d + "b.json --op union -o " + d + "u.json", dir).code, 0);
  const CliRun info = run("info " + d + "u.json --json", dir);
  ASSERT_EQ(info.code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["curves"].get<int>(), 20);
  EXPECT_EQ(j["points"].get<int>(), 12);
  EXPECT_EQ(j["shared_surfaces"].get<int>(), 1);
  EXPECT_EQ(j["boundary_surfaces"].get<int>(), 10);
  EXPECT_EQ(j["trimmed_topology"]["euler_characteristic"].get<int>(), 2);
  EXPECT_EQ(j["trimmed_topology"]["cell_euler_characteristics"], nlohmann::json({2, 2}));
  const CliRun ok = run("check " + d + "u.json", dir);
  EXPECT_EQ(ok.code, 0) << ok.out;
  EXPECT_NE(ok.out.find("trimming edges: 20 V-curves, 12 V-points"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("V - E + F = 2, mesh watertight, Euler characteristic 2"), std::string::npos) << ok.out;
  // A model mixing an untrimmed cell (the left cube) and a trimmed one (the right cell of the union) solves as
  // one: the first Laplace eigenvalue of the 2 x 1 x 1 box, pi^2 (1/4 + 1 + 1).
  VModel mixed;
  mixed.add_cell(cube_at(0).cell(0));
  const VModel u = io::vmodel_from_json(nlohmann::json::parse(std::ifstream(d + "u.json")), "u");
  for (const VCell& c : u.cells())
    if (c.trim()->bounding_box().lo[0] > 0.5) mixed.add_cell(c);
  ASSERT_EQ(mixed.num_cells(), 2);
  std::ofstream(d + "mixed.json") << io::to_json(mixed).dump();
  const CliRun modes = run("solve modes " + d + "mixed.json --physics laplace --modes 1 --refine 4", dir);
  ASSERT_EQ(modes.code, 0) << modes.out << modes.err;
  EXPECT_NE(modes.out.find("mixed model: 1 untrimmed cells"), std::string::npos) << modes.out;
  const auto at = modes.out.find("mode 1: lambda ");
  ASSERT_NE(at, std::string::npos) << modes.out;
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(std::stod(modes.out.substr(at + 15)), 2.25 * pi * pi, 2e-3 * 2.25 * pi * pi) << modes.out;
  // The first loop's first curve names the edge of its second curve instead of its own.
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(d + "u.json"));
  std::function<bool(nlohmann::json&)> rename = [&](nlohmann::json& v) {
    if (v.is_array() && v.size() > 1 && v[0].is_object() && v[0].contains("edge") && v[0].contains("pcurve")) {
      v[0]["edge"] = v[1]["edge"];
      return true;
    }
    for (auto& x : v)
      if ((x.is_object() || x.is_array()) && rename(x)) return true;
    return false;
  };
  ASSERT_TRUE(rename(doc));
  std::ofstream(d + "bad.json") << doc.dump();
  const CliRun bad = run("check " + d + "bad.json", dir);
  EXPECT_EQ(bad.code, 3) << bad.out << bad.err;
  EXPECT_NE(bad.out.find("face loops (a closed boundary uses every edge twice)"), std::string::npos) << bad.out;
  std::filesystem::remove_all(dir);
}
