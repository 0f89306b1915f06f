// STEP files on the command line: info (entity statistics, geometry with the faces using it), convert in both
// directions for tensor splines, LR splines and V-models. Reference values: the source files' own evaluation
// (a STEP round trip must not change the geometry) and the entity counts of hand-written test files.
#include "cli/cli_fixture.hpp"

using namespace cli_test;

class StepCli : public Cli {
protected:
  std::vector<double> eval(const std::string& file, const std::string& params) const {
    return numbers_after(ok("eval " + file + " " + params + " --derivs 1").out, "S");
  }
};

TEST_F(StepCli, InfoListsEntitiesAndTheGeometryOfACadFile) {
  const std::string file = std::string(TRIVAR_TEST_DATA) + "/step/geometry/cad_part_ap214.stp";
  const std::string text = ok("info " + file).out;
  EXPECT_NE(text.find("AUTOMOTIVE_DESIGN"), std::string::npos) << text;
  EXPECT_NE(text.find("ADVANCED_FACE"), std::string::npos) << text;
  const nlohmann::json j = nlohmann::json::parse(ok("info --json " + file).out);
  EXPECT_EQ(j.at("format"), "step");
  EXPECT_EQ(j.at("entities").at("ADVANCED_FACE").at("count"), 3);
  EXPECT_EQ(j.at("entities").at("CARTESIAN_POINT").at("count"), 15);
  std::size_t surfaces = 0, with_faces = 0;
  for (const auto& o : j.at("objects")) {
    surfaces += o.at("kind") == "surface" ? 1 : 0;
    with_faces += o.at("step").at("faces").empty() ? 0 : 1;
  }
  EXPECT_EQ(j.at("objects").size(), 5u);
  EXPECT_EQ(surfaces, 2u);
  EXPECT_EQ(with_faces, 2u);
}

TEST_F(StepCli, TensorVolumeRoundTripEvaluatesIdentically) {
  ok("make revolve --radii 1 2 --height 1 --angle 270 -o ring.json");
  ok("convert ring.json ring.stp");
  ok("convert ring.stp back.json");
  ok("convert ring.stp back.g2");
  for (const char* p : {"0 0 0", "0.3 0.4 0.5", "1 1 1", "0.77 0.01 0.5"}) {
    const auto a = eval("ring.json", p), b = eval("back.json", p), c = eval("back.g2", p);
    ASSERT_EQ(a.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      // Rational points are written Cartesian, so w * x may differ by an ulp after reading back.
      EXPECT_NEAR(b[k], a[k], 1e-14) << p;
      EXPECT_NEAR(c[k], a[k], 1e-14) << p;
    }
  }
  const nlohmann::json j = nlohmann::json::parse(ok("info --json ring.stp").out);
  EXPECT_EQ(j.at("objects").at(0).at("kind"), "volume");
  EXPECT_EQ(j.at("objects").at(0).at("step").at("entity").get<std::string>().find("RATIONAL_B_SPLINE_VOLUME") !=
                std::string::npos,
            true);
}

TEST_F(StepCli, LRVolumeAndVModelRoundTrips) {
  ok("make box --lr --degree 2 --elements 3 3 3 -o box.lr");
  ok("refine box.lr -o fine.lr --strategy fullspan --elements 0 5 --report");
  ok("convert fine.lr fine.stp");
  ok("convert fine.stp back.lr");
  const nlohmann::json a = nlohmann::json::parse(ok("info --json fine.lr").out).at("objects").at(0);
  const nlohmann::json b = nlohmann::json::parse(ok("info --json back.lr").out).at("objects").at(0);
  EXPECT_EQ(a.at("num_basis"), b.at("num_basis"));
  EXPECT_GT(a.at("num_basis").get<int>(), 64);
  for (const char* p : {"0.1 0.2 0.3", "0.5 0.5 0.5", "0.95 0.05 0.6"}) EXPECT_EQ(eval("fine.lr", p), eval("back.lr", p)) << p;

  ok("make ball --radius 2 -o ball.json");
  ok("convert ball.json ball.stp");
  const nlohmann::json j = nlohmann::json::parse(ok("info --json ball.stp").out);
  EXPECT_EQ(j.at("objects").size(), 7u);
  EXPECT_TRUE(j.at("lr_objects").empty());
}

TEST_F(StepCli, BadFilesFailWithOneLine) {
  for (const char* f : {"truncated_instance.stp", "bad_escape.stp"})
    fails("convert " + std::string(TRIVAR_TEST_DATA) + "/step/malformed/" + f + " out.json");
  // Instances the geometry reader skips are not tokenised, so a missing ';' there swallows the next instance:
  // what remains is a reference to no instance (a warning), and no geometry (the error).
  const std::string swallowed = std::string(TRIVAR_TEST_DATA) + "/step/malformed/missing_semicolon.stp";
  const Result r = run("convert " + swallowed + " out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, "trivar: warning: " + swallowed + ":8:1: #1: NAME refers to undefined instance #2\n"
                   "trivar: error: convert: " + swallowed + " holds no B-spline or locally refined geometry\n");
  fails("convert " + swallowed + " out.json --strict");
  fails("info " + std::string(TRIVAR_TEST_DATA) + "/step/malformed/unterminated_string.stp");
  write("nothing.stp", "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
                       "FILE_SCHEMA(('X'));\nENDSEC;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n");
  fails("convert nothing.stp out.json");
}

TEST_F(StepCli, SkippedAnalyticFacesAreReported) {
  const std::string file = std::string(TRIVAR_TEST_DATA) + "/step/geometry/cad_part_ap214.stp";
  const Result r = ok("convert " + file + " out.g2");
  // The hand-written part has three faces: a B-spline patch, a rational B-spline quarter cylinder and a PLANE.
  EXPECT_EQ(r.err, "trivar: warning: " + file + ": skipped 1 of 3 faces (surface not a spline): 1 PLANE\n");
  const nlohmann::json j = nlohmann::json::parse(ok("info --json " + file).out);
  EXPECT_EQ(j.at("faces"), 3);
  EXPECT_EQ(j.at("unmapped_faces"), (nlohmann::json{{"PLANE", 1}}));
  const Result info = ok("info " + file);
  EXPECT_NE(info.out.find("\n  skipped 1 of 3 faces (surface not a spline): 1 PLANE\n"), std::string::npos) << info.out;
  EXPECT_EQ(info.err, "");
}

TEST_F(StepCli, DeparturesWarnByDefaultAndFailWithStrict) {
  write("lax.stp", "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','',' ');\n"
                   "FILE_SCHEMA(('X'));\nENDSEC;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\n"
                   "#2=cartesian_point('',(1.,0.,0.));\n#3=B_SPLINE_CURVE_WITH_KNOTS('',1,(#1,#2),.UNSPECIFIED.,.F.,"
                   ".F.,(2,2),(0.,1.),.UNSPECIFIED.);\n#4=PRODUCT('p','p','',(#99));\nENDSEC;\nEND-ISO-10303-21;\n");
  const Result r = ok("convert lax.stp out.json");
  EXPECT_EQ(r.err,
            "trivar: warning: lax.stp:9:4: #2: keyword 'CARTESIAN_POINT' written in lower case (ISO 10303-21 requires "
            "upper case)\ntrivar: warning: lax.stp:11:1: #4: PRODUCT refers to undefined instance #99\n");
  fails("convert lax.stp strict.json --strict");
  EXPECT_FALSE(exists("strict.json"));
  fails("info lax.stp --strict");
  // An originating system of blanks is no origin: the first line ends after the schema.
  const std::string text = ok("info lax.stp").out;
  EXPECT_EQ(text.substr(0, text.find('\n')), "lax.stp: STEP (ISO 10303-21), schema X");
}
