#pragma once
// Expression: a small arithmetic language for attributes given by formulas, e.g. "0.5*(1 + sin(2*pi*x))".
//
// Grammar (whitespace ignored):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?          right associative: 2^3^2 = 2^9; -2^2 = -4; 2^-1 = 0.5
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
// Numbers: decimal with optional fraction and exponent (1, .5, 2.5e-3). Names: the variables given at parse
// time, the constant pi, and the functions sin cos tan exp log (natural) sqrt abs (one argument), pow and
// atan2(y, x) (two), min max (two or more).
//
// Parsing compiles to a postfix program; eval() runs it on a fixed-size stack, so it never allocates and is
// thread-safe. IEEE semantics are kept: log(-1) is NaN, 1/0 is inf (no exception in the evaluation path).
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace trivar {

class Expression {
public:
  // Deepest evaluation stack, and deepest nesting of signs, powers, parentheses and arguments, a parse accepts.
  static constexpr int kMaxStack = 64, kMaxNesting = 256;

  Expression() = default;
  // Throws trivar::Error with a one-line message naming the expression, the problem and its position (0-based
  // character offset), e.g. "expression '2*(x+1': missing ')' at position 6 (end of input)". Variable names must
  // be identifiers distinct from pi and the function names.
  static Expression parse(std::string_view text, std::vector<std::string> variables);

  // vars holds one value per variable, in the order given to parse(). Throws trivar::Error on a size mismatch.
  double eval(std::span<const double> vars) const;
  // eval() at n points at once: vars[v][i] is variable v at point i, out[i] gets the value there. Each
  // instruction runs over a block of points, so the dispatch is paid once per block and the arithmetic
  // vectorises; every value is bit-identical to eval() at the same point. Throws like eval().
  void eval_many(std::span<const double* const> vars, std::size_t n, double* out) const;

  const std::string& text() const { return text_; }
  const std::vector<std::string>& variables() const { return variables_; }

  enum class Op : unsigned char { number, variable, add, sub, mul, div, pow, neg, sin, cos, tan, exp, log, sqrt, abs, min, max, atan2 };
  struct Instruction {
    Op op;
    int arg = 0;       // variable index, or argument count of min / max
    double value = 0;  // literal of Op::number
  };

private:
  std::string text_;
  std::vector<std::string> variables_;
  std::vector<Instruction> program_;
};

}  // namespace trivar
