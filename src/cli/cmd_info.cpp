// trivar info FILE [--json] [--check-independence peeling|exact]: what a spline file, an LR spline file, a
// STEP file (entity statistics and the spline geometry found, with the faces and edges using it) or a V-model
// holds.
#include <algorithm>
#include <cstdio>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "hier_cli.hpp"
#include "lr_cli.hpp"
#include "trivar/core/error.hpp"
#include "step_cli.hpp"
#include "tspline_cli.hpp"
#include "trivar/io/step/step_file.hpp"

namespace trivar::cli {

namespace {

// Distinct knots with multiplicities "0(3) 0.5 1(3)", the middle elided when there are many.
std::string knot_summary(const KnotVector& kv) {
  const std::vector<double> u = kv.unique();
  const std::vector<int> m = kv.multiplicities();
  constexpr std::size_t kShown = 4;  // first and last values kept when eliding
  std::string s;
  for (std::size_t i = 0; i < u.size(); ++i) {
    if (u.size() > 2 * kShown + 1 && i == kShown) {
      s += " ... (" + std::to_string(u.size() - 2 * kShown) + " more)";
      i = u.size() - kShown - 1;
      continue;
    }
    if (!s.empty()) s += ' ';
    s += fmt(u[i]);
    if (m[i] > 1) s += "(" + std::to_string(m[i]) + ")";
  }
  return s;
}

template <int D>
nlohmann::json describe(const TensorSpline<D>& s) {
  nlohmann::json j;
  j["kind"] = kind_name(D);
  j["parametric_dim"] = D;
  j["dim"] = s.dim();
  j["rational"] = s.is_rational();
  const Box<D> dom = s.domain();
  int elements = 1;
  for (int k = 0; k < D; ++k) {
    const KnotVector& kv = s.knots(k);
    j["degrees"].push_back(kv.degree());
    j["counts"].push_back(kv.size());
    j["elements"].push_back(kv.num_elements());
    j["domain"].push_back({dom.lo[k], dom.hi[k]});
    j["knots"].push_back(kv.knots());
    elements *= kv.num_elements();
  }
  j["num_control_points"] = s.num_coefs();
  j["num_elements"] = elements;
  std::vector<double> lo(s.dim()), hi(s.dim());
  s.control_bounds(lo.data(), hi.data());
  j["control_bounds"] = {{"lo", lo}, {"hi", hi}};
  return j;
}

template <int D>
void print_text(const TensorSpline<D>& s) {
  const char* names = "uvw";
  auto per_direction = [&](auto&& value, const char* sep) {
    std::string r;
    for (int k = 0; k < D; ++k) r += (k ? sep : "") + value(k);
    return r;
  };
  const Box<D> dom = s.domain();
  int elements = 1;
  for (int k = 0; k < D; ++k) elements *= s.knots(k).num_elements();
  std::vector<double> lo(s.dim()), hi(s.dim());
  s.control_bounds(lo.data(), hi.data());
  std::string bounds;
  for (int d = 0; d < s.dim(); ++d) bounds += (d ? " x [" : "[") + fmt(lo[d]) + ", " + fmt(hi[d]) + "]";

  std::printf("  kind: %s, control dim %d, %s\n", kind_name(D), s.dim(), s.is_rational() ? "rational (NURBS)" : "polynomial");
  std::printf("  degrees: %s\n", per_direction([&](int k) { return std::to_string(s.degree(k)); }, " ").c_str());
  std::printf("  control points: %s = %d\n", per_direction([&](int k) { return std::to_string(s.count(k)); }, " x ").c_str(),
              s.num_coefs());
  for (int k = 0; k < D; ++k)
    std::printf("  knots %c: %d knots, %s\n", names[k], static_cast<int>(s.knots(k).knots().size()),
                knot_summary(s.knots(k)).c_str());
  std::printf("  domain: %s\n",
              per_direction([&](int k) { return "[" + fmt(dom.lo[k]) + ", " + fmt(dom.hi[k]) + "]"; }, " x ").c_str());
  std::printf("  elements: %s = %d\n",
              per_direction([&](int k) { return std::to_string(s.knots(k).num_elements()); }, " x ").c_str(), elements);
  std::printf("  control bounding box: %s\n", bounds.c_str());
}

void print_lr_info(const std::string& file, const std::vector<AnyLRSpline>& objects, bool json,
                   const std::string& check) {
  if (json) {
    nlohmann::json out{{"file", file}, {"objects", nlohmann::json::array()}};
    for (const AnyLRSpline& o : objects) out["objects"].push_back(describe_lr(o, check));
    std::printf("%s\n", out.dump(2).c_str());
    return;
  }
  std::printf("%s: %zu LR object%s\n", file.c_str(), objects.size(), objects.size() == 1 ? "" : "s");
  for (std::size_t i = 0; i < objects.size(); ++i) {
    std::printf("object %zu:\n", i);
    print_lr_text(describe_lr(objects[i], check));
  }
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  return first == std::string::npos ? std::string() : s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// Where a STEP object came from: "#id 'name' ENTITY, faces #a #b, edges #c".
std::string step_origin(const io::step::StepObject& o) {
  std::string r = "#" + std::to_string(o.id) + (o.name.empty() ? "" : " '" + o.name + "'") + " " + o.entity;
  auto refs = [&](const char* what, const std::vector<std::uint64_t>& ids) {
    if (ids.empty()) return;
    r += std::string(", ") + what;
    for (std::uint64_t id : ids) r += " #" + std::to_string(id);
  };
  refs("faces", o.faces);
  refs("edges", o.edges);
  return r;
}

nlohmann::json step_origin_json(const io::step::StepObject& o) {
  return {{"id", o.id}, {"name", o.name}, {"entity", o.entity}, {"step_kind", io::step::to_string(o.kind)},
          {"faces", o.faces}, {"edges", o.edges}};
}

void print_step_info(const std::string& file, bool json, const std::string& check, bool strict, bool kernel_volume) {
  const io::step::StepContents c = read_step_warning(file, strict, false);
  // Entity kinds by decreasing count (ties by name) so the bulk of the file comes first.
  std::vector<std::pair<std::string, io::step::EntityCount>> kinds(c.entities.begin(), c.entities.end());
  std::stable_sort(kinds.begin(), kinds.end(), [](const auto& a, const auto& b) { return a.second.total() > b.second.total(); });
  if (json) {
    nlohmann::json out{{"file", file},
                       {"format", "step"},
                       {"schemas", c.header.schemas},
                       {"originating_system", c.header.originating_system},
                       {"instances", c.instance_count()},
                       {"faces", c.faces},
                       {"unmapped_faces", c.unmapped_faces},
                       {"warnings", nlohmann::json::array()},
                       {"entities", nlohmann::json::object()},
                       {"objects", nlohmann::json::array()},
                       {"lr_objects", nlohmann::json::array()},
                       {"brep", brep_info_json(file, kernel_volume)}};
    for (const auto& [k, n] : kinds) out["entities"][k] = {{"count", n.total()}, {"mapped", n.kept}};
    for (const io::step::ReadWarning& w : c.warnings) out["warnings"].push_back({{"first", w.first}, {"count", w.count}});
    for (std::size_t i = 0; i < c.splines.size(); ++i) {
      nlohmann::json d = std::visit([](const auto& s) { return describe(s); }, c.splines[i]);
      d["step"] = step_origin_json(c.spline_info[i]);
      out["objects"].push_back(std::move(d));
    }
    for (std::size_t i = 0; i < c.lr_splines.size(); ++i) {
      nlohmann::json d = describe_lr(c.lr_splines[i], check);
      d["step"] = step_origin_json(c.lr_info[i]);
      out["lr_objects"].push_back(std::move(d));
    }
    std::printf("%s\n", out.dump(2).c_str());
    return;
  }
  std::string schemas;
  for (const auto& sc : c.header.schemas) schemas += (schemas.empty() ? "" : ", ") + sc;
  const std::string from = trimmed(c.header.originating_system);
  std::printf("%s: STEP (ISO 10303-21), schema %s%s%s\n", file.c_str(), schemas.empty() ? "(none)" : schemas.c_str(),
              from.empty() ? "" : ", from ", from.c_str());
  std::printf("  instances: %zu of %zu entity kinds; geometry found: %zu B-spline object%s, %zu locally refined\n",
              c.instance_count(), kinds.size(), c.splines.size(), c.splines.size() == 1 ? "" : "s", c.lr_splines.size());
  constexpr std::size_t kListed = 25;
  for (std::size_t i = 0; i < kinds.size() && i < kListed; ++i)
    std::printf("  %8zu  %s\n", kinds[i].second.total(), kinds[i].first.c_str());
  if (kinds.size() > kListed) std::printf("  ... %zu more entity kinds (--json lists all)\n", kinds.size() - kListed);
  if (const std::string faces = c.unmapped_faces_summary(); !faces.empty()) std::printf("  %s\n", faces.c_str());
  print_brep_info(file, kernel_volume);
  for (std::size_t i = 0; i < c.splines.size(); ++i) {
    std::printf("object %zu: %s\n", i, step_origin(c.spline_info[i]).c_str());
    std::visit([](const auto& s) { print_text(s); }, c.splines[i]);
  }
  for (std::size_t i = 0; i < c.lr_splines.size(); ++i) {
    std::printf("LR object %zu: %s\n", i, step_origin(c.lr_info[i]).c_str());
    print_lr_text(describe_lr(c.lr_splines[i], check));
  }
}

}  // namespace

void add_info_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("info", "Describe the splines in a file (kind, degrees, counts, knots, domain) or a V-model (topology, volume, attributes)");
  auto file = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("FILE", *file, "Spline file (.json, .g2, .lr), STEP file (.stp, .step) or V-model (.json)")->required();
  auto check = std::make_shared<std::string>();
  cmd->add_flag("--json", *json, "Print one JSON document instead of text");
  auto strict = std::make_shared<bool>(false);
  cmd->add_flag("--strict", *strict,
                "STEP: refuse departures from ISO 10303-21 (lower-case keywords, stray bytes in strings, dangling "
                "references, reference cycles) instead of warning");
  cmd->add_option("--check-independence", *check,
                  "LR splines: test the linear independence of the B-splines (peeling: fast, may be inconclusive; "
                  "exact: rank of the Bezier extraction)")
      ->check(CLI::IsMember({"peeling", "exact"}));
  auto kernel_volume = std::make_shared<bool>(false);
  cmd->add_flag("--kernel-volume", *kernel_volume,
                "STEP: also compute OpenCASCADE's own volume of each B-rep solid, beside trivar's exact-boundary "
                "volume (a cross-check that costs extra time)");
  cmd->callback([file, json, check, strict, kernel_volume] {
    if (is_t_spline_file(*file)) {
      require(check->empty(), "info: --check-independence applies to LR splines; T-splines are classified always");
      print_tspline_info(*file, *json);
      return;
    }
    if (is_step_file(*file)) {
      print_step_info(*file, *json, *check, *strict, *kernel_volume);
      return;
    }
    if (const std::optional<VModel> model = read_model_if_any(*file)) {
      require(check->empty(), "info: --check-independence applies to LR splines; " + *file + " holds a V-model");
      print_model_info(*file, *model, *json);
      return;
    }
    if (const auto lr = read_lr_if_any(*file)) {
      print_lr_info(*file, *lr, *json, *check);
      return;
    }
    if (const auto h = read_hierarchical_if_any(*file)) {
      require(check->empty() && !*json, "info: --check-independence and --json apply to tensor and LR splines, not to "
                                        "the hierarchical splines of " + *file);
      print_hierarchical_info(*file, *h);
      return;
    }
    require(check->empty(), "info: --check-independence applies to LR splines; " + *file +
                                " holds tensor-product splines (linearly independent by construction)");
    const std::vector<AnySpline> objects = read_objects(*file);
    if (*json) {
      nlohmann::json out{{"file", *file}, {"objects", nlohmann::json::array()}};
      for (const AnySpline& o : objects) out["objects"].push_back(std::visit([](const auto& s) { return describe(s); }, o));
      std::printf("%s\n", out.dump(2).c_str());
      return;
    }
    std::printf("%s: %zu object%s\n", file->c_str(), objects.size(), objects.size() == 1 ? "" : "s");
    for (std::size_t i = 0; i < objects.size(); ++i) {
      std::printf("object %zu:\n", i);
      std::visit([](const auto& s) { print_text(s); }, objects[i]);
    }
  });
}

}  // namespace trivar::cli
