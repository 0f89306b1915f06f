#include "trivar/io/lr_format.hpp"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <unordered_set>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/read_limits.hpp"
#include "trivar/lr/lr_mesh.hpp"

namespace trivar::io {

namespace {

// Character-level cursor over the text: the format mixes numbers with punctuation ([ ] x : ( ) , { }) and
// needs no whitespace around it, so a whitespace tokenizer does not fit.
class Cursor {
public:
  Cursor(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const { fail_at(line_, what); }
  [[noreturn]] void fail_at(int line, const std::string& what) const {
    throw Error(name_ + ":" + std::to_string(line) + ": " + what);
  }
  int line() const { return line_; }

  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_])))
      if (text_[pos_++] == '\n') ++line_;
  }
  // Skips whitespace and whole '#' comment lines.
  void skip_comments() {
    for (skip_space(); pos_ < text_.size() && text_[pos_] == '#'; skip_space())
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  }
  bool at_end() {
    skip_space();
    return pos_ >= text_.size();
  }
  bool starts_with(std::string_view s) {
    skip_space();
    return text_.substr(pos_).starts_with(s);
  }
  // The rest of the current line after leading whitespace, not consumed.
  std::string_view peek_line() {
    skip_space();
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    return text_.substr(pos_, end - pos_);
  }
  std::string_view line_text() {
    skip_space();
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    std::string_view l = text_.substr(pos_, end - pos_);
    while (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    pos_ = end;
    return l;
  }
  bool accept(char c) {
    skip_space();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  void expect(char c, const char* where) {
    if (!accept(c)) fail(std::string("expected '") + c + "' " + where + ", found " + next_token());
  }
  double number(const char* what) {
    skip_space();
    double x = 0;
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + text_.size();
    if (first < last && *first == '+') ++first;  // from_chars rejects a leading '+', C++ streams write none
    const auto r = std::from_chars(first, last, x);
    if (r.ec != std::errc() || r.ptr == first) fail(std::string("expected ") + what + ", found " + next_token());
    if (!std::isfinite(x)) fail(std::string(what) + " is not finite");
    pos_ = static_cast<std::size_t>(r.ptr - text_.data());
    return x;
  }
  long integer(const char* what) {
    skip_space();
    long x = 0;
    const char* first = text_.data() + pos_;
    const auto r = std::from_chars(first, text_.data() + text_.size(), x);
    if (r.ec != std::errc() || r.ptr == first) fail(std::string("expected ") + what + ", found " + next_token());
    pos_ = static_cast<std::size_t>(r.ptr - text_.data());
    return x;
  }
  int count(const char* what, long max) {
    const long n = integer(what);
    if (n < 0 || n > max) fail(std::string(what) + " " + std::to_string(n) + " is out of range");
    return static_cast<int>(n);
  }

private:
  std::string next_token() {
    skip_space();
    if (pos_ >= text_.size()) return "end of file";
    std::size_t end = pos_ + 1;
    while (end < text_.size() && end - pos_ < 20 && !std::isspace(static_cast<unsigned char>(text_[end]))) ++end;
    std::string quoted = "'";
    quoted.append(text_.substr(pos_, end - pos_));
    quoted += '\'';
    return quoted;
  }

  std::string_view text_;
  const std::string& name_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// Orders are read as ints; degrees above this are not splines anyone writes and would only blow up memory.
constexpr long kMaxOrder = 64;

template <int D>
std::string box_text(const Box<D>& b) {
  std::string t;
  for (int corner = 0; corner < 2; ++corner) {
    t += corner ? " x (" : "(";
    for (int k = 0; k < D; ++k) t += (k ? ", " : "") + format_number(corner ? b.hi[k] : b.lo[k]);
    t += ')';
  }
  return t;
}

// Numbers s's elements as the block lists them, so element ids are the file's positions. The corners must
// agree with the mesh's elements up to rounding in the last digits (writers that print 16 significant digits
// round their mesh lines and element corners alike, but not necessarily to the same double as trivar's).
template <int D>
void adopt_element_order(const Cursor& in, LRSpline<D>& s, const std::vector<Box<D>>& listed,
                         const std::vector<int>& lines) {
  const Box<D>& dom = s.domain();
  ElementGrid<D> grid(dom, static_cast<std::size_t>(s.num_elements()));
  for (int e = 0; e < s.num_elements(); ++e) grid.add(e, s.element(e));
  const auto same = [&](const Box<D>& a, const Box<D>& b) {
    for (int k = 0; k < D; ++k) {
      const double tol = 1e-13 * dom.extent(k);
      if (std::abs(a.lo[k] - b.lo[k]) > tol || std::abs(a.hi[k] - b.hi[k]) > tol) return false;
    }
    return true;
  };
  const std::string counts = "the mesh has " + std::to_string(s.num_elements()) + " elements, the block lists " +
                             std::to_string(listed.size());
  std::vector<int> order, listed_as(static_cast<std::size_t>(s.num_elements()), -1);
  order.reserve(listed.size());
  for (std::size_t i = 0; i < listed.size(); ++i) {
    const Param<D> c = listed[i].center();
    int found = -1;
    grid.query(Box<D>{c, c}, [&](int e) {
      if (found < 0 && same(s.element(e), listed[i])) found = e;
    });
    const auto where = "element " + std::to_string(i) + " of the block, " + box_text(listed[i]);
    if (found < 0)
      in.fail_at(lines[i], where + ", is not an element of the mesh (" + counts +
                               "; elements are the boxes the mesh rectangles cut the domain into)");
    if (listed_as[static_cast<std::size_t>(found)] >= 0)
      in.fail_at(lines[i], where + ", repeats element " + std::to_string(listed_as[static_cast<std::size_t>(found)]));
    listed_as[static_cast<std::size_t>(found)] = static_cast<int>(i);
    order.push_back(found);
  }
  for (int e = 0; e < s.num_elements(); ++e)
    if (listed_as[static_cast<std::size_t>(e)] < 0)
      in.fail(counts + ": the mesh element " + box_text(s.element(e)) + " is missing from the block");
  s.reorder_elements(order);
}

template <int D>
LRSpline<D> parse_block(Cursor& in) {
  Ints<D> degrees{};
  for (int k = 0; k < D; ++k) degrees[k] = in.count("order", kMaxOrder) - 1;
  for (int k = 0; k < D; ++k)
    if (degrees[k] < 0) in.fail("order of direction " + std::to_string(k) + " must be at least 1");
  const int nbasis = in.count("number of basis functions", kMaxCount);
  const int nmesh = in.count("number of mesh lines", kMaxCount);
  const int nel = in.count("number of elements", kMaxCount);
  const int dim = in.count("dimension", 1024);
  if (dim < 1) in.fail("dimension must be at least 1");
  const long rat = in.integer("rational flag");
  if (rat != 0 && rat != 1) in.fail("rational flag must be 0 or 1, got " + std::to_string(rat));
  const int stride = dim + static_cast<int>(rat);

  std::vector<LRBSpline<D>> basis(static_cast<std::size_t>(nbasis));
  std::unordered_set<long> ids;
  for (LRBSpline<D>& b : basis) {
    in.skip_comments();
    const long id = in.integer("basis function id");
    if (!ids.insert(id).second) in.fail("basis function id " + std::to_string(id) + " appears twice");
    in.expect(':', "after a basis function id");
    for (int k = 0; k < D; ++k) {
      if (k > 0) in.expect('x', "between local knot vectors");
      in.expect('[', "before a local knot vector");
      b.knots[k].resize(static_cast<std::size_t>(degrees[k] + 2));
      for (double& t : b.knots[k]) t = in.number("local knot");
      in.expect(']', "after a local knot vector (wrong number of knots for the order?)");
    }
    b.coef.resize(static_cast<std::size_t>(stride));
    for (double& c : b.coef) c = in.number("control value");
    in.expect('(', "before the scaling factor (wrong number of control values for dim and rat?)");
    b.gamma = in.number("scaling factor");
    in.expect(')', "after the scaling factor");
  }

  std::vector<MeshRectangle<D>> mesh(static_cast<std::size_t>(nmesh));
  for (MeshRectangle<D>& r : mesh) {
    in.skip_comments();
    int constant = -1;
    for (int k = 0; k < D; ++k) {
      if (k > 0) in.expect('x', "between mesh rectangle extents");
      double lo = 0, hi = 0;
      if (in.accept('[')) {
        lo = in.number("mesh extent start");
        in.expect(',', "in a mesh extent");
        hi = in.number("mesh extent end");
        in.expect(']', "after a mesh extent");
      } else {
        lo = hi = in.number("mesh line value");
      }
      if (lo == hi) {
        if (constant >= 0) in.fail("mesh rectangle is degenerate in two directions");
        constant = k;
      } else if (lo > hi) {
        in.fail("mesh extent [" + format_number(lo) + ", " + format_number(hi) + "] is reversed");
      }
      r.extent.lo[k] = lo;
      r.extent.hi[k] = hi;
    }
    if (constant < 0) in.fail("mesh rectangle has no constant direction");
    r.dir = constant;
    r.value = r.extent.lo[constant];
    in.expect('(', "before the mesh multiplicity");
    r.multiplicity = in.count("mesh multiplicity", kMaxOrder);
    in.expect(')', "after the mesh multiplicity");
  }

  // Elements are implied by the mesh; the file's list must name exactly the mesh's elements (any order, which
  // becomes the element numbering) and known basis function ids.
  std::vector<Box<D>> listed(static_cast<std::size_t>(nel));
  std::vector<int> lines(static_cast<std::size_t>(nel));
  for (int e = 0; e < nel; ++e) {
    in.skip_comments();
    lines[static_cast<std::size_t>(e)] = in.line();
    in.integer("element id");
    in.expect('[', "before the element dimension");
    if (in.integer("element dimension") != D) in.fail("element dimension must be " + std::to_string(D));
    in.expect(']', "after the element dimension");
    in.expect(':', "after the element dimension");
    for (int corner = 0; corner < 2; ++corner) {
      if (corner > 0) in.expect('x', "between element corners");
      in.expect('(', "before an element corner");
      for (int k = 0; k < D; ++k) {
        if (k > 0) in.expect(',', "in an element corner");
        (corner == 0 ? listed[static_cast<std::size_t>(e)].lo : listed[static_cast<std::size_t>(e)].hi)[k] =
            in.number("element corner coordinate");
      }
      in.expect(')', "after an element corner");
    }
    in.expect('{', "before an element support list");
    if (!in.accept('}')) {
      do {
        const long id = in.integer("basis function id");
        if (!ids.contains(id)) in.fail("element " + std::to_string(e) + " refers to unknown basis function " + std::to_string(id));
      } while (in.accept(','));
      in.expect('}', "after an element support list");
    }
  }

  // The constructor validates knots, scaling factors and the mesh; its message gets the block's position.
  std::optional<LRSpline<D>> s;
  try {
    s.emplace(degrees, dim, rat == 1, std::move(basis), std::move(mesh));
  } catch (const Error& e) {
    in.fail(e.what());
  }
  adopt_element_order(in, *s, listed, lines);
  return std::move(*s);
}

template <int D>
void write_block(std::ostream& os, const LRSpline<D>& s) {
  os << (D == 2 ? "# LRSPLINE SURFACE\n#\tp1\tp2\t" : "# LRSPLINE VOLUME\n#\tp1\tp2\tp3\t")
     << "Nbasis\tNline\tNel\tdim\trat\n\t";
  for (int k = 0; k < D; ++k) os << s.degree(k) + 1 << '\t';
  os << s.num_basis() << '\t' << s.mesh().size() << '\t' << s.num_elements() << '\t' << s.dim() << '\t'
     << (s.is_rational() ? 1 : 0) << '\n';
  os << "# Basis functions:\n";
  for (int i = 0; i < s.num_basis(); ++i) {
    const LRBSpline<D>& b = s.basis_function(i);
    os << i << ": ";
    for (int k = 0; k < D; ++k) {
      if (k > 0) os << "x ";
      os << '[';
      for (double t : b.knots[k]) {
        write_number(os, t);
        os << ' ';
      }
      os << "] ";
    }
    for (double c : b.coef) {
      write_number(os, c);
      os << ' ';
    }
    os << '(';
    write_number(os, b.gamma);
    os << ")\n";
  }
  os << (D == 2 ? "# Mesh lines:\n" : "# Mesh rectangles:\n");
  for (const MeshRectangle<D>& r : s.mesh()) {
    for (int k = 0; k < D; ++k) {
      if (k > 0) os << " x ";
      if (D == 2 && k == r.dir) {
        write_number(os, r.value);
        continue;
      }
      os << '[';
      write_number(os, k == r.dir ? r.value : r.extent.lo[k]);
      os << ", ";
      write_number(os, k == r.dir ? r.value : r.extent.hi[k]);
      os << ']';
    }
    os << " (" << r.multiplicity << ")\n";
  }
  // Elements in id order, so the n-th element listed is element n everywhere (refine --elements, VTK cells);
  // the reader keeps the listed order, so write(read(write(s))) == write(s).
  os << "# Elements:\n";
  for (int e = 0; e < s.num_elements(); ++e) {
    const Box<D>& el = s.element(e);
    os << e << " [" << D << "] : (";
    for (int k = 0; k < D; ++k) {
      if (k > 0) os << ", ";
      write_number(os, el.lo[k]);
    }
    os << ") x (";
    for (int k = 0; k < D; ++k) {
      if (k > 0) os << ", ";
      write_number(os, el.hi[k]);
    }
    os << ")    {";
    bool first = true;
    for (int id : s.element_support(e)) {
      os << (first ? "" : ", ") << id;
      first = false;
    }
    os << "}\n";
  }
}

// The parametric dimension of the next block, after its comment lines: from a "# LRSPLINE SURFACE" or
// "# LRSPLINE VOLUME" comment when there is one. Older LRsplines versions wrote a bare "# LRSPLINE" (surfaces),
// and LRsplines' reader skips every comment line, so otherwise the header line decides by its number of values:
// 7 for a surface (p1 p2 Nbasis Nline Nel dim rat), 8 for a volume (p3 after p2).
int block_dimension(Cursor& in) {
  int dimension = 0;
  while (in.starts_with("#")) {
    const int at = in.line();
    const std::string_view line = in.line_text();
    if (!line.starts_with("# LRSPLINE") || dimension != 0) continue;
    std::string_view kind = line.substr(10);
    while (!kind.empty() && std::isspace(static_cast<unsigned char>(kind.front()))) kind.remove_prefix(1);
    while (!kind.empty() && std::isspace(static_cast<unsigned char>(kind.back()))) kind.remove_suffix(1);
    if (kind == "SURFACE") dimension = 2;
    else if (kind == "VOLUME") dimension = 3;
    else if (!kind.empty())
      in.fail_at(at, "unsupported LR spline kind '" + std::string(kind.substr(0, 20)) +
                         "' (expected '# LRSPLINE SURFACE' or '# LRSPLINE VOLUME')");
  }
  if (dimension != 0) return dimension;
  std::istringstream header{std::string(in.peek_line())};
  int values = 0;
  for (std::string token; header >> token;) ++values;
  if (values == 7) return 2;
  if (values == 8) return 3;
  in.fail("expected a header line 'p1 p2 [p3] Nbasis Nline Nel dim rat' (7 values for a surface, 8 for a "
          "volume), found " + std::to_string(values) + " values");
}

}  // namespace

std::vector<AnyLRSpline> parse_lr(std::string_view text, const std::string& name) {
  Cursor in(text, name);
  std::vector<AnyLRSpline> out;
  while (!in.at_end()) {
    if (block_dimension(in) == 2)
      out.emplace_back(parse_block<2>(in));
    else
      out.emplace_back(parse_block<3>(in));
  }
  if (out.empty()) throw Error(name + ":1: no LR spline found (empty file)");
  return out;
}

std::vector<AnyLRSpline> read_lr(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  require(f.good(), [&] { return "cannot open " + path; });
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_lr(ss.str(), path);
}

void write_lr(std::ostream& os, const AnyLRSpline& s) {
  std::visit([&](const auto& lr) { write_block(os, lr); }, s);
}

void write_lr(const std::string& path, const std::vector<AnyLRSpline>& objects) {
  require(!objects.empty(), [&] { return "nothing to write to " + path; });
  write_file_atomically(path, [&](std::ostream& os) {
    for (const AnyLRSpline& s : objects) write_lr(os, s);
  });
}

}  // namespace trivar::io
