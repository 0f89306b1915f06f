#include "trivar/model/expression.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "trivar/core/error.hpp"
#include "trivar/spline/simd_level.hpp"

using namespace trivar;

namespace {

double value(const char* text, std::vector<double> vars = {}, std::vector<std::string> names = {}) {
  return Expression::parse(text, std::move(names)).eval(vars);
}

std::string error_of(const char* text) {
  try {
    Expression::parse(text, {"x", "y", "z"});
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Expression, PrecedenceAndAssociativityFollowMathematics) {
  EXPECT_EQ(value("1+2*3"), 7.0);
  EXPECT_EQ(value("(1+2)*3"), 9.0);
  EXPECT_EQ(value("10/4"), 2.5);
  EXPECT_EQ(value("8-3-2"), 3.0);          // left associative
  EXPECT_EQ(value("16/4/2"), 2.0);
  EXPECT_EQ(value("2^3^2"), 512.0);        // right associative: 2^9
  EXPECT_EQ(value("-2^2"), -4.0);          // unary minus binds looser than ^
  EXPECT_EQ(value("2^-1"), 0.5);
  EXPECT_EQ(value("2*-3"), -6.0);
  EXPECT_EQ(value("--3"), 3.0);
  EXPECT_EQ(value("+4"), 4.0);
  EXPECT_EQ(value("1.5e2 + .5 + 2E-1"), 150.7);
}

TEST(Expression, FunctionsAndConstantsMatchTheStandardLibrary) {
  const double pi = std::numbers::pi;
  EXPECT_NEAR(value("sin(pi/2)"), 1.0, 1e-15);
  EXPECT_NEAR(value("cos(pi)"), -1.0, 1e-15);
  EXPECT_NEAR(value("tan(pi/4)"), 1.0, 1e-15);
  EXPECT_NEAR(value("log(exp(1.5))"), 1.5, 1e-15);
  EXPECT_EQ(value("sqrt(16)+abs(-3)"), 7.0);
  EXPECT_EQ(value("pow(2, 10)"), 1024.0);
  EXPECT_NEAR(value("atan2(1, -1)"), 0.75 * pi, 1e-15);
  EXPECT_EQ(value("max(1, 5, 3)"), 5.0);
  EXPECT_EQ(value("min(2, -1)"), -1.0);
  EXPECT_EQ(value("pi"), pi);
  EXPECT_TRUE(std::isnan(value("log(-1)")));  // IEEE semantics, no exception
  EXPECT_TRUE(std::isinf(value("1/0")));
}

TEST(Expression, VariablesBindInTheGivenOrder) {
  const auto e = Expression::parse("x*y - z^2 + 0.5*sin(x)", {"x", "y", "z"});
  for (double x : {-1.0, 0.3, 2.0})
    for (double z : {0.0, 1.5}) {
      const double vars[3] = {x, 4.0, z};
      EXPECT_NEAR(e.eval(vars), x * 4.0 - z * z + 0.5 * std::sin(x), 1e-15);
    }
  const auto uvw = Expression::parse("u + 10*v + 100*w", {"u", "v", "w"});
  const double p[3] = {1, 2, 3};
  EXPECT_EQ(uvw.eval(p), 321.0);
  const double two[2] = {1, 2};
  EXPECT_THROW(uvw.eval(two), Error);
}

TEST(Expression, DeepNestingWithinTheStackLimitEvaluates) {
  std::string text = "1";
  for (int k = 0; k < 40; ++k) text = "(" + text + "+1)";
  EXPECT_EQ(value(text.c_str()), 41.0);
  std::string deep = "1";
  for (int k = 0; k < 80; ++k) deep = "1+(" + deep + ")";  // 81 pending operands
  EXPECT_THROW(Expression::parse(deep, {}), Error);
}

TEST(Expression, MalformedInputGivesOneLineMessagesWithPositions) {
  EXPECT_EQ(error_of(""), "expression '': empty expression at position 0 (end of input)");
  EXPECT_EQ(error_of("1+"), "expression '1+': expected a number, variable, function or '(' at position 2 (end of input)");
  EXPECT_EQ(error_of("2*(x+1"), "expression '2*(x+1': missing ')' at position 6 (end of input)");
  EXPECT_EQ(error_of("foo(1)"), "expression 'foo(1)': unknown function 'foo' at position 0");
  EXPECT_EQ(error_of("x + q"), "expression 'x + q': unknown name 'q' at position 4");
  EXPECT_EQ(error_of("sin(1, 2)"), "expression 'sin(1, 2)': function 'sin' takes 1 argument, got 2 at position 0");
  EXPECT_EQ(error_of("max(1)"), "expression 'max(1)': function 'max' takes at least 2 arguments, got 1 at position 0");
  EXPECT_EQ(error_of("pow(1)"), "expression 'pow(1)': function 'pow' takes 2 arguments, got 1 at position 0");
  EXPECT_EQ(error_of("1 2"), "expression '1 2': unexpected '2' after a complete expression at position 2");
  EXPECT_EQ(error_of("2e+"), "expression '2e+': malformed exponent in number at position 0");
  EXPECT_EQ(error_of("3 # 4"), "expression '3 # 4': unexpected '#' after a complete expression at position 2");
  EXPECT_EQ(error_of("x * #"), "expression 'x * #': unexpected '#' at position 4");
  EXPECT_EQ(error_of("sin + 1"), "expression 'sin + 1': function 'sin' needs an argument list at position 0");
  EXPECT_EQ(error_of("(x))"), "expression '(x))': unexpected ')' after a complete expression at position 3");
  EXPECT_EQ(error_of("."), "expression '.': malformed number at position 0");
  EXPECT_THROW(Expression::parse("x", {"sin"}), Error);
  EXPECT_THROW(Expression::parse("x", {"x", "x"}), Error);
  EXPECT_THROW(Expression::parse("x", {"1x"}), Error);
}

// The parser recurses once per nesting level; a bound on the nesting keeps its stack use bounded on any input.
TEST(Expression, NestingBeyondTheLimitIsAnErrorNotAStackOverflow) {
  const int limit = Expression::kMaxNesting;
  std::string signs(static_cast<std::size_t>(limit - 1), '-');
  EXPECT_EQ(value((signs + "2").c_str()), limit % 2 == 0 ? -2.0 : 2.0);  // limit - 1 signs
  const std::string many_signs = std::string(200000, '-') + "1";
  EXPECT_EQ(error_of(many_signs.c_str()),
            "expression '" + many_signs.substr(0, 80) + "...': nesting deeper than " + std::to_string(limit) +
                " levels of signs, powers, parentheses or function arguments at position " + std::to_string(limit));
  const std::string parens = std::string(100000, '(') + "1" + std::string(100000, ')');
  EXPECT_EQ(error_of(parens.c_str()),
            "expression '" + parens.substr(0, 80) + "...': nesting deeper than " + std::to_string(limit) +
                " levels of signs, powers, parentheses or function arguments at position " + std::to_string(limit));
  std::string calls = "x";
  for (int k = 0; k < 300; ++k) calls = "sin(" + calls + ")";
  EXPECT_THROW(Expression::parse(calls, {"x"}), Error);
  std::string powers = "2";
  for (int k = 0; k < 300; ++k) powers += "^1";
  EXPECT_THROW(Expression::parse(powers, {}), Error);
}

TEST(Expression, ManyPointsGiveTheSameBitsAsOnePointAtATime) {
  // Every instruction, NaN and infinity inputs, and a count that is not a multiple of the block of points.
  const Expression e = Expression::parse(
      "min(x, y, 0.5*z) + max(x, -y) + x^y + atan2(y, x) + sin(x) - cos(y) + tan(z) + exp(-x*x) + log(abs(y)) + "
      "sqrt(abs(z))/3 - pow(abs(x), 0.25) + -(z) + pi",
      {"x", "y", "z"});
  const std::size_t n = 101;
  std::vector<double> x(n), y(n), z(n), many(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = std::sin(1.7 * static_cast<double>(i)) * 3;
    y[i] = std::cos(0.9 * static_cast<double>(i)) * 2;
    z[i] = 0.01 * static_cast<double>(i) - 0.4;
  }
  x[7] = NAN;
  y[40] = INFINITY;
  z[99] = 0;
  const double* const vars[3] = {x.data(), y.data(), z.data()};
  e.eval_many(vars, n, many.data());
  for (std::size_t i = 0; i < n; ++i) {
    const double one = e.eval(std::vector<double>{x[i], y[i], z[i]});
    if (std::isnan(one)) EXPECT_TRUE(std::isnan(many[i])) << i;
    else EXPECT_EQ(many[i], one) << i;
  }
  EXPECT_EQ(many[0], std::min({x[0], y[0], 0.5 * z[0]}) + std::max(x[0], -y[0]) + std::pow(x[0], y[0]) + std::atan2(y[0], x[0]) + std::sin(x[0]) -
                         std::cos(y[0]) + std::tan(z[0]) + std::exp(-x[0] * x[0]) + std::log(std::abs(y[0])) +
                         std::sqrt(std::abs(z[0])) / 3 - std::pow(std::abs(x[0]), 0.25) + -z[0] + std::numbers::pi)
      << "the formula written out in C++ at the first point";
  e.eval_many(vars, 0, many.data());  // no points: nothing to do
  const double* const two[2] = {x.data(), y.data()};
  EXPECT_THROW(e.eval_many(two, n, many.data()), Error);
}

TEST(Expression, ManyPointsGiveTheSameBitsOnEveryInstructionSetAndBlockLength) {
  // The generic and the AVX2 block loops (chosen at run time), more variables than the columns kept on the
  // stack, and counts around the block of 32 points (a short block is padded).
  const Expression e = Expression::parse("sqrt(a*a + b*b + c*c) / 20 - min(1, d / e) * f + max(a, f) - 1 / (b - c)",
                                         {"a", "b", "c", "d", "e", "f"});
  const std::size_t n = 70;
  std::vector<std::vector<double>> columns(6, std::vector<double>(n));
  for (std::size_t v = 0; v < 6; ++v)
    for (std::size_t i = 0; i < n; ++i) columns[v][i] = std::sin(0.3 * static_cast<double>(i * (v + 1)) + 0.1 * static_cast<double>(v));
  columns[4][5] = 0;  // d / 0
  columns[1][9] = columns[2][9];  // 1 / 0
  const double* const vars[6] = {columns[0].data(), columns[1].data(), columns[2].data(),
                                 columns[3].data(), columns[4].data(), columns[5].data()};
  for (const SimdLevel level : {SimdLevel::generic, SimdLevel::avx2}) {
    limit_simd_level(level);
    for (const std::size_t count : {std::size_t{1}, std::size_t{31}, std::size_t{32}, std::size_t{33}, std::size_t{64}, n}) {
      std::vector<double> many(count, -7.0);
      e.eval_many(vars, count, many.data());
      for (std::size_t i = 0; i < count; ++i) {
        std::vector<double> point(6);
        for (std::size_t v = 0; v < 6; ++v) point[v] = columns[v][i];
        const double one = e.eval(point);
        if (std::isnan(one)) EXPECT_TRUE(std::isnan(many[i])) << i;
        else EXPECT_EQ(many[i], one) << simd_level_name(level) << ", " << count << " points, point " << i;
      }
    }
  }
  limit_simd_level(supported_simd_level());
}
