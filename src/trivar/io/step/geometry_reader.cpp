#include "trivar/io/step/geometry_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

#include "trivar/core/error.hpp"
#include "trivar/io/step/bspline_entity_names.hpp"
#include "trivar/lr/knot_line_mesh.hpp"
#include "trivar/spline/knot_refinement.hpp"

namespace trivar::io::step {

namespace {

constexpr std::array<const char*, 3> kBezier = {"BEZIER_CURVE", "BEZIER_SURFACE", "BEZIER_VOLUME"};
constexpr std::array<const char*, 3> kUniform = {"UNIFORM_CURVE", "UNIFORM_SURFACE", "UNIFORM_VOLUME"};
constexpr std::array<const char*, 3> kQuasi = {"QUASI_UNIFORM_CURVE", "QUASI_UNIFORM_SURFACE",
                                               "QUASI_UNIFORM_VOLUME"};
constexpr std::array<const char*, 3> kLR = {"LOCALLY_REFINED_SPLINE_CURVE", "LOCALLY_REFINED_SPLINE_SURFACE",
                                            "LOCALLY_REFINED_SPLINE_VOLUME"};
constexpr std::array<const char*, 3> kRationalLR = {"RATIONAL_LOCALLY_REFINED_SPLINE_CURVE",
                                                    "RATIONAL_LOCALLY_REFINED_SPLINE_SURFACE",
                                                    "RATIONAL_LOCALLY_REFINED_SPLINE_VOLUME"};
// Explicit attributes after the name: of b_spline_{curve,surface,volume} and of its _with_knots subtype.
constexpr std::array<int, 3> kBaseCount = {5, 7, 4};
constexpr std::array<int, 3> kKnotsCount = {3, 5, 6};
// Of locally_refined_spline_{curve,surface,volume}.
constexpr std::array<int, 3> kLRCount = {8, 12, 11};
constexpr std::array<char, 3> kDir = {'u', 'v', 'w'};

enum class KnotForm { knots, bezier, uniform, quasi_uniform };

template <int D>
struct ScaledCollection {
  Ints<D> degrees{};
  int dim = 0;
  bool rational = false;
  std::vector<LRBSpline<D>> basis;
  std::string type;  // locally_refined_spline_type
};

// Error reporting and typed access for one instance being mapped.
class Scope {
public:
  Scope(const ExchangeFile& file, const std::string& file_name, const Instance& in)
      : file_(file), file_name_(file_name), in_(in) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw Error(file_name_ + ":" + std::to_string(in_.line) + ":" + std::to_string(in_.column) + ": #" +
                std::to_string(in_.id) + ": " + in_.type_name() + ": " + message);
  }
  void check(bool ok, const std::string& message) const {
    if (!ok) fail(message);
  }

  static const Parameter& unboxed(const Parameter& p) {
    const Parameter* q = &p;
    while (const auto* t = q->get_if<Typed>()) q = &t->value();
    return *q;
  }
  double number(const Parameter& p, const std::string& what) const {
    const auto v = unboxed(p).number();
    if (!v) fail(what + ": expected a number, found " + kind_name(unboxed(p).kind()));
    if (!std::isfinite(*v)) fail(what + ": not finite");
    return *v;
  }
  std::int64_t integer(const Parameter& p, const std::string& what) const {
    const auto* v = unboxed(p).get_if<std::int64_t>();
    if (!v) fail(what + ": expected an integer, found " + kind_name(unboxed(p).kind()));
    return *v;
  }
  const std::vector<Parameter>& list(const Parameter& p, const std::string& what) const {
    const auto* l = p.get_if<List>();
    if (!l) fail(what + ": expected a list, found " + kind_name(p.kind()));
    return l->items;
  }
  std::string enumeration(const Parameter& p, const std::string& what) const {
    const auto* e = p.get_if<Enumeration>();
    if (!e) fail(what + ": expected an enumeration, found " + kind_name(p.kind()));
    return e->name;
  }
  std::vector<double> numbers(const Parameter& p, const std::string& what) const {
    const auto& items = list(p, what);
    std::vector<double> out;
    out.reserve(items.size());
    for (std::size_t i = 0; i < items.size(); ++i) out.push_back(number(items[i], what + "[" + std::to_string(i) + "]"));
    return out;
  }
  std::vector<std::int64_t> integers(const Parameter& p, const std::string& what) const {
    const auto& items = list(p, what);
    std::vector<std::int64_t> out;
    out.reserve(items.size());
    for (std::size_t i = 0; i < items.size(); ++i)
      out.push_back(integer(items[i], what + "[" + std::to_string(i) + "]"));
    return out;
  }
  // The instance a reference names, which must have the given keyword.
  const Instance& resolve(const Parameter& p, const char* keyword, const std::string& what) const {
    const auto* r = p.get_if<Reference>();
    if (!r) fail(what + ": expected a reference to a " + keyword + ", found " + kind_name(p.kind()));
    const Instance* target = file_.find(r->id);
    if (!target) {
      if (file_.point(r->id))  // held compactly by the reader
        fail(what + ": #" + std::to_string(r->id) + " is a CARTESIAN_POINT, expected a " + keyword);
      if (file_.is_skipped(r->id)) fail(what + ": #" + std::to_string(r->id) + " is not a " + keyword);
      fail(what + ": reference to undefined instance #" + std::to_string(r->id));
    }
    if (!target->is(keyword))
      fail(what + ": #" + std::to_string(r->id) + " is a " + target->type_name() + ", expected a " + keyword);
    return *target;
  }
  // Appends the coordinates of the CARTESIAN_POINT `p` refers to; all points of an object have `dim` coordinates
  // (set by the first one when 0).
  void point(const Parameter& p, const std::string& what, int& dim, std::vector<double>& out) const {
    if (const auto* r = p.get_if<Reference>())
      if (const ExchangeFile::Point* compact = file_.point(r->id)) {
        if (dim == 0) dim = compact->dimension;
        if (compact->dimension != dim)
          fail(what + " (#" + std::to_string(r->id) + "): " + std::to_string(compact->dimension) +
               " coordinates, the first control point has " + std::to_string(dim));
        out.insert(out.end(), compact->coordinates.begin(), compact->coordinates.begin() + dim);
        return;
      }
    const Instance& pt = resolve(p, "CARTESIAN_POINT", what);
    const Record& r = *pt.record("CARTESIAN_POINT");
    const std::string where = what + " (#" + std::to_string(pt.id) + ")";
    if (r.params.size() != 2)
      fail(where + ": CARTESIAN_POINT has " + std::to_string(r.params.size()) + " parameters, expected 2");
    const auto& c = list(r.params[1], where + ": coordinates");
    if (c.empty() || c.size() > 3) fail(where + ": " + std::to_string(c.size()) + " coordinates, expected 1 to 3");
    if (dim == 0) dim = static_cast<int>(c.size());
    if (static_cast<int>(c.size()) != dim)
      fail(where + ": " + std::to_string(c.size()) + " coordinates, the first control point has " +
           std::to_string(dim));
    for (std::size_t i = 0; i < c.size(); ++i) out.push_back(number(c[i], where + ": coordinate " + std::to_string(i)));
  }
  // The parameters of record `keyword` of the instance, checking their number.
  const std::vector<Parameter>& record(const char* keyword, std::size_t count) const {
    const Record* r = in_.record(keyword);
    if (!r) fail(std::string("missing partial record ") + keyword);
    if (r->params.size() != count)
      fail(std::string(keyword) + " has " + std::to_string(r->params.size()) + " parameters, expected " +
           std::to_string(count));
    return r->params;
  }
private:
  const ExchangeFile& file_;
  const std::string& file_name_;
  const Instance& in_;
};

// Flattens a D-deep nested list into its leaves in STEP order (first index outermost), checking the shape.
template <int D>
void flatten(const Scope& s, const Parameter& p, const std::string& what, int depth, std::string path,
             std::array<int, D>& n, std::vector<const Parameter*>& out) {
  const auto& items = s.list(p, what + path);
  const int size = static_cast<int>(items.size());
  if (n[depth] < 0) {
    if (size < 2) s.fail(what + path + ": " + std::to_string(size) + " entries, expected at least 2");
    n[depth] = size;
  } else if (size != n[depth]) {
    s.fail(what + path + ": " + std::to_string(size) + " entries, expected " + std::to_string(n[depth]));
  }
  for (int i = 0; i < size; ++i) {
    if (depth + 1 == D)
      out.push_back(&items[static_cast<std::size_t>(i)]);
    else
      flatten<D>(s, items[static_cast<std::size_t>(i)], what, depth + 1, path + "[" + std::to_string(i) + "]", n, out);
  }
}

// trivar's linear index (u fastest) of the STEP-order position `step` (u outermost) in a grid of counts n.
template <int D>
std::size_t to_trivar_index(std::size_t step, const std::array<int, D>& n) {
  std::array<std::size_t, D> idx{};
  for (int k = D - 1; k >= 0; --k) {
    idx[static_cast<std::size_t>(k)] = step % static_cast<std::size_t>(n[k]);
    step /= static_cast<std::size_t>(n[k]);
  }
  std::size_t lin = 0;
  for (int k = D - 1; k >= 0; --k) lin = lin * static_cast<std::size_t>(n[k]) + idx[static_cast<std::size_t>(k)];
  return lin;
}

// Knots of direction `dir` (degree p, n control points) from explicit multiplicities and values.
std::vector<double> explicit_knots(const Scope& s, int dir, int p, int n, const Parameter& mults_p,
                                   const Parameter& knots_p, bool curve) {
  const std::string d = curve ? "" : std::string(1, kDir[static_cast<std::size_t>(dir)]) + "_";
  const auto mults = s.integers(mults_p, d + (curve ? "knot_multiplicities" : "multiplicities"));
  const auto values = s.numbers(knots_p, d + "knots");
  if (mults.size() != values.size())
    s.fail(d + "knots: " + std::to_string(values.size()) + " values but " + std::to_string(mults.size()) +
           " multiplicities");
  if (values.size() < 2) s.fail(d + "knots: " + std::to_string(values.size()) + " values, expected at least 2");
  std::int64_t sum = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0 && !(values[i - 1] < values[i]))
      s.fail(d + "knots: not strictly increasing at index " + std::to_string(i));
    const bool end = i == 0 || i + 1 == values.size();
    const std::int64_t hi = end ? p + 1 : p;
    if (mults[i] < 1 || mults[i] > hi)
      s.fail(d + "knots: multiplicity " + std::to_string(mults[i]) + " of knot " + std::to_string(i) +
             " outside 1.." + std::to_string(hi));
    sum += mults[i];
  }
  if (sum != n + p + 1)
    s.fail(d + "knots: multiplicities sum to " + std::to_string(sum) + ", expected " + std::to_string(n + p + 1) +
           " (" + std::to_string(n) + " control points + degree " + std::to_string(p) + " + 1)");
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(sum));
  for (std::size_t i = 0; i < values.size(); ++i) t.insert(t.end(), static_cast<std::size_t>(mults[i]), values[i]);
  return t;
}

// Knots Part 42 defines for the uniform, quasi-uniform and piecewise Bezier forms (spacing 1).
std::vector<double> implied_knots(const Scope& s, int dir, KnotForm form, int p, int n) {
  std::vector<double> t;
  const std::string d(1, kDir[static_cast<std::size_t>(dir)]);
  switch (form) {
    case KnotForm::uniform:
      for (int i = 0; i < n + p + 1; ++i) t.push_back(static_cast<double>(i - p));
      break;
    case KnotForm::quasi_uniform:
      if (n < p + 1)
        s.fail(d + ": " + std::to_string(n) + " control points, a quasi-uniform form of degree " + std::to_string(p) +
               " needs at least " + std::to_string(p + 1));
      t.assign(static_cast<std::size_t>(p + 1), 0.0);
      for (int i = 1; i < n - p; ++i) t.push_back(i);
      t.insert(t.end(), static_cast<std::size_t>(p + 1), static_cast<double>(n - p));
      break;
    case KnotForm::bezier: {
      if ((n - 1) % p != 0)
        s.fail(d + ": " + std::to_string(n) + " control points, a piecewise Bezier form of degree " +
               std::to_string(p) + " needs a multiple of " + std::to_string(p) + " plus 1");
      const int segments = (n - 1) / p;
      t.assign(static_cast<std::size_t>(p + 1), 0.0);
      for (int i = 1; i < segments; ++i) t.insert(t.end(), static_cast<std::size_t>(p), static_cast<double>(i));
      t.insert(t.end(), static_cast<std::size_t>(p + 1), static_cast<double>(segments));
      break;
    }
    case KnotForm::knots: break;
  }
  return t;
}

std::string prefix_lr(const std::string& message) {
  // LRSpline's own messages start with "LRSpline: "; the scope names the entity already.
  constexpr std::string_view tag = "LRSpline: ";
  return message.starts_with(tag) ? message.substr(tag.size()) : message;
}

struct LocalBSpline {
  int degree = 0;
  std::vector<std::int64_t> knots, mults;
};

}  // namespace

const char* to_string(GeometryKind kind) {
  switch (kind) {
    case GeometryKind::curve: return "curve";
    case GeometryKind::surface: return "surface";
    case GeometryKind::volume: return "volume";
    case GeometryKind::lr_curve: return "lr_curve";
    case GeometryKind::lr_surface: return "lr_surface";
    case GeometryKind::lr_volume: return "lr_volume";
    case GeometryKind::none: break;
  }
  return "none";
}

GeometryKind geometry_kind(const Instance& in) {
  for (std::size_t d = 0; d < 3; ++d) {
    const auto tensor = static_cast<GeometryKind>(static_cast<int>(GeometryKind::curve) + static_cast<int>(d));
    const auto lr = static_cast<GeometryKind>(static_cast<int>(GeometryKind::lr_curve) + static_cast<int>(d));
    if (in.is(kBase[d]) || in.is(kWithKnots[d]) || in.is(kBezier[d]) || in.is(kUniform[d]) || in.is(kQuasi[d]) ||
        in.is(kRational[d]))
      return tensor;
    if (in.is(kLR[d]) || in.is(kRationalLR[d])) return lr;
  }
  return GeometryKind::none;
}

bool is_geometry_keyword(std::string_view k) {
  if (k == "CARTESIAN_POINT" || k == "LOCAL_B_SPLINE") return true;
  for (std::size_t d = 0; d < 3; ++d)
    if (k == kBase[d] || k == kWithKnots[d] || k == kBezier[d] || k == kUniform[d] || k == kQuasi[d] ||
        k == kRational[d] || k == kLR[d] || k == kRationalLR[d])
      return true;
  return false;
}

GeometryReader::GeometryReader(const ExchangeFile& file, std::string file_name)
    : file_(file), file_name_(std::move(file_name)) {}

std::string GeometryReader::name(const Instance& in) const {
  const Record* r = in.complex ? in.record("REPRESENTATION_ITEM") : &in.records.front();
  if (!r || r->params.empty()) return {};
  const auto* s = r->params.front().get_if<std::string>();
  return s ? *s : std::string();
}

AnySpline GeometryReader::tensor_spline(const Instance& in) const {
  switch (geometry_kind(in)) {
    case GeometryKind::curve: return read_tensor<1>(in);
    case GeometryKind::surface: return read_tensor<2>(in);
    case GeometryKind::volume: return read_tensor<3>(in);
    case GeometryKind::lr_curve: return read_lr_curve(in);
    default: Scope(file_, file_name_, in).fail("not a B-spline curve, surface or volume");
  }
}

AnyLRSpline GeometryReader::lr_spline(const Instance& in) const {
  switch (geometry_kind(in)) {
    case GeometryKind::lr_surface: return read_lr<2>(in);
    case GeometryKind::lr_volume: return read_lr<3>(in);
    case GeometryKind::lr_curve: Scope(file_, file_name_, in).fail("a locally refined curve is read as a B-spline curve");
    default: Scope(file_, file_name_, in).fail("not a locally refined surface or volume");
  }
}

template <int D>
TensorSpline<D> GeometryReader::read_tensor(const Instance& in) const {
  const Scope s(file_, file_name_, in);
  constexpr std::size_t d = D - 1;
  const std::size_t nb = static_cast<std::size_t>(kBaseCount[d]), nk = static_cast<std::size_t>(kKnotsCount[d]);
  // The attributes in simple-instance order (without the name): base, then the knots subtype's, then weights.
  std::vector<const Parameter*> base, knots;
  const Parameter* weights = nullptr;
  KnotForm form = KnotForm::knots;
  if (!in.complex) {
    const Record& r = in.records.front();
    std::size_t expected = 1 + nb;
    if (r.keyword == kWithKnots[d]) {
      expected += nk;
    } else if (r.keyword == kBezier[d]) {
      form = KnotForm::bezier;
    } else if (r.keyword == kUniform[d]) {
      form = KnotForm::uniform;
    } else if (r.keyword == kQuasi[d]) {
      form = KnotForm::quasi_uniform;
    } else {
      s.fail(std::string("a simple instance needs a knot form; write ") + kBase[d] + " with " + kWithKnots[d] +
             " (or a uniform, quasi-uniform or Bezier form) as a complex instance");
    }
    s.check(r.params.size() == expected, std::to_string(r.params.size()) + " parameters, expected " +
                                             std::to_string(expected));
    for (std::size_t i = 1; i <= nb; ++i) base.push_back(&r.params[i]);
    for (std::size_t i = 1 + nb; i < expected; ++i) knots.push_back(&r.params[i]);
  } else {
    for (const Parameter& p : s.record(kBase[d], nb)) base.push_back(&p);
    const int forms = in.is(kWithKnots[d]) + in.is(kBezier[d]) + in.is(kUniform[d]) + in.is(kQuasi[d]);
    s.check(forms == 1, std::string("expected exactly one of ") + kWithKnots[d] + ", " + kBezier[d] + ", " +
                            kUniform[d] + ", " + kQuasi[d] + ", found " + std::to_string(forms));
    if (in.is(kWithKnots[d])) {
      for (const Parameter& p : s.record(kWithKnots[d], nk)) knots.push_back(&p);
    } else {
      const char* kw = in.is(kBezier[d]) ? kBezier[d] : in.is(kUniform[d]) ? kUniform[d] : kQuasi[d];
      s.record(kw, 0);
      form = in.is(kBezier[d]) ? KnotForm::bezier : in.is(kUniform[d]) ? KnotForm::uniform : KnotForm::quasi_uniform;
    }
    if (in.is(kRational[d])) weights = &s.record(kRational[d], 1).front();
  }

  std::array<int, D> p{};
  for (int k = 0; k < D; ++k) {
    const std::string what = D == 1 ? "degree" : std::string(1, kDir[static_cast<std::size_t>(k)]) + "_degree";
    const std::int64_t v = s.integer(*base[static_cast<std::size_t>(k)], what);
    s.check(v >= 1 && v <= 64, what + " " + std::to_string(v) + " outside 1..64");
    p[static_cast<std::size_t>(k)] = static_cast<int>(v);
  }
  std::array<int, D> n;
  n.fill(-1);
  std::vector<const Parameter*> leaves;
  flatten<D>(s, *base[D], "control_points_list", 0, "", n, leaves);

  int dim = 0;
  std::vector<double> step_points;
  step_points.reserve(leaves.size() * 3);
  for (std::size_t i = 0; i < leaves.size(); ++i)
    s.point(*leaves[i], "control point " + std::to_string(i), dim, step_points);

  std::array<KnotVector, D> kv;
  for (int k = 0; k < D; ++k) {
    const std::size_t uk = static_cast<std::size_t>(k);
    std::vector<double> t = form == KnotForm::knots
                                ? explicit_knots(s, k, p[uk], n[uk], *knots[uk], *knots[D + uk], D == 1)
                                : implied_knots(s, k, form, p[uk], n[uk]);
    try {
      kv[uk] = KnotVector(p[uk], std::move(t));
    } catch (const Error& e) {
      s.fail(std::string(1, kDir[uk]) + " knots: " + e.what());
    }
  }
  if (form == KnotForm::knots && D < 3) {
    const std::string spec = s.enumeration(*knots.back(), "knot_spec");
    s.check(spec == "UNIFORM_KNOTS" || spec == "QUASI_UNIFORM_KNOTS" || spec == "PIECEWISE_BEZIER_KNOTS" ||
                spec == "UNSPECIFIED",
            "knot_spec: unknown value ." + spec + ".");
  }

  const std::size_t count = leaves.size();
  std::vector<double> points(count * static_cast<std::size_t>(dim)), w;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t j = to_trivar_index<D>(i, n);
    std::copy_n(step_points.begin() + static_cast<std::ptrdiff_t>(i * static_cast<std::size_t>(dim)), dim,
                points.begin() + static_cast<std::ptrdiff_t>(j * static_cast<std::size_t>(dim)));
  }
  if (weights) {
    std::array<int, D> wn;
    wn.fill(-1);
    std::vector<const Parameter*> wl;
    flatten<D>(s, *weights, "weights_data", 0, "", wn, wl);
    s.check(wn == n, "weights_data: shape differs from control_points_list");
    w.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double x = s.number(*wl[i], "weights_data " + std::to_string(i));
      s.check(x > 0.0, "weights_data " + std::to_string(i) + ": weight " + std::to_string(x) + " is not positive");
      w[to_trivar_index<D>(i, n)] = x;
    }
  }
  try {
    return TensorSpline<D>::from_cartesian(std::move(kv), dim, points, w);
  } catch (const Error& e) {
    s.fail(e.what());
  }
}

// The scaled B-splines of a locally refined curve, surface or volume, validated.
template <int D>
ScaledCollection<D> read_scaled(const Scope& s, const Instance& in) {
  constexpr std::size_t d = D - 1;
  const std::size_t na = static_cast<std::size_t>(kLRCount[d]);
  std::vector<const Parameter*> a;
  const Parameter* weights = nullptr;
  if (!in.complex) {
    const Record& r = in.records.front();
    const bool rational = r.keyword == kRationalLR[d];
    const std::size_t expected = 1 + na + (rational ? 1 : 0);
    s.check(r.params.size() == expected, std::to_string(r.params.size()) + " parameters, expected " +
                                             std::to_string(expected));
    for (std::size_t i = 1; i <= na; ++i) a.push_back(&r.params[i]);
    if (rational) weights = &r.params.back();
  } else {
    for (const Parameter& q : s.record(kLR[d], na)) a.push_back(&q);
    if (in.is(kRationalLR[d])) weights = &s.record(kRationalLR[d], 1).front();
  }
  // Attribute positions: D b-spline lists, D knot lists, control points, scaling factors, independence (the
  // curve has closed_curve there), type, ..., domain.
  const Parameter& cps = *a[2 * D];
  const Parameter& scaling = *a[2 * D + 1];
  if constexpr (D > 1) {
    const std::string independence = s.enumeration(*a[2 * D + 2], "linearly_independent");
    s.check(independence == "INDEPENDENT" || independence == "NOT_INDEPENDENT" || independence == "NOT_TESTED",
            "linearly_independent: unknown value ." + independence + ".");
  }
  const std::string type = s.enumeration(*a[2 * D + 3], "locally_refined_spline_type");
  s.check(type == "ANALYSIS_SUITABLE_T_SPLINE" || type == "HIERARCHICAL_B_SPLINE" || type == "LR_B_SPLINE" ||
              type == "SEMI_STANDARD_T_SPLINE" || type == "STANDARD_T_SPLINE",
          "locally_refined_spline_type: unknown value ." + type + ".");

  const auto& points = s.list(cps, "control_points_list");
  const std::size_t count = points.size();
  s.check(count >= (std::size_t{1} << D), "control_points_list: " + std::to_string(count) +
                                              " points, expected at least " + std::to_string(1 << D));
  int dim = 0;
  std::vector<double> xyz;
  xyz.reserve(count * 3);
  for (std::size_t i = 0; i < count; ++i) s.point(points[i], "control point " + std::to_string(i), dim, xyz);
  const auto gammas = s.numbers(scaling, "scaling_factors");
  s.check(gammas.size() == count, "scaling_factors: " + std::to_string(gammas.size()) + " values for " +
                                      std::to_string(count) + " control points");
  for (std::size_t i = 0; i < count; ++i)
    s.check(gammas[i] > 0.0 && gammas[i] <= 1.0,
            "scaling_factors[" + std::to_string(i) + "]: " + std::to_string(gammas[i]) + " outside (0, 1]");
  std::vector<double> w;
  if (weights) {
    w = s.numbers(*weights, "weights_data");
    s.check(w.size() == count,
            "weights_data: " + std::to_string(w.size()) + " values for " + std::to_string(count) + " control points");
    for (std::size_t i = 0; i < count; ++i)
      s.check(w[i] > 0.0, "weights_data[" + std::to_string(i) + "]: weight " + std::to_string(w[i]) +
                              " is not positive");
  }

  // Local B-splines per direction (shared instances parsed once), then the index base over the whole entity.
  std::array<std::vector<double>, D> values;
  std::array<std::vector<const LocalBSpline*>, D> local;
  std::unordered_map<std::uint64_t, LocalBSpline> parsed;
  std::int64_t min_index = INT64_MAX;
  Ints<D> degrees{};
  for (std::size_t k = 0; k < D; ++k) {
    const std::string dn(1, kDir[k]);
    values[k] = s.numbers(*a[D + k], dn + "_knots");
    s.check(values[k].size() >= 2, dn + "_knots: fewer than 2 values");
    for (std::size_t i = 1; i < values[k].size(); ++i)
      s.check(values[k][i - 1] < values[k][i], dn + "_knots: not strictly increasing at index " + std::to_string(i));
    const auto& refs = s.list(*a[k], dn + "_b_splines");
    s.check(refs.size() == count, dn + "_b_splines: " + std::to_string(refs.size()) + " entries for " +
                                      std::to_string(count) + " control points");
    for (std::size_t i = 0; i < count; ++i) {
      const std::string what = dn + "_b_splines[" + std::to_string(i) + "]";
      const Instance& b = s.resolve(refs[i], "LOCAL_B_SPLINE", what);
      auto [it, fresh] = parsed.try_emplace(b.id);
      LocalBSpline& lb = it->second;
      if (fresh) {
        const std::string where = what + " (#" + std::to_string(b.id) + ")";
        const Record& r = *b.record("LOCAL_B_SPLINE");
        s.check(r.params.size() == 4, where + ": LOCAL_B_SPLINE has " + std::to_string(r.params.size()) +
                                          " parameters, expected 4");
        const std::int64_t deg = s.integer(r.params[1], where + ": degree");
        s.check(deg >= 1 && deg <= 64, where + ": degree " + std::to_string(deg) + " outside 1..64");
        lb.degree = static_cast<int>(deg);
        lb.knots = s.integers(r.params[2], where + ": knots");
        lb.mults = s.integers(r.params[3], where + ": multiplicities");
        s.check(lb.knots.size() == lb.mults.size() && lb.knots.size() >= 2,
                where + ": knots and multiplicities must have the same length, at least 2");
        std::int64_t sum = 0;
        for (std::size_t j = 0; j < lb.knots.size(); ++j) {
          s.check(j == 0 || lb.knots[j - 1] < lb.knots[j], where + ": knot indices not strictly increasing");
          s.check(lb.mults[j] >= 1, where + ": multiplicity " + std::to_string(lb.mults[j]) + " is not positive");
          sum += lb.mults[j];
        }
        s.check(sum == deg + 2, where + ": multiplicities sum to " + std::to_string(sum) + ", expected degree + 2 = " +
                                    std::to_string(deg + 2));
      }
      if (i == 0) degrees[k] = lb.degree;
      s.check(lb.degree == degrees[k], what + ": degree " + std::to_string(lb.degree) + ", the first " + dn +
                                           " B-spline has " + std::to_string(degrees[k]));
      min_index = std::min(min_index, lb.knots.front());
      local[k].push_back(&lb);
    }
  }
  const std::int64_t base = min_index == 0 ? 0 : 1;

  std::vector<LRBSpline<D>> basis(count);
  const int st = dim + (weights ? 1 : 0);
  for (std::size_t i = 0; i < count; ++i) {
    LRBSpline<D>& b = basis[i];
    for (std::size_t k = 0; k < D; ++k) {
      const LocalBSpline& lb = *local[k][i];
      for (std::size_t j = 0; j < lb.knots.size(); ++j) {
        const std::int64_t ix = lb.knots[j] - base;
        s.check(ix >= 0 && ix < static_cast<std::int64_t>(values[k].size()),
                std::string(1, kDir[k]) + "_b_splines[" + std::to_string(i) + "]: knot index " +
                    std::to_string(lb.knots[j]) + " outside the " + std::to_string(values[k].size()) + " " +
                    std::string(1, kDir[k]) + "_knots (" + std::to_string(base) + "-based)");
        b.knots[k].insert(b.knots[k].end(), static_cast<std::size_t>(lb.mults[j]),
                          values[k][static_cast<std::size_t>(ix)]);
      }
    }
    b.gamma = gammas[i];
    b.coef.resize(static_cast<std::size_t>(st));
    const double wi = weights ? w[i] : 1.0;
    for (int c = 0; c < dim; ++c) b.coef[static_cast<std::size_t>(c)] = xyz[i * static_cast<std::size_t>(dim) + static_cast<std::size_t>(c)] * (weights ? wi : 1.0);
    if (weights) b.coef[static_cast<std::size_t>(dim)] = wi;
  }

  // Domain: the attribute must agree with the union of the supports.
  Box<D> hull = Box<D>::empty();
  for (const auto& b : basis)
    for (std::size_t k = 0; k < D; ++k) {
      hull.lo[k] = std::min(hull.lo[k], b.knots[k].front());
      hull.hi[k] = std::max(hull.hi[k], b.knots[k].back());
    }
  const auto& dom = s.list(*a.back(), "domain");
  s.check(D == 1 || dom.size() == D, "domain: " + std::to_string(dom.size()) + " entries, expected " + std::to_string(D));
  for (std::size_t k = 0; k < D; ++k) {
    // A curve's domain is one pair, a surface's or volume's a list of pairs.
    const auto range = s.numbers(D == 1 ? *a.back() : dom[k], "domain[" + std::to_string(k) + "]");
    s.check(range.size() == 2, "domain[" + std::to_string(k) + "]: expected 2 values");
    const double tol = 1e-9 * std::max({1.0, std::abs(hull.lo[k]), std::abs(hull.hi[k])});
    s.check(std::abs(range[0] - hull.lo[k]) <= tol && std::abs(range[1] - hull.hi[k]) <= tol,
            "domain[" + std::to_string(k) + "]: (" + std::to_string(range[0]) + ", " + std::to_string(range[1]) +
                ") differs from the B-splines' extent (" + std::to_string(hull.lo[k]) + ", " +
                std::to_string(hull.hi[k]) + ")");
  }

  return {degrees, dim, weights != nullptr, std::move(basis), type};
}

std::string GeometryReader::locally_refined_type(const Instance& in) const {
  const GeometryKind kind = geometry_kind(in);
  if (kind != GeometryKind::lr_surface && kind != GeometryKind::lr_volume) return {};
  const std::size_t D = kind == GeometryKind::lr_surface ? 2 : 3;
  const Record* r = in.complex ? in.record(kLR[D - 1]) : &in.records.front();
  const std::size_t at = in.complex ? 2 * D + 3 : 2 * D + 4;  // a simple instance starts with the name
  if (!r || r->params.size() <= at) return {};
  const Enumeration* e = r->params[at].get_if<Enumeration>();
  return e ? e->name : std::string();
}

LocallyRefinedSurfaceParts GeometryReader::locally_refined_surface_parts(const Instance& in) const {
  const Scope s(file_, file_name_, in);
  s.check(geometry_kind(in) == GeometryKind::lr_surface, "not a locally refined surface");
  auto c = read_scaled<2>(s, in);
  return {c.degrees, c.dim, c.rational, std::move(c.basis), std::move(c.type)};
}

LocallyRefinedParts<3> GeometryReader::locally_refined_volume_parts(const Instance& in) const {
  const Scope s(file_, file_name_, in);
  s.check(geometry_kind(in) == GeometryKind::lr_volume, "not a locally refined volume");
  auto c = read_scaled<3>(s, in);
  return {c.degrees, c.dim, c.rational, std::move(c.basis), std::move(c.type)};
}

template <int D>
LRSpline<D> GeometryReader::read_lr(const Instance& in) const {
  const Scope s(file_, file_name_, in);
  auto [degrees, dim, rational, basis, type] = read_scaled<D>(s, in);
  // STEP stores no box mesh: it is the union of the B-splines' knot lines.
  std::vector<MeshRectangle<D>> mesh = knot_line_mesh<D>(basis);
  try {
    return LRSpline<D>(degrees, dim, rational, std::move(basis), std::move(mesh));
  } catch (const Error& e) {
    // Hierarchical B-splines (trivar writes HB and THB splines so) are read only when their B-splines also form
    // an LR spline; an HB basis in general does not sum to one, so the error says which kind was refused.
    s.fail(prefix_lr(e.what()) + (type == "HIERARCHICAL_B_SPLINE"
                                      ? " (a HIERARCHICAL_B_SPLINE entity is read only when it is also an LR spline)"
                                      : ""));
  }
}

// A univariate LR B-spline space lies in the spline space on the union of the local knot vectors (each knot
// with its largest local multiplicity, the ends raised to degree + 1 so the domain is the union of the
// supports), so the curve is exactly a B-spline curve there: every scaled B-spline is written in that basis
// by knot insertion and the homogeneous coefficients are summed.
TensorSpline<1> GeometryReader::read_lr_curve(const Instance& in) const {
  const Scope s(file_, file_name_, in);
  const auto [degrees, dim, rational, basis, type] = read_scaled<1>(s, in);
  const int p = degrees[0];
  std::map<double, int> mult;
  for (const auto& b : basis)
    for (std::size_t j = 0; j < b.knots[0].size();) {
      std::size_t e = j;
      while (e < b.knots[0].size() && b.knots[0][e] == b.knots[0][j]) ++e;
      int& m = mult[b.knots[0][j]];
      m = std::max(m, static_cast<int>(e - j));
      j = e;
    }
  mult.begin()->second = p + 1;
  mult.rbegin()->second = p + 1;
  std::vector<double> t;
  for (const auto& [value, m] : mult) t.insert(t.end(), static_cast<std::size_t>(m), value);
  KnotVector kv;
  try {
    kv = KnotVector(p, t);
  } catch (const Error& e) {
    s.fail(std::string("knots of the B-splines: ") + e.what());
  }
  const std::size_t stride = static_cast<std::size_t>(dim + (rational ? 1 : 0));
  std::vector<double> coefs(static_cast<std::size_t>(kv.size()) * stride, 0.0);
  std::vector<double> c;
  for (const auto& b : basis) {
    int first = 0;
    express_in(b.knots[0], p, kv, first, c);
    for (std::size_t j = 0; j < c.size(); ++j)
      for (std::size_t q = 0; q < stride; ++q)
        coefs[(static_cast<std::size_t>(first) + j) * stride + q] += b.gamma * c[j] * b.coef[q];
  }
  try {
    return TensorSpline<1>({std::move(kv)}, dim, rational, std::move(coefs));
  } catch (const Error& e) {
    s.fail(e.what());
  }
}

}  // namespace trivar::io::step
