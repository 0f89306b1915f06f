// The reader on hand-written files: every grammar feature, the streaming path with tiny chunks, filters.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>

#include "step/step_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/writer.hpp"

using namespace trivar;
using namespace trivar::io::step;
using test::step_data;
using test::step_file;

namespace {

const Parameter& param(const ExchangeFile& f, std::uint64_t id, std::size_t k) { return f.at(id).records.at(0).params.at(k); }

}  // namespace

TEST(StepParser, GrammarFileHeader) {
  const ExchangeFile f = read_exchange_file(step_data("grammar.stp"));
  const Header& h = f.header;
  EXPECT_EQ(h.description, (std::vector<std::string>{"grammar test", "second line"}));
  EXPECT_EQ(h.implementation_level, "2;1");
  EXPECT_EQ(h.name, "grammar.stp");
  EXPECT_EQ(h.time_stamp, "2025-01-01T00:00:00");
  EXPECT_EQ(h.author, std::vector<std::string>{"J. O'Brien"});
  EXPECT_EQ(h.organization, std::vector<std::string>{"Org"});
  EXPECT_EQ(h.preprocessor_version, "hand");
  EXPECT_EQ(h.originating_system, "editor");
  EXPECT_EQ(h.authorization, "none");
  EXPECT_EQ(h.schemas, std::vector<std::string>{"AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }"});
  ASSERT_EQ(h.extra.size(), 1u);
  EXPECT_EQ(h.extra[0].keyword, "!VENDOR_HEADER");
}

TEST(StepParser, GrammarFileInstances) {
  const ExchangeFile f = read_exchange_file(step_data("grammar.stp"));
  // Two DATA sections, skipped ANCHOR/REFERENCE/SIGNATURE sections, #100 of the reference section not an instance.
  EXPECT_EQ(f.size(), 13u);
  EXPECT_EQ(f.find(100), nullptr);
  EXPECT_EQ(f.instances().front().id, 1u);  // file order
  EXPECT_EQ(f.instances().back().id, 21u);

  EXPECT_EQ(f.at(1).records[0].keyword, "PRODUCT_LIKE");
  EXPECT_EQ(param(f, 1, 1), reference(3));  // forward reference
  EXPECT_EQ(param(f, 1, 2).kind(), Kind::unset);
  EXPECT_EQ(param(f, 1, 3).kind(), Kind::derived);
  EXPECT_EQ(f.at(1).line, 15u);
  EXPECT_EQ(f.at(1).column, 1u);
  EXPECT_EQ(f.at(2).line, 16u);

  const std::vector<Parameter> numbers = {std::int64_t{0}, std::int64_t{-7}, std::int64_t{12}, 1.0, -0.0, 1e300, 1.5e-3,
                                          0.5, std::int64_t{9223372036854775807}};
  EXPECT_EQ(f.at(3).records[0].params, numbers);
  EXPECT_TRUE(std::signbit(*param(f, 3, 4).get_if<double>()));

  EXPECT_EQ(param(f, 4, 0).boolean(), true);
  EXPECT_EQ(param(f, 4, 1).boolean(), false);
  EXPECT_EQ(param(f, 4, 2).boolean(), std::nullopt);
  EXPECT_TRUE(param(f, 4, 2).is_enumeration("U"));
  EXPECT_TRUE(param(f, 4, 3).is_enumeration("UNSPECIFIED"));
  EXPECT_TRUE(param(f, 4, 4).is_enumeration("PIECEWISE_BEZIER_KNOTS"));  // upper-cased leniently

  EXPECT_EQ(param(f, 5, 0), typed("PARAMETER_VALUE", 0.5));
  EXPECT_EQ(param(f, 5, 1), typed("LENGTH_MEASURE", 2.0));
  EXPECT_EQ(param(f, 5, 2), list({typed("POSITIVE_LENGTH_MEASURE", 1.0), typed("COUNT_MEASURE", std::int64_t{3})}));

  EXPECT_EQ(param(f, 6, 0), list({list({std::int64_t{1}, std::int64_t{2}}), list({std::int64_t{3}, std::int64_t{4}})}));
  EXPECT_EQ(param(f, 6, 1), list({}));
  EXPECT_EQ(param(f, 6, 2), list({list({list({})})}));
  EXPECT_EQ(param(f, 6, 3), list({reference(2), reference(1)}));

  EXPECT_EQ(param(f, 7, 0), Binary{"0FF"});
  EXPECT_EQ(param(f, 7, 1), Binary{"1C"});
  EXPECT_EQ(param(f, 7, 2), Binary{"0"});
  EXPECT_EQ(param(f, 7, 3), Binary{"3ABC"});

  const Instance& c = f.at(8);
  EXPECT_TRUE(c.complex);
  ASSERT_EQ(c.records.size(), 3u);
  EXPECT_EQ(c.records[1].keyword, "GLOBAL_UNIT_ASSIGNED_CONTEXT");
  ASSERT_NE(c.record("REPRESENTATION_CONTEXT"), nullptr);
  EXPECT_EQ(c.record("REPRESENTATION_CONTEXT")->params[1], Parameter(std::string("3D")));
  EXPECT_EQ(c.type_name(), "GEOMETRIC_REPRESENTATION_CONTEXT+GLOBAL_UNIT_ASSIGNED_CONTEXT+REPRESENTATION_CONTEXT");

  EXPECT_EQ(f.at(9).records[0].keyword, "!VENDOR_THING");

  const std::vector<Parameter> strings = {
      std::string(""),         std::string("it's"),  std::string("back\\slash"),    std::string("\xC3\x84"),
      std::string("\xC4\x84"), std::string("\xC3\xA9t\xC3\xA9"), std::string("\xCE\xB1\xCE\xB2"),
      std::string("\xF0\x9F\x98\x80"), std::string("linebreak")};
  EXPECT_EQ(f.at(10).records[0].params, strings);

  EXPECT_TRUE(f.at(11).complex);
  EXPECT_TRUE(f.at(11).records[0].params.empty());
  EXPECT_EQ(param(f, 20, 1), reference(10));
  EXPECT_TRUE(f.at(21).records[0].params.empty());
}

TEST(StepParser, StreamingWithTinyChunksMatchesWholeText) {
  const std::string text = test::slurp_file(step_data("grammar.stp"));
  const ExchangeFile whole = parse_exchange_file(text, "grammar.stp");
  for (std::size_t chunk : {1u, 2u, 3u, 7u, 64u}) {
    std::istringstream in(text);
    ReadOptions o;
    o.chunk_size = chunk;
    const ExchangeFile streamed = read_exchange_file(in, "grammar.stp", o);
    EXPECT_EQ(streamed.instances(), whole.instances()) << chunk;
    for (std::size_t k = 0; k < whole.size(); ++k) {
      EXPECT_EQ(streamed.instances()[k].line, whole.instances()[k].line);
      EXPECT_EQ(streamed.instances()[k].column, whole.instances()[k].column);
    }
  }
}

TEST(StepParser, FilterKeepsChosenKeywordsAndCountsTheRest) {
  ReadOptions o;
  o.keep = [](std::string_view k) { return k == "CARTESIAN_POINT" || k == "B_SPLINE_VOLUME"; };
  const ExchangeFile f = read_exchange_file(step_data("volume.stp"), o);
  EXPECT_EQ(f.size(), 9u);  // 8 points and the complex rational volume (kept through one partial record)
  EXPECT_TRUE(f.at(11).complex);
  EXPECT_EQ(f.find(10), nullptr);
  EXPECT_TRUE(f.is_skipped(10));
  EXPECT_TRUE(f.is_skipped(21));
  EXPECT_FALSE(f.is_skipped(1));
  EXPECT_FALSE(f.is_skipped(99));
  EXPECT_EQ(f.skipped(), (std::map<std::string, std::size_t>{
                             {"B_SPLINE_VOLUME_WITH_KNOTS", 1}, {"GEOMETRIC_REPRESENTATION_CONTEXT", 1}, {"REPRESENTATION", 1}}));
  EXPECT_EQ(f.skipped_total(), 3u);
  // A kept instance referring to a dropped one is fine; the reference check knows the dropped ids.
  ReadOptions only_representation;
  only_representation.keep = [](std::string_view k) { return k == "REPRESENTATION"; };
  EXPECT_NO_THROW(read_exchange_file(step_data("volume.stp"), only_representation));
}

TEST(StepParser, DroppedInstancesWithTrickyBodiesAreSkippedExactly) {
  // Semicolons and comment markers inside strings, comments inside the body, line breaks for line counting.
  const std::string text = step_file(
      "#1=DROP('a;b''c;', /* ; */ \"0F\", (1,\n2));\n#2=KEEP(#1);\n#3=DROP('/*');\n#4=KEEP(#3);");
  ReadOptions o;
  o.keep = [](std::string_view k) { return k == "KEEP"; };
  const ExchangeFile f = parse_exchange_file(text, "t.stp", o);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f.at(2).line, 10u);
  EXPECT_EQ(f.at(4).line, 12u);
}

TEST(StepParser, VolumeExampleFromTheFormatNotes) {
  const ExchangeFile f = read_exchange_file(step_data("volume.stp"));
  EXPECT_EQ(f.size(), 12u);
  const Instance& v = f.at(11);
  ASSERT_TRUE(v.complex);
  const Record* w = v.record("RATIONAL_B_SPLINE_VOLUME");
  ASSERT_NE(w, nullptr);
  const auto& weights = w->params[0].get_if<List>()->items;
  EXPECT_EQ(weights[1].get_if<List>()->items[0].get_if<List>()->items[1], Parameter(0.5));
  EXPECT_EQ(v.record("REPRESENTATION_ITEM")->params[0], Parameter(std::string()));
  EXPECT_TRUE(v.record("VOLUME")->params.empty());
}

TEST(StepParser, ReferenceCheckCanBeDeferred) {
  const std::string text = step_file("#1=A(#2);");
  EXPECT_THROW(parse_exchange_file(text), Error);
  ReadOptions o;
  o.check_references = false;
  const ExchangeFile f = parse_exchange_file(text, "t", o);
  EXPECT_THROW(f.check_references("t"), Error);
}

TEST(StepParser, MissingFileNamesThePath) {
  try {
    read_exchange_file("/nonexistent/x.stp");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.stp"), std::string::npos);
  }
}

TEST(StepParser, CompactPointsKeepTheirCoordinatesAndCannotBeWritten) {
  const std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
      "FILE_SCHEMA(('X'));\nENDSEC;\nDATA;\n#3=CARTESIAN_POINT('',(1.5,-2.,3));\n#1=CARTESIAN_POINT('',(0.25));\n"
      "#2=CARTESIAN_POINT('named',(1.,2.,3.));\n#4=LINE('',#3,#2);\nENDSEC;\nEND-ISO-10303-21;\n";
  ReadOptions o;
  o.compact_points = true;
  const ExchangeFile f = parse_exchange_file(text, "t.stp", o);
  EXPECT_EQ(f.point_count(), 2u);
  ASSERT_NE(f.point(3), nullptr);
  EXPECT_EQ(f.point(3)->dimension, 3);
  EXPECT_EQ(f.point(3)->coordinates, (std::array<double, 3>{1.5, -2.0, 3.0}));  // the integer 3 as a number
  ASSERT_NE(f.point(1), nullptr);  // found although read after #3
  EXPECT_EQ(f.point(1)->dimension, 1);
  EXPECT_EQ(f.point(1)->coordinates[0], 0.25);
  EXPECT_EQ(f.find(3), nullptr);
  EXPECT_EQ(f.point(2), nullptr);  // a name is kept: a generic instance
  ASSERT_NE(f.find(2), nullptr);
  EXPECT_EQ(f.size(), 2u);
  std::ostringstream out;
  EXPECT_THROW(write_exchange_file(out, f), Error);  // the points' references would dangle
}
