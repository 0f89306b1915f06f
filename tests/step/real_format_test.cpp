// Reals in P21 form: always a decimal point, E exponent, and the shortest text that reads back bit-exact.
#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <limits>
#include <random>

#include "trivar/core/error.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/real_format.hpp"

using namespace trivar;
using namespace trivar::io::step;

TEST(StepRealFormat, P21Shapes) {
  EXPECT_EQ(format_real(1.0), "1.");
  EXPECT_EQ(format_real(0.5), "0.5");
  EXPECT_EQ(format_real(-0.0), "-0.");
  EXPECT_EQ(format_real(100.0), "100.");
  EXPECT_EQ(format_real(1e300), "1.E300");
  EXPECT_EQ(format_real(1e-300), "1.E-300");
  EXPECT_EQ(format_real(2.5e-7), "2.5E-7");
  EXPECT_EQ(format_real(0.1), "0.1");
  EXPECT_THROW(format_real(std::numeric_limits<double>::infinity()), Error);
  EXPECT_THROW(format_real(std::nan("")), Error);
}

// Every value goes through the real P21 reader (not from_chars alone), so the lexer's number path is checked.
TEST(StepRealFormat, BitExactThroughTheReader) {
  std::vector<double> values = {0.0, -0.0, 1.0, 0.1, 1.0 / 3.0, std::numeric_limits<double>::max(),
                                -std::numeric_limits<double>::max(), std::numeric_limits<double>::min(),
                                std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
                                std::nextafter(std::numeric_limits<double>::min(), 0.0), 5e-324, 1e-310, 1e23, 9007199254740993.0};
  std::mt19937_64 rng(21);
  for (int k = 0; k < 3000; ++k) {  // random bit patterns cover all exponents, subnormals included
    const double x = std::bit_cast<double>(rng());
    if (std::isfinite(x)) values.push_back(x);
  }
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int k = 0; k < 1000; ++k) values.push_back(unit(rng));
  std::string data = "#1=R((";
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) data += ',';
    data += format_real(values[k]);
  }
  data += "));";
  const std::string text = "ISO-10303-21;HEADER;ENDSEC;DATA;" + data + "ENDSEC;END-ISO-10303-21;";
  const ExchangeFile f = parse_exchange_file(text);
  const auto& items = f.at(1).records[0].params[0].get_if<List>()->items;
  ASSERT_EQ(items.size(), values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    ASSERT_EQ(items[k].kind(), Kind::real) << format_real(values[k]);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(*items[k].get_if<double>()), std::bit_cast<std::uint64_t>(values[k]))
        << format_real(values[k]);
  }
}
