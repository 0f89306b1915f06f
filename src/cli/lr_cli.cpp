#include "lr_cli.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/json_format.hpp"
#include "trivar/io/lr_format.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/lr_g2_format.hpp"
#include "trivar/io/lr_json.hpp"
#include "trivar/lr/dimension_formula.hpp"

namespace trivar::cli {

namespace {

bool is_lr_kind(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("kind")) return false;
  const nlohmann::json& kind = j["kind"];
  return kind == "lr_surface" || kind == "lr_volume";
}

// The first object's kind decides (see the header): a single object, or the first entry of "objects".
bool json_holds_lr(const nlohmann::json& doc) {
  if (is_lr_kind(doc)) return true;
  if (!doc.is_object() || !doc.contains("objects")) return false;
  const nlohmann::json& objects = doc["objects"];
  return objects.is_array() && !objects.empty() && is_lr_kind(objects.front());
}

template <int D>
nlohmann::json describe(const LRSpline<D>& lr, const std::string& check) {
  nlohmann::json j;
  j["kind"] = D == 2 ? "lr_surface" : "lr_volume";
  j["parametric_dim"] = D;
  j["dim"] = lr.dim();
  j["rational"] = lr.is_rational();
  for (int k = 0; k < D; ++k) {
    j["degrees"].push_back(lr.degree(k));
    j["domain"].push_back({lr.domain().lo[k], lr.domain().hi[k]});
  }
  j["num_basis"] = lr.num_basis();
  j["num_elements"] = lr.num_elements();
  j["num_meshrects"] = lr.mesh().size();
  double gmin = 1.0, gmax = 0.0;
  for (const LRBSpline<D>& b : lr.basis_functions()) {
    gmin = std::min(gmin, b.gamma);
    gmax = std::max(gmax, b.gamma);
  }
  j["gamma"] = {{"min", gmin}, {"max", gmax}};
  if (check == "peeling") {
    const PeelingResult r = peeling_test(lr);
    j["independence"] = {{"method", "peeling"},
                         {"status", to_string(r.status)},
                         {"overloaded_elements", r.overloaded_elements},
                         {"overloaded_basis", r.overloaded_basis},
                         {"unresolved", r.unresolved.size()}};
  } else if (check == "exact") {
    const ExactResult r = exact_test(lr);
    j["independence"] = {{"method", "exact"}, {"status", to_string(r.status)}, {"tested", r.tested},
                         {"rank", r.rank},    {"nullity", r.nullity()},          {"blocks", r.blocks}};
  }
  if constexpr (D == 2) {
    if (!check.empty()) {
      const HandInHand h = hand_in_hand(lr.num_basis(), lr.mesh(), lr.degrees());
      j["dimension_formula"] = {{"basis", h.basis_count}, {"dimension", h.dimension}, {"status", to_string(h.status)}};
    }
  }
  return j;
}

}  // namespace

std::optional<std::vector<AnyLRSpline>> read_lr_if_any(const std::string& path) {
  const std::string ext = io::file_extension(path);
  if (ext == ".lr") return io::read_lr(path);
  if (ext == ".g2") {
    std::ifstream f(path, std::ios::binary);
    if (!f) return std::nullopt;  // the tensor reader reports the unreadable file
    std::stringstream ss;
    ss << f.rdbuf();
    const std::string text = ss.str();
    long type = 0;
    std::istringstream first(text);
    if (!(first >> type) || (type != 293 && type != 793)) return std::nullopt;
    return io::parse_lr_g2(text, path);
  }
  if (ext == ".json") {
    const nlohmann::json doc = io::read_json_document(path);
    if (!json_holds_lr(doc)) return std::nullopt;
    std::vector<AnyLRSpline> out;
    for (const auto& [j, where] : io::object_documents(doc, path, "LR spline")) out.push_back(io::lr_spline_from_json(j, where));
    return out;
  }
  return std::nullopt;
}

std::vector<AnyLRSpline> read_as_lr(const std::string& path, const std::string& command) {
  if (auto lr = read_lr_if_any(path)) return std::move(*lr);
  const std::vector<AnySpline> objects = read_objects(path);
  std::vector<AnyLRSpline> out;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (const auto* s = std::get_if<TensorSpline<2>>(&objects[i])) out.emplace_back(LRSpline<2>(*s));
    else if (const auto* v = std::get_if<TensorSpline<3>>(&objects[i])) out.emplace_back(LRSpline<3>(*v));
    else
      throw Error(command + ": " + path + " object " + std::to_string(i) +
                  " is a curve; LR splines are surfaces or volumes");
  }
  return out;
}

bool lr_output_extension(const std::string& path) {
  const std::string ext = io::file_extension(path);
  return ext == ".lr" || ext == ".g2" || ext == ".json" || ext == ".vtu";
}

bool is_lr_extension(const std::string& path) { return io::file_extension(path) == ".lr"; }

void write_lr_file(const std::string& path, const std::vector<AnyLRSpline>& objects, const std::string& command,
                   const io::LRVtkOptions& vtk) {
  const std::string ext = io::file_extension(path);
  if (ext == ".lr") io::write_lr(path, objects);
  else if (ext == ".g2") io::write_lr_g2(path, objects);
  else if (ext == ".json") io::write_lr_json(path, objects);
  else if (ext == ".vtu") io::write_lr_vtu(path, objects, vtk);
  else
    throw Error(command + ": cannot write LR splines to '" + path + "' (use .lr, .g2, .json or .vtu)");
}

nlohmann::json describe_lr(const AnyLRSpline& s, const std::string& check) {
  return std::visit([&](const auto& lr) { return describe(lr, check); }, s);
}

void print_lr_text(const nlohmann::json& d) {
  const int D = d["parametric_dim"].get<int>();
  std::string degrees, domain;
  for (int k = 0; k < D; ++k) {
    degrees += (k ? " " : "") + std::to_string(d["degrees"][k].get<int>());
    domain += std::string(k ? " x " : "") + "[" + fmt(d["domain"][k][0].get<double>()) + ", " +
              fmt(d["domain"][k][1].get<double>()) + "]";
  }
  std::printf("  kind: LR %s, control dim %d, %s\n", kind_name(D), d["dim"].get<int>(),
              d["rational"].get<bool>() ? "rational" : "polynomial");
  std::printf("  degrees: %s\n", degrees.c_str());
  std::printf("  B-splines: %d\n", d["num_basis"].get<int>());
  std::printf("  elements: %d\n", d["num_elements"].get<int>());
  std::printf("  mesh rectangles: %d\n", d["num_meshrects"].get<int>());
  std::printf("  domain: %s\n", domain.c_str());
  std::printf("  gamma: min %s, max %s\n", fmt(d["gamma"]["min"].get<double>()).c_str(),
              fmt(d["gamma"]["max"].get<double>()).c_str());
  if (d.contains("independence")) {
    const nlohmann::json& r = d["independence"];
    const std::string method = r["method"].get<std::string>();
    std::string detail;
    if (method == "peeling")
      detail = std::to_string(r["overloaded_elements"].get<int>()) + " overloaded elements, " +
               std::to_string(r["unresolved"].get<int>()) + " B-splines unresolved";
    else
      detail = "rank " + std::to_string(r["rank"].get<int>()) + " of " + std::to_string(r["tested"].get<int>()) +
               " tested, nullity " + std::to_string(r["nullity"].get<int>());
    std::printf("  independence (%s): %s (%s)\n", method.c_str(), r["status"].get<std::string>().c_str(),
                detail.c_str());
  }
  if (d.contains("dimension_formula")) {
    const nlohmann::json& h = d["dimension_formula"];
    std::printf("  dimension formula: %lld for %d B-splines: %s\n", h["dimension"].get<long long>(),
                h["basis"].get<int>(), h["status"].get<std::string>().c_str());
  }
}

}  // namespace trivar::cli
