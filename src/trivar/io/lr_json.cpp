#include "trivar/io/lr_json.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <optional>

#include "trivar/core/error.hpp"
#include "trivar/io/json_format.hpp"

namespace trivar::io {

namespace {

using nlohmann::json;

constexpr std::array<const char*, 2> kKinds = {"lr_surface", "lr_volume"};
constexpr std::array<const char*, 8> kKeys = {"trivar", "kind", "dim", "rational", "degrees", "basis", "mesh", "objects"};

[[noreturn]] void fail(const std::string& where, const std::string& path, const std::string& what) {
  throw Error(where + ": " + (path.empty() ? "" : path + ": ") + what);
}

std::string indexed(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

const json& member(const json& j, const char* key, const std::string& where, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end()) fail(where, path, std::string("missing key \"") + key + "\"");
  return *it;
}

void only_keys(const json& j, std::initializer_list<const char*> keys, const std::string& where,
               const std::string& path) {
  for (const auto& [key, value] : j.items())
    if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; }))
      fail(where, path, "unexpected key \"" + key + "\"");
}

std::string join(const std::string& path, const char* key) { return path.empty() ? key : path + "." + key; }

int get_int(const json& j, const std::string& where, const std::string& path, long long lo, long long hi) {
  if (!j.is_number_integer())
    fail(where, path, "expected an integer, got " + (j.is_number() ? j.dump() : std::string(j.type_name())));
  const auto v = j.get<long long>();
  if (v < lo || v > hi)
    fail(where, path, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + j.dump());
  return static_cast<int>(v);
}

double get_real(const json& j, const std::string& where, const std::string& path) {
  if (!j.is_number()) fail(where, path, std::string("expected a number, got ") + j.type_name());
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(where, path, "expected a finite number, got " + j.dump());
  return v;
}

const json& get_array(const json& j, const std::string& where, const std::string& path) {
  if (!j.is_array()) fail(where, path, std::string("expected an array, got ") + j.type_name());
  return j;
}

const json& get_array(const json& j, const std::string& where, const std::string& path, std::size_t size) {
  get_array(j, where, path);
  if (j.size() != size)
    fail(where, path, "expected " + std::to_string(size) + " entries, got " + std::to_string(j.size()));
  return j;
}

std::vector<double> get_reals(const json& j, const std::string& where, const std::string& path, std::size_t size) {
  get_array(j, where, path, size);
  std::vector<double> v(size);
  for (std::size_t i = 0; i < size; ++i) v[i] = get_real(j[i], where, indexed(path, i));
  return v;
}

template <int D>
LRSpline<D> lr_of_kind(const json& j, const std::string& where, int dim, bool rational) {
  const json& deg = get_array(member(j, "degrees", where, ""), where, "degrees", D);
  Ints<D> degrees{};
  for (int k = 0; k < D; ++k) degrees[k] = get_int(deg[k], where, indexed("degrees", k), 1, 64);
  const std::size_t stride = static_cast<std::size_t>(dim) + (rational ? 1 : 0);

  const json& basis_json = get_array(member(j, "basis", where, ""), where, "basis");
  if (basis_json.empty()) fail(where, "basis", "expected at least one B-spline");
  std::vector<LRBSpline<D>> basis(basis_json.size());
  for (std::size_t i = 0; i < basis.size(); ++i) {
    const std::string path = indexed("basis", i);
    const json& b = basis_json[i];
    if (!b.is_object()) fail(where, path, std::string("expected an object, got ") + b.type_name());
    only_keys(b, {"knots", "gamma", "coef"}, where, path);
    const json& knots = get_array(member(b, "knots", where, path), where, join(path, "knots"), D);
    for (int k = 0; k < D; ++k)
      basis[i].knots[k] = get_reals(knots[static_cast<std::size_t>(k)], where, indexed(join(path, "knots"), static_cast<std::size_t>(k)),
                                    static_cast<std::size_t>(degrees[k]) + 2);
    basis[i].gamma = get_real(member(b, "gamma", where, path), where, join(path, "gamma"));
    basis[i].coef = get_reals(member(b, "coef", where, path), where, join(path, "coef"), stride);
  }

  const json& mesh_json = get_array(member(j, "mesh", where, ""), where, "mesh");
  std::vector<MeshRectangle<D>> mesh(mesh_json.size());
  for (std::size_t i = 0; i < mesh.size(); ++i) {
    const std::string path = indexed("mesh", i);
    const json& r = mesh_json[i];
    if (!r.is_object()) fail(where, path, std::string("expected an object, got ") + r.type_name());
    only_keys(r, {"dir", "value", "lo", "hi", "multiplicity"}, where, path);
    const int dir = get_int(member(r, "dir", where, path), where, join(path, "dir"), 0, D - 1);
    const double value = get_real(member(r, "value", where, path), where, join(path, "value"));
    const std::vector<double> lo = get_reals(member(r, "lo", where, path), where, join(path, "lo"), D);
    const std::vector<double> hi = get_reals(member(r, "hi", where, path), where, join(path, "hi"), D);
    if (lo[static_cast<std::size_t>(dir)] != value || hi[static_cast<std::size_t>(dir)] != value)
      fail(where, path, "lo and hi must equal \"value\" in direction \"dir\"");
    const int mult = get_int(member(r, "multiplicity", where, path), where, join(path, "multiplicity"), 1, 65);
    Param<D> l{}, h{};
    std::copy(lo.begin(), lo.end(), l.begin());
    std::copy(hi.begin(), hi.end(), h.begin());
    mesh[i] = MeshRectangle<D>::make(dir, value, l, h, mult);
  }

  // Knots, gammas, supports and the mesh are validated by the constructor; its message names the B-spline or
  // rectangle by its index in the lists.
  try {
    return LRSpline<D>(degrees, dim, rational, std::move(basis), std::move(mesh));
  } catch (const Error& e) {
    fail(where, "", e.what());
  }
}

template <int D>
json lr_to_json(const LRSpline<D>& s) {
  json degrees = json::array();
  for (int k = 0; k < D; ++k) degrees.push_back(s.degree(k));
  json basis = json::array();
  for (const LRBSpline<D>& b : s.basis_functions()) {
    json knots = json::array();
    for (int k = 0; k < D; ++k) knots.push_back(b.knots[k]);
    for (double c : b.coef) require(std::isfinite(c), "an LR B-spline coefficient is not finite");
    basis.push_back({{"knots", std::move(knots)}, {"gamma", b.gamma}, {"coef", b.coef}});
  }
  json mesh = json::array();
  for (const MeshRectangle<D>& r : s.mesh()) {
    json lo = json::array(), hi = json::array();
    for (int k = 0; k < D; ++k) {
      lo.push_back(k == r.dir ? r.value : r.extent.lo[k]);
      hi.push_back(k == r.dir ? r.value : r.extent.hi[k]);
    }
    mesh.push_back({{"dir", r.dir}, {"value", r.value}, {"lo", std::move(lo)}, {"hi", std::move(hi)},
                    {"multiplicity", r.multiplicity}});
  }
  json j = json::object();
  j["trivar"] = 1;
  j["kind"] = kKinds[D - 2];
  j["dim"] = s.dim();
  j["rational"] = s.is_rational();
  j["degrees"] = std::move(degrees);
  j["basis"] = std::move(basis);
  j["mesh"] = std::move(mesh);
  return j;
}

}  // namespace

json to_json(const AnyLRSpline& s) {
  return std::visit([](const auto& lr) { return lr_to_json(lr); }, s);
}

AnyLRSpline lr_spline_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) fail(where, "", std::string("expected an LR spline object, got ") + j.type_name());
  for (const auto& [key, value] : j.items())
    if (key == "objects" || std::find_if(kKeys.begin(), kKeys.end(), [&](const char* k) { return key == k; }) == kKeys.end())
      fail(where, "", "unexpected key \"" + key + "\"");
  if (j.contains("trivar") && j["trivar"] != 1)
    fail(where, "trivar", "unsupported format version " + j["trivar"].dump() + " (expected 1)");
  const json& kind = member(j, "kind", where, "");
  const int dim = get_int(member(j, "dim", where, ""), where, "dim", 1, INT_MAX);
  const json& rational = member(j, "rational", where, "");
  if (!rational.is_boolean()) fail(where, "rational", std::string("expected true or false, got ") + rational.dump());
  if (kind == kKinds[0]) return lr_of_kind<2>(j, where, dim, rational.get<bool>());
  if (kind == kKinds[1]) return lr_of_kind<3>(j, where, dim, rational.get<bool>());
  fail(where, "kind", "expected \"lr_surface\" or \"lr_volume\", got " + kind.dump());
}

std::vector<AnyLRSpline> read_lr_json(const std::string& path) {
  std::vector<AnyLRSpline> out;
  for (const auto& [j, where] : object_documents(read_json_document(path), path, "LR spline"))
    out.push_back(lr_spline_from_json(j, where));
  return out;
}

void write_lr_json(const std::string& path, const std::vector<AnyLRSpline>& objects) {
  require(!objects.empty(), path + ": nothing to write (no objects)");
  std::vector<json> docs;
  try {
    for (const AnyLRSpline& s : objects) docs.push_back(to_json(s));
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  write_json_document(path, document_of(std::move(docs)));
}

}  // namespace trivar::io
