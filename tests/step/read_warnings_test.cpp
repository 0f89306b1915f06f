// Departures from ISO 10303-21 outside the geometry: accepted with one counted warning line per kind naming
// the first instance, or refused in strict mode with that line.
#include <gtest/gtest.h>

#include "trivar/core/error.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/step_file.hpp"

using namespace trivar;
using namespace trivar::io::step;

namespace {

std::string file_with(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
         "FILE_SCHEMA(('X'));\nENDSEC;\nDATA;\n" + data + "ENDSEC;\nEND-ISO-10303-21;\n";
}

// The warnings of a lenient read (keeping CARTESIAN_POINT and ORIENTED_EDGE, skipping the rest unparsed as a
// geometry reader does), and the strict read's error message ("" when it succeeds).
struct Outcome {
  std::vector<ReadWarning> warnings;
  std::string strict_error;
};

Outcome read_both(const std::string& data) {
  ReadOptions o;
  o.keep = [](std::string_view k) { return k == "CARTESIAN_POINT" || k == "ORIENTED_EDGE"; };
  Outcome r;
  r.warnings = parse_exchange_file(file_with(data), "t.stp", o).warnings;
  o.strict = true;
  try {
    parse_exchange_file(file_with(data), "t.stp", o);
  } catch (const Error& e) {
    r.strict_error = e.what();
  }
  return r;
}

}  // namespace

TEST(StepReadWarnings, ConformingFileHasNone) {
  const Outcome r = read_both("#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=VERTEX_POINT('',#1);\n#3=EDGE_CURVE('',#2,#2,#1,.T.);\n");
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(r.strict_error, "");
}

TEST(StepReadWarnings, LowerCaseKeywordsAndEnumerations) {
  const Outcome r = read_both("#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=vertex_point('',#1);\n#3=Vertex_Point('',#1);\n"
                              "#4=ORIENTED_EDGE('',*,*,#2,.t.);\n");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].kind, Departure::lowercase_keyword);
  EXPECT_EQ(r.warnings[0].count, 3u);
  EXPECT_EQ(r.warnings[0].text(),
            "t.stp:9:4: #2: keyword 'VERTEX_POINT' written in lower case (ISO 10303-21 requires upper case) "
            "(3 occurrences in the file)");
  EXPECT_EQ(r.strict_error,
            "t.stp:9:4: #2: keyword 'VERTEX_POINT' written in lower case (ISO 10303-21 requires upper case) (strict reading)");
}

TEST(StepReadWarnings, StrayBytesInStrings) {
  const Outcome r = read_both("#1=CARTESIAN_POINT('caf\xE9',(0.,0.,0.));\n#2=PRODUCT('a\x01" "b','','',());\n");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].kind, Departure::stray_bytes);
  EXPECT_EQ(r.warnings[0].count, 1u);  // the skipped PRODUCT's string is not read
  EXPECT_EQ(r.warnings[0].first,
            "t.stp:8:20: #1: byte 0xE9 at character 4 of a string is not allowed (ISO 10303-21 strings hold printable "
            "ISO 8859-1 characters and escapes)");
  EXPECT_EQ(r.strict_error, r.warnings[0].first);
}

TEST(StepReadWarnings, DanglingReferencesOutsideTheKeptInstances) {
  const Outcome r = read_both("#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=VERTEX_POINT('',#1);\n"
                              "#3=EDGE_CURVE('',#2,#77,#1,.T.);\n#4=FACE_BOUND('',#78,.T.);\n");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].kind, Departure::dangling_reference);
  EXPECT_EQ(r.warnings[0].count, 2u);
  EXPECT_EQ(r.warnings[0].text(), "t.stp:10:1: #3: EDGE_CURVE refers to undefined instance #77 (2 occurrences in the file)");
  EXPECT_EQ(r.strict_error, "t.stp:10:1: #3: EDGE_CURVE refers to undefined instance #77 (strict reading)");
}

TEST(StepReadWarnings, ReferenceCycles) {
  // Through skipped instances and a kept one (ORIENTED_EDGE); the search starts in file order.
  const Outcome r = read_both("#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=FACE_BOUND('',#3,.T.);\n#3=EDGE_LOOP('',(#4));\n"
                              "#4=ORIENTED_EDGE('',*,*,#2,.T.);\n");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].kind, Departure::reference_cycle);
  EXPECT_EQ(r.warnings[0].first,
            "t.stp: #2: reference cycle #2 -> #3 -> #4 -> #2 (FACE_BOUND -> EDGE_LOOP -> ORIENTED_EDGE -> FACE_BOUND)");
  EXPECT_EQ(r.strict_error, r.warnings[0].first + " (strict reading)");
}

TEST(StepReadWarnings, ReadStepPassesThemOnAndStrictRefuses) {
  const std::string text = file_with("#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=cartesian_point('',(1.,0.,0.));\n"
                                     "#3=B_SPLINE_CURVE_WITH_KNOTS('',1,(#1,#2),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),"
                                     ".UNSPECIFIED.);\n");
  const StepContents c = parse_step(text, "t.stp");
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].kind, Departure::lowercase_keyword);
  EXPECT_EQ(c.splines.size(), 1u);
  EXPECT_THROW(parse_step(text, "t.stp", true), Error);
}

TEST(StepUnmappedFaces, CountedPerSurfaceEntity) {
  // Faces on two planes, a cylinder (one of them a FACE_SURFACE) and a B-spline patch: only the patch maps.
  const std::string text = file_with(
      "#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=CARTESIAN_POINT('',(1.,0.,0.));\n#3=CARTESIAN_POINT('',(0.,1.,0.));\n"
      "#4=CARTESIAN_POINT('',(1.,1.,0.));\n#5=DIRECTION('',(0.,0.,1.));\n#6=DIRECTION('',(1.,0.,0.));\n"
      "#7=AXIS2_PLACEMENT_3D('',#1,#5,#6);\n#10=PLANE('',#7);\n#11=PLANE('',#7);\n"
      "#12=CYLINDRICAL_SURFACE('',#7,2.5);\n"
      "#13=B_SPLINE_SURFACE_WITH_KNOTS('',1,1,((#1,#2),(#3,#4)),.UNSPECIFIED.,.F.,.F.,.F.,(2,2),(2,2),(0.,1.),(0.,1.),"
      ".UNSPECIFIED.);\n"
      "#20=ADVANCED_FACE('',(),#10,.T.);\n#21=ADVANCED_FACE('',(),#11,.F.);\n#22=ADVANCED_FACE('',(),#12,.T.);\n"
      "#23=FACE_SURFACE('',(),#12,.T.);\n#24=ADVANCED_FACE('',(),#13,.T.);\n#25=ADVANCED_FACE('',(),#10,.T.);\n");
  const StepContents c = parse_step(text, "t.stp");
  EXPECT_EQ(c.faces, 6u);
  EXPECT_EQ(c.unmapped_faces, (std::map<std::string, std::size_t>{{"CYLINDRICAL_SURFACE", 2}, {"PLANE", 3}}));
  EXPECT_EQ(c.unmapped_faces_summary(), "skipped 5 of 6 faces (surface not a spline): 3 PLANE, 2 CYLINDRICAL_SURFACE");
  ASSERT_EQ(c.splines.size(), 1u);
  EXPECT_EQ(c.spline_info[0].faces, (std::vector<std::uint64_t>{24}));
  EXPECT_EQ(c.entities.at("CARTESIAN_POINT").kept, 4u);  // held compactly, still counted
}
