// The writer: exact header text, deterministic numbering, alphabetical partial records, escaped strings,
// and parse -> write -> parse round trips that are equal value for value (reals bit for bit).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <filesystem>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "step/step_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/writer.hpp"

using namespace trivar;
using namespace trivar::io::step;

namespace {

WriteOptions fixed_options() {
  WriteOptions o;
  o.time_stamp = "2026-02-03T04:05:06";
  o.version = "9.9.9";
  return o;
}

std::string write_text(const ExchangeFile& f, const WriteOptions& o = fixed_options()) {
  std::ostringstream s;
  write_exchange_file(s, f, o);
  return s.str();
}

}  // namespace

TEST(StepWriter, HeaderAndBodyText) {
  ExchangeFile f;
  f.header.description = {"trivar test"};
  f.header.name = "out.stp";
  f.header.author = {"A. Uthor"};
  f.header.organization = {"Org"};
  f.header.originating_system = "trivar";
  f.header.schemas = {"AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }"};
  const std::uint64_t p = f.add({"CARTESIAN_POINT", {std::string("o'k"), list({0.0, 0.5, -1e-300})}});
  f.add_complex({{"REPRESENTATION_ITEM", {std::string("")}}, {"GEOMETRIC_REPRESENTATION_ITEM", {}},
                 {"B_SPLINE_CURVE", {std::int64_t{1}, list({reference(p), reference(p)}), enumeration("UNSPECIFIED"),
                                     enumeration("F"), enumeration("U")}}});
  f.add({"MISC", {Unset{}, Derived{}, Binary{"0FF"}, typed("PARAMETER_VALUE", 1.0), std::string("\xC3\xA9")}});
  WriteOptions wide = fixed_options();
  wide.line_width = 200;  // wrapping is tested below
  EXPECT_EQ(write_text(f, wide),
            "ISO-10303-21;\n"
            "HEADER;\n"
            "FILE_DESCRIPTION(('trivar test'),'2;1');\n"
            "FILE_NAME('out.stp','2026-02-03T04:05:06',('A. Uthor'),('Org'),'trivar 9.9.9','trivar','');\n"
            "FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }'));\n"
            "ENDSEC;\n"
            "DATA;\n"
            "#1=CARTESIAN_POINT('o''k',(0.,0.5,-1.E-300));\n"
            "#2=(B_SPLINE_CURVE(1,(#1,#1),.UNSPECIFIED.,.F.,.U.)GEOMETRIC_REPRESENTATION_ITEM()REPRESENTATION_ITEM(''));\n"
            "#3=MISC($,*,\"0FF\",PARAMETER_VALUE(1.),'\\X2\\00E9\\X0\\');\n"
            "ENDSEC;\n"
            "END-ISO-10303-21;\n");
}

TEST(StepWriter, TimeStampDefaultsToNowInIso8601) {
  ExchangeFile f;
  f.header.schemas = {"S"};
  const std::string text = write_text(f, WriteOptions{});
  const std::string now = iso8601_now();
  ASSERT_EQ(now.size(), 19u);
  EXPECT_EQ(now[4], '-');
  EXPECT_EQ(now[10], 'T');
  EXPECT_NE(text.find("'" + now.substr(0, 10)), std::string::npos);  // same day (a midnight race is harmless)
  EXPECT_NE(text.find(std::string("'trivar ") + TRIVAR_VERSION + "'"), std::string::npos);
}

TEST(StepWriter, RenumbersInInsertionOrder) {
  ExchangeFile f;
  f.header.schemas = {"S"};
  f.insert({50, {{"B", {reference(7)}}}, false});
  f.insert({7, {{"A", {reference(50)}}}, false});
  const std::string text = write_text(f);
  EXPECT_NE(text.find("#1=B(#2);\n#2=A(#1);\n"), std::string::npos) << text;
  WriteOptions keep = fixed_options();
  keep.renumber = false;
  EXPECT_NE(write_text(f, keep).find("#50=B(#7);\n#7=A(#50);\n"), std::string::npos);
}

TEST(StepWriter, LongInstancesAreWrappedAtCommasAndReadBack) {
  ExchangeFile f;
  f.header.schemas = {"S"};
  std::vector<Parameter> many;
  for (int k = 0; k < 500; ++k) many.emplace_back(0.1 * k);
  f.add({"LONG", {list(many), std::string(300, 'x')}});
  const std::string text = write_text(f);
  std::istringstream lines(text);
  std::size_t longest = 0;
  for (std::string line; std::getline(lines, line);) longest = std::max(longest, line.size());
  EXPECT_LE(longest, 310u);  // the 300-character string stays whole; everything else wraps near 80
  const ExchangeFile g = parse_exchange_file(text);
  EXPECT_EQ(g.instances(), f.instances());
}

TEST(StepWriter, RejectsWhatP21CannotExpress) {
  ExchangeFile f;
  f.header.schemas = {"S"};
  f.add({"X", {std::numeric_limits<double>::quiet_NaN()}});
  EXPECT_THROW(write_text(f), Error);
  ExchangeFile g;
  g.header.schemas = {"S"};
  g.add({"lower", {}});
  EXPECT_THROW(write_text(g), Error);
  ExchangeFile h;
  h.header.schemas = {"S"};
  h.add({"X", {reference(99)}});
  EXPECT_THROW(write_text(h), Error);
  ExchangeFile no_schema;
  EXPECT_THROW(write_text(no_schema), Error);
}

TEST(StepWriter, RoundTripOfTheGrammarFile) {
  const ExchangeFile a = read_exchange_file(test::step_data("grammar.stp"));
  WriteOptions o = fixed_options();
  o.renumber = false;  // ids kept, so instances compare directly
  const std::string text = write_text(a, o);
  const ExchangeFile b = parse_exchange_file(text, "written");
  EXPECT_EQ(b.instances().size(), a.instances().size());
  for (const Instance& i : a.instances()) {
    ASSERT_NE(b.find(i.id), nullptr);
    Instance sorted = i;  // the writer puts partial records in alphabetical order
    std::sort(sorted.records.begin(), sorted.records.end(), [](const Record& x, const Record& y) { return x.keyword < y.keyword; });
    EXPECT_EQ(*b.find(i.id), sorted) << i.id;
  }
  EXPECT_EQ(b.header.description, a.header.description);
  EXPECT_EQ(b.header.author, a.header.author);
  EXPECT_EQ(b.header.schemas, a.header.schemas);
  EXPECT_EQ(b.header.extra, a.header.extra);
  EXPECT_EQ(b.header.preprocessor_version, "trivar 9.9.9");
  // Renumbered output is a fixed point: writing what was read gives the same text.
  const std::string once = write_text(a);
  EXPECT_EQ(write_text(parse_exchange_file(once)), once);
}

TEST(StepWriter, RandomDoublesRoundTripBitExact) {
  std::mt19937_64 rng(4);
  ExchangeFile f;
  f.header.schemas = {"S"};
  std::vector<double> values = {std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::lowest(), std::numeric_limits<double>::min(), -0.0};
  while (values.size() < 20000) {
    const double x = std::bit_cast<double>(rng());
    if (std::isfinite(x)) values.push_back(x);
  }
  for (std::size_t k = 0; k < values.size(); k += 100) {
    std::vector<Parameter> row(values.begin() + static_cast<std::ptrdiff_t>(k),
                               values.begin() + static_cast<std::ptrdiff_t>(std::min(values.size(), k + 100)));
    f.add({"ROW", {list(row)}});
  }
  const ExchangeFile g = parse_exchange_file(write_text(f));
  std::size_t n = 0;
  for (const Instance& i : g.instances())
    for (const Parameter& p : i.records[0].params[0].get_if<List>()->items) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(*p.get_if<double>()), std::bit_cast<std::uint64_t>(values[n])) << n;
      ++n;
    }
  EXPECT_EQ(n, values.size());
}

TEST(StepWriter, RandomStringsRoundTrip) {
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> len(0, 30), pick(0, 9);
  ExchangeFile f;
  f.header.schemas = {"S"};
  std::vector<std::string> strings;
  for (int k = 0; k < 300; ++k) {
    std::string s;
    for (int c = len(rng); c > 0; --c) {
      static const char32_t pool[] = {'a', '\'', '\\', ' ', '\n', 0xE9, 0x3B1, 0x20AC, 0x1F600, 0x10FFFF};
      const char32_t cp = pool[pick(rng)];
      if (cp < 0x80) s += static_cast<char>(cp);
      else if (cp < 0x800) s += {static_cast<char>(0xC0 | (cp >> 6)), static_cast<char>(0x80 | (cp & 0x3F))};
      else if (cp < 0x10000)
        s += {static_cast<char>(0xE0 | (cp >> 12)), static_cast<char>(0x80 | ((cp >> 6) & 0x3F)), static_cast<char>(0x80 | (cp & 0x3F))};
      else
        s += {static_cast<char>(0xF0 | (cp >> 18)), static_cast<char>(0x80 | ((cp >> 12) & 0x3F)),
              static_cast<char>(0x80 | ((cp >> 6) & 0x3F)), static_cast<char>(0x80 | (cp & 0x3F))};
    }
    strings.push_back(s);
    f.add({"S", {s}});
  }
  const ExchangeFile g = parse_exchange_file(write_text(f));
  for (std::size_t k = 0; k < strings.size(); ++k) EXPECT_EQ(*g.instances()[k].records[0].params[0].get_if<std::string>(), strings[k]);
}

TEST(StepWriter, WritesFilesAtomically) {
  const std::string path = std::filesystem::temp_directory_path() / ("trivar_step_writer_" + std::to_string(::getpid()) + ".stp");
  ExchangeFile bad;
  bad.header.schemas = {"S"};
  bad.add({"X", {std::numeric_limits<double>::infinity()}});
  EXPECT_THROW(write_exchange_file(path, bad, fixed_options()), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
  const ExchangeFile good = read_exchange_file(test::step_data("volume.stp"));
  write_exchange_file(path, good, fixed_options());
  EXPECT_EQ(read_exchange_file(path).instances().size(), good.size());
  std::filesystem::remove(path);
}
