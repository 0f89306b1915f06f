// make vmodel, info, export and the V-model JSON of trimmed cells, end to end through the command line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "cad/occt_solids.hpp"
#include "trivar/io/stl_writer.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/model/trimmed_tessellation.hpp"

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
