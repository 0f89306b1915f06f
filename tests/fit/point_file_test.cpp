// Point files: text / CSV with comments and a header, the binary format (round trip, every byte of the header
// checked), and one-line errors for bad input. Also the pictures of a fit.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "trivar/core/error.hpp"
#include "trivar/fit/height_image.hpp"
#include "trivar/fit/least_squares.hpp"
#include "trivar/fit/lr_approximation.hpp"
#include "trivar/fit/point_file.hpp"

namespace trivar {
namespace {

std::string message_of(std::string_view text) {
  try {
    parse_point_bytes(text, "pts.xyz");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PointFile, TextWithHeaderCommentsAndSeparators) {
  const PointTable t = parse_point_bytes("x,y,z\n# survey 7\n1,2,3\n\n 4 5\t6 # a comment\n7;8;+9e0\r\n", "a.csv");
  ASSERT_EQ(t.columns, 3);
  EXPECT_EQ(t.values, (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST(PointFile, TextErrorsNameTheLine) {
  EXPECT_NE(message_of("1 2 3\n4 5\n").find("line 2: 2 numbers, the rows before have 3"), std::string::npos);
  EXPECT_NE(message_of("1 2 3\n4 x 6\n").find("line 2: 'x' is not a number"), std::string::npos);
  EXPECT_NE(message_of("1 2 3\n4 nan 6\n").find("line 2: 'nan' is not a finite number"), std::string::npos);
  EXPECT_NE(message_of("1 2 inf\n").find("line 1"), std::string::npos);
  EXPECT_NE(message_of("").find("no points"), std::string::npos);
  EXPECT_NE(message_of("# only a comment\nx y z\n").find("no points"), std::string::npos);
}

TEST(PointFile, BinaryRoundTripAndTruncation) {
  const std::string path = ::testing::TempDir() + "trivar_points.tvp";
  PointTable t;
  t.columns = 4;
  for (int i = 0; i < 40; ++i) t.values.push_back(i * 0.25 - 3);
  write_point_file(path, t);
  const PointTable r = read_point_file(path);
  EXPECT_EQ(r.columns, 4);
  EXPECT_EQ(r.values, t.values);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 24u + 8u * 40u);
  EXPECT_EQ(bytes.substr(0, 8), "TRIVARPT");
  EXPECT_EQ(bytes[8], 4);   // columns, little-endian
  EXPECT_EQ(bytes[16], 10); // rows
  EXPECT_THROW(parse_point_bytes(std::string_view(bytes).substr(0, bytes.size() - 1), "b"), Error);
  std::string bad = bytes;
  bad[8] = 0;
  EXPECT_THROW(parse_point_bytes(bad, "b"), Error);
  // A row count whose byte size does not fit in 64 bits (found by the fuzz target): one line, no overflow.
  bad = bytes;
  for (int i = 16; i < 24; ++i) bad[static_cast<std::size_t>(i)] = static_cast<char>(0xff);
  try {
    parse_point_bytes(bad, "b");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("needs more than 2^64 bytes"), std::string::npos) << e.what();
  }
  bad = bytes;
  bad[24 + 7] = static_cast<char>(0x7f);  // first number's exponent all ones, mantissa non-zero: NaN
  bad[24 + 6] = static_cast<char>(0xf8);
  EXPECT_THROW(parse_point_bytes(bad, "b"), Error);
  std::filesystem::remove(path);
  EXPECT_THROW(read_point_file(path), Error);
}

TEST(PointFile, TableToDataChecksColumns) {
  PointTable t;
  t.columns = 2;
  t.values = {0, 0, 1, 1, 2, 0};
  EXPECT_THROW(scattered_data<2>(t, "p"), Error);
  t.columns = 3;
  t.values = {0, 0, 1, 1, 0, 2, 0, 1, 3, 1, 1, 4};
  const ScatteredData<2> d = scattered_data<2>(t, "p");
  EXPECT_EQ(d.size(), 4u);
  EXPECT_EQ(d.dim, 1);
  EXPECT_EQ(d.value(3)[0], 4.0);
}

TEST(FitPictures, HeightAndErrorColours) {
  // A plane rising to the east: the west column is the lowest colour, the east the highest.
  ScatteredData<2> d;
  d.dim = 1;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 10; ++j) {
      d.params.push_back({i * 0.1, j * 0.1});
      d.values.push_back(i * 0.1);
    }
  ApproximationOptions o;
  o.tolerance = 1e-6;
  const Approximation<2> a = approximate(d, o);
  const LayerImage<std::uint8_t> img = height_image(a.spline, 100);
  EXPECT_EQ(img.width(), 100);
  EXPECT_EQ(img.height(), 50);
  // Slope 1 exaggerated by 0.2 * 2 / 1.98 (width over the pixel centres' height range), lit from the north-west:
  // Lambert factor (0.202 * 0.5 + 0.7071) / |(-0.202, 0, 1)| = 0.7921, shade 0.55 + 0.45 * 0.7921 = 0.9065.
  const double shade = 0.55 + 0.45 * ((0.2 * 2 / 1.98) * 0.5 + 0.7071067811865476) / std::hypot(0.2 * 2 / 1.98, 1.0);
  EXPECT_NEAR(img(0, 25, 2), 0.6 * 255 * shade, 1.0);  // the lowest colour (0.2, 0.3, 0.6)
  EXPECT_NEAR(img(99, 25, 0), 255 * shade, 1.0);       // the highest: white
  std::vector<double> err(d.size(), 0.0);
  err[0] = 2.0;  // the south-west corner point outside the tolerance 1
  const LayerImage<std::uint8_t> e = error_image(d, err, 1.0, 21);
  EXPECT_EQ(e(0, 0, 0), 115);  // purple
  EXPECT_EQ(e(0, 0, 1), 0);
  EXPECT_EQ(e(20, 10, 0), 255);  // white: error 0
  EXPECT_EQ(e(20, 10, 2), 255);
  EXPECT_THROW(height_image(a.spline, 0), Error);
}

}  // namespace
}  // namespace trivar
