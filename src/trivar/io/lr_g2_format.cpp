#include "trivar/io/lr_g2_format.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/read_limits.hpp"

namespace trivar::io {

namespace {

constexpr int kSurfaceClass = 293;
constexpr int kVolumeClass = 793;
constexpr const char* kDirNames = "uvw";

// Whitespace-separated tokens with their line numbers.
class Tokens {
public:
  Tokens(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(name_ + ":" + std::to_string(line_) + ": " + what);
  }
  [[noreturn]] void fail_at(int line, const std::string& what) const {
    throw Error(name_ + ":" + std::to_string(line) + ": " + what);
  }
  int line() const { return line_; }

  bool at_end() {
    skip_space();
    return pos_ >= text_.size();
  }
  long integer(const char* what, long lo, long hi) {
    const std::string_view t = next(what);
    long x = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(std::string("expected ") + what + " (an integer), found " + quoted(t));
    if (x < lo || x > hi)
      fail(std::string(what) + " " + std::to_string(x) + " is out of range [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    return x;
  }
  int count(const char* what, long hi = kMaxCount) { return static_cast<int>(integer(what, 0, hi)); }
  double number(const char* what) {
    std::string_view t = next(what);
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);  // from_chars rejects a leading '+'
    double x = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(std::string("expected ") + what + " (a number), found " + quoted(t));
    if (!std::isfinite(x)) fail(std::string(what) + " is not finite");
    return x;
  }

private:
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_])))
      if (text_[pos_++] == '\n') ++line_;
  }
  std::string_view next(const char* what) {
    skip_space();
    if (pos_ >= text_.size()) fail(std::string("expected ") + what + ", found end of file");
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  static std::string quoted(std::string_view t) {
    std::string s = "'";
    s.append(t.substr(0, 40));
    s += t.size() > 40 ? "...'" : "'";
    return s;
  }

  std::string_view text_;
  const std::string& name_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// A double near `guess` that `back` maps exactly onto `target`, so that a conversion followed by its inverse
// reproduces the original bits; `guess` itself when no double within a few units in the last place does.
template <class Back>
double exact_preimage(double guess, double target, Back back) {
  if (back(guess) == target) return guess;
  double up = guess, down = guess;
  for (int i = 0; i < 4; ++i) {
    up = std::nextafter(up, HUGE_VAL);
    if (back(up) == target) return up;
    down = std::nextafter(down, -HUGE_VAL);
    if (back(down) == target) return down;
  }
  return guess;
}

template <int D>
LRSpline<D> parse_object(Tokens& in, int header_line) {
  const long rat = in.integer("rational flag", 0, 1);
  in.number("knot tolerance");

  std::array<std::vector<double>, D> knots;
  for (int k = 0; k < D; ++k) {
    const std::string what = std::string("number of distinct knots in ") + kDirNames[k];
    knots[k].resize(static_cast<std::size_t>(in.count(what.c_str())));
    if (knots[k].size() < 2) in.fail(what + " must be at least 2");
    for (std::size_t i = 0; i < knots[k].size(); ++i) {
      knots[k][i] = in.number("knot value");
      if (i > 0 && knots[k][i] <= knots[k][i - 1])
        in.fail(std::string("distinct knots in ") + kDirNames[k] + " must increase strictly, got " +
                format_number(knots[k][i - 1]) + " then " + format_number(knots[k][i]));
    }
  }

  std::vector<MeshRectangle<D>> mesh;
  for (int k = 0; k < D; ++k) {
    const int n = in.count("number of mesh lines");
    if (static_cast<std::size_t>(n) != knots[k].size())
      in.fail(std::string("expected ") + std::to_string(knots[k].size()) + " mesh entries in " + kDirNames[k] +
              " (one per distinct knot), got " + std::to_string(n));
    for (int i = 0; i < n; ++i) {
      const double value = knots[k][static_cast<std::size_t>(i)];
      const int runs = in.count("number of mesh segments");
      if constexpr (D == 2) {
        const int a = 1 - k;
        const long last = static_cast<long>(knots[a].size()) - 1;
        std::vector<std::pair<long, int>> seg(static_cast<std::size_t>(runs));
        for (auto& [ix, mult] : seg) {
          ix = in.integer("mesh segment start index", 0, last - 1);
          mult = static_cast<int>(in.integer("mesh multiplicity", 0, kMaxDegree + 1));
        }
        for (std::size_t r = 0; r < seg.size(); ++r) {
          const long end = r + 1 < seg.size() ? seg[r + 1].first : last;
          if (end <= seg[r].first)
            in.fail("mesh segments of " + std::string(1, kDirNames[k]) + " = " + format_number(value) +
                    " are not in increasing order");
          if (seg[r].second == 0) continue;
          Param<D> lo{}, hi{};
          lo[a] = knots[a][static_cast<std::size_t>(seg[r].first)];
          hi[a] = knots[a][static_cast<std::size_t>(end)];
          mesh.push_back(MeshRectangle<D>::make(k, value, lo, hi, seg[r].second));
        }
      } else {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const long na = static_cast<long>(knots[a].size()) - 1, nb = static_cast<long>(knots[b].size()) - 1;
        for (int r = 0; r < runs; ++r) {
          const long a0 = in.integer("mesh rectangle index", 0, na), b0 = in.integer("mesh rectangle index", 0, nb);
          const long a1 = in.integer("mesh rectangle index", 0, na), b1 = in.integer("mesh rectangle index", 0, nb);
          const int mult = static_cast<int>(in.integer("mesh multiplicity", 0, kMaxDegree + 1));
          if (a1 <= a0 || b1 <= b0) in.fail("mesh rectangle has an empty index range");
          if (mult == 0) continue;
          Param<D> lo{}, hi{};
          lo[a] = knots[a][static_cast<std::size_t>(a0)];
          hi[a] = knots[a][static_cast<std::size_t>(a1)];
          lo[b] = knots[b][static_cast<std::size_t>(b0)];
          hi[b] = knots[b][static_cast<std::size_t>(b1)];
          mesh.push_back(MeshRectangle<D>::make(k, value, lo, hi, mult));
        }
      }
    }
  }

  const int nbasis = in.count("number of B-splines");
  if (nbasis == 0) in.fail("an LR spline needs at least one B-spline");
  std::vector<LRBSpline<D>> basis(static_cast<std::size_t>(nbasis));
  int dim = 0;
  Ints<D> degrees{};
  for (int i = 0; i < nbasis; ++i) {
    LRBSpline<D>& b = basis[static_cast<std::size_t>(i)];
    const std::string who = "B-spline " + std::to_string(i);
    const int d = static_cast<int>(in.integer("B-spline dimension", 1, 1024));
    if (i == 0) dim = d;
    if (d != dim) in.fail(who + " has dimension " + std::to_string(d) + ", the first has " + std::to_string(dim));
    if (in.integer("B-spline rational flag", 0, 1) != rat)
      in.fail(who + ": rational flag differs from the object's (" + std::to_string(rat) + ")");
    std::vector<double> c(static_cast<std::size_t>(dim));
    for (double& x : c) x = in.number("coefficient");
    b.gamma = in.number("scaling factor gamma");
    if (!(b.gamma > 0)) in.fail(who + ": scaling factor gamma must be positive, got " + format_number(b.gamma));
    const double weight = in.number("weight");
    if (rat == 1 && !(weight > 0)) in.fail(who + ": weight must be positive, got " + format_number(weight));
    for (int k = 0; k < D; ++k) {
      const int size = in.count("local knot vector size", kMaxDegree + 2);
      if (size < 2) in.fail(who + ": local knot vector in " + kDirNames[k] + " needs at least 2 knots");
      if (i == 0) degrees[k] = size - 2;
      if (size - 2 != degrees[k])
        in.fail(who + " has degree " + std::to_string(size - 2) + " in " + kDirNames[k] + ", the first has " +
                std::to_string(degrees[k]));
      b.knots[k].resize(static_cast<std::size_t>(size));
      long prev = 0;
      for (int j = 0; j < size; ++j) {
        const long ix = in.integer("knot index", 0, static_cast<long>(knots[k].size()) - 1);
        if (j > 0 && ix < prev) in.fail(who + ": knot indices in " + kDirNames[k] + " decrease");
        prev = ix;
        b.knots[k][static_cast<std::size_t>(j)] = knots[k][static_cast<std::size_t>(ix)];
      }
    }
    if (rat == 1) {
      const double w = weight / b.gamma;
      b.coef.resize(static_cast<std::size_t>(dim) + 1);
      for (int j = 0; j < dim; ++j) b.coef[static_cast<std::size_t>(j)] = c[static_cast<std::size_t>(j)] * w;
      b.coef.back() = w;
    } else {
      b.coef.resize(static_cast<std::size_t>(dim));
      for (int j = 0; j < dim; ++j) b.coef[static_cast<std::size_t>(j)] = c[static_cast<std::size_t>(j)] / b.gamma;
    }
  }

  std::optional<LRSpline<D>> s;
  try {
    s.emplace(degrees, dim, rat == 1, std::move(basis), std::move(mesh));
  } catch (const Error& e) {
    in.fail_at(header_line, e.what());
  }
  return std::move(*s);
}

// Distinct knot values per direction: the mesh lines' values (the domain ends included).
template <int D>
std::array<std::vector<double>, D> distinct_knots(const LRSpline<D>& s) {
  std::array<std::vector<double>, D> t;
  for (int k = 0; k < D; ++k) t[k] = {s.domain().lo[k], s.domain().hi[k]};
  for (const MeshRectangle<D>& r : s.mesh()) t[r.dir].push_back(r.value);
  for (auto& v : t) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  return t;
}

int index_of(const std::vector<double>& t, double x) {
  const auto it = std::lower_bound(t.begin(), t.end(), x);
  require(it != t.end() && *it == x, [&] { return "knot " + format_number(x) + " is not a mesh line"; });
  return static_cast<int>(it - t.begin());
}

// Multiplicity of every cell of the plane {u_k = t[k][i]} on the grid of the other directions' knots
// ((k+1) % D fastest): the largest multiplicity of the mesh rectangles covering it, 0 where none does.
template <int D>
std::vector<int> plane_multiplicities(const LRSpline<D>& s, const std::array<std::vector<double>, D>& t, int k,
                                      double value, int& na, int& nb) {
  const int a = (k + 1) % D, b = (k + 2) % D;
  na = static_cast<int>(t[a].size()) - 1;
  nb = D == 3 ? static_cast<int>(t[b].size()) - 1 : 1;
  std::vector<int> m(static_cast<std::size_t>(na) * static_cast<std::size_t>(nb), 0);
  for (const MeshRectangle<D>& r : s.mesh()) {
    if (r.dir != k || r.value != value) continue;
    const int a0 = index_of(t[a], r.extent.lo[a]), a1 = index_of(t[a], r.extent.hi[a]);
    const int b0 = D == 3 ? index_of(t[b], r.extent.lo[b]) : 0, b1 = D == 3 ? index_of(t[b], r.extent.hi[b]) : 1;
    for (int j = b0; j < b1; ++j)
      for (int i = a0; i < a1; ++i) {
        int& x = m[static_cast<std::size_t>(j) * static_cast<std::size_t>(na) + static_cast<std::size_t>(i)];
        x = std::max(x, r.multiplicity);
      }
  }
  return m;
}

template <int D>
void write_object(std::ostream& os, const LRSpline<D>& s) {
  const auto t = distinct_knots(s);
  const bool rat = s.is_rational();
  os << (D == 2 ? kSurfaceClass : kVolumeClass) << " 1 0 0\n" << (rat ? 1 : 0) << " 1e-08\n";
  for (int k = 0; k < D; ++k) {
    os << t[k].size();
    for (double x : t[k]) {
      os << ' ';
      write_number(os, x);
    }
    os << '\n';
  }
  for (int k = 0; k < D; ++k) {
    os << t[k].size() << '\n';
    for (double value : t[k]) {
      int na = 0, nb = 0;
      const std::vector<int> m = plane_multiplicities<D>(s, t, k, value, na, nb);
      if constexpr (D == 2) {
        // Runs of equal multiplicity along the line, the first one starting at index 0 even when empty.
        std::vector<std::pair<int, int>> runs;
        for (int i = 0; i < na; ++i)
          if (runs.empty() || runs.back().second != m[static_cast<std::size_t>(i)])
            runs.emplace_back(i, m[static_cast<std::size_t>(i)]);
        os << runs.size();
        for (const auto& [ix, mult] : runs) os << ' ' << ix << ' ' << mult;
        os << '\n';
      } else {
        // Greedy cover of the non-zero cells by disjoint rectangles of one multiplicity each.
        std::vector<char> done(m.size(), 0);
        std::vector<std::array<int, 5>> rects;
        const auto at = [&](int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(na) + static_cast<std::size_t>(i); };
        for (int j = 0; j < nb; ++j)
          for (int i = 0; i < na; ++i) {
            const int mult = m[at(i, j)];
            if (mult == 0 || done[at(i, j)]) continue;
            int i1 = i + 1;
            while (i1 < na && m[at(i1, j)] == mult && !done[at(i1, j)]) ++i1;
            int j1 = j + 1;
            for (; j1 < nb; ++j1) {
              bool row = true;
              for (int x = i; x < i1 && row; ++x) row = m[at(x, j1)] == mult && !done[at(x, j1)];
              if (!row) break;
            }
            for (int y = j; y < j1; ++y)
              for (int x = i; x < i1; ++x) done[at(x, y)] = 1;
            rects.push_back({i, j, i1, j1, mult});
          }
        os << rects.size();
        for (const auto& r : rects) os << ' ' << r[0] << ' ' << r[1] << ' ' << r[2] << ' ' << r[3] << ' ' << r[4];
        os << '\n';
      }
    }
  }
  os << s.num_basis() << '\n';
  const int dim = s.dim();
  std::vector<double> c(static_cast<std::size_t>(dim));
  for (const LRBSpline<D>& b : s.basis_functions()) {
    const double g = b.gamma;
    double weight = 1.0;
    if (rat) {
      const double w = b.coef[static_cast<std::size_t>(dim)];
      weight = exact_preimage(w * g, w, [g](double x) { return x / g; });
      const double w_back = weight / g;
      for (int j = 0; j < dim; ++j) {
        const double h = b.coef[static_cast<std::size_t>(j)];
        c[static_cast<std::size_t>(j)] = exact_preimage(h / w, h, [w_back](double x) { return x * w_back; });
      }
    } else {
      for (int j = 0; j < dim; ++j) {
        const double x = b.coef[static_cast<std::size_t>(j)];
        c[static_cast<std::size_t>(j)] = exact_preimage(x * g, x, [g](double y) { return y / g; });
      }
    }
    os << dim << ' ' << (rat ? 1 : 0) << '\n';
    for (double x : c) {
      write_number(os, x);
      os << ' ';
    }
    write_number(os, g);
    os << ' ';
    write_number(os, weight);
    os << '\n';
    for (int k = 0; k < D; ++k) {
      os << b.knots[k].size();
      for (double x : b.knots[k]) os << ' ' << index_of(t[k], x);
      os << '\n';
    }
  }
}

}  // namespace

std::vector<AnyLRSpline> parse_lr_g2(std::string_view text, const std::string& name) {
  Tokens in(text, name);
  std::vector<AnyLRSpline> out;
  while (!in.at_end()) {
    const long type = in.integer("class type", 0, 100000);
    const int header_line = in.line();
    if (type != kSurfaceClass && type != kVolumeClass)
      in.fail("unsupported class type " + std::to_string(type) + " (LR splines are 293 LRSplineSurface and 793 LRSplineVolume)");
    const long major = in.integer("major version", 0, 100000);
    if (major != 1) in.fail("unsupported major version " + std::to_string(major) + " (expected 1)");
    in.integer("minor version", 0, 100000);
    const int aux = in.count("number of auxiliary values", 1000);
    for (int i = 0; i < aux; ++i) in.number("auxiliary value");
    if (type == kSurfaceClass)
      out.emplace_back(parse_object<2>(in, header_line));
    else
      out.emplace_back(parse_object<3>(in, header_line));
  }
  if (out.empty()) throw Error(name + ":1: no LR spline found (empty file)");
  return out;
}

std::vector<AnyLRSpline> read_lr_g2(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  require(f.good(), [&] { return "cannot open " + path; });
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_lr_g2(ss.str(), path);
}

void write_lr_g2(std::ostream& os, const AnyLRSpline& s) {
  std::visit([&](const auto& lr) { write_object(os, lr); }, s);
}

void write_lr_g2(const std::string& path, const std::vector<AnyLRSpline>& objects) {
  require(!objects.empty(), [&] { return "nothing to write to " + path; });
  write_file_atomically(path, [&](std::ostream& os) {
    for (const AnyLRSpline& s : objects) write_lr_g2(os, s);
  });
}

}  // namespace trivar::io
