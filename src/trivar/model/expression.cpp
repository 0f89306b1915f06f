#include "trivar/model/expression.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "trivar/core/error.hpp"
#include "trivar/spline/simd_level.hpp"

namespace trivar {

namespace {

struct FunctionInfo {
  std::string_view name;
  Expression::Op op;
  int min_args, max_args;  // max_args < 0: unbounded
};

constexpr std::array<FunctionInfo, 11> kFunctions{{{"sin", Expression::Op::sin, 1, 1},
                                                   {"cos", Expression::Op::cos, 1, 1},
                                                   {"tan", Expression::Op::tan, 1, 1},
                                                   {"exp", Expression::Op::exp, 1, 1},
                                                   {"log", Expression::Op::log, 1, 1},
                                                   {"sqrt", Expression::Op::sqrt, 1, 1},
                                                   {"abs", Expression::Op::abs, 1, 1},
                                                   {"pow", Expression::Op::pow, 2, 2},
                                                   {"atan2", Expression::Op::atan2, 2, 2},
                                                   {"min", Expression::Op::min, 2, -1},
                                                   {"max", Expression::Op::max, 2, -1}}};

const FunctionInfo* find_function(std::string_view name) {
  for (const auto& f : kFunctions)
    if (f.name == name) return &f;
  return nullptr;
}

bool is_identifier(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// Recursive descent over the grammar in expression.hpp, emitting postfix code and tracking the stack depth.
class Parser {
public:
  Parser(std::string_view text, const std::vector<std::string>& vars) : s_(text), vars_(vars) {}

  std::vector<Expression::Instruction> run() {
    skip();
    if (pos_ == s_.size()) fail("empty expression", pos_);
    expr();
    skip();
    if (pos_ != s_.size()) fail("unexpected '" + std::string(1, s_[pos_]) + "' after a complete expression", pos_);
    return std::move(code_);
  }

private:
  [[noreturn]] void fail(const std::string& what, std::size_t at) const {
    // A formula is quoted whole up to a line's worth of characters; longer ones are cut, the position says where.
    constexpr std::size_t kQuoted = 80;
    const std::string quoted = s_.size() <= kQuoted ? std::string(s_) : std::string(s_.substr(0, kQuoted)) + "...";
    throw Error("expression '" + quoted + "': " + what + " at position " + std::to_string(at) +
                (at >= s_.size() ? " (end of input)" : ""));
  }
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool accept(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  // Stack effect of each instruction: +1 for a push, 1 - n for an n-ary operation.
  void emit(Expression::Op op, int arg = 0, double value = 0, int effect = 0) {
    code_.push_back({op, arg, value});
    depth_ += effect;
    if (depth_ > Expression::kMaxStack)
      fail("nesting deeper than " + std::to_string(Expression::kMaxStack) + " operands", pos_);
  }

  void expr() {
    term();
    for (;;) {
      if (accept('+')) term(), emit(Expression::Op::add, 0, 0, -1);
      else if (accept('-')) term(), emit(Expression::Op::sub, 0, 0, -1);
      else return;
    }
  }
  void term() {
    unary();
    for (;;) {
      if (accept('*')) unary(), emit(Expression::Op::mul, 0, 0, -1);
      else if (accept('/')) unary(), emit(Expression::Op::div, 0, 0, -1);
      else return;
    }
  }
  // Every recursion of the grammar (signs, powers, parentheses, arguments) passes through unary(), so
  // bounding its depth bounds the parser's stack use on any input.
  void unary() {
    if (++nesting_ > Expression::kMaxNesting)
      fail("nesting deeper than " + std::to_string(Expression::kMaxNesting) +
               " levels of signs, powers, parentheses or function arguments",
           pos_);
    unary_body();
    --nesting_;
  }
  void unary_body() {
    if (accept('-')) {
      unary();
      emit(Expression::Op::neg);
    } else if (accept('+')) {
      unary();
    } else {
      power();
    }
  }
  void power() {
    primary();
    if (accept('^')) {
      unary();
      emit(Expression::Op::pow, 0, 0, -1);
    }
  }
  void primary() {
    skip();
    const std::size_t start = pos_;
    if (pos_ == s_.size()) fail("expected a number, variable, function or '('", pos_);
    const char c = s_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
      const std::string_view name = s_.substr(start, pos_ - start);
      skip();
      if (pos_ < s_.size() && s_[pos_] == '(') return call(name, start);
      if (name == "pi") return emit(Expression::Op::number, 0, std::numbers::pi, 1);
      for (std::size_t k = 0; k < vars_.size(); ++k)
        if (vars_[k] == name) return emit(Expression::Op::variable, static_cast<int>(k), 0, 1);
      if (find_function(name)) fail("function '" + std::string(name) + "' needs an argument list", start);
      fail("unknown name '" + std::string(name) + "'", start);
    }
    if (accept('(')) {
      expr();
      if (!accept(')')) fail("missing ')'", pos_);
      return;
    }
    fail("unexpected '" + std::string(1, c) + "'", pos_);
  }
  void number() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    if (pos_ < s_.size() && s_[pos_] == '.') ++pos_;
    while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    if (pos_ - start == 1 && s_[start] == '.') fail("malformed number", start);
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
      if (pos_ == s_.size() || !std::isdigit(static_cast<unsigned char>(s_[pos_])))
        fail("malformed exponent in number", start);
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    }
    const std::string literal(s_.substr(start, pos_ - start));
    emit(Expression::Op::number, 0, std::strtod(literal.c_str(), nullptr), 1);
  }
  void call(std::string_view name, std::size_t start) {
    const FunctionInfo* f = find_function(name);
    if (!f) fail("unknown function '" + std::string(name) + "'", start);
    accept('(');
    int n = 0;
    do {
      expr();
      ++n;
    } while (accept(','));
    if (!accept(')')) fail("missing ')' after the arguments of '" + std::string(name) + "'", pos_);
    if (n < f->min_args || (f->max_args >= 0 && n > f->max_args)) {
      const std::string expected = f->max_args < 0               ? "at least " + std::to_string(f->min_args)
                                   : f->min_args == f->max_args ? std::to_string(f->min_args)
                                                                : std::to_string(f->min_args) + " to " +
                                                                      std::to_string(f->max_args);
      fail("function '" + std::string(name) + "' takes " + expected + " argument" + (expected == "1" ? "" : "s") +
               ", got " + std::to_string(n),
           start);
    }
    emit(f->op, n, 0, 1 - n);
  }

  std::string_view s_;
  const std::vector<std::string>& vars_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  int nesting_ = 0;
  std::vector<Expression::Instruction> code_;
};

}  // namespace

Expression Expression::parse(std::string_view text, std::vector<std::string> variables) {
  for (std::size_t k = 0; k < variables.size(); ++k) {
    const std::string& v = variables[k];
    require(is_identifier(v) && v != "pi" && !find_function(v),
            "expression '" + std::string(text) + "': '" + v + "' cannot be a variable name");
    require(std::find(variables.begin(), variables.begin() + static_cast<std::ptrdiff_t>(k), v) ==
                variables.begin() + static_cast<std::ptrdiff_t>(k),
            "expression '" + std::string(text) + "': variable '" + v + "' is listed twice");
  }
  Expression e;
  e.program_ = Parser(text, variables).run();
  e.text_ = std::string(text);
  e.variables_ = std::move(variables);
  return e;
}

double Expression::eval(std::span<const double> vars) const {
  require(vars.size() == variables_.size(), [&] {
    return "expression '" + text_ + "': " + std::to_string(variables_.size()) + " variable values expected, got " +
           std::to_string(vars.size());
  });
  // The message is built only on failure: attributes evaluate formulas once per slicer pixel.
  require(!program_.empty(), [] { return std::string("expression: evaluating an empty (default-constructed) expression"); });
  std::array<double, kMaxStack> st;
  int top = -1;  // index of the top of the stack
  for (const Instruction& in : program_) {
    switch (in.op) {
      case Op::number: st[++top] = in.value; break;
      case Op::variable: st[++top] = vars[static_cast<std::size_t>(in.arg)]; break;
      case Op::add: --top, st[top] += st[top + 1]; break;
      case Op::sub: --top, st[top] -= st[top + 1]; break;
      case Op::mul: --top, st[top] *= st[top + 1]; break;
      case Op::div: --top, st[top] /= st[top + 1]; break;
      case Op::pow: --top, st[top] = std::pow(st[top], st[top + 1]); break;
      case Op::atan2: --top, st[top] = std::atan2(st[top], st[top + 1]); break;
      case Op::neg: st[top] = -st[top]; break;
      case Op::sin: st[top] = std::sin(st[top]); break;
      case Op::cos: st[top] = std::cos(st[top]); break;
      case Op::tan: st[top] = std::tan(st[top]); break;
      case Op::exp: st[top] = std::exp(st[top]); break;
      case Op::log: st[top] = std::log(st[top]); break;
      case Op::sqrt: st[top] = std::sqrt(st[top]); break;
      case Op::abs: st[top] = std::abs(st[top]); break;
      case Op::min:
      case Op::max: {
        const int first = top - in.arg + 1;
        double r = st[first];
        for (int k = first + 1; k <= top; ++k) r = in.op == Op::min ? std::min(r, st[k]) : std::max(r, st[k]);
        top = first;
        st[top] = r;
        break;
      }
    }
  }
  return st[0];
}

namespace {

// Points per block of eval_many: 64 stack levels of 32 points are 16 KiB, and 32 points amortise the dispatch of
// an instruction well.
constexpr std::size_t kManyBlock = 32;
using ManyStack = double[Expression::kMaxStack][kManyBlock];

// One block of the program over kManyBlock points. Every loop has the block's fixed length (a short block's
// columns are padded), so the compiler unrolls and vectorises it without a remainder loop; the operations
// are the IEEE ones of eval() lane by lane (no contraction into fused multiply-adds), so the vector width does
// not change a bit of the result.
[[gnu::always_inline]] inline void run_block(std::span<const Expression::Instruction> program,
                                             const double* const* columns, ManyStack& st) {
  using Op = Expression::Op;
  constexpr std::size_t m = kManyBlock;
  auto unary = [&](double* a, auto f) {
    for (std::size_t i = 0; i < m; ++i) a[i] = f(a[i]);
  };
  int top = -1;
  for (const Expression::Instruction& in : program) {
    double* a = top >= 0 ? st[top] : nullptr;
    const double* b = top >= 1 ? st[top] : nullptr;
    double* c = top >= 1 ? st[top - 1] : nullptr;  // binary: c op= b, the result on c
    switch (in.op) {
      case Op::number: std::fill_n(st[++top], m, in.value); break;
      case Op::variable: std::copy_n(columns[static_cast<std::size_t>(in.arg)], m, st[++top]); break;
      case Op::add: for (std::size_t i = 0; i < m; ++i) c[i] += b[i]; --top; break;
      case Op::sub: for (std::size_t i = 0; i < m; ++i) c[i] -= b[i]; --top; break;
      case Op::mul: for (std::size_t i = 0; i < m; ++i) c[i] *= b[i]; --top; break;
      case Op::div: for (std::size_t i = 0; i < m; ++i) c[i] /= b[i]; --top; break;
      case Op::pow: for (std::size_t i = 0; i < m; ++i) c[i] = std::pow(c[i], b[i]); --top; break;
      case Op::atan2: for (std::size_t i = 0; i < m; ++i) c[i] = std::atan2(c[i], b[i]); --top; break;
      case Op::neg: unary(a, [](double v) { return -v; }); break;
      case Op::sin: unary(a, [](double v) { return std::sin(v); }); break;
      case Op::cos: unary(a, [](double v) { return std::cos(v); }); break;
      case Op::tan: unary(a, [](double v) { return std::tan(v); }); break;
      case Op::exp: unary(a, [](double v) { return std::exp(v); }); break;
      case Op::log: unary(a, [](double v) { return std::log(v); }); break;
      case Op::sqrt: unary(a, [](double v) { return std::sqrt(v); }); break;
      case Op::abs: unary(a, [](double v) { return std::abs(v); }); break;
      case Op::min:
      case Op::max: {
        const int lowest = top - in.arg + 1;
        double* r = st[lowest];
        for (int k = lowest + 1; k <= top; ++k) {
          const double* v = st[k];
          if (in.op == Op::min)
            for (std::size_t i = 0; i < m; ++i) r[i] = std::min(r[i], v[i]);
          else
            for (std::size_t i = 0; i < m; ++i) r[i] = std::max(r[i], v[i]);
        }
        top = lowest;
        break;
      }
    }
  }
}

void run_block_generic(std::span<const Expression::Instruction> program, const double* const* columns, ManyStack& st) {
  run_block(program, columns, st);
}
// 4-wide loops on CPUs with AVX2 (chosen at run time: the portable build's loops are 2-wide). No "fma" target:
// contraction would change results.
[[gnu::target("avx2")]] void run_block_avx2(std::span<const Expression::Instruction> program,
                                            const double* const* columns, ManyStack& st) {
  run_block(program, columns, st);
}

}  // namespace

void Expression::eval_many(std::span<const double* const> vars, std::size_t n, double* out) const {
  require(vars.size() == variables_.size(), [&] {
    return "expression '" + text_ + "': " + std::to_string(variables_.size()) + " variable columns expected, got " +
           std::to_string(vars.size());
  });
  require(!program_.empty(), [] { return std::string("expression: evaluating an empty (default-constructed) expression"); });
  const auto run = simd_level() >= SimdLevel::avx2 ? run_block_avx2 : run_block_generic;
  alignas(64) ManyStack st;
  // Column pointers of the block, and zero-padded copies of a short last block's columns (on the stack for the
  // usual few variables).
  constexpr std::size_t kFew = 4;
  const double* few_columns[kFew];
  alignas(64) double few_padded[kFew][kManyBlock];
  std::vector<const double*> many_columns;
  std::vector<double> many_padded;
  const double** columns = few_columns;
  double* padded = few_padded[0];
  if (vars.size() > kFew) {
    many_columns.resize(vars.size());
    many_padded.resize(vars.size() * kManyBlock);
    columns = many_columns.data();
    padded = many_padded.data();
  }
  for (std::size_t first = 0; first < n; first += kManyBlock) {
    const std::size_t m = std::min(kManyBlock, n - first);
    for (std::size_t v = 0; v < vars.size(); ++v) {
      columns[v] = vars[v] + first;
      if (m < kManyBlock) {
        double* p = padded + v * kManyBlock;
        std::fill(std::copy_n(vars[v] + first, m, p), p + kManyBlock, 0.0);
        columns[v] = p;
      }
    }
    run(program_, columns, st);
    std::copy_n(st[0], m, out + first);
  }
}

}  // namespace trivar
