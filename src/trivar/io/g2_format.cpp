#include "trivar/io/g2_format.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"

namespace trivar::io {

namespace {

constexpr std::array<int, 3> kClassTypes = {100, 200, 700};
constexpr std::array<const char*, 3> kClassNames = {"SplineCurve", "SplineSurface", "SplineVolume"};
constexpr std::array<char, 3> kDirections = {'u', 'v', 'w'};

struct Token {
  std::string_view text;
  int line = 0;
};

std::vector<Token> tokenize(std::string_view text) {
  std::vector<Token> out;
  int line = 1;
  std::size_t i = 0;
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; };
  while (i < text.size()) {
    if (space(text[i])) {
      if (text[i++] == '\n') ++line;
      continue;
    }
    const std::size_t start = i;
    while (i < text.size() && !space(text[i])) ++i;
    out.push_back({text.substr(start, i - start), line});
  }
  return out;
}

// Recursive-descent reader over whitespace-separated tokens; every error names file and line.
class G2Reader {
public:
  G2Reader(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {
    tokens_ = tokenize(text_);
  }

  std::vector<AnySpline> read() {
    if (tokens_.empty()) throw Error(path_ + ":1: no objects found (empty file)");
    std::vector<AnySpline> out;
    while (pos_ < tokens_.size()) out.push_back(read_object(static_cast<int>(out.size()) + 1));
    return out;
  }

private:
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(line) + ": " + what);
  }

  static std::string quoted(std::string_view t) {
    return "'" + std::string(t.substr(0, 40)) + (t.size() > 40 ? "...'" : "'");
  }

  // `expected` describes the token for error messages; it is a string or a callable building one, so the
  // per-coefficient descriptions are only formatted when something is wrong.
  template <class E>
  static std::string describe(const E& expected) {
    if constexpr (std::is_invocable_v<E>)
      return expected();
    else
      return std::string(expected);
  }

  template <class E>
  const Token& next(const E& expected) {
    if (pos_ >= tokens_.size())
      fail(tokens_.empty() ? 1 : tokens_.back().line, "truncated file: expected " + describe(expected));
    return tokens_[pos_++];
  }

  template <class E>
  int read_int(const E& expected) {
    const Token& t = next(expected);
    int v = 0;
    const auto r = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
    if (r.ec != std::errc() || r.ptr != t.text.data() + t.text.size())
      fail(t.line, "expected " + describe(expected) + ", found " + quoted(t.text));
    return v;
  }

  template <class E>
  double read_real(const E& expected) {
    const Token& t = next(expected);
    std::string_view s = t.text;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);  // from_chars rejects a leading '+'
    double v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
      fail(t.line, "expected " + describe(expected) + " (a finite number), found " + quoted(t.text));
    return v;
  }

  int line() const { return tokens_[pos_ - 1].line; }

  AnySpline read_object(int object) {
    const std::string header = "an object header 'classType major minor nAux'";
    const int type = read_int(header + (object > 1 ? " (trailing data, or wrong number of coefficients in object " +
                                                         std::to_string(object - 1) + "?)"
                                                   : std::string()));
    const int header_line = line();
    const auto it = std::find(kClassTypes.begin(), kClassTypes.end(), type);
    if (it == kClassTypes.end())
      fail(header_line, "unsupported class type " + std::to_string(type) +
                            " (supported: 100 SplineCurve, 200 SplineSurface, 700 SplineVolume)");
    const int major = read_int("major version in " + header);
    const int minor = read_int("minor version in " + header);
    if (major != 1)
      fail(line(), "unsupported g2 version " + std::to_string(major) + "." + std::to_string(minor) +
                       " (expected major version 1)");
    const int aux = read_int("number of auxiliary values in " + header);
    if (aux < 0) fail(line(), "negative number of auxiliary values " + std::to_string(aux));
    // Auxiliary data (e.g. a display colour) carries no geometry.
    for (int i = 0; i < aux; ++i) read_real("auxiliary value " + std::to_string(i + 1) + " of " + std::to_string(aux));
    switch (it - kClassTypes.begin()) {
      case 0:
        return read_spline<1>(object);
      case 1:
        return read_spline<2>(object);
      default:
        return read_spline<3>(object);
    }
  }

  template <int D>
  AnySpline read_spline(int object) {
    const std::string name = std::string(kClassNames[D - 1]) + " (object " + std::to_string(object) + ")";
    const int dim = read_int("'dim rational' of " + name);
    if (dim < 1) fail(line(), "control dimension of " + name + " must be >= 1, got " + std::to_string(dim));
    const int rational = read_int("'dim rational' of " + name);
    if (rational != 0 && rational != 1)
      fail(line(), "rational flag of " + name + " must be 0 or 1, got " + std::to_string(rational));

    std::array<KnotVector, D> kv;
    long long n = 1;
    for (int k = 0; k < D; ++k) {
      const std::string dir = std::string("direction ") + kDirections[k];
      const std::string expected = "'ncoef order' for " + dir;
      const int ncoef = read_int(expected);
      const int order = read_int(expected);
      if (order < 1) fail(line(), dir + ": order must be >= 1, got " + std::to_string(order));
      if (ncoef < order || ncoef > INT_MAX - order)
        fail(line(), dir + ": ncoef " + std::to_string(ncoef) + " must be >= order " + std::to_string(order));
      std::vector<double> t;
      int first_line = 0;
      for (int i = 0; i < ncoef + order; ++i) {
        t.push_back(read_real(
            [&] { return "knot " + std::to_string(i) + " of " + std::to_string(ncoef + order) + " in " + dir; }));
        if (i == 0) first_line = line();
      }
      try {
        kv[k] = KnotVector(order - 1, std::move(t));
      } catch (const Error& e) {
        fail(first_line, "invalid knot vector in " + dir + ": " + e.what());
      }
      n *= ncoef;
    }
    const int stride = dim + rational;
    if (n > INT_MAX || n * stride > INT_MAX)
      fail(line(), name + " has too many coefficients (" + std::to_string(n) + ")");

    std::vector<double> coefs;
    coefs.reserve(std::min(static_cast<std::size_t>(n * stride), tokens_.size() - pos_));
    for (long long i = 0; i < n; ++i) {
      for (int d = 0; d < stride; ++d)
        coefs.push_back(read_real([&] {
          return "value " + std::to_string(d + 1) + " of coefficient " + std::to_string(i + 1) + " of " +
                 std::to_string(n) + " (" + std::to_string(stride) + " values each) of " + name;
        }));
      if (rational && coefs.back() <= 0)
        fail(line(), "non-positive weight " + std::string(tokens_[pos_ - 1].text) + " of coefficient " +
                         std::to_string(i + 1) + " of " + name);
    }
    // Coefficients end a line; more values on that line mean ncoef or dim does not match the data.
    if (pos_ < tokens_.size() && tokens_[pos_].line == line())
      fail(line(), "more values than expected: the line goes on after the last coefficient of " + name +
                       ", which has " + std::to_string(n) + " coefficients of " + std::to_string(stride) +
                       " values (wrong number of coefficients or values per coefficient?)");
    return TensorSpline<D>(std::move(kv), dim, rational == 1, std::move(coefs));
  }

  std::string path_;
  std::string text_;  // owns the characters the tokens view
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
};

template <int D>
void write_spline(std::ostream& os, const TensorSpline<D>& s) {
  os << kClassTypes[D - 1] << " 1 0 0\n" << s.dim() << ' ' << (s.is_rational() ? 1 : 0) << '\n';
  for (int k = 0; k < D; ++k) {
    os << s.count(k) << ' ' << s.knots(k).order() << '\n';
    const auto& t = s.knots(k).knots();
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (i) os << ' ';
      write_number(os, t[i]);
    }
    os << '\n';
  }
  const int st = s.stride();
  for (int l = 0; l < s.num_coefs(); ++l) {
    for (int d = 0; d < st; ++d) {
      if (d) os << ' ';
      write_number(os, s.coef(l)[d]);
    }
    os << '\n';
  }
}

}  // namespace

std::vector<AnySpline> read_g2(const std::string& path) {
  require(!std::filesystem::is_directory(path), path + ": is a directory, expected a g2 file");
  std::ifstream in(path, std::ios::binary);
  require(static_cast<bool>(in), path + ": cannot open file for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_g2(std::move(text).str(), path);
}

std::vector<AnySpline> parse_g2(std::string text, const std::string& name) {
  return G2Reader(name, std::move(text)).read();
}

void write_g2(const std::string& path, const std::vector<AnySpline>& objects) {
  require(!objects.empty(), path + ": nothing to write (no objects)");
  for (std::size_t i = 0; i < objects.size(); ++i)
    std::visit(
        [&](const auto& s) {
          require(s.dim() >= 1,
                  path + ": object " + std::to_string(i + 1) + ": cannot write an empty spline (no control points)");
        },
        objects[i]);
  write_file_atomically(path, [&](std::ostream& os) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (i) os << '\n';
      std::visit([&](const auto& s) { write_spline(os, s); }, objects[i]);
    }
  });
}

}  // namespace trivar::io
