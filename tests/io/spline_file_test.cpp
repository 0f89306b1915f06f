#include "trivar/io/spline_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/io_test_support.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

using test::slurp;

struct Malformed {
  const char* file;
  const char* message;  // expected right after "<path>"
};

// Every malformed file fails with one line naming the file (and, for g2, the line) and the problem.
const Malformed kMalformed[] = {
    {"g2_unsupported_class.g2", ":1: unsupported class type 210"},
    {"g2_truncated_header.g2", ":1: truncated file: expected number of auxiliary values"},
    {"g2_bad_ncoef.g2", ":5: expected 'ncoef order' for direction v, found 'x'"},
    {"g2_bad_knots.g2", ":4: invalid knot vector in direction u: knot vector: knot 2"},
    {"g2_non_numeric.g2", ":6: expected value 2 of coefficient 2 of 2 (3 values each)"},
    {"g2_truncated_coefs.g2", ":6: truncated file: expected value 1 of coefficient 3 of 3"},
    {"g2_too_many_values.g2", ":6: more values than expected: the line goes on after the last coefficient"},
    {"g2_trailing_garbage.g2", ":7: expected an object header 'classType major minor nAux'"},
    {"g2_nonpositive_weight.g2", ":6: non-positive weight -1 of coefficient 2 of SplineCurve (object 1)"},
    {"g2_bad_rational_flag.g2", ":2: rational flag of SplineCurve (object 1) must be 0 or 1, got 2"},
    {"g2_order_zero.g2", ":3: direction u: order must be >= 1"},
    {"g2_nan.g2",
     ":5: expected value 3 of coefficient 1 of 2 (3 values each) of SplineCurve (object 1) (a finite "
     "number), found 'nan'"},
    {"g2_bad_version.g2", ":1: unsupported g2 version 2.0"},
    {"g2_empty.g2", ":1: no objects found"},
    {"g2_zero_dim.g2", ":2: control dimension of SplineCurve (object 1) must be >= 1"},
    {"g2_missing_coefficient.g2",
     ":14: more values than expected: the line goes on after the last coefficient of "
     "SplineCurve (object 2), which has 2 coefficients"},
    {"json_syntax_error.json", ": invalid JSON: parse error at line 3"},
    {"json_missing_trivar.json", ": missing key \"trivar\""},
    {"json_wrong_version.json", ": trivar: unsupported format version 2"},
    {"json_bad_kind.json", ": kind: expected \"curve\", \"surface\" or \"volume\", got \"solid\""},
    {"json_knot_not_number.json", ": knots[0][2]: expected a number, got string"},
    {"json_wrong_point_count.json", ": control_points: expected 2 entries, got 3"},
    {"json_point_wrong_dim.json", ": control_points[1]: expected 2 entries, got 3"},
    {"json_missing_weights.json", ": missing key \"weights\""},
    {"json_nonpositive_weight.json", ": weights[1]: weights must be positive"},
    {"json_weights_not_rational.json", ": weights: present but \"rational\" is false"},
    {"json_bad_knot_vector.json", ": knots[1]: invalid knot vector in direction v: knot vector: knot 2"},
    {"json_unknown_key.json", ": unexpected key \"degree\""},
    {"json_empty_objects.json", ": objects: expected a non-empty array"},
    {"json_trailing_garbage.json", ": invalid JSON: parse error at line 2"},
    {"json_bad_object_entry.json", ": objects[1]: degrees[0]: expected an integer, got 1.5"},
    {"json_not_an_object.json", ": expected a JSON object, got array"},
    {"json_zero_dim.json", ": dim: expected an integer >= 1, got 0"},
    {"json_overflow.json", ": invalid JSON: number overflow parsing '1e999'"},
};

}  // namespace

TEST(SplineFile, MalformedFilesFailWithAOneLineMessageNamingTheFile) {
  for (const Malformed& m : kMalformed) {
    const std::string path = std::string(TRIVAR_TEST_DATA "/io/malformed/") + m.file;
    try {
      io::read_spline_file(path);
      ADD_FAILURE() << m.file << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path + m.message, 0), 0u) << m.file << ": " << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(SplineFile, DispatchesByExtension) {
  test::TempDir dir;
  const auto objects = test::random_objects(false, 31);
  for (const char* name : {"a.json", "b.G2", "c.JSON", "d.g2"}) {
    io::write_spline_file(dir.file(name), objects);
    const auto back = io::read_spline_file(dir.file(name));
    ASSERT_EQ(back.size(), objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) test::expect_identical(objects[i], back[i]);
  }
  EXPECT_EQ(slurp(dir.file("b.G2")).substr(0, 10), "100 1 0 0\n");
  EXPECT_EQ(slurp(dir.file("a.json")).substr(0, 15), "{\n  \"trivar\": 1");

  io::write_spline_file(dir.file("e.vtu"), objects);
  const std::string vtu = slurp(dir.file("e.vtu"));
  std::size_t pieces = 0;
  for (std::size_t p = vtu.find("<Piece "); p != std::string::npos; p = vtu.find("<Piece ", p + 1)) ++pieces;
  EXPECT_EQ(pieces, objects.size());

  try {
    io::read_spline_file(dir.file("e.vtu"));
    ADD_FAILURE() << "read a .vtu";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir.file("e.vtu") + ": .vtu is an output-only format; read .json, .g2, .lr, .stp, .step, .p21 or .xml");
  }
  EXPECT_THROW(io::read_spline_file(dir.file("f.stl")), Error);
  EXPECT_THROW(io::write_spline_file(dir.file("f.stl"), objects), Error);
  EXPECT_THROW(io::read_spline_file(dir.file("missing.g2")), Error);
  EXPECT_THROW(io::read_spline_file(dir.file("missing.json")), Error);
}

TEST(SplineFile, FailedWritesLeaveNothingBehind) {
  test::TempDir dir;
  const auto objects = test::random_objects(true, 32);
  for (const char* name : {"x.json", "x.g2", "x.vtu"}) {
    // Missing directory.
    EXPECT_THROW(io::write_spline_file(dir.file(std::string("no_such_dir/") + name), objects), Error) << name;
    // A spline that cannot be written, last in the list.
    std::vector<AnySpline> bad = objects;
    bad.emplace_back();
    EXPECT_THROW(io::write_spline_file(dir.file(name), bad), Error) << name;
  }
  EXPECT_EQ(dir.entries(), 0);

  // A failed write does not touch an existing file.
  io::write_spline_file(dir.file("keep.g2"), objects);
  const std::string before = slurp(dir.file("keep.g2"));
  EXPECT_THROW(io::write_spline_file(dir.file("keep.g2"), {objects[0], AnySpline{}}), Error);
  EXPECT_EQ(slurp(dir.file("keep.g2")), before);
  EXPECT_EQ(dir.entries(), 1);
}
