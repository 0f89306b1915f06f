// The malformed corpus (tests/data/step/malformed): each file fails with one line naming file, line,
// column, the instance when there is one, and what was wrong.
#include <gtest/gtest.h>

#include <filesystem>

#include "step/step_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/step/parser.hpp"

using namespace trivar;
using namespace trivar::io::step;

namespace {

struct Case {
  const char* file;
  const char* where;  // line:column
  const char* message;
};

// Positions counted by hand in the files; every file has a 7-line header before its first instance.
const Case cases[] = {
    {"truncated_instance.stp", "9:1", "#1: expected a parameter, found end of file"},
    {"truncated_no_end.stp", "9:1", "expected an instance or ENDSEC, found end of file"},
    {"bad_escape.stp", "8:9", "#1: bad string escape at character 2"},
    {"bad_x2_escape.stp", "8:9", "#1: bad string escape at character 1"},
    {"unterminated_x2.stp", "8:9", "#1: bad string escape at character 1"},
    {"dangling_reference.stp", "9:1", "#2: VERTEX_POINT refers to undefined instance #7"},
    {"duplicate_id.stp", "10:1", "#1: duplicate instance id (first defined at line 8)"},
    {"unterminated_string.stp", "8:9", "#1: unterminated string"},
    {"unterminated_comment.stp", "8:1", "unterminated comment"},
    {"bad_token.stp", "8:12", "#1: unexpected '%'"},
    {"missing_paren.stp", "8:14", "#1: expected ',' or ')', found ';'"},
    {"missing_semicolon.stp", "9:1", "#1: expected ';', found an instance name"},
    {"bad_number.stp", "8:9", "#1: malformed number '1.2.3'"},
    {"integer_overflow.stp", "8:9", "#1: number out of range '99999999999999999999'"},
    {"real_overflow.stp", "8:9", "#1: number out of range '1.E400'"},
    {"bad_enumeration.stp", "8:9", "#1: malformed enumeration"},
    {"bad_binary.stp", "8:9", "#1: malformed binary \"4F\""},
    {"empty_complex.stp", "8:5", "#1: expected a partial record, found ')'"},
    {"zero_id.stp", "8:1", "bad instance name #0"},
    {"lone_slash.stp", "8:13", "#1: unexpected '/'"},
    {"deep_nesting.stp", "8:74", "#1: parameters nested deeper than 64"},
    {"no_data.stp", "5:17", "no DATA section"},
    {"missing_header_semicolon.stp", "2:1", "expected ';', found a keyword (HEADER)"},
    {"empty.stp", "1:1", "expected ISO-10303-21, found end of file"},
    {"bad_header_type.stp", "3:1", "FILE_NAME: name must be a string"},
    {"unterminated_anchor.stp", "10:1", "section without ENDSEC;"},
    {"hyphen_keyword.stp", "8:4", "#1: bad keyword 'BAD-NAME'"},
};

}  // namespace

TEST(StepMalformed, EachFileFailsWithAOneLinePositionedMessage) {
  for (const Case& c : cases) {
    const std::string path = test::step_data(std::string("malformed/") + c.file);
    const std::string expected = path + ":" + c.where + ": " + c.message;
    try {
      read_exchange_file(path);
      ADD_FAILURE() << c.file << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(expected, 0), 0u) << c.file << "\n  got:      " << what << "\n  expected: " << expected;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(StepMalformed, CorpusIsCompletelyListed) {
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(test::step_data("malformed"))) ++files;
  EXPECT_EQ(files, std::size(cases));
}

TEST(StepMalformed, ErrorsInDroppedInstancesAreNotReported) {
  // Documented trade-off of the fast skip path: only the kept part is tokenised.
  ReadOptions o;
  o.keep = [](std::string_view k) { return k != "NAME"; };
  EXPECT_NO_THROW(read_exchange_file(test::step_data("malformed/bad_number.stp"), o));
  // Structural errors that the skip path does see still fail.
  EXPECT_THROW(read_exchange_file(test::step_data("malformed/truncated_instance.stp"), o), Error);
  EXPECT_THROW(read_exchange_file(test::step_data("malformed/duplicate_id.stp"), o), Error);
}
