#include "trivar/io/json_format.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string_view>
#include <utility>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"

namespace trivar::io {

namespace {

using nlohmann::json;

// Far deeper than any trivar document (the points of a V-model's field attribute sit at depth 8).
constexpr std::size_t kMaxJsonDepth = 64;

constexpr std::array<const char*, 3> kKinds = {"curve", "surface", "volume"};
constexpr std::array<char, 3> kDirections = {'u', 'v', 'w'};
// Written in this order (nlohmann::json sorts keys alphabetically, which would bury "trivar" and "kind").
constexpr std::array<std::string_view, 9> kKeyOrder = {"trivar", "kind",           "dim",     "rational", "degrees",
                                                       "knots",  "control_points", "weights", "objects"};

// Error naming the file/object (`where`), the JSON path inside the object (may be empty) and the problem.
[[noreturn]] void fail(const std::string& where, const std::string& path, const std::string& what) {
  throw Error(where + ": " + (path.empty() ? "" : path + ": ") + what);
}

std::string indexed(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

const json& member(const json& j, const char* key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) fail(where, "", std::string("missing key \"") + key + "\"");
  return *it;
}

int get_int(const json& j, const std::string& where, const std::string& path, int lo) {
  if (!j.is_number_integer())
    fail(where, path, "expected an integer, got " + (j.is_number() ? j.dump() : std::string(j.type_name())));
  const auto v = j.get<long long>();
  if (v < lo || v > INT_MAX) fail(where, path, "expected an integer >= " + std::to_string(lo) + ", got " + j.dump());
  return static_cast<int>(v);
}

double get_real(const json& j, const std::string& where, const std::string& path) {
  if (!j.is_number()) fail(where, path, std::string("expected a number, got ") + j.type_name());
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(where, path, "expected a finite number, got " + j.dump());
  return v;
}

const json& get_array(const json& j, const std::string& where, const std::string& path, std::size_t size) {
  if (!j.is_array()) fail(where, path, std::string("expected an array, got ") + j.type_name());
  if (j.size() != size)
    fail(where, path, "expected " + std::to_string(size) + " entries, got " + std::to_string(j.size()));
  return j;
}

template <int D>
AnySpline spline_of_kind(const json& j, const std::string& where, int dim, bool rational) {
  const json& degrees = get_array(member(j, "degrees", where), where, "degrees", D);
  const json& knots = get_array(member(j, "knots", where), where, "knots", D);
  std::array<KnotVector, D> kv;
  long long n = 1;
  for (int k = 0; k < D; ++k) {
    const int p = get_int(degrees[k], where, indexed("degrees", k), 0);
    const std::string path = indexed("knots", k);
    if (!knots[k].is_array()) fail(where, path, std::string("expected an array, got ") + knots[k].type_name());
    std::vector<double> t(knots[k].size());
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = get_real(knots[k][i], where, indexed(path, i));
    try {
      kv[k] = KnotVector(p, std::move(t));
    } catch (const Error& e) {
      fail(where, path, std::string("invalid knot vector in direction ") + kDirections[k] + ": " + e.what());
    }
    n *= kv[k].size();
  }
  if (n > INT_MAX) fail(where, "knots", "too many control points (" + std::to_string(n) + ")");
  const auto count = static_cast<std::size_t>(n);

  const json& cps = get_array(member(j, "control_points", where), where, "control_points", count);
  // The shape is checked before anything is allocated, so a declared "dim" or knot count can never ask for
  // more memory than the document itself holds.
  for (std::size_t i = 0; i < count; ++i) get_array(cps[i], where, indexed("control_points", i), dim);
  std::vector<double> points(count * dim);
  for (std::size_t i = 0; i < count; ++i) {
    const std::string path = indexed("control_points", i);
    for (int d = 0; d < dim; ++d) points[i * dim + d] = get_real(cps[i][d], where, indexed(path, d));
  }
  std::vector<double> weights;
  if (rational) {
    const json& w = get_array(member(j, "weights", where), where, "weights", count);
    weights.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      weights[i] = get_real(w[i], where, indexed("weights", i));
      if (weights[i] <= 0) fail(where, indexed("weights", i), "weights must be positive, got " + w[i].dump());
    }
  } else if (j.contains("weights")) {
    fail(where, "weights", "present but \"rational\" is false");
  }
  try {
    return TensorSpline<D>::from_cartesian(std::move(kv), dim, points, weights);
  } catch (const Error& e) {
    fail(where, "", e.what());
  }
}

// Scalars and arrays of scalars on one line, structure indented: control points come out one per line.
void print(std::ostream& os, const json& j, int indent) {
  const std::string pad(static_cast<std::size_t>(indent) + 2, ' ');
  if (j.is_object() && !j.empty()) {
    std::vector<std::string> keys;
    for (std::string_view k : kKeyOrder)
      if (j.contains(k)) keys.emplace_back(k);
    for (const auto& [k, v] : j.items())
      if (std::find(kKeyOrder.begin(), kKeyOrder.end(), k) == kKeyOrder.end()) keys.push_back(k);
    os << "{\n";
    for (std::size_t i = 0; i < keys.size(); ++i) {
      os << pad << json(keys[i]).dump() << ": ";
      print(os, j.at(keys[i]), indent + 2);
      os << (i + 1 < keys.size() ? ",\n" : "\n");
    }
    os << std::string(static_cast<std::size_t>(indent), ' ') << "}";
  } else if (j.is_array() && std::any_of(j.begin(), j.end(), [](const json& e) { return e.is_structured(); })) {
    os << "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      os << pad;
      print(os, j[i], indent + 2);
      os << (i + 1 < j.size() ? ",\n" : "\n");
    }
    os << std::string(static_cast<std::size_t>(indent), ' ') << "]";
  } else {
    os << j.dump();
  }
}

// `in` is anything nlohmann::json::parse reads (a stream or a string_view); `path` names it in messages.
template <class Input>
json parse_document(Input&& in, const std::string& path) {
  // Each open object or array, with the selector of its current child, so a duplicate key can be named by its
  // path. The depth is bounded here because copying, comparing and printing a json value recurse.
  struct Open {
    bool object;
    std::set<std::string> keys;
    std::string key;
    std::size_t index = 0;
  };
  std::vector<Open> open;
  const auto location = [&] {
    std::string at;
    for (std::size_t i = 0; i + 1 < open.size(); ++i)
      at += open[i].object ? (at.empty() ? "" : ".") + open[i].key : "[" + std::to_string(open[i].index) + "]";
    return at.empty() ? std::string("the top-level object") : at;
  };
  const auto next_element = [&] {
    if (!open.empty() && !open.back().object) ++open.back().index;
  };
  const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        require(open.size() < kMaxJsonDepth, [&] {
          return path + ": objects and arrays nested deeper than " + std::to_string(kMaxJsonDepth) + " levels";
        });
        open.push_back({event == json::parse_event_t::object_start, {}, {}, 0});
        break;
      case json::parse_event_t::key: {
        Open& o = open.back();
        o.key = parsed.get<std::string>();
        require(o.keys.insert(o.key).second,
                [&] { return path + ": duplicate key \"" + o.key + "\" in " + location(); });
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        open.pop_back();
        next_element();
        break;
      case json::parse_event_t::value:
        next_element();
        break;
    }
    return true;
  };
  json doc;
  try {
    doc = json::parse(std::forward<Input>(in), track);
  } catch (const json::exception& e) {
    // Syntax errors and out-of-range numbers. nlohmann prefixes "[json.exception.<kind>.N] " and may quote
    // input containing line breaks.
    std::string what = e.what();
    if (const auto p = what.find("] "); p != std::string::npos) what.erase(0, p + 2);
    std::replace(what.begin(), what.end(), '\n', ' ');
    throw Error(path + ": invalid JSON: " + what);
  }
  if (!doc.is_object()) fail(path, "", std::string("expected a JSON object, got ") + doc.type_name());
  if (!doc.contains("trivar")) fail(path, "", "missing key \"trivar\" (not a trivar file)");
  if (doc["trivar"] != 1) fail(path, "trivar", "unsupported format version " + doc["trivar"].dump() + " (expected 1)");
  return doc;
}

}  // namespace

json to_json(const AnySpline& any) {
  return std::visit(
      [](const auto& s) {
        constexpr int D = std::decay_t<decltype(s)>::kDim;
        require(s.dim() >= 1, "cannot write an empty spline (no control points)");
        json j = json::object();
        j["trivar"] = 1;
        j["kind"] = kKinds[D - 1];
        j["dim"] = s.dim();
        j["rational"] = s.is_rational();
        json degrees = json::array(), knots = json::array();
        for (int k = 0; k < D; ++k) {
          degrees.push_back(s.degree(k));
          knots.push_back(s.knots(k).knots());
        }
        j["degrees"] = std::move(degrees);
        j["knots"] = std::move(knots);
        json cps = json::array(), weights = json::array();
        std::vector<double> x(s.dim());
        for (int l = 0; l < s.num_coefs(); ++l) {
          s.control_point(l, x.data());
          for (int d = 0; d < s.dim(); ++d)
            require(std::isfinite(x[d]), "control point " + std::to_string(l) +
                                             " is not finite in Cartesian form (weight " + std::to_string(s.weight(l)) +
                                             " too small)");
          cps.push_back(x);
          if (s.is_rational()) weights.push_back(s.weight(l));
        }
        j["control_points"] = std::move(cps);
        if (s.is_rational()) j["weights"] = std::move(weights);
        return j;
      },
      any);
}

AnySpline spline_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) fail(where, "", std::string("expected a spline object, got ") + j.type_name());
  for (const auto& [key, value] : j.items())
    if (key == "objects" || std::find(kKeyOrder.begin(), kKeyOrder.end(), key) == kKeyOrder.end())
      fail(where, "", "unexpected key \"" + key + "\"");
  if (j.contains("trivar") && j["trivar"] != 1)
    fail(where, "trivar", "unsupported format version " + j["trivar"].dump() + " (expected 1)");
  const json& kind = member(j, "kind", where);
  const auto k = std::find_if(kKinds.begin(), kKinds.end(), [&](const char* s) { return kind == s; });
  if (k == kKinds.end()) fail(where, "kind", "expected \"curve\", \"surface\" or \"volume\", got " + kind.dump());
  const int dim = get_int(member(j, "dim", where), where, "dim", 1);
  const json& rational = member(j, "rational", where);
  if (!rational.is_boolean()) fail(where, "rational", std::string("expected true or false, got ") + rational.dump());
  switch (k - kKinds.begin()) {
    case 0:
      return spline_of_kind<1>(j, where, dim, rational.get<bool>());
    case 1:
      return spline_of_kind<2>(j, where, dim, rational.get<bool>());
    default:
      return spline_of_kind<3>(j, where, dim, rational.get<bool>());
  }
}

json read_json_document(const std::string& path) {
  require(!std::filesystem::is_directory(path), path + ": is a directory, expected a JSON file");
  std::ifstream in(path);
  require(static_cast<bool>(in), path + ": cannot open file for reading");
  return parse_document(in, path);
}

json parse_json_document(std::string_view text, const std::string& name) { return parse_document(text, name); }

void write_json_document(const std::string& path, const json& doc) {
  write_file_atomically(path, [&](std::ostream& os) {
    print(os, doc, 0);
    os << '\n';
  });
}

std::vector<std::pair<json, std::string>> object_documents(const json& doc, const std::string& path, const char* what) {
  if (!doc.contains("objects")) return {{doc, path}};
  for (const auto& [key, value] : doc.items())
    if (key != "trivar" && key != "objects") fail(path, "", "unexpected key \"" + key + "\" next to \"objects\"");
  const json& objects = doc["objects"];
  if (!objects.is_array() || objects.empty())
    fail(path, "objects",
         std::string("expected a non-empty array of ") + what + " objects, got " +
             (objects.is_array() ? "an empty array" : objects.type_name()));
  std::vector<std::pair<json, std::string>> out;
  for (std::size_t i = 0; i < objects.size(); ++i) out.emplace_back(objects[i], indexed(path + ": objects", i));
  return out;
}

json document_of(std::vector<json> objects) {
  if (objects.size() == 1) return std::move(objects.front());
  json doc{{"trivar", 1}, {"objects", json::array()}};
  for (json& j : objects) {
    j.erase("trivar");
    doc["objects"].push_back(std::move(j));
  }
  return doc;
}

std::vector<AnySpline> read_json(const std::string& path) {
  std::vector<AnySpline> out;
  for (const auto& [j, where] : object_documents(read_json_document(path), path, "spline"))
    out.push_back(spline_from_json(j, where));
  return out;
}

void write_json(const std::string& path, const std::vector<AnySpline>& objects) {
  require(!objects.empty(), path + ": nothing to write (no objects)");
  std::vector<json> docs;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    try {
      docs.push_back(to_json(objects[i]));
    } catch (const Error& e) {
      throw Error((objects.size() == 1 ? path : indexed(path + ": objects", i)) + ": " + e.what());
    }
  }
  write_json_document(path, document_of(std::move(docs)));
}

}  // namespace trivar::io
