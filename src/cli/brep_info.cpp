// `trivar info part.stp`: the B-rep section (the geometry kernel's reading of the file's topology).
#include <cstdio>
#include <string>

#include "cli.hpp"
#include "trivar/cad/step_import.hpp"
#include "trivar/core/error.hpp"

namespace trivar::cli {

nlohmann::json brep_info_json(const std::string& file, bool kernel_volume) {
  cad::StepImport im;
  try {
    im = cad::import_step(file, {.kernel_volume = kernel_volume});
  } catch (const Error& e) {
    // A file of B-spline volumes or LR splines only holds no B-rep; the rest of `info` still applies.
    return {{"error", e.what()}};
  }
  const cad::BrepReport& r = im.report;
  nlohmann::json j{{"solids", r.solids},       {"shells", r.shells},       {"faces", r.faces},
                   {"edges", r.edges},         {"vertices", r.vertices},   {"faces_by_kind", r.faces_by_kind},
                   {"not_solid", r.not_solid}, {"repairs", r.repairs},     {"unmapped_faces", nlohmann::json::array()},
                   {"open_boundaries", r.open_boundaries}, {"solid_info", nlohmann::json::array()}};
  for (const cad::UnmappedFace& f : r.unmapped) j["unmapped_faces"].push_back({{"name", f.name}, {"reason", f.reason}});
  for (const cad::ImportedSolid& s : im.solids) {
    nlohmann::json d{{"name", s.name}, {"mapped", s.solid != nullptr}};
    if (s.kernel_volume) d["kernel_volume"] = *s.kernel_volume;
    if (s.solid) {
      d["faces"] = s.solid->boundary().faces.size();
      d["volume"] = s.solid->volume();
      d["triangles"] = s.solid->boundary().mesh.triangles.size();
      d["chordal_tolerance"] = s.solid->boundary().chordal_tolerance;
    }
    if (s.closure)
      d["closure"] = {{"area_vector", s.closure->area_vector},  {"norm", s.closure->norm},
                      {"area", s.closure->area},                {"relative", s.closure->relative},
                      {"volume_uncertainty", s.closure->volume_uncertainty}, {"allowance", s.closure->allowance},
                      {"closed", s.closure->closed()}};
    j["solid_info"].push_back(std::move(d));
  }
  return j;
}

void print_brep_info(const std::string& file, bool kernel_volume) {
  const nlohmann::json j = brep_info_json(file, kernel_volume);
  if (j.contains("error")) {
    std::printf("  B-rep: none (%s)\n", j["error"].get<std::string>().c_str());
    return;
  }
  std::string kinds;
  for (const auto& [k, n] : j["faces_by_kind"].items()) kinds += (kinds.empty() ? "" : ", ") + std::to_string(n.get<int>()) + " " + k;
  std::printf("  B-rep: %d solids, %d shells, %d faces (%s), %d edges, %d vertices\n", j["solids"].get<int>(),
              j["shells"].get<int>(), j["faces"].get<int>(), kinds.empty() ? "none" : kinds.c_str(), j["edges"].get<int>(),
              j["vertices"].get<int>());
  for (const auto& s : j["not_solid"]) std::printf("  not a solid: %s\n", s.get<std::string>().c_str());
  for (const auto& s : j["repairs"]) std::printf("  repaired: %s\n", s.get<std::string>().c_str());
  for (const auto& f : j["unmapped_faces"])
    std::printf("  unmapped face %s: %s\n", f["name"].get<std::string>().c_str(), f["reason"].get<std::string>().c_str());
  for (const auto& s : j["solid_info"]) {
    const std::string kernel = s.contains("kernel_volume") ? fmt(s["kernel_volume"].get<double>()) : "";
    if (!s["mapped"].get<bool>()) {
      std::printf("  solid %s: not mapped (see the unmapped faces)%s\n", s["name"].get<std::string>().c_str(),
                  kernel.empty() ? "" : (", OpenCASCADE volume " + kernel).c_str());
      continue;
    }
    std::printf("  solid %s: %zu trimmed NURBS faces, volume %s (exact boundary%s), mesh %zu triangles within %s\n",
                s["name"].get<std::string>().c_str(), s["faces"].get<std::size_t>(), fmt(s["volume"].get<double>()).c_str(),
                kernel.empty() ? "" : ("; OpenCASCADE " + kernel).c_str(), s["triangles"].get<std::size_t>(),
                fmt(s["chordal_tolerance"].get<double>()).c_str());
    if (s.contains("closure")) {
      const nlohmann::json& c = s["closure"];
      std::printf("    closure: integral of the normal over the faces %s (%s of the area %s; volume uncertain by %s)\n",
                  fmt(c["norm"].get<double>()).c_str(), fmt(c["relative"].get<double>()).c_str(),
                  fmt(c["area"].get<double>()).c_str(), fmt(c["volume_uncertainty"].get<double>()).c_str());
    }
  }
  for (const auto& w : j["open_boundaries"]) std::printf("  warning: %s\n", w.get<std::string>().c_str());
}

}  // namespace trivar::cli
